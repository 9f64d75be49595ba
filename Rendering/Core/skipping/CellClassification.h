// CellClassification: per-cell data the CPU ray caster needs from the transfer function:
// the Marching Cubes configuration against the opacity threshold (semi-transparent cell
// leaping) and whether any value in the cell may be opaque (empty-space leaping).
#ifndef accelvolume_CellClassification_h
#define accelvolume_CellClassification_h

#include "common/ParallelFor.h"
#include "common/VolumeView.h"
#include "skipping/OpacityRange.h"

#include <cstdint>
#include <vector>

namespace accelvolume
{

struct CellClassification
{
  int cellDims[3] = { 0, 0, 0 }; // max(dims - 1, 1) per axis
  // Bit c set when corner c (CellLeapTable numbering) has value >= threshold; a one-voxel
  // axis repeats its voxel on both sides. NaN corners count as transparent (below).
  std::vector<std::uint8_t> configuration;
  // 1 when the range of the cell's 8 corner values may be opaque (OpacityRange::MayBeOpaque).
  std::vector<std::uint8_t> nonEmpty;
};

// Cell (i, j, k) is the cube of voxels [i, i+1] x [j, j+1] x [k, k+1] (clamped). Identical
// results for any ParallelFor. threshold: the configuration's opacity threshold (usually
// OpacityRange::TransparentBelow() lowered by a rounding margin); the comparison is exact, as
// if made in double (a NaN threshold sets no bits, -inf every non-NaN corner). No data or an
// axis with < 1 voxel gives an empty result (cellDims 0). Cells x fastest, like the volume.
// Cost: a few vectorized passes over the voxels; for 8- and 16-bit scalars emptiness comes from
// per-value tables (2^16 MayBeOpaque calls per call), otherwise from MayBeOpaque per cell.
CellClassification ClassifyCells(const VolumeView& volume, const OpacityRange& opacity,
  double threshold, const ParallelFor& parallel);

// The same into an existing result, reusing its buffers: a renderer that reclassifies on every
// transfer-function edit avoids reallocating (and the kernel re-zeroing) two cell-sized arrays.
void ClassifyCells(const VolumeView& volume, const OpacityRange& opacity, double threshold,
  const ParallelFor& parallel, CellClassification& result);

}

#endif
