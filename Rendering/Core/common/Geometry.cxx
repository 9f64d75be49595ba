// Geometry: slice proxy geometry, region faces, cropping boxes and ray/region intersection.
#include "common/Geometry.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace accelvolume
{

namespace
{
// Signed distances this close to a plane (relative to the coordinates involved) count as on the
// plane, so coplanar faces and duplicated planes do not nibble polygons through rounding.
constexpr double PlaneTolerance = 1e-11;
// Vertices closer than this (relative to the polygon extent) are merged.
constexpr double VertexTolerance = 1e-12;
// Polygons with less area than this times their squared extent are slivers and dropped.
constexpr double AreaTolerance = 1e-13;
// Fewer than this many vertices cannot bound an area.
constexpr std::size_t MinimumPolygonVertices = 3;

double Component(const Vec3& v, int axis)
{
  return axis == 0 ? v.x : (axis == 1 ? v.y : v.z);
}

void SetComponent(Vec3& v, int axis, double value)
{
  (axis == 0 ? v.x : (axis == 1 ? v.y : v.z)) = value;
}

double MaxAbsCoordinate(const Polygon& polygon)
{
  double result = 0;
  for (const Vec3& v : polygon)
  {
    result = std::max({ result, std::abs(v.x), std::abs(v.y), std::abs(v.z) });
  }
  return result;
}

double Extent(const Polygon& polygon)
{
  if (polygon.empty())
  {
    return 0;
  }
  Vec3 lower = polygon[0], upper = polygon[0];
  for (const Vec3& v : polygon)
  {
    lower = { std::min(lower.x, v.x), std::min(lower.y, v.y), std::min(lower.z, v.z) };
    upper = { std::max(upper.x, v.x), std::max(upper.y, v.y), std::max(upper.z, v.z) };
  }
  const Vec3 size = upper - lower;
  return std::max({ size.x, size.y, size.z });
}

// Removes repeated vertices and returns empty for polygons without area.
Polygon Cleaned(Polygon polygon)
{
  const double extent = Extent(polygon);
  const double mergeDistance = VertexTolerance * extent;
  Polygon result;
  result.reserve(polygon.size());
  for (const Vec3& v : polygon)
  {
    if (result.empty() || Length(v - result.back()) > mergeDistance)
    {
      result.push_back(v);
    }
  }
  while (result.size() > 1 && Length(result.front() - result.back()) <= mergeDistance)
  {
    result.pop_back();
  }
  if (result.size() < MinimumPolygonVertices || extent <= 0 ||
    PolygonArea(result) <= AreaTolerance * extent * extent)
  {
    return {};
  }
  return result;
}

HalfSpace NormalizedHalfSpace(const HalfSpace& halfSpace)
{
  const double length = Length(halfSpace.normal);
  return { halfSpace.normal * (1.0 / length), halfSpace.offset / length };
}

bool SamePlane(const HalfSpace& a, const HalfSpace& b, double scale)
{
  return Length(a.normal - b.normal) <= PlaneTolerance &&
    std::abs(a.offset - b.offset) <= PlaneTolerance * (1 + scale);
}

Polygon BoxFace(const std::array<Vec3, 8>& corners, std::array<int, 4> indices)
{
  return { corners[indices[0]], corners[indices[1]], corners[indices[2]], corners[indices[3]] };
}
} // namespace

bool Box::IsEmpty() const
{
  return lower.x > upper.x || lower.y > upper.y || lower.z > upper.z;
}

std::vector<HalfSpace> BoxHalfSpaces(const Box& box)
{
  return { { { 1, 0, 0 }, -box.lower.x }, { { -1, 0, 0 }, box.upper.x },
    { { 0, 1, 0 }, -box.lower.y }, { { 0, -1, 0 }, box.upper.y }, { { 0, 0, 1 }, -box.lower.z },
    { { 0, 0, -1 }, box.upper.z } };
}

double PolygonArea(const Polygon& polygon)
{
  if (polygon.size() < MinimumPolygonVertices)
  {
    return 0;
  }
  Vec3 sum;
  for (std::size_t i = 1; i + 1 < polygon.size(); ++i)
  {
    sum = sum + Cross(polygon[i] - polygon[0], polygon[i + 1] - polygon[0]);
  }
  return 0.5 * Length(sum);
}

Polygon ClipPolygon(const Polygon& polygon, const HalfSpace& halfSpace)
{
  if (polygon.size() < MinimumPolygonVertices)
  {
    return {};
  }
  const double tolerance = PlaneTolerance *
    (Length(halfSpace.normal) * MaxAbsCoordinate(polygon) + std::abs(halfSpace.offset));
  std::vector<double> distances(polygon.size());
  for (std::size_t i = 0; i < polygon.size(); ++i)
  {
    const double distance = Dot(halfSpace.normal, polygon[i]) + halfSpace.offset;
    distances[i] = std::abs(distance) <= tolerance ? 0.0 : distance;
  }
  Polygon result;
  result.reserve(polygon.size() + 1);
  for (std::size_t i = 0; i < polygon.size(); ++i)
  {
    const std::size_t next = (i + 1) % polygon.size();
    const double d0 = distances[i], d1 = distances[next];
    if (d0 >= 0)
    {
      result.push_back(polygon[i]);
    }
    if ((d0 >= 0) != (d1 >= 0))
    {
      const double t = d0 / (d0 - d1);
      result.push_back(polygon[i] + t * (polygon[next] - polygon[i]));
    }
  }
  return Cleaned(std::move(result));
}

Polygon PlaneRegionPolygon(
  const Vec3& normal, double value, const Box& box, const std::vector<HalfSpace>& clip)
{
  const double normalLength = Length(normal);
  if (box.IsEmpty() || !(normalLength > 0))
  {
    return {};
  }
  const Vec3 unitNormal = normal * (1.0 / normalLength);
  const Vec3 center = 0.5 * (box.lower + box.upper);
  const double halfDiagonal = 0.5 * Length(box.upper - box.lower);
  const double centerDistance = value / normalLength - Dot(unitNormal, center);
  if (std::abs(centerDistance) > halfDiagonal * (1 + PlaneTolerance) + PlaneTolerance)
  {
    return {};
  }
  // Any point of box ∩ plane lies within halfDiagonal of the projected centre, so a square of
  // half-size twice that covers it with margin.
  const double halfSize = halfDiagonal > 0 ? 2 * halfDiagonal : 1;
  const Vec3 planeCenter = center + centerDistance * unitNormal;
  const Vec3 least = std::abs(unitNormal.x) <= std::abs(unitNormal.y) &&
      std::abs(unitNormal.x) <= std::abs(unitNormal.z)
    ? Vec3{ 1, 0, 0 }
    : (std::abs(unitNormal.y) <= std::abs(unitNormal.z) ? Vec3{ 0, 1, 0 } : Vec3{ 0, 0, 1 });
  const Vec3 u = Normalize(Cross(unitNormal, least)) * halfSize;
  const Vec3 v = Cross(unitNormal, u); // u x v points along +normal: counterclockwise
  Polygon polygon = { planeCenter - u - v, planeCenter + u - v, planeCenter + u + v,
    planeCenter - u + v };
  for (const HalfSpace& halfSpace : BoxHalfSpaces(box))
  {
    polygon = ClipPolygon(polygon, halfSpace);
  }
  for (const HalfSpace& halfSpace : clip)
  {
    if (polygon.empty())
    {
      break;
    }
    polygon = ClipPolygon(polygon, halfSpace);
  }
  return polygon;
}

std::vector<Polygon> ComputeRegionBoundaryFaces(
  const Box& region, const std::vector<HalfSpace>& clip)
{
  std::vector<Polygon> faces;
  if (region.IsEmpty())
  {
    return faces;
  }
  std::array<Vec3, 8> corners;
  for (int c = 0; c < 8; ++c)
  {
    corners[c] = { (c & 1) ? region.upper.x : region.lower.x,
      (c & 2) ? region.upper.y : region.lower.y, (c & 4) ? region.upper.z : region.lower.z };
  }
  // Corner bit 0/1/2 selects the upper x/y/z; each face is counterclockwise seen from outside.
  const std::array<std::array<int, 4>, 6> faceCorners = { { { 0, 4, 6, 2 }, { 1, 3, 7, 5 },
    { 0, 1, 5, 4 }, { 2, 6, 7, 3 }, { 0, 2, 3, 1 }, { 4, 5, 7, 6 } } };
  for (const auto& indices : faceCorners)
  {
    Polygon face = Cleaned(BoxFace(corners, indices));
    for (const HalfSpace& halfSpace : clip)
    {
      if (face.empty())
      {
        break;
      }
      face = ClipPolygon(face, halfSpace);
    }
    if (!face.empty())
    {
      faces.push_back(std::move(face));
    }
  }

  const double scale = std::max(MaxAbsCoordinate({ region.lower, region.upper }), 1.0);
  const std::vector<HalfSpace> boxHalfSpaces = BoxHalfSpaces(region);
  for (std::size_t a = 0; a < clip.size(); ++a)
  {
    if (!(Length(clip[a].normal) > 0))
    {
      continue; // a constant half-space has no boundary plane
    }
    const HalfSpace unit = NormalizedHalfSpace(clip[a]);
    bool duplicate = std::any_of(boxHalfSpaces.begin(), boxHalfSpaces.end(),
      [&](const HalfSpace& boxHalfSpace) { return SamePlane(unit, boxHalfSpace, scale); });
    std::vector<HalfSpace> others;
    for (std::size_t b = 0; b < clip.size(); ++b)
    {
      if (b < a && Length(clip[b].normal) > 0 &&
        SamePlane(unit, NormalizedHalfSpace(clip[b]), scale))
      {
        duplicate = true;
      }
      if (b != a)
      {
        others.push_back(clip[b]);
      }
    }
    if (duplicate)
    {
      continue;
    }
    // The outside lies along -normal, so the plane is described with -normal to wind outward.
    Polygon face = PlaneRegionPolygon(-clip[a].normal, clip[a].offset, region, others);
    if (!face.empty())
    {
      faces.push_back(std::move(face));
    }
  }
  return faces;
}

void SampleIndexRange(double minimumDepth, double maximumDepth, double phase, double spacing,
  long long& first, long long& last)
{
  first = static_cast<long long>(std::floor((minimumDepth - phase) / spacing)) + 1;
  last = static_cast<long long>(std::ceil((maximumDepth - phase) / spacing)) - 1;
  // Rounding in the divisions may land one step off the strict range.
  while (phase + (first - 1) * spacing > minimumDepth)
  {
    --first;
  }
  while (phase + first * spacing <= minimumDepth)
  {
    ++first;
  }
  while (phase + (last + 1) * spacing < maximumDepth)
  {
    ++last;
  }
  while (phase + last * spacing >= maximumDepth)
  {
    --last;
  }
}

bool RegionDepthRange(const Box& region, const std::vector<HalfSpace>& clip,
  const Vec3& depthGradient, double depthOffset, double& minimumDepth, double& maximumDepth)
{
  minimumDepth = std::numeric_limits<double>::infinity();
  maximumDepth = -minimumDepth;
  for (const Polygon& face : ComputeRegionBoundaryFaces(region, clip))
  {
    for (const Vec3& v : face)
    {
      const double depth = Dot(depthGradient, v) + depthOffset;
      minimumDepth = std::min(minimumDepth, depth);
      maximumDepth = std::max(maximumDepth, depth);
    }
  }
  return maximumDepth > minimumDepth;
}

SliceStack ComputeViewAlignedSlices(const Box& region, const std::vector<HalfSpace>& clip,
  const Vec3& depthGradient, double depthOffset, double spacing, double phase, SliceOrder order)
{
  SliceStack stack;
  if (!(spacing > 0) || !(Length(depthGradient) > 0) || !std::isfinite(phase))
  {
    return stack;
  }
  double minimumDepth = 0.0;
  double maximumDepth = 0.0;
  if (!RegionDepthRange(region, clip, depthGradient, depthOffset, minimumDepth, maximumDepth))
  {
    return stack;
  }
  long long first = 0;
  long long last = -1;
  SampleIndexRange(minimumDepth, maximumDepth, phase, spacing, first, last);
  for (long long k = first; k <= last; ++k)
  {
    const double depth = phase + static_cast<double>(k) * spacing;
    // Described with -gradient so that the polygon winds counterclockwise toward the viewer.
    Polygon polygon = PlaneRegionPolygon(-depthGradient, depthOffset - depth, region, clip);
    if (!polygon.empty())
    {
      stack.polygons.push_back(std::move(polygon));
      stack.depths.push_back(depth);
    }
  }
  if (order == SliceOrder::BackToFront)
  {
    std::reverse(stack.polygons.begin(), stack.polygons.end());
    std::reverse(stack.depths.begin(), stack.depths.end());
  }
  return stack;
}

std::vector<Box> CroppingRegionBoxes(const Box& volume, const double planes[6], int flags)
{
  std::vector<Box> boxes;
  if (volume.IsEmpty())
  {
    return boxes;
  }
  struct Interval
  {
    int region;
    double lower, upper;
  };
  std::array<std::vector<Interval>, 3> intervals;
  for (int axis = 0; axis < 3; ++axis)
  {
    const double lower = Component(volume.lower, axis), upper = Component(volume.upper, axis);
    double low = std::clamp(planes[2 * axis], lower, upper);
    double high = std::clamp(planes[2 * axis + 1], lower, upper);
    if (low > high)
    {
      std::swap(low, high);
    }
    if (low > lower)
    {
      intervals[axis].push_back({ 0, lower, low });
    }
    intervals[axis].push_back({ 1, low, high });
    if (upper > high)
    {
      intervals[axis].push_back({ 2, high, upper });
    }
  }
  const int countX = static_cast<int>(intervals[0].size());
  const int countY = static_cast<int>(intervals[1].size());
  const int countZ = static_cast<int>(intervals[2].size());
  // open[i][j][k]: the cell is visible and not yet part of a box.
  bool open[3][3][3] = {};
  for (int k = 0; k < countZ; ++k)
  {
    for (int j = 0; j < countY; ++j)
    {
      for (int i = 0; i < countX; ++i)
      {
        const int bit =
          intervals[0][i].region + 3 * intervals[1][j].region + 9 * intervals[2][k].region;
        open[i][j][k] = ((flags >> bit) & 1) != 0;
      }
    }
  }
  auto allOpen = [&](int i0, int i1, int j0, int j1, int k0, int k1)
  {
    for (int k = k0; k <= k1; ++k)
      for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i)
          if (!open[i][j][k])
            return false;
    return true;
  };
  for (int k = 0; k < countZ; ++k)
  {
    for (int j = 0; j < countY; ++j)
    {
      for (int i = 0; i < countX; ++i)
      {
        if (!open[i][j][k])
        {
          continue;
        }
        // Grow greedily along x, then y, then z while the grown block stays fully open.
        int i1 = i, j1 = j, k1 = k;
        while (i1 + 1 < countX && allOpen(i1 + 1, i1 + 1, j, j, k, k))
          ++i1;
        while (j1 + 1 < countY && allOpen(i, i1, j1 + 1, j1 + 1, k, k))
          ++j1;
        while (k1 + 1 < countZ && allOpen(i, i1, j, j1, k1 + 1, k1 + 1))
          ++k1;
        for (int kk = k; kk <= k1; ++kk)
          for (int jj = j; jj <= j1; ++jj)
            for (int ii = i; ii <= i1; ++ii)
              open[ii][jj][kk] = false;
        Box box;
        const int first[3] = { i, j, k }, last[3] = { i1, j1, k1 };
        for (int axis = 0; axis < 3; ++axis)
        {
          SetComponent(box.lower, axis, intervals[axis][first[axis]].lower);
          SetComponent(box.upper, axis, intervals[axis][last[axis]].upper);
        }
        boxes.push_back(box);
      }
    }
  }
  return boxes;
}

void AppendTriangleFan(const Polygon& polygon, std::vector<float>& xyz)
{
  for (std::size_t i = 1; i + 1 < polygon.size(); ++i)
  {
    for (const Vec3* v : { &polygon[0], &polygon[i], &polygon[i + 1] })
    {
      xyz.push_back(static_cast<float>(v->x));
      xyz.push_back(static_cast<float>(v->y));
      xyz.push_back(static_cast<float>(v->z));
    }
  }
}

bool IntersectRayRegion(const Vec3& origin, const Vec3& direction, const Box& box,
  const std::vector<HalfSpace>& clip, double& t0, double& t1)
{
  if (box.IsEmpty())
  {
    return false;
  }
  double enter = -std::numeric_limits<double>::infinity();
  double leave = std::numeric_limits<double>::infinity();
  // rate * t + value >= 0 bounds t from one side.
  auto narrowBy = [&](double rate, double value)
  {
    if (rate > 0)
    {
      enter = std::max(enter, -value / rate);
    }
    else if (rate < 0)
    {
      leave = std::min(leave, -value / rate);
    }
    else if (value < 0)
    {
      return false;
    }
    return enter <= leave;
  };
  auto narrow = [&](const HalfSpace& halfSpace)
  {
    return narrowBy(
      Dot(halfSpace.normal, direction), Dot(halfSpace.normal, origin) + halfSpace.offset);
  };
  // The box's six half-spaces (BoxHalfSpaces' order) with their unit normals' dot products
  // written out (the same values: this runs per ray).
  const double o[3] = { origin.x, origin.y, origin.z };
  const double d[3] = { direction.x, direction.y, direction.z };
  const double lower[3] = { box.lower.x, box.lower.y, box.lower.z };
  const double upper[3] = { box.upper.x, box.upper.y, box.upper.z };
  for (int a = 0; a < 3; ++a)
  {
    if (!narrowBy(d[a], o[a] + -lower[a]) || !narrowBy(-d[a], -o[a] + upper[a]))
    {
      return false;
    }
  }
  for (const HalfSpace& halfSpace : clip)
  {
    if (!narrow(halfSpace))
    {
      return false;
    }
  }
  t0 = enter;
  t1 = leave;
  return true;
}

} // namespace accelvolume
