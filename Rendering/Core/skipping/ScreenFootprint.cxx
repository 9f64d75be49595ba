#include "skipping/ScreenFootprint.h"

#include "common/Avx512.h"
#include "skipping/CellBricks.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace accelvolume
{

namespace
{

// The pixel ranges from the projected extremes `low` / `high` (ProjectBox's last step).
void PixelRanges(const double low[2], const double high[2], const int size[2], int pixels[4])
{
  for (int a = 0; a < 2; ++a)
  {
    const double from = std::max(std::floor(low[a]) - 1.0, 0.0);
    const double to = std::min(std::ceil(high[a]) + 1.0, size[a] - 1.0);
    pixels[2 * a] = from <= to ? static_cast<int>(from) : 0;
    pixels[2 * a + 1] = from <= to ? static_cast<int>(to) : -1;
  }
}

// Whether brick (bx, by, bz) of a CellBricks-layout distance map holds a non-empty cell (0 in
// the low byte); only its cells inside the grid count (padding entries are not cells).
template <typename Entry>
bool BrickHasNonEmptyCell(
  const Entry* distance, const CellBricks& bricks, const int cellDims[3], int bx, int by, int bz)
{
  constexpr int Size = CellBricks::Size;
  const int x0 = bx * Size, y0 = by * Size, z0 = bz * Size;
  const int nx = std::min(Size, cellDims[0] - x0), ny = std::min(Size, cellDims[1] - y0),
            nz = std::min(Size, cellDims[2] - z0);
  const Entry* entries = distance + bricks.Index(x0, y0, z0);
  for (int z = 0; z < nz; ++z)
  {
    for (int y = 0; y < ny; ++y)
    {
      for (int x = 0; x < nx; ++x)
      {
        if ((entries[(z * Size + y) * Size + x] & 0xff) == 0)
        {
          return true;
        }
      }
    }
  }
  return false;
}

template <typename Entry>
void ComputeMacroCellsOf(const int cellDims[3], const Entry* distance, const ParallelFor& parallel,
  MacroCells& macro, std::size_t maximumMacroCells)
{
  const auto macroCount = [cellDims](int shift)
  {
    std::size_t count = 1;
    for (int a = 0; a < 3; ++a)
    {
      count *= static_cast<std::size_t>((cellDims[a] + (1 << shift) - 1) >> shift);
    }
    return count;
  };
  macro.shift = 3;
  while (macro.shift < 30 && macroCount(macro.shift) > maximumMacroCells)
  {
    ++macro.shift;
  }
  for (int a = 0; a < 3; ++a)
  {
    macro.dims[a] = (cellDims[a] + (1 << macro.shift) - 1) >> macro.shift;
  }
  macro.nonEmpty.assign(macroCount(macro.shift), 0);
  const CellBricks bricks(cellDims);
  const int bricksPerMacro = 1 << (macro.shift - CellBricks::Shift);
  int brickDims[3];
  for (int a = 0; a < 3; ++a)
  {
    brickDims[a] = (cellDims[a] + CellBricks::Size - 1) / CellBricks::Size;
  }
  // Macro planes in parallel: each writes its own rows; a macro cell's scan stops at its first
  // non-empty brick.
  parallel(static_cast<std::size_t>(macro.dims[2]),
    [&](std::size_t begin, std::size_t end)
    {
      for (std::size_t mz = begin; mz < end; ++mz)
      {
        const int bz0 = static_cast<int>(mz) * bricksPerMacro;
        const int bz1 = std::min(bz0 + bricksPerMacro, brickDims[2]);
        for (int bz = bz0; bz < bz1; ++bz)
        {
          for (int by = 0; by < brickDims[1]; ++by)
          {
            std::uint8_t* row = macro.nonEmpty.data() +
              (mz * macro.dims[1] + static_cast<std::size_t>(by / bricksPerMacro)) * macro.dims[0];
            for (int bx = 0; bx < brickDims[0]; ++bx)
            {
              std::uint8_t& flag = row[bx / bricksPerMacro];
              flag = flag || BrickHasNonEmptyCell(distance, bricks, cellDims, bx, by, bz) ? 1 : 0;
            }
          }
        }
      }
    });
}

} // namespace

void ComputeMacroCells(const int cellDims[3], const std::uint8_t* distance,
  const ParallelFor& parallel, MacroCells& macro, std::size_t maximumMacroCells)
{
  ComputeMacroCellsOf(cellDims, distance, parallel, macro, maximumMacroCells);
}

void ComputeMacroCells(const int cellDims[3], const std::uint16_t* distance,
  const ParallelFor& parallel, MacroCells& macro, std::size_t maximumMacroCells)
{
  ComputeMacroCellsOf(cellDims, distance, parallel, macro, maximumMacroCells);
}

bool ProjectBox(
  const Box& box, const double indexToClip[4][4], int width, int height, int pixels[4])
{
  const int size[2] = { width, height };
  double low[2] = { std::numeric_limits<double>::infinity(),
    std::numeric_limits<double>::infinity() };
  double high[2] = { -low[0], -low[1] };
  for (int corner = 0; corner < 8; ++corner)
  {
    const double p[3] = { corner & 1 ? box.upper.x : box.lower.x,
      corner & 2 ? box.upper.y : box.lower.y, corner & 4 ? box.upper.z : box.lower.z };
    double clip[4];
    for (int r = 0; r < 4; ++r)
    {
      clip[r] = indexToClip[r][0] * p[0] + indexToClip[r][1] * p[1] + indexToClip[r][2] * p[2] +
        indexToClip[r][3];
    }
    if (!(clip[3] > 1.0e-12))
    {
      return false;
    }
    for (int a = 0; a < 2; ++a)
    {
      const double pixel = (clip[a] / clip[3] + 1.0) * 0.5 * size[a] - 0.5;
      if (!std::isfinite(pixel))
      {
        return false;
      }
      low[a] = std::min(low[a], pixel);
      high[a] = std::max(high[a], pixel);
    }
  }
  PixelRanges(low, high, size, pixels);
  return true;
}

namespace
{

#if ACCELVOLUME_AVX512_BUILD
// ProjectBox with the eight corners in the lanes of AVX-512 registers: the same operations in
// the same order per corner (this file never contracts them into FMA), so the same pixels. A
// frame projects every non-empty macro cell (tens of thousands on a noisy volume).
ACCELVOLUME_AVX512 bool ProjectBoxInLanes(
  const Box& box, const double indexToClip[4][4], int width, int height, int pixels[4])
{
  const Vec3& lo = box.lower;
  const Vec3& up = box.upper;
  // Corner c takes upper along x when c & 1, along y when c & 2, along z when c & 4.
  const __m512d p[3] = { _mm512_setr_pd(lo.x, up.x, lo.x, up.x, lo.x, up.x, lo.x, up.x),
    _mm512_setr_pd(lo.y, lo.y, up.y, up.y, lo.y, lo.y, up.y, up.y),
    _mm512_setr_pd(lo.z, lo.z, lo.z, lo.z, up.z, up.z, up.z, up.z) };
  __m512d clip[4];
  for (int r = 0; r < 4; ++r)
  {
    const double* m = indexToClip[r];
    clip[r] = _mm512_add_pd(_mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(_mm512_set1_pd(m[0]), p[0]),
                                            _mm512_mul_pd(_mm512_set1_pd(m[1]), p[1])),
                              _mm512_mul_pd(_mm512_set1_pd(m[2]), p[2])),
      _mm512_set1_pd(m[3]));
  }
  if (_mm512_cmp_pd_mask(clip[3], _mm512_set1_pd(1.0e-12), _CMP_GT_OQ) != 0xff)
  {
    return false;
  }
  const int size[2] = { width, height };
  double low[2], high[2];
  for (int a = 0; a < 2; ++a)
  {
    const __m512d pixel = _mm512_sub_pd(
      _mm512_mul_pd(
        _mm512_mul_pd(
          _mm512_add_pd(_mm512_div_pd(clip[a], clip[3]), _mm512_set1_pd(1.0)), _mm512_set1_pd(0.5)),
        _mm512_set1_pd(static_cast<double>(size[a]))),
      _mm512_set1_pd(0.5));
    if (_mm512_fpclass_pd_mask(pixel, 0x99) != 0) // NaN or infinite (not std::isfinite)
    {
      return false;
    }
    low[a] = _mm512_reduce_min_pd(pixel);
    high[a] = _mm512_reduce_max_pd(pixel);
  }
  PixelRanges(low, high, size, pixels);
  return true;
}
#endif

} // namespace

bool ProjectBoxFast(
  const Box& box, const double indexToClip[4][4], int width, int height, int pixels[4])
{
#if ACCELVOLUME_AVX512_BUILD
  if (CpuHasAvx512())
  {
    return ProjectBoxInLanes(box, indexToClip, width, height, pixels);
  }
#endif
  return ProjectBox(box, indexToClip, width, height, pixels);
}

bool ProjectFootprint(const MacroCells& macro, const int volumeDims[3],
  const double indexToClip[4][4], int width, int height, ScreenFootprint& footprint)
{
  footprint.blocks[0] = (width + (1 << FootprintBlockShift) - 1) >> FootprintBlockShift;
  footprint.blocks[1] = (height + (1 << FootprintBlockShift) - 1) >> FootprintBlockShift;
  footprint.covered.assign(
    static_cast<std::size_t>(footprint.blocks[0]) * static_cast<std::size_t>(footprint.blocks[1]),
    0);
  const int side = 1 << macro.shift;
  std::size_t at = 0;
  for (int mz = 0; mz < macro.dims[2]; ++mz)
  {
    for (int my = 0; my < macro.dims[1]; ++my)
    {
      for (int mx = 0; mx < macro.dims[0]; ++mx, ++at)
      {
        if (!macro.nonEmpty[at])
        {
          continue;
        }
        // Cells [m side, (m + 1) side) span voxels [m side, (m + 1) side], within the volume;
        // one voxel more each way.
        const int m[3] = { mx, my, mz };
        double lower[3], upper[3];
        for (int a = 0; a < 3; ++a)
        {
          lower[a] = m[a] * side - 1.0;
          upper[a] = std::min((m[a] + 1) * side, std::max(volumeDims[a] - 1, 0)) + 1.0;
        }
        const Box box{ { lower[0], lower[1], lower[2] }, { upper[0], upper[1], upper[2] } };
        int pixels[4];
        if (!ProjectBoxFast(box, indexToClip, width, height, pixels))
        {
          footprint.covered.clear();
          return false;
        }
        if (pixels[0] > pixels[1] || pixels[2] > pixels[3])
        {
          continue; // off the image
        }
        // The blocks those pixels are in.
        const int first = pixels[0] >> FootprintBlockShift, last = pixels[1] >> FootprintBlockShift;
        for (int by = pixels[2] >> FootprintBlockShift; by <= pixels[3] >> FootprintBlockShift;
             ++by)
        {
          std::uint8_t* row =
            footprint.covered.data() + static_cast<std::size_t>(by) * footprint.blocks[0];
          std::fill(row + first, row + last + 1, std::uint8_t(1));
        }
      }
    }
  }
  return true;
}

} // namespace accelvolume
