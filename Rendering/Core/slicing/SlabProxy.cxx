// SlabProxy: projects the region between two depth planes onto the front one along the view rays.
#include "slicing/SlabProxy.h"

#include "slicing/CompositeSlices.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

namespace accelvolume
{

namespace
{
// A perspective front at or behind the eye is raised to this fraction of the way to back.
constexpr double MinimumFrontFraction = 1e-6;
// Same sliver and merge thresholds as Geometry.cxx, so a one-sample slab drops exactly the
// sections that ComputeViewAlignedSlices drops.
constexpr double VertexTolerance = 1e-12;
constexpr double AreaTolerance = 1e-13;

struct Point2
{
  double a = 0, b = 0;
};

double Cross2(const Point2& o, const Point2& p, const Point2& q)
{
  return (p.a - o.a) * (q.b - o.b) - (p.b - o.b) * (q.a - o.a);
}

double Depth(const ViewRays& rays, const Vec3& p)
{
  return Dot(rays.depthGradient, p) + rays.depthOffset;
}

// The plane a slab's polygon lies on: front, raised for a perspective front at or behind the eye.
double PlaneDepth(const ViewRays& rays, double front, double back)
{
  if (!rays.perspective)
  {
    return front;
  }
  const double eyeDepth = Depth(rays, rays.eye);
  return front > eyeDepth ? front : eyeDepth + MinimumFrontFraction * (back - eyeDepth);
}

// Distinct vertices of the region's boundary faces: the region's vertices. Computed once per stack
// since ComputeRegionBoundaryFaces is the expensive part.
std::vector<Vec3> RegionVertices(const Box& region, const std::vector<HalfSpace>& clip)
{
  std::vector<Vec3> vertices;
  for (const Polygon& face : ComputeRegionBoundaryFaces(region, clip))
  {
    vertices.insert(vertices.end(), face.begin(), face.end());
  }
  return vertices;
}

// Andrew's monotone chain; collinear and repeated points are dropped. Counterclockwise.
std::vector<Point2> ConvexHull(std::vector<Point2> points)
{
  std::sort(points.begin(), points.end(),
    [](const Point2& p, const Point2& q) { return p.a < q.a || (p.a == q.a && p.b < q.b); });
  if (points.size() < 3)
  {
    return {};
  }
  std::vector<Point2> hull(2 * points.size());
  std::size_t count = 0;
  for (const Point2& p : points) // lower chain
  {
    while (count >= 2 && Cross2(hull[count - 2], hull[count - 1], p) <= 0)
    {
      --count;
    }
    hull[count++] = p;
  }
  const std::size_t lowerCount = count + 1;
  for (std::size_t i = points.size() - 1; i-- > 0;) // upper chain
  {
    while (count >= lowerCount && Cross2(hull[count - 2], hull[count - 1], points[i]) <= 0)
    {
      --count;
    }
    hull[count++] = points[i];
  }
  hull.resize(count - 1); // the last point repeats the first
  return hull;
}

// The polygon for a slab given the region's vertices. Vertices of region ∩ {front <= depth <=
// back} are region vertices inside the slab or lie on a bounding plane, where they are vertices of
// that plane's section; taking those rather than clipping the region's faces by the slab keeps
// thin slabs exact (sliver side faces would otherwise be dropped with their vertices).
Polygon SlabPolygon(const std::vector<Vec3>& regionVertices, const Box& region,
  const std::vector<HalfSpace>& clip, const ViewRays& rays, double front, double back)
{
  const Vec3& gradient = rays.depthGradient;
  const double gradientSquared = Dot(gradient, gradient);
  if (!(gradientSquared > 0) || !(front <= back))
  {
    return {};
  }
  const double eyeDepth = Depth(rays, rays.eye);
  const double directionRate = Dot(gradient, rays.direction);
  if (rays.perspective)
  {
    if (!(back > eyeDepth))
    {
      return {};
    }
    front = PlaneDepth(rays, front, back);
  }
  else if (!(directionRate != 0))
  {
    return {};
  }

  std::vector<Vec3> points;
  for (const Vec3& v : regionVertices)
  {
    const double depth = Depth(rays, v);
    if (depth >= front && depth <= back)
    {
      points.push_back(v);
    }
  }
  // Described with -gradient as ComputeViewAlignedSlices does, so front == back matches it.
  for (const double depth : { front, back })
  {
    const Polygon section = PlaneRegionPolygon(-gradient, rays.depthOffset - depth, region, clip);
    points.insert(points.end(), section.begin(), section.end());
    if (back == front)
    {
      break;
    }
  }
  if (points.size() < 3)
  {
    return {};
  }

  // Project along the rays onto depth == front.
  Vec3 center;
  for (Vec3& p : points)
  {
    const double depth = Depth(rays, p);
    if (rays.perspective)
    {
      p = rays.eye + (p - rays.eye) * ((front - eyeDepth) / (depth - eyeDepth));
    }
    else
    {
      p = p + rays.direction * ((front - depth) / directionRate);
    }
    center = center + p;
  }
  center = center * (1.0 / static_cast<double>(points.size()));
  // Put the origin exactly on the plane so the rebuilt vertices are on it to rounding.
  center = center + gradient * ((front - Depth(rays, center)) / gradientSquared);

  // u x v == -gradient direction: counterclockwise in (u, v) faces the viewer.
  const Vec3 normal = -Normalize(gradient);
  const Vec3 least =
    std::abs(normal.x) <= std::abs(normal.y) && std::abs(normal.x) <= std::abs(normal.z)
    ? Vec3{ 1, 0, 0 }
    : (std::abs(normal.y) <= std::abs(normal.z) ? Vec3{ 0, 1, 0 } : Vec3{ 0, 0, 1 });
  const Vec3 u = Normalize(Cross(normal, least));
  const Vec3 v = Cross(normal, u);
  std::vector<Point2> planar;
  planar.reserve(points.size());
  for (const Vec3& p : points)
  {
    planar.push_back({ Dot(p - center, u), Dot(p - center, v) });
  }
  const std::vector<Point2> hull = ConvexHull(std::move(planar));

  Polygon polygon;
  for (const Point2& p : hull)
  {
    polygon.push_back(center + u * p.a + v * p.b);
  }
  // Merge near-duplicates and drop slivers as Geometry's ClipPolygon does.
  double extent = 0;
  for (const Vec3& p : polygon)
  {
    for (const Vec3& q : polygon)
    {
      extent = std::max(extent, Length(p - q));
    }
  }
  Polygon result;
  for (const Vec3& p : polygon)
  {
    if (result.empty() || Length(p - result.back()) > VertexTolerance * extent)
    {
      result.push_back(p);
    }
  }
  while (result.size() > 1 && Length(result.front() - result.back()) <= VertexTolerance * extent)
  {
    result.pop_back();
  }
  if (result.size() < 3 || !(extent > 0) || PolygonArea(result) <= AreaTolerance * extent * extent)
  {
    return {};
  }
  return result;
}

// The bounding box of the table's bounds at samples first ... first + count - 1 (empty if none).
Box SlabBounds(const SliceBoundsTable& table, long long first, long long count)
{
  const double infinity = std::numeric_limits<double>::infinity();
  Box box{ { infinity, infinity, infinity }, { -infinity, -infinity, -infinity } };
  for (long long k = first; k < first + count; ++k)
  {
    const Box at = table.At(k);
    if (!at.IsEmpty())
    {
      box.lower = { std::min(box.lower.x, at.lower.x), std::min(box.lower.y, at.lower.y),
        std::min(box.lower.z, at.lower.z) };
      box.upper = { std::max(box.upper.x, at.upper.x), std::max(box.upper.y, at.upper.y),
        std::max(box.upper.z, at.upper.z) };
    }
  }
  return box;
}

Box Intersect(const Box& a, const Box& b)
{
  return Box{ { std::max(a.lower.x, b.lower.x), std::max(a.lower.y, b.lower.y),
                std::max(a.lower.z, b.lower.z) },
    { std::min(a.upper.x, b.upper.x), std::min(a.upper.y, b.upper.y),
      std::min(a.upper.z, b.upper.z) } };
}

long long FloorDivide(long long a, long long b)
{
  const long long quotient = a / b;
  return (a % b != 0 && (a < 0) != (b < 0)) ? quotient - 1 : quotient;
}
} // namespace

Polygon ComputeSlabProxyPolygon(const Box& region, const std::vector<HalfSpace>& clip,
  const ViewRays& rays, double front, double back)
{
  if (region.IsEmpty() || !(front <= back))
  {
    return {};
  }
  return SlabPolygon(RegionVertices(region, clip), region, clip, rays, front, back);
}

SlabStack ComputeSlabProxyPolygons(const Box& region, const std::vector<HalfSpace>& clip,
  const ViewRays& rays, double spacing, double phase, int samplesPerSlab,
  const std::vector<Box>* nonEmpty)
{
  SlabStack stack;
  if (!(spacing > 0) || samplesPerSlab < 1 || !(Length(rays.depthGradient) > 0) ||
    !std::isfinite(phase))
  {
    return stack;
  }
  const std::vector<Vec3> vertices = RegionVertices(region, clip);
  double minimumDepth = std::numeric_limits<double>::infinity();
  double maximumDepth = -minimumDepth;
  for (const Vec3& v : vertices)
  {
    minimumDepth = std::min(minimumDepth, Depth(rays, v));
    maximumDepth = std::max(maximumDepth, Depth(rays, v));
  }
  if (!(maximumDepth > minimumDepth))
  {
    return stack;
  }
  // Sample indices strictly inside the depth range, fixed up exactly as ComputeViewAlignedSlices
  // does so that both pick the same samples.
  long long first = 0;
  long long last = -1;
  SampleIndexRange(minimumDepth, maximumDepth, phase, spacing, first, last);
  if (first > last)
  {
    return stack;
  }
  const long long n = samplesPerSlab;
  std::unique_ptr<SliceBoundsTable> bounds;
  if (nonEmpty)
  {
    bounds = std::make_unique<SliceBoundsTable>(
      *nonEmpty, rays.depthGradient, rays.depthOffset, spacing, phase);
  }
  for (long long k = FloorDivide(last, n); k >= FloorDivide(first, n); --k) // back to front
  {
    const double front = phase + static_cast<double>(k * n) * spacing;
    const double back = phase + static_cast<double>(k * n + n - 1) * spacing;
    Polygon polygon;
    if (bounds)
    {
      const Box culled = Intersect(region, SlabBounds(*bounds, k * n, n));
      if (!culled.IsEmpty())
      {
        polygon = SlabPolygon(RegionVertices(culled, clip), culled, clip, rays, front, back);
      }
    }
    else
    {
      polygon = SlabPolygon(vertices, region, clip, rays, front, back);
    }
    if (!polygon.empty())
    {
      stack.polygons.push_back(std::move(polygon));
      stack.fronts.push_back(front);
      stack.depths.push_back(PlaneDepth(rays, front, back));
    }
  }
  return stack;
}

} // namespace accelvolume
