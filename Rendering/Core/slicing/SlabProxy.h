// SlabProxy: proxy polygons for slab rendering, where each fragment takes several samples in depth.
#ifndef accelvolume_SlabProxy_h
#define accelvolume_SlabProxy_h

#include "common/Geometry.h"

#include <vector>

namespace accelvolume
{

// The viewing rays, in the same (index) coordinates as the region.
struct ViewRays
{
  // depth(p) = Dot(depthGradient, p) + depthOffset: eye depth, growing away from the viewer.
  Vec3 depthGradient;
  double depthOffset = 0;
  bool perspective = true;
  // Perspective: the eye point (depth(eye) == 0 for a true eye; any other value is honoured by
  // treating depth(eye) as the apex depth).
  Vec3 eye;
  // Parallel: the ray direction, with Dot(depthGradient, direction) > 0. Only the line matters (the
  // opposite direction gives the same polygons); one parallel to the depth planes gives none.
  Vec3 direction;
};

// Convex polygon on the plane depth == front covering the projection, along the rays, of
// region ∩ clip ∩ {front <= depth <= back}: every pixel whose ray meets the region at a depth in
// [front, back] is covered, and the polygon is the exact projection (tight). Wound counterclockwise
// seen from the viewer (right-hand normal -depthGradient), like ComputeViewAlignedSlices. Empty
// when that set is empty or has no projected area, when back < front, or for a zero gradient.
// With front == back it is the PlaneRegionPolygon / ComputeViewAlignedSlices section at that depth.
// Perspective: depths at or behind the eye cannot be projected, so a front at or behind the eye is
// raised to depth(eye) + 1e-6 * (back - depth(eye)) and the polygon lies on that plane instead;
// samples nearer than that are lost (a renderer with the eye inside the volume should rather
// start its slabs at its near plane). A back at or behind the eye gives an empty polygon.
Polygon ComputeSlabProxyPolygon(const Box& region, const std::vector<HalfSpace>& clip,
  const ViewRays& rays, double front, double back);

struct SlabStack
{
  std::vector<Polygon> polygons;
  // fronts[n] is the nominal front depth of slab n (its first sample depth). The polygon lies on
  // that plane, except where ComputeSlabProxyPolygon raises a perspective front to the eye.
  std::vector<double> fronts;
  // depths[n] is the depth of the plane polygons[n] lies on: fronts[n], or the raised front.
  std::vector<double> depths;
};

// Slabs of samplesPerSlab samples each: sample m sits at depth phase + m * spacing (computed with
// that formula, as ComputeViewAlignedSlices does, so both agree bit for bit), slab k holds samples
// k * samplesPerSlab ... k * samplesPerSlab + samplesPerSlab - 1, so front_k = phase +
// (k * samplesPerSlab) * spacing and back_k = front_k + (samplesPerSlab - 1) * spacing. Every slab
// with a sample strictly inside the region's depth range is produced (so every sample that
// ComputeViewAlignedSlices would slice is covered), except those whose polygon is empty; ordered
// back to front. Spacing <= 0, samplesPerSlab < 1, a zero gradient or a region without volume give
// no slabs.
// With nonEmpty, each slab's region is first cut to the bounding box of the boxes holding one of
// its sample depths (SliceBoundsTable, so flat boxes count as half a voxel thick): what a slab
// loses lies outside every non-empty box, and slabs crossing none are left out.
SlabStack ComputeSlabProxyPolygons(const Box& region, const std::vector<HalfSpace>& clip,
  const ViewRays& rays, double spacing, double phase, int samplesPerSlab,
  const std::vector<Box>* nonEmpty = nullptr);

} // namespace accelvolume

#endif
