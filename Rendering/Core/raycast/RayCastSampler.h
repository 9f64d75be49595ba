// RayCastSampler: how the CPU ray caster reads the volume (internal to RayCastKernel): one
// cell lookup shared by the leaping tests and the interpolation, so both see bit-identical
// inputs.
#ifndef accelvolume_RayCastSampler_h
#define accelvolume_RayCastSampler_h

#include "common/IndexRay.h"
#include "common/VolumeView.h"
#include "skipping/CellBricks.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>

// Inlined into each SIMD build of its callers (RayCastKernelBatch.inl's lanes).
#if defined(__GNUC__) || defined(__clang__)
#define ACCELVOLUME_ALWAYS_INLINE __attribute__((always_inline)) inline
#else
#define ACCELVOLUME_ALWAYS_INLINE inline
#endif

namespace accelvolume
{
namespace detail
{

inline float Lerp(float a, float b, float t)
{
  return a + t * (b - a);
}

// A sample's cell: base voxel offset, per-axis corner offsets (0 on one-voxel axes) and the
// fractional position, computed once and shared by the leaping tests and the interpolation so
// both see bit-identical inputs.
struct SampleCell
{
  std::ptrdiff_t base = 0;
  std::ptrdiff_t offset[3] = { 0, 0, 0 };
  float f[3] = { 0, 0, 0 };
  std::size_t cell = 0; // index into the CellBricks layout of per-cell arrays
};

// A voxel's precomputed gradient (its central differences in the ray caster's gradient units;
// any floats, NaN as 0) in 32 bits: three 10-bit two's-complement mantissas (x in bits 0-9, y
// 10-19, z 20-29) sharing a 2-bit exponent e (30-31), each component mantissa * 4^e. e is the
// smallest that keeps every |mantissa| <= 511: integer differences up to 511 units are exact, and a
// component is within half a step (half a unit while all are within 511 units, else under
// 1/255 of the largest component: the direction within ~0.3 degree).
// Two of them (x neighbours) are one 64-bit load: half the ray packets' gradient gathers.
inline std::uint32_t EncodeGradient(const float g[3])
{
  // 511 * 4^e and 4^-e (exact powers of two: the same as std::ldexp, without its call).
  static constexpr float Limit[4] = { 511.0f, 2044.0f, 8176.0f, 32704.0f };
  static constexpr float Inverse[4] = { 1.0f, 0.25f, 0.0625f, 0.015625f };
  float largest = 0;
  for (int k = 0; k < 3; ++k)
  {
    largest = std::max(largest, std::abs(g[k]));
  }
  int exponent = 0;
  while (exponent < 3 && largest > Limit[exponent])
  {
    ++exponent;
  }
  std::uint32_t word = static_cast<std::uint32_t>(exponent) << 30;
  for (int k = 0; k < 3; ++k)
  {
    // Values past 511 * 64 (infinities too) clamp; NaN fails both comparisons and becomes 0.
    // Then round half away from zero.
    const float scaled = g[k] * Inverse[exponent];
    const float value =
      scaled > -511.0f ? (scaled < 511.0f ? scaled : 511.0f) : (scaled <= -511.0f ? -511.0f : 0.0f);
    const int mantissa = static_cast<int>(value + (value >= 0 ? 0.5f : -0.5f));
    word |= (static_cast<std::uint32_t>(mantissa) & 0x3ffu) << (10 * k);
  }
  return word;
}

// EncodeGradient's components as floats (exact: a 10-bit mantissa times a power of two).
ACCELVOLUME_ALWAYS_INLINE void DecodeGradient(std::uint32_t word, float g[3])
{
  const std::uint32_t scaleBits = (2 * (word >> 30) + 127u) << 23;
  float scale;
  std::memcpy(&scale, &scaleBits, sizeof(scale));
  g[0] = static_cast<float>(static_cast<std::int32_t>(word << 22) >> 22) * scale;
  g[1] = static_cast<float>(static_cast<std::int32_t>(word << 12) >> 22) * scale;
  g[2] = static_cast<float>(static_cast<std::int32_t>(word << 2) >> 22) * scale;
}

// Gradient's trilinear interpolation of one sample's precomputed gradients (`at`: the corners'
// offsets), corner by corner in Gradient's order; each component sees the same multiplies and
// adds as the ray packets' lanes (same bits).
ACCELVOLUME_ALWAYS_INLINE void InterpolateGradient(const std::uint32_t* d,
  const std::ptrdiff_t at[8], float fx, const float wy[2], const float wz[2], float g[3])
{
  g[0] = g[1] = g[2] = 0;
  for (int c = 0; c < 8; ++c)
  {
    const float w = ((c & 1) ? fx : 1 - fx) * wy[(c >> 1) & 1] * wz[c >> 2];
    float corner[3];
    DecodeGradient(d[at[c]], corner);
    for (int k = 0; k < 3; ++k)
    {
      g[k] += w * corner[k];
    }
  }
}

// A ray's step per sample along each axis and its inverse |1 / step| (0 for axes the ray
// does not move along), for the distance-map leaps.
struct LeapSteps
{
  double along[3] = { 0, 0, 0 };
  double inverse[3] = { 0, 0, 0 };

  LeapSteps() = default;
  explicit LeapSteps(const Vec3& step)
    : along{ step.x, step.y, step.z }
  {
    for (int a = 0; a < 3; ++a)
    {
      this->inverse[a] = this->along[a] != 0 ? 1.0 / std::abs(this->along[a]) : 0.0;
    }
  }
};

// Samples after the current one a distance-map value d > 0 lets the ray skip. Every cell
// within chessboard distance d - 1 is empty: from the sample's place in its cell, along axis
// a the ray may go d - f (forward) or d - 1 + f (backward) cells before it can reach a
// non-empty one. A small safety margin absorbs the float fraction; one-voxel axes never
// change cell.
ACCELVOLUME_ALWAYS_INLINE std::int64_t DistanceLeap(
  const SampleCell& cell, int d, const LeapSteps& steps)
{
  double room = 1.0e30;
  for (int a = 0; a < 3; ++a)
  {
    if (steps.inverse[a] > 0 && cell.offset[a] != 0)
    {
      const double along = steps.along[a] > 0 ? d - cell.f[a] : d - 1 + cell.f[a];
      room = std::min(room, (along - 1.0e-4) * steps.inverse[a]);
    }
  }
  return static_cast<std::int64_t>(std::max(0.0, std::min(room, 1.0e18)));
}

// The samples of one ray interval in 32.32 fixed point: sample k (at t0 + (k + 0.5) h) lies at
// start + k * step, exactly, whether the walk reaches it sample by sample or after a leap, and
// its cell comes from integer shifts (Sampler::LocateFixed) instead of a chain of double / int
// conversions. Every walk of the ray caster places its samples here.
struct FixedSteps
{
  static constexpr double Scale = 4294967296.0; // 2^32
  std::int64_t start[3] = { 0, 0, 0 };
  std::int64_t step[3] = { 0, 0, 0 };

  FixedSteps() = default;
  FixedSteps(const IndexRay& ray, double t0, double h)
  {
    const double t = t0 + 0.5 * h;
    const double first[3] = { ray.origin.x + t * ray.direction.x,
      ray.origin.y + t * ray.direction.y, ray.origin.z + t * ray.direction.z };
    const double along[3] = { ray.direction.x * h, ray.direction.y * h, ray.direction.z * h };
    for (int a = 0; a < 3; ++a)
    {
      this->start[a] = ToFixed(first[a]);
      this->step[a] = ToFixed(along[a]);
    }
  }

  // Beyond +-2^30 voxels (and NaN) the value is clamped: such samples are outside any volume.
  static std::int64_t ToFixed(double x)
  {
    constexpr double Limit = 1073741824.0;
    const double c = x > -Limit ? (x < Limit ? x : Limit) : -Limit;
    return static_cast<std::int64_t>(std::floor(c * Scale + 0.5));
  }

  void At(std::int64_t k, std::int64_t q[3]) const
  {
    for (int a = 0; a < 3; ++a)
    {
      q[a] = this->start[a] + k * this->step[a];
    }
  }

  // The same point in doubles (exact while |q| < 2^53, i.e. within 2^21 voxels).
  static void ToPoint(const std::int64_t q[3], double p[3])
  {
    for (int a = 0; a < 3; ++a)
    {
      p[a] = static_cast<double>(q[a]) * (1.0 / Scale);
    }
  }
};

template <typename T>
class Sampler
{
public:
  // Component `component` of `components` interleaved per voxel: samplers of one volume's
  // components share Locate's cells (their strides are equal).
  explicit Sampler(const VolumeView& volume, int components = 1, int component = 0)
    : Data(static_cast<const T*>(volume.data) + component)
  {
    for (int a = 0; a < 3; ++a)
    {
      this->Dims[a] = volume.dims[a];
      this->CellDims[a] = std::max(volume.dims[a] - 1, 1);
    }
    this->Bricks = CellBricks(this->CellDims);
    this->Stride[0] = components;
    this->Stride[1] = static_cast<std::ptrdiff_t>(volume.dims[0]) * components;
    this->Stride[2] = static_cast<std::ptrdiff_t>(volume.dims[0]) * volume.dims[1] * components;
  }

  void Locate(const double p[3], SampleCell& s) const
  {
    int c[3];
    this->LocateWith(
      s,
      [p](int a, int n, int& i, float& f)
      {
        // Clamp like GL_CLAMP_TO_EDGE; the comparisons also turn NaN into 0.
        const double q = p[a] > 0 ? (p[a] < n - 1 ? p[a] : n - 1.0) : 0.0;
        i = std::min(static_cast<int>(q), n - 2);
        f = static_cast<float>(q - i);
      },
      c);
    s.cell = this->CellIndex(c);
  }

  // Locate for a fixed-point position (FixedSteps): the same cell, fractions included, as
  // Locate(FixedSteps::ToPoint(q)) (the unit tests compare them), from integer operations.
  void LocateFixed(const std::int64_t q[3], SampleCell& s) const
  {
    int c[3];
    this->LocateFixedCell(q, s, c);
    s.cell = this->CellIndex(c);
  }

  // LocateFixed without SampleCell::cell, which is left as it was: the cell's coordinates go
  // to `c`, for CellIndex when the caller needs the index (it costs more than the rest).
  void LocateFixedCell(const std::int64_t q[3], SampleCell& s, int c[3]) const
  {
    this->LocateWith(
      s,
      [q](int a, int n, int& i, float& f)
      {
        const std::int64_t top = static_cast<std::int64_t>(n - 1) << 32;
        const std::int64_t clamped = q[a] > 0 ? (q[a] < top ? q[a] : top) : 0;
        i = std::min(static_cast<int>(clamped >> 32), n - 2);
        f = static_cast<float>(clamped - (static_cast<std::int64_t>(i) << 32)) *
          (1.0f / 4294967296.0f);
      },
      c);
  }

  // SampleCell::cell of the cell with coordinates c.
  std::size_t CellIndex(const int c[3]) const { return this->Bricks.Index(c[0], c[1], c[2]); }

  const T* Voxels() const { return this->Data; }

  float Corner(const SampleCell& s, int c) const
  {
    return static_cast<float>(this->Data[s.base + ((c & 1) ? s.offset[0] : 0) +
      ((c & 2) ? s.offset[1] : 0) + ((c & 4) ? s.offset[2] : 0)]);
  }

  // x first, then y, then z: the x-edge lerps are those the cell-leap test evaluates.
  float Trilinear(const SampleCell& s) const
  {
    const T* d = this->Data + s.base;
    const std::ptrdiff_t ox = s.offset[0], oy = s.offset[1], oz = s.offset[2];
    const float c00 = Lerp(static_cast<float>(d[0]), static_cast<float>(d[ox]), s.f[0]);
    const float c10 = Lerp(static_cast<float>(d[oy]), static_cast<float>(d[oy + ox]), s.f[0]);
    const float c01 = Lerp(static_cast<float>(d[oz]), static_cast<float>(d[oz + ox]), s.f[0]);
    const float c11 =
      Lerp(static_cast<float>(d[oz + oy]), static_cast<float>(d[oz + oy + ox]), s.f[0]);
    return Lerp(Lerp(c00, c10, s.f[1]), Lerp(c01, c11, s.f[1]), s.f[2]);
  }

  // Like GL_NEAREST: voxel floor(p + 0.5), clamped.
  float Nearest(const double p[3]) const
  {
    std::ptrdiff_t at = 0;
    for (int a = 0; a < 3; ++a)
    {
      const double q = std::floor(p[a] + 0.5);
      const int i = q > 0 ? (q < this->Dims[a] - 1 ? static_cast<int>(q) : this->Dims[a] - 1) : 0;
      at += i * this->Stride[a];
    }
    return static_cast<float>(this->Data[at]);
  }

  float Sample(const double p[3], bool nearest) const
  {
    if (nearest)
    {
      return this->Nearest(p);
    }
    SampleCell s;
    this->Locate(p, s);
    return this->Trilinear(s);
  }

private:
  // Locate's and LocateFixed's common part: axis(a, n, i, f) finds the cell index i and the
  // fraction f along axis a, which has n > 1 voxels; one-voxel axes keep cell 0. The cell's
  // coordinates go to c.
  template <typename Axis>
  void LocateWith(SampleCell& s, Axis&& axis, int c[3]) const
  {
    std::ptrdiff_t base = 0;
    for (int a = 0; a < 3; ++a)
    {
      const int n = this->Dims[a];
      int i = 0;
      float f = 0;
      if (n > 1)
      {
        axis(a, n, i, f);
        s.offset[a] = this->Stride[a];
      }
      else
      {
        s.offset[a] = 0;
      }
      s.f[a] = f;
      base += i * this->Stride[a];
      c[a] = i;
    }
    s.base = base;
  }

  const T* Data;
  int Dims[3];
  int CellDims[3];
  CellBricks Bricks;
  std::ptrdiff_t Stride[3];
};

}
}

#endif
