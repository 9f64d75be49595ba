// CompositeSlices: depth-ordered proxy slices for compositing, culled by non-empty boxes.
#ifndef accelvolume_CompositeSlices_h
#define accelvolume_CompositeSlices_h

#include "common/Geometry.h"

#include <utility>
#include <vector>

namespace accelvolume
{
struct CompositeSlices
{
  // (depth, polygon) in drawing order; slices of different regions at one depth are disjoint,
  // so drawing depth-major keeps every ray's samples in compositing order.
  std::vector<std::pair<double, Polygon>> slices;
  double keptAreaFraction = 1.0; // slice area kept by the culling
  double fullArea = 0.0;         // slice area before / after the culling
  double keptArea = 0.0;
};

// View-aligned slices of every region (see ComputeViewAlignedSlices), ordered front to back
// (or back to front). When nonEmpty is given, each slice keeps only the part inside the
// bounding box of the boxes its plane crosses: one convex polygon per slice, so neighbouring
// pieces never crack; whatever is cut lies outside every non-empty box. A box flat along an
// axis (octree boxes of a one-voxel axis) counts as half a voxel thick on each side, as the
// one-voxel-thick slab the regions draw there.
CompositeSlices ComputeCompositeSlices(const std::vector<Box>& regions,
  const std::vector<HalfSpace>& clip, const Vec3& depthGradient, double depthOffset, double spacing,
  double phase, bool frontToBack, const std::vector<Box>* nonEmpty);
}

#endif
