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

// For each sample index k (slice depth phase + k * spacing), the bounding box of the boxes whose
// depth interval holds that depth (boxes flat along an axis widened as above). Built in time
// proportional to the slices each box spans, not boxes x slices.
class SliceBoundsTable
{
public:
  SliceBoundsTable(const std::vector<Box>& boxes, const Vec3& depthGradient, double depthOffset,
    double spacing, double phase);
  // The bounds at slice k; an empty box where no box holds its depth.
  Box At(long long k) const;

private:
  long long First = 0;
  std::vector<Box> Bounds;
};

// One slice to generate on the GPU: its plane's depth and the box it is drawn across (the
// region, or the region cut to the non-empty bounds at that depth).
struct SliceBox
{
  double depth = 0.0;
  Box box;
};

// The slices of one box-shaped region without clip planes, as ComputeCompositeSlices orders and
// culls them, each as (depth, box): the slice's polygon is the plane's section of its box, which
// is exactly the polygon ComputeCompositeSlices clips (up to the slivers it drops). Slices whose
// box is empty or not crossed by the plane are left out.
std::vector<SliceBox> ComputeSliceBoxes(const Box& region, const Vec3& depthGradient,
  double depthOffset, double spacing, double phase, bool frontToBack, const std::vector<Box>* nonEmpty);

// The area of the plane depth = depthGradient . p + depthOffset inside the box (0 if it misses).
double PlaneBoxSectionArea(const Vec3& depthGradient, double depthOffset, double depth, const Box& box);
}

#endif
