// CompositeSlices: depth-ordered proxy slices for compositing, culled by non-empty boxes.
#include "slicing/CompositeSlices.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

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

void Widen(double& lower, double& upper)
{
  if (lower == upper)
  {
    lower -= 0.5;
    upper += 0.5;
  }
}

// Octree boxes span voxel centres, so a one-voxel axis makes them flat, while the regions draw
// that axis as a slab one voxel thick: a flat axis widens by half a voxel each way (only ever
// keeping more), else every oblique slice through the slab would be culled.
std::vector<Box> Widened(const std::vector<Box>& boxes)
{
  std::vector<Box> widened = boxes;
  for (Box& box : widened)
  {
    Widen(box.lower.x, box.upper.x);
    Widen(box.lower.y, box.upper.y);
    Widen(box.lower.z, box.upper.z);
  }
  return widened;
}

Box EmptyBox()
{
  Box box;
  box.lower = { Huge, Huge, Huge };
  box.upper = { -Huge, -Huge, -Huge };
  return box;
}

void Include(Box& bounds, const Box& box)
{
  bounds.lower = { std::min(bounds.lower.x, box.lower.x), std::min(bounds.lower.y, box.lower.y),
    std::min(bounds.lower.z, box.lower.z) };
  bounds.upper = { std::max(bounds.upper.x, box.upper.x), std::max(bounds.upper.y, box.upper.y),
    std::max(bounds.upper.z, box.upper.z) };
}

Box Intersection(const Box& a, const Box& b)
{
  Box box;
  box.lower = { std::max(a.lower.x, b.lower.x), std::max(a.lower.y, b.lower.y),
    std::max(a.lower.z, b.lower.z) };
  box.upper = { std::min(a.upper.x, b.upper.x), std::min(a.upper.y, b.upper.y),
    std::min(a.upper.z, b.upper.z) };
  return box;
}

// The sample indices k with low <= phase + k * spacing <= high, tested with that exact
// expression (the divisions only give the start).
void ClosedIndexRange(
  double low, double high, double phase, double spacing, long long& first, long long& last)
{
  first = static_cast<long long>(std::floor((low - phase) / spacing));
  last = static_cast<long long>(std::ceil((high - phase) / spacing));
  while (phase + static_cast<double>(first) * spacing < low)
  {
    ++first;
  }
  while (phase + static_cast<double>(first - 1) * spacing >= low)
  {
    --first;
  }
  while (phase + static_cast<double>(last) * spacing > high)
  {
    --last;
  }
  while (phase + static_cast<double>(last + 1) * spacing <= high)
  {
    ++last;
  }
}
}

CompositeSlices ComputeCompositeSlices(const std::vector<Box>& regions,
  const std::vector<HalfSpace>& clip, const Vec3& depthGradient, double depthOffset, double spacing,
  double phase, bool frontToBack, const std::vector<Box>* nonEmpty)
{
  std::unique_ptr<SliceBoundsTable> bounds;
  if (nonEmpty)
  {
    bounds.reset(new SliceBoundsTable(*nonEmpty, depthGradient, depthOffset, spacing, phase));
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
      if (bounds)
      {
        const long long index = std::llround((stack.depths[k] - phase) / spacing);
        for (const HalfSpace& half : BoxHalfSpaces(bounds->At(index)))
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

SliceBoundsTable::SliceBoundsTable(const std::vector<Box>& boxes, const Vec3& depthGradient,
  double depthOffset, double spacing, double phase)
{
  if (!(spacing > 0) || boxes.empty())
  {
    return;
  }
  const std::vector<Box> widened = Widened(boxes);
  std::vector<std::pair<long long, long long>> spans;
  spans.reserve(widened.size());
  long long first = std::numeric_limits<long long>::max();
  long long last = std::numeric_limits<long long>::min();
  for (const Box& box : widened)
  {
    const std::pair<double, double> depths = DepthRange(box, depthGradient, depthOffset);
    long long k0 = 0;
    long long k1 = -1;
    ClosedIndexRange(depths.first, depths.second, phase, spacing, k0, k1);
    spans.emplace_back(k0, k1);
    if (k0 <= k1)
    {
      first = std::min(first, k0);
      last = std::max(last, k1);
    }
  }
  if (first > last)
  {
    return;
  }
  this->First = first;
  // Each span is covered by two runs of 2^j slices (j = floor(log2 length)), which may overlap:
  // the bounds are minima and maxima, so that is harmless. Level j's run at i is then split
  // into level j - 1's runs at i and i + 2^(j-1), down to single slices: the same bounds as
  // including each box at every slice of its span, in O(boxes + slices x log span).
  const size_t count = static_cast<size_t>(last - first + 1);
  long long longest = 1;
  for (const auto& span : spans)
  {
    longest = std::max(longest, span.second - span.first + 1);
  }
  int levels = 1;
  while ((2LL << (levels - 1)) <= longest)
  {
    ++levels;
  }
  std::vector<std::vector<Box>> runs(static_cast<size_t>(levels), std::vector<Box>());
  for (int j = 0; j < levels; ++j)
  {
    runs[static_cast<size_t>(j)].assign(count - static_cast<size_t>((1LL << j) - 1), EmptyBox());
  }
  for (size_t b = 0; b < widened.size(); ++b)
  {
    const long long k0 = spans[b].first;
    const long long k1 = spans[b].second;
    if (k0 > k1)
    {
      continue;
    }
    int j = 0;
    while ((2LL << j) <= k1 - k0 + 1)
    {
      ++j;
    }
    std::vector<Box>& level = runs[static_cast<size_t>(j)];
    Include(level[static_cast<size_t>(k0 - first)], widened[b]);
    Include(level[static_cast<size_t>(k1 - (1LL << j) + 1 - first)], widened[b]);
  }
  for (int j = levels - 1; j > 0; --j)
  {
    const std::vector<Box>& level = runs[static_cast<size_t>(j)];
    std::vector<Box>& below = runs[static_cast<size_t>(j - 1)];
    const size_t half = static_cast<size_t>(1LL << (j - 1));
    for (size_t i = 0; i < level.size(); ++i)
    {
      if (!level[i].IsEmpty())
      {
        Include(below[i], level[i]);
        Include(below[i + half], level[i]);
      }
    }
  }
  this->Bounds = std::move(runs[0]);
}

Box SliceBoundsTable::At(long long k) const
{
  if (k < this->First || k >= this->First + static_cast<long long>(this->Bounds.size()))
  {
    return EmptyBox();
  }
  return this->Bounds[static_cast<size_t>(k - this->First)];
}

std::vector<SliceBox> ComputeSliceBoxes(const Box& region, const Vec3& depthGradient,
  double depthOffset, double spacing, double phase, bool frontToBack,
  const std::vector<Box>* nonEmpty)
{
  std::vector<SliceBox> slices;
  if (!(spacing > 0) || !(Length(depthGradient) > 0) || !std::isfinite(phase) || region.IsEmpty())
  {
    return slices;
  }
  const std::pair<double, double> depths = DepthRange(region, depthGradient, depthOffset);
  if (!(depths.second > depths.first))
  {
    return slices;
  }
  long long first = 0;
  long long last = -1;
  SampleIndexRange(depths.first, depths.second, phase, spacing, first, last);
  std::unique_ptr<SliceBoundsTable> bounds;
  if (nonEmpty)
  {
    bounds.reset(new SliceBoundsTable(*nonEmpty, depthGradient, depthOffset, spacing, phase));
  }
  slices.reserve(static_cast<size_t>(std::max(0LL, last - first + 1)));
  for (long long n = 0; n <= last - first; ++n)
  {
    const long long k = frontToBack ? first + n : last - n;
    SliceBox slice;
    slice.depth = phase + static_cast<double>(k) * spacing;
    slice.box = bounds ? Intersection(region, bounds->At(k)) : region;
    if (slice.box.IsEmpty())
    {
      continue;
    }
    // The cut box may lie beside the plane (the boxes that reach this depth do so outside the
    // region): no section, as the CPU path finds its clipped polygon empty. Kept slices then
    // match, and so do early termination's batches of them.
    const std::pair<double, double> boxDepths =
      bounds ? DepthRange(slice.box, depthGradient, depthOffset) : depths;
    if (boxDepths.first < slice.depth && slice.depth < boxDepths.second)
    {
      slices.push_back(slice);
    }
  }
  return slices;
}

double PlaneBoxSectionArea(
  const Vec3& depthGradient, double depthOffset, double depth, const Box& box)
{
  if (box.IsEmpty())
  {
    return 0.0;
  }
  const Polygon section = PlaneRegionPolygon(-depthGradient, depthOffset - depth, box, {});
  return section.empty() ? 0.0 : PolygonArea(section);
}
}
