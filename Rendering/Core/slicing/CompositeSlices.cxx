// CompositeSlices: depth-ordered proxy slices for compositing, culled by non-empty boxes.
#include "slicing/CompositeSlices.h"

#include <algorithm>
#include <limits>

namespace accelvolume
{
namespace
{
constexpr double Huge = std::numeric_limits<double>::max();

// Depth interval a box spans (its eight corners).
std::pair<double, double> DepthRange(const Box& box, const Vec3& depthGradient, double depthOffset)
{
  double low = Huge;
  double high = -Huge;
  for (int corner = 0; corner < 8; ++corner)
  {
    const Vec3 p{ corner & 1 ? box.upper.x : box.lower.x, corner & 2 ? box.upper.y : box.lower.y,
      corner & 4 ? box.upper.z : box.lower.z };
    const double depth = Dot(depthGradient, p) + depthOffset;
    low = std::min(low, depth);
    high = std::max(high, depth);
  }
  return { low, high };
}

// Bounding box of the boxes whose depth interval contains depth (empty box if none).
Box BoundsAtDepth(
  const std::vector<Box>& boxes, const std::vector<std::pair<double, double>>& depths, double depth)
{
  Box bounds;
  bounds.lower = { Huge, Huge, Huge };
  bounds.upper = { -Huge, -Huge, -Huge };
  for (size_t b = 0; b < boxes.size(); ++b)
  {
    if (depths[b].first <= depth && depth <= depths[b].second)
    {
      bounds.lower = { std::min(bounds.lower.x, boxes[b].lower.x),
        std::min(bounds.lower.y, boxes[b].lower.y), std::min(bounds.lower.z, boxes[b].lower.z) };
      bounds.upper = { std::max(bounds.upper.x, boxes[b].upper.x),
        std::max(bounds.upper.y, boxes[b].upper.y), std::max(bounds.upper.z, boxes[b].upper.z) };
    }
  }
  return bounds;
}
}

CompositeSlices ComputeCompositeSlices(const std::vector<Box>& regions,
  const std::vector<HalfSpace>& clip, const Vec3& depthGradient, double depthOffset, double spacing,
  double phase, bool frontToBack, const std::vector<Box>* nonEmpty)
{
  // Octree boxes span voxel centres, so a one-voxel axis makes them flat, while the regions
  // draw that axis as a slab one voxel thick: a flat axis widens by half a voxel each way (only
  // ever keeping more), else every oblique slice through the slab would be culled.
  std::vector<Box> widened;
  std::vector<std::pair<double, double>> nonEmptyDepths;
  if (nonEmpty)
  {
    const auto widen = [](double& lower, double& upper)
    {
      if (lower == upper)
      {
        lower -= 0.5;
        upper += 0.5;
      }
    };
    widened = *nonEmpty;
    for (Box& box : widened)
    {
      widen(box.lower.x, box.upper.x);
      widen(box.lower.y, box.upper.y);
      widen(box.lower.z, box.upper.z);
      nonEmptyDepths.push_back(DepthRange(box, depthGradient, depthOffset));
    }
    nonEmpty = &widened;
  }
  CompositeSlices result;
  double fullArea = 0.0;
  double keptArea = 0.0;
  for (const Box& region : regions)
  {
    SliceStack stack = ComputeViewAlignedSlices(
      region, clip, depthGradient, depthOffset, spacing, phase, SliceOrder::FrontToBack);
    for (size_t k = 0; k < stack.polygons.size(); ++k)
    {
      Polygon polygon = std::move(stack.polygons[k]);
      fullArea += PolygonArea(polygon);
      if (nonEmpty)
      {
        const Box bounds = BoundsAtDepth(*nonEmpty, nonEmptyDepths, stack.depths[k]);
        for (const HalfSpace& half : BoxHalfSpaces(bounds))
        {
          polygon = polygon.empty() ? polygon : ClipPolygon(polygon, half);
        }
      }
      if (!polygon.empty())
      {
        keptArea += PolygonArea(polygon);
        result.slices.emplace_back(stack.depths[k], std::move(polygon));
      }
    }
  }
  result.keptAreaFraction = fullArea > 0 ? keptArea / fullArea : 1.0;
  result.fullArea = fullArea;
  result.keptArea = keptArea;
  std::stable_sort(result.slices.begin(), result.slices.end(),
    [frontToBack](const auto& a, const auto& b)
    { return frontToBack ? a.first < b.first : a.first > b.first; });
  return result;
}
}
