// CellClassification: per-cell Marching Cubes configuration and emptiness for the CPU ray
// caster, recomputed on every transfer-function change.
//
// The 8 corner loads of a cell are shared with its neighbours, so the work is separable: for a
// row of cells (j, k) the voxel rows (y, z0) and (y, z1) are first folded along z into a row of
// (min, max, 2 configuration bits) per x, two such rows (y0, y1) are folded along y, and each
// cell then folds its two x neighbours. A z-folded row is reused by the next cell row of the
// same chunk. Every loop but the emptiness lookup runs on plain arrays and vectorizes.
//
// Emptiness is OpacityRange::MayBeOpaque(min, max) of the cell's non-NaN corners. For 8- and
// 16-bit scalars it comes from two tables over every value v, built with MayBeOpaque itself:
// point[v] = MayBeOpaque(v, v) and a prefix count of pair[v] = MayBeOpaque(v, v + 1). Since the
// map from values to table positions is monotone (also in floating point), the positions of
// [lo, hi] are the union of those of the pairs [v, v + 1], v in [lo, hi), and contain those of
// [lo, lo]; so MayBeOpaque(lo, hi) == point[lo] || (some pair in [lo, hi) is opaque), exactly.
#include "skipping/CellClassification.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <type_traits>

namespace accelvolume
{

namespace
{
// Scalars with at most this many bits use the per-value emptiness tables.
constexpr int TableBits = 16;

// Elements per inner block of the row loops: a compile-time trip count lets the compiler
// vectorize them even under -O2's cheap vectorizer cost model. A row's last block overlaps the
// previous one instead of leaving a scalar tail (every row operation writes a pure function of
// other arrays, so recomputing elements is harmless).
constexpr std::size_t Block = 64;

// value >= threshold for a scalar type, without a double conversion per voxel: integer types
// compare against ceil(threshold), float against the smallest float >= threshold; `mask`
// clears the bit when no value can pass. NaN values and a NaN threshold compare false.
template <typename T>
struct AtLeast
{
  T value{};
  std::uint8_t mask = 1;

  explicit AtLeast(double threshold)
  {
    if constexpr (std::is_integral<T>::value)
    {
      const double bound = std::ceil(threshold);
      if (std::isnan(bound) || bound > static_cast<double>(std::numeric_limits<T>::max()))
      {
        this->mask = 0;
      }
      else
      {
        this->value = bound <= static_cast<double>(std::numeric_limits<T>::lowest())
          ? std::numeric_limits<T>::lowest()
          : static_cast<T>(bound);
      }
    }
    else if constexpr (std::is_same<T, float>::value)
    {
      constexpr float largest = std::numeric_limits<float>::max();
      if (!std::isfinite(threshold))
      {
        this->value = static_cast<float>(threshold); // +-inf exact; NaN: nothing passes
      }
      else if (threshold > largest)
      {
        this->value = std::numeric_limits<float>::infinity(); // only +inf voxels pass
      }
      else if (threshold < -largest)
      {
        this->value = -largest; // every finite voxel and +inf pass, -inf does not
      }
      else
      {
        float f = static_cast<float>(threshold); // may round down
        if (static_cast<double>(f) < threshold)
        {
          f = std::nextafter(f, std::numeric_limits<float>::infinity());
        }
        this->value = f;
      }
    }
    else
    {
      this->value = static_cast<T>(threshold);
    }
  }
};

// NaN-free keys for the running min / max: NaN voxels become +inf / -inf, so they never win and
// an all-NaN cell ends with min > max (empty).
template <typename T>
inline T LowKey(T v)
{
  if constexpr (std::is_floating_point<T>::value)
  {
    return v == v ? v : std::numeric_limits<T>::infinity();
  }
  return v;
}

template <typename T>
inline T HighKey(T v)
{
  if constexpr (std::is_floating_point<T>::value)
  {
    return v == v ? v : -std::numeric_limits<T>::infinity();
  }
  return v;
}

template <typename T>
inline T Lower(T a, T b)
{
  return b < a ? b : a;
}

template <typename T>
inline T Higher(T a, T b)
{
  return b > a ? b : a;
}

// Runs kernel<Block>(x) over x in [0, n) (overlapping last block), or kernel<1>(x) per element
// for rows shorter than a block.
template <typename Kernel>
void ForBlocks(std::size_t n, const Kernel& kernel)
{
  if (n >= Block)
  {
    for (std::size_t x = 0; x + Block <= n; x += Block)
    {
      kernel.template Run<Block>(x);
    }
    kernel.template Run<Block>(n - Block);
  }
  else
  {
    for (std::size_t x = 0; x < n; ++x)
    {
      kernel.template Run<1>(x);
    }
  }
}

// Folds voxel rows a (plane z0) and b (plane z1) of one y: min, max and the corner bits,
// dz = 0 at bit 0 and dz = 1 at bit 4. (Free functions with restrict parameters: GCC honours
// restrict there, so the loops vectorize without alias checks.)
template <std::size_t N, typename T>
inline void FoldZKernel(const T* __restrict a, const T* __restrict b, T* __restrict lo,
  T* __restrict hi, std::uint8_t* __restrict bit, T value, std::uint8_t mask)
{
  for (std::size_t k = 0; k < N; ++k)
  {
    lo[k] = Lower(LowKey(a[k]), LowKey(b[k]));
    hi[k] = Higher(HighKey(a[k]), HighKey(b[k]));
    bit[k] = static_cast<std::uint8_t>(((a[k] >= value ? 1 : 0) | (b[k] >= value ? 16 : 0)) & mask);
  }
}

template <typename T>
struct FoldZ
{
  const T* r0;
  const T* r1;
  T* low;
  T* high;
  std::uint8_t* bits;
  T value;
  std::uint8_t mask; // 17 (both bits) or 0

  template <std::size_t N>
  void Run(std::size_t x) const
  {
    FoldZKernel<N>(this->r0 + x, this->r1 + x, this->low + x, this->high + x, this->bits + x,
      this->value, this->mask);
  }
};

// Folds two z-folded rows (y0, y1): dy = 1 bits move up by 2.
template <std::size_t N, typename T>
inline void FoldYKernel(const T* __restrict l0, const T* __restrict l1, const T* __restrict h0,
  const T* __restrict h1, const std::uint8_t* __restrict b0, const std::uint8_t* __restrict b1,
  T* __restrict lo, T* __restrict hi, std::uint8_t* __restrict bit)
{
  for (std::size_t k = 0; k < N; ++k)
  {
    lo[k] = Lower(l0[k], l1[k]);
    hi[k] = Higher(h0[k], h1[k]);
    bit[k] = static_cast<std::uint8_t>(b0[k] | (b1[k] << 2));
  }
}

template <typename T>
struct FoldY
{
  const T *low0, *low1, *high0, *high1;
  const std::uint8_t *bits0, *bits1;
  T* low;
  T* high;
  std::uint8_t* bits;

  template <std::size_t N>
  void Run(std::size_t x) const
  {
    FoldYKernel<N>(this->low0 + x, this->low1 + x, this->high0 + x, this->high1 + x,
      this->bits0 + x, this->bits1 + x, this->low + x, this->high + x, this->bits + x);
  }
};

// Folds x neighbours (i, i + 1) of the y-folded row into cells: dx = 1 bits move up by 1.
template <std::size_t N, typename T>
inline void FoldXKernel(const T* __restrict l, const T* __restrict h,
  const std::uint8_t* __restrict b, T* __restrict lo, T* __restrict hi, std::uint8_t* __restrict c)
{
  for (std::size_t k = 0; k < N; ++k)
  {
    lo[k] = Lower(l[k], l[k + 1]);
    hi[k] = Higher(h[k], h[k + 1]);
    c[k] = static_cast<std::uint8_t>(b[k] | (b[k + 1] << 1));
  }
}

template <typename T>
struct FoldX
{
  const T* low;
  const T* high;
  const std::uint8_t* bits;
  T* cellLow;
  T* cellHigh;
  std::uint8_t* configuration;

  template <std::size_t N>
  void Run(std::size_t i) const
  {
    FoldXKernel<N>(this->low + i, this->high + i, this->bits + i, this->cellLow + i,
      this->cellHigh + i, this->configuration + i);
  }
};

// Converts the cells' min / max to doubles for OpacityRange's batch call.
template <std::size_t N, typename T>
inline void ToDoubleKernel(
  const T* __restrict l, const T* __restrict h, double* __restrict lo, double* __restrict hi)
{
  for (std::size_t k = 0; k < N; ++k)
  {
    lo[k] = static_cast<double>(l[k]);
    hi[k] = static_cast<double>(h[k]);
  }
}

template <typename T>
struct ToDouble
{
  const T* low;
  const T* high;
  double* lowOut;
  double* highOut;

  template <std::size_t N>
  void Run(std::size_t i) const
  {
    ToDoubleKernel<N>(this->low + i, this->high + i, this->lowOut + i, this->highOut + i);
  }
};

// Per-value emptiness tables of the 8- and 16-bit types (see the file comment).
struct ValueTables
{
  std::vector<std::uint8_t> point;  // MayBeOpaque(v, v), by v - lowest
  std::vector<std::uint32_t> pairs; // pairs[i]: opaque pairs (v, v + 1) among the first i
};

template <typename T>
ValueTables BuildValueTables(const OpacityRange& opacity)
{
  ValueTables tables;
  const std::int64_t lowest = std::numeric_limits<T>::lowest();
  const std::size_t count =
    static_cast<std::size_t>(std::int64_t(std::numeric_limits<T>::max()) - lowest + 1);
  tables.point.resize(count);
  tables.pairs.assign(count, 0);
  for (std::size_t i = 0; i < count; ++i)
  {
    const double v = static_cast<double>(lowest + static_cast<std::int64_t>(i));
    tables.point[i] = opacity.MayBeOpaque(v, v) ? 1 : 0;
    if (i + 1 < count)
    {
      tables.pairs[i + 1] = tables.pairs[i] + (opacity.MayBeOpaque(v, v + 1.0) ? 1 : 0);
    }
  }
  return tables;
}

// Row buffers of one work chunk.
template <typename T>
struct Rows
{
  // z-folded voxel rows: two, alternating between cell rows.
  std::vector<T> low[2], high[2];
  std::vector<std::uint8_t> bits[2];
  // y-folded row and the cells' own min / max (also as doubles when no tables are used).
  std::vector<T> yLow, yHigh, cellLow, cellHigh;
  std::vector<std::uint8_t> yBits;
  std::vector<double> cellLowDouble, cellHighDouble;

  Rows(std::size_t nx, std::size_t cx)
  {
    for (int b = 0; b < 2; ++b)
    {
      this->low[b].resize(nx);
      this->high[b].resize(nx);
      this->bits[b].resize(nx);
    }
    this->yLow.resize(nx);
    this->yHigh.resize(nx);
    this->yBits.resize(nx);
    this->cellLow.resize(cx);
    this->cellHigh.resize(cx);
    this->cellLowDouble.resize(cx);
    this->cellHighDouble.resize(cx);
  }
};

template <typename T>
void ClassifyTyped(const T* data, const int dims[3], const int cellDims[3],
  const OpacityRange& opacity, double threshold, const ParallelFor& parallel,
  std::uint8_t* configuration, std::uint8_t* nonEmpty)
{
  const std::size_t nx = static_cast<std::size_t>(dims[0]);
  const std::size_t ny = static_cast<std::size_t>(dims[1]);
  const std::size_t nz = static_cast<std::size_t>(dims[2]);
  const std::size_t cx = static_cast<std::size_t>(cellDims[0]);
  const std::size_t cy = static_cast<std::size_t>(cellDims[1]);
  const std::size_t cz = static_cast<std::size_t>(cellDims[2]);
  const AtLeast<T> atLeast(threshold);
  constexpr bool useTables = std::is_integral<T>::value && sizeof(T) * 8 <= TableBits;
  ValueTables tables;
  if constexpr (useTables)
  {
    tables = BuildValueTables<T>(opacity);
  }

  // Work items are cell rows (j, k), k slowest, so chunks reuse z-folded rows along j.
  parallel(cy * cz,
    [&](std::size_t begin, std::size_t end)
    {
      Rows<T> rows(nx, cx);
      int current = 0;
      for (std::size_t r = begin; r < end; ++r)
      {
        const std::size_t j = r % cy;
        const std::size_t k = r / cy;
        const std::size_t y0 = j, y1 = std::min(j + 1, ny - 1);
        const T* plane0 = data + k * nx * ny;
        const T* plane1 = data + std::min(k + 1, nz - 1) * nx * ny;
        const auto foldZ = [&](std::size_t y, int buffer)
        {
          ForBlocks(nx,
            FoldZ<T>{ plane0 + y * nx, plane1 + y * nx, rows.low[buffer].data(),
              rows.high[buffer].data(), rows.bits[buffer].data(), atLeast.value,
              static_cast<std::uint8_t>(atLeast.mask * 17) });
        };
        if (r == begin || j == 0)
        {
          foldZ(y0, current);
        }
        // Row y1 (equal to y0 on a one-voxel y axis) goes to the other buffer.
        const int other = y1 != y0 ? 1 - current : current;
        if (y1 != y0)
        {
          foldZ(y1, other);
        }
        ForBlocks(nx,
          FoldY<T>{ rows.low[current].data(), rows.low[other].data(), rows.high[current].data(),
            rows.high[other].data(), rows.bits[current].data(), rows.bits[other].data(),
            rows.yLow.data(), rows.yHigh.data(), rows.yBits.data() });
        const std::size_t cellRow = (k * cy + j) * cx;
        std::uint8_t* config = configuration + cellRow;
        if (nx > 1)
        {
          ForBlocks(cx,
            FoldX<T>{ rows.yLow.data(), rows.yHigh.data(), rows.yBits.data(), rows.cellLow.data(),
              rows.cellHigh.data(), config });
        }
        else
        {
          // A one-voxel x axis repeats its voxel on both sides.
          rows.cellLow[0] = rows.yLow[0];
          rows.cellHigh[0] = rows.yHigh[0];
          config[0] = static_cast<std::uint8_t>(rows.yBits[0] | (rows.yBits[0] << 1));
        }
        std::uint8_t* flags = nonEmpty + cellRow;
        if constexpr (useTables)
        {
          const std::int64_t lowest = std::numeric_limits<T>::lowest();
          const std::uint8_t* point = tables.point.data();
          const std::uint32_t* pairs = tables.pairs.data();
          for (std::size_t i = 0; i < cx; ++i)
          {
            const std::size_t lo = static_cast<std::size_t>(rows.cellLow[i] - lowest);
            const std::size_t hi = static_cast<std::size_t>(rows.cellHigh[i] - lowest);
            flags[i] = static_cast<std::uint8_t>(point[lo] | (pairs[hi] != pairs[lo] ? 1 : 0));
          }
        }
        else
        {
          ForBlocks(cx,
            ToDouble<T>{ rows.cellLow.data(), rows.cellHigh.data(), rows.cellLowDouble.data(),
              rows.cellHighDouble.data() });
          opacity.MayBeOpaque(rows.cellLowDouble.data(), rows.cellHighDouble.data(), cx, flags);
        }
        current = other;
      }
    });
}
}

CellClassification ClassifyCells(const VolumeView& volume, const OpacityRange& opacity,
  double threshold, const ParallelFor& parallel)
{
  CellClassification result;
  ClassifyCells(volume, opacity, threshold, parallel, result);
  return result;
}

void ClassifyCells(const VolumeView& volume, const OpacityRange& opacity, double threshold,
  const ParallelFor& parallel, CellClassification& result)
{
  if (!volume.data || volume.dims[0] < 1 || volume.dims[1] < 1 || volume.dims[2] < 1)
  {
    result = CellClassification();
    return;
  }
  std::size_t cells = 1;
  for (int a = 0; a < 3; ++a)
  {
    result.cellDims[a] = std::max(volume.dims[a] - 1, 1);
    cells *= static_cast<std::size_t>(result.cellDims[a]);
  }
  result.configuration.resize(cells);
  result.nonEmpty.resize(cells);
  const auto run = [&](auto data)
  {
    ClassifyTyped(data, volume.dims, result.cellDims, opacity, threshold, parallel,
      result.configuration.data(), result.nonEmpty.data());
  };
  switch (volume.type)
  {
    case ScalarType::Int8:
      run(static_cast<const std::int8_t*>(volume.data));
      break;
    case ScalarType::UInt8:
      run(static_cast<const std::uint8_t*>(volume.data));
      break;
    case ScalarType::Int16:
      run(static_cast<const std::int16_t*>(volume.data));
      break;
    case ScalarType::UInt16:
      run(static_cast<const std::uint16_t*>(volume.data));
      break;
    case ScalarType::Int32:
      run(static_cast<const std::int32_t*>(volume.data));
      break;
    case ScalarType::Float32:
      run(static_cast<const float*>(volume.data));
      break;
    case ScalarType::Float64:
      run(static_cast<const double*>(volume.data));
      break;
  }
}

}
