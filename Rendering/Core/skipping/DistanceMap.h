// DistanceMap: chessboard (L-infinity) distance, in cells, from every cell to the nearest
// non-empty cell (Zuiderveld et al. 1992; Cohen & Shefer's proximity clouds): a ray standing in
// a cell of distance d can move up to d - 1 cells along every axis without meeting anything
// non-empty.
#ifndef accelvolume_DistanceMap_h
#define accelvolume_DistanceMap_h

#include "common/ParallelFor.h"

#include <cstdint>
#include <vector>

namespace accelvolume
{

// Largest stored distance; farther cells store it too (still a valid, shorter leap).
constexpr int DistanceMapSaturation = 255;

// cellDims: cells per axis (>= 1 each); nonEmpty: one flag per cell, x fastest.
// Result per cell: 0 for non-empty cells, else min(chessboard distance to the nearest
// non-empty cell, DistanceMapSaturation); DistanceMapSaturation everywhere when no cell is
// non-empty. Exact; identical for any ParallelFor. An empty vector when an axis has < 1 cell or
// nonEmpty's size is not the cell count. O(cells): a few vectorized sweeps.
std::vector<std::uint8_t> ComputeDistanceMap(
  const int cellDims[3], const std::vector<std::uint8_t>& nonEmpty, const ParallelFor& parallel);

// The same into `distance`, reusing its buffer (no reallocation when the cell count is
// unchanged: the map is recomputed on every transfer-function edit).
void ComputeDistanceMap(const int cellDims[3], const std::vector<std::uint8_t>& nonEmpty,
  const ParallelFor& parallel, std::vector<std::uint8_t>& distance);

}

#endif
