// DistanceMap: exact chessboard distance transform of the non-empty cells, saturated.
//
// The chessboard distance is the length of the shortest path of unit moves to the 26
// neighbours (Rosenfeld & Pfaltz 1966), and it separates by axis:
//   D1(x, y, z) = 1D distance along x to the nearest non-empty cell of the row,
//   D2(x, y, z) = min_y' max(|y - y'|, D1(x, y', z)),   d = min_z' max(|z - z'|, D2(x, y, z')).
// The min-max steps are done as sweeps of local moves rather than per line: a forward and a
// backward sweep along y of D(y) = min(D(y), 1 + min(D(x-1..x+1, y -/+ 1))) turn D1 into D2.
// Unrolled over r rows a sweep takes min over |x - x'| <= r of D1(x', y - r) + r, which equals
// max(r, D1(x, y - r)) because D1 drops by one per move toward the nearest feature (and never
// faster); the two directions cover y' below and above. The same sweeps along z with the 3x3
// neighbourhood of the adjacent plane turn D2 into d. So:
// 1. per z-plane (in parallel): D1 by two scans per row (rows interleaved for instruction-level
//    parallelism), then the two y sweeps (vectorized row operations);
// 2. the two z sweeps, one plane after the other, the rows of a plane in parallel (vectorized).
// Every step is a min of path lengths, so saturating the +1 at DistanceMapSaturation gives
// exactly min(distance, DistanceMapSaturation), and "no feature" is simply the cap. O(cells);
// each value depends only on its inputs, so any ParallelFor gives the same map.
#include "skipping/DistanceMap.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace accelvolume
{

namespace
{
constexpr std::uint8_t Cap = static_cast<std::uint8_t>(DistanceMapSaturation);
// Elements per inner block of the vectorized row loops: a compile-time trip count lets the
// compiler vectorize them even under -O2's cheap vectorizer cost model.
constexpr std::size_t Block = 64;

inline std::uint8_t Increment(std::uint8_t v)
{
  return static_cast<std::uint8_t>(v + (v != Cap ? 1 : 0));
}

inline std::uint8_t Min3(std::uint8_t a, std::uint8_t b, std::uint8_t c)
{
  return std::min(std::min(a, b), c);
}

// One block of RelaxFromRow's interior (a[-1] and a[Block] must be readable).
inline void RelaxBlock(std::uint8_t* __restrict r, const std::uint8_t* __restrict a)
{
  for (std::size_t b = 0; b < Block; ++b)
  {
    r[b] = std::min(r[b], Increment(Min3(a[b - 1], a[b], a[b + 1])));
  }
}

// One block of RowMinimum.
inline void MinimumBlock(std::uint8_t* __restrict out, const std::uint8_t* __restrict a,
  const std::uint8_t* __restrict b, const std::uint8_t* __restrict c)
{
  for (std::size_t k = 0; k < Block; ++k)
  {
    out[k] = Min3(a[k], b[k], c[k]);
  }
}

// row[x] = min(row[x], 1 + min(neighbour[x-1], neighbour[x], neighbour[x+1])) (clamped ends):
// the moves from an adjacent row (same plane) or an adjacent plane's 3x3 minimum.
void RelaxFromRow(
  std::uint8_t* __restrict row, const std::uint8_t* __restrict neighbour, std::size_t n)
{
  if (n == 1)
  {
    row[0] = std::min(row[0], Increment(neighbour[0]));
    return;
  }
  row[0] = std::min(row[0], Increment(std::min(neighbour[0], neighbour[1])));
  // Interior x in [1, n - 2], in blocks; the last block overlaps the previous one instead of
  // leaving a scalar tail (the update is idempotent, as row and neighbour do not overlap).
  if (n - 2 >= Block)
  {
    for (std::size_t x = 1; x + Block <= n - 1; x += Block)
    {
      RelaxBlock(row + x, neighbour + x);
    }
    RelaxBlock(row + n - 1 - Block, neighbour + n - 1 - Block);
  }
  else
  {
    for (std::size_t x = 1; x < n - 1; ++x)
    {
      row[x] = std::min(row[x], Increment(Min3(neighbour[x - 1], neighbour[x], neighbour[x + 1])));
    }
  }
  row[n - 1] = std::min(row[n - 1], Increment(std::min(neighbour[n - 2], neighbour[n - 1])));
}

// out[x] = min(a[x], b[x], c[x]).
void RowMinimum(std::uint8_t* __restrict out, const std::uint8_t* __restrict a,
  const std::uint8_t* __restrict b, const std::uint8_t* __restrict c, std::size_t n)
{
  if (n >= Block)
  {
    for (std::size_t x = 0; x + Block <= n; x += Block)
    {
      MinimumBlock(out + x, a + x, b + x, c + x);
    }
    // Overlapping last block: out does not alias the inputs.
    MinimumBlock(out + n - Block, a + n - Block, b + n - Block, c + n - Block);
  }
  else
  {
    for (std::size_t x = 0; x < n; ++x)
    {
      out[x] = Min3(a[x], b[x], c[x]);
    }
  }
}

// One step of the forward scan: distance since the last flagged cell (uncapped, branch-free).
inline int ForwardStep(int state, std::uint8_t flag)
{
  return (state + 1) & -static_cast<int>(flag == 0);
}

// The 1D distances along x to the nearest flagged cell of 4 adjacent rows (capped), one scan
// each way. The rows run interleaved in named variables: each scan is a dependency chain, so
// four independent chains keep the core busy. Returns whether any cell was flagged.
bool RowDistances4(const std::uint8_t* flags, std::uint8_t* out, std::size_t nx)
{
  const std::uint8_t* f0 = flags;
  const std::uint8_t* f1 = flags + nx;
  const std::uint8_t* f2 = flags + 2 * nx;
  const std::uint8_t* f3 = flags + 3 * nx;
  std::uint8_t* o0 = out;
  std::uint8_t* o1 = out + nx;
  std::uint8_t* o2 = out + 2 * nx;
  std::uint8_t* o3 = out + 3 * nx;
  // No feature yet: at least the cap (the states grow uncapped and are stored capped).
  int s0 = Cap, s1 = Cap, s2 = Cap, s3 = Cap;
  int any = 0;
  for (std::size_t x = 0; x < nx; ++x)
  {
    any |= f0[x] | f1[x] | f2[x] | f3[x];
    s0 = ForwardStep(s0, f0[x]);
    s1 = ForwardStep(s1, f1[x]);
    s2 = ForwardStep(s2, f2[x]);
    s3 = ForwardStep(s3, f3[x]);
    o0[x] = static_cast<std::uint8_t>(std::min<int>(s0, Cap));
    o1[x] = static_cast<std::uint8_t>(std::min<int>(s1, Cap));
    o2[x] = static_cast<std::uint8_t>(std::min<int>(s2, Cap));
    o3[x] = static_cast<std::uint8_t>(std::min<int>(s3, Cap));
  }
  // Backward: the stored values are <= Cap, so the minimum needs no saturation.
  s0 = s1 = s2 = s3 = Cap;
  for (std::size_t x = nx; x-- > 0;)
  {
    s0 = std::min<int>(o0[x], s0 + 1);
    s1 = std::min<int>(o1[x], s1 + 1);
    s2 = std::min<int>(o2[x], s2 + 1);
    s3 = std::min<int>(o3[x], s3 + 1);
    o0[x] = static_cast<std::uint8_t>(s0);
    o1[x] = static_cast<std::uint8_t>(s1);
    o2[x] = static_cast<std::uint8_t>(s2);
    o3[x] = static_cast<std::uint8_t>(s3);
  }
  return any != 0;
}

// RowDistances4 for a single row.
bool RowDistances1(const std::uint8_t* flags, std::uint8_t* out, std::size_t nx)
{
  int state = Cap;
  int any = 0;
  for (std::size_t x = 0; x < nx; ++x)
  {
    any |= flags[x];
    state = ForwardStep(state, flags[x]);
    out[x] = static_cast<std::uint8_t>(std::min<int>(state, Cap));
  }
  state = Cap;
  for (std::size_t x = nx; x-- > 0;)
  {
    state = std::min<int>(out[x], state + 1);
    out[x] = static_cast<std::uint8_t>(state);
  }
  return any != 0;
}

// Step 1 on one plane: the 1D distances along x, then a forward and a backward sweep along y
// of the moves from the adjacent row. Returns false (the plane then is all at the cap) when the
// plane has no non-empty cell.
bool PlaneDistance(const std::uint8_t* flags, std::uint8_t* plane, std::size_t nx, std::size_t ny)
{
  bool any = false;
  std::size_t y = 0;
  for (; y + 4 <= ny; y += 4)
  {
    any |= RowDistances4(flags + y * nx, plane + y * nx, nx);
  }
  for (; y < ny; ++y)
  {
    any |= RowDistances1(flags + y * nx, plane + y * nx, nx);
  }
  if (!any)
  {
    return false;
  }
  for (y = 1; y < ny; ++y)
  {
    RelaxFromRow(plane + y * nx, plane + (y - 1) * nx, nx);
  }
  for (y = ny - 1; y-- > 0;)
  {
    RelaxFromRow(plane + y * nx, plane + (y + 1) * nx, nx);
  }
  return true;
}

// Step 2 for one plane: relaxes `plane` from its neighbour plane `from` (rows in parallel).
void RelaxFromPlane(std::uint8_t* plane, const std::uint8_t* from, std::size_t nx, std::size_t ny,
  const ParallelFor& parallel)
{
  parallel(ny,
    [=](std::size_t begin, std::size_t end)
    {
      std::vector<std::uint8_t> around(nx); // 3-row minimum of `from` around row y
      for (std::size_t y = begin; y < end; ++y)
      {
        const std::uint8_t* above = from + (y > 0 ? y - 1 : y) * nx;
        const std::uint8_t* below = from + (y + 1 < ny ? y + 1 : y) * nx;
        RowMinimum(around.data(), above, from + y * nx, below, nx);
        RelaxFromRow(plane + y * nx, around.data(), nx);
      }
    });
}
}

std::vector<std::uint8_t> ComputeDistanceMap(
  const int cellDims[3], const std::vector<std::uint8_t>& nonEmpty, const ParallelFor& parallel)
{
  std::vector<std::uint8_t> distance;
  ComputeDistanceMap(cellDims, nonEmpty, parallel, distance);
  return distance;
}

void ComputeDistanceMap(const int cellDims[3], const std::vector<std::uint8_t>& nonEmpty,
  const ParallelFor& parallel, std::vector<std::uint8_t>& distance)
{
  if (cellDims[0] < 1 || cellDims[1] < 1 || cellDims[2] < 1)
  {
    distance.clear();
    return;
  }
  const std::size_t nx = static_cast<std::size_t>(cellDims[0]);
  const std::size_t ny = static_cast<std::size_t>(cellDims[1]);
  const std::size_t nz = static_cast<std::size_t>(cellDims[2]);
  const std::size_t planeSize = nx * ny;
  if (nonEmpty.size() != planeSize * nz)
  {
    distance.clear();
    return;
  }
  // Every element is written below; resizing to the same size touches nothing.
  distance.resize(nonEmpty.size());
  std::uint8_t* data = distance.data();
  const std::uint8_t* flags = nonEmpty.data();

  // Step 1: 2D distances per plane. below[z]: plane z may hold values under the cap.
  std::vector<std::uint8_t> below(nz, 0);
  std::uint8_t* belowData = below.data();
  parallel(nz,
    [=](std::size_t begin, std::size_t end)
    {
      for (std::size_t z = begin; z < end; ++z)
      {
        belowData[z] = PlaneDistance(flags + z * planeSize, data + z * planeSize, nx, ny) ? 1 : 0;
      }
    });

  // Step 2: sweeps along z, skipping neighbour planes that are all at the cap (they would
  // change nothing).
  for (std::size_t z = 1; z < nz; ++z)
  {
    if (below[z - 1])
    {
      RelaxFromPlane(data + z * planeSize, data + (z - 1) * planeSize, nx, ny, parallel);
      below[z] = 1;
    }
  }
  for (std::size_t z = nz - 1; z-- > 0;)
  {
    if (below[z + 1])
    {
      RelaxFromPlane(data + z * planeSize, data + (z + 1) * planeSize, nx, ny, parallel);
      below[z] = 1;
    }
  }
}

}
