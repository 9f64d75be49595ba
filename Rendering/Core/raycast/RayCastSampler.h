// RayCastSampler: how the CPU ray caster reads the volume (internal to RayCastKernel): one
// cell lookup shared by the leaping tests and the interpolation, so both see bit-identical
// inputs.
#ifndef accelvolume_RayCastSampler_h
#define accelvolume_RayCastSampler_h

#include "common/VolumeView.h"
#include "skipping/CellBricks.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

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
    std::ptrdiff_t base = 0;
    int c[3];
    for (int a = 0; a < 3; ++a)
    {
      const int n = this->Dims[a];
      int i = 0;
      float f = 0;
      if (n > 1)
      {
        // Clamp like GL_CLAMP_TO_EDGE; the comparisons also turn NaN into 0.
        const double q = p[a] > 0 ? (p[a] < n - 1 ? p[a] : n - 1.0) : 0.0;
        i = std::min(static_cast<int>(q), n - 2);
        f = static_cast<float>(q - i);
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
    s.cell = this->Bricks.Index(c[0], c[1], c[2]);
  }

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
  const T* Data;
  int Dims[3];
  int CellDims[3];
  CellBricks Bricks;
  std::ptrdiff_t Stride[3];
};

}
}

#endif
