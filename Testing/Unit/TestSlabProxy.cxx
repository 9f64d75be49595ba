// TestSlabProxy: checks slab proxy polygons for coverage and tightness by brute force.
#include "RandomGeometry.h"
#include "slicing/SlabProxy.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace
{
using namespace accelvolume;

constexpr double Tolerance = 1e-9;

using accelvolume_test::RandomBox;
using accelvolume_test::RandomPoint;
using accelvolume_test::RandomUnit;
using accelvolume_test::Uniform;

std::vector<HalfSpace> RandomClip(std::mt19937& random, const Box& box)
{
  std::vector<HalfSpace> clip;
  const int count = std::uniform_int_distribution<int>(0, 3)(random);
  for (int i = 0; i < count; ++i)
  {
    const Vec3 normal = RandomUnit(random);
    // Through a point of the inner part of the box, keeping most of the region non-empty.
    const Vec3 center = 0.5 * (box.lower + box.upper);
    const Vec3 p = center + 0.5 * (RandomPoint(random, box) - center);
    clip.push_back({ normal, -Dot(normal, p) });
  }
  return clip;
}

double Depth(const ViewRays& rays, const Vec3& p)
{
  return Dot(rays.depthGradient, p) + rays.depthOffset;
}

// Perspective or parallel rays with an arbitrary (non-unit, skewed) depth gradient, standing in
// for a non-orthogonal index-to-world matrix. eyeDistance is measured from the box centre.
ViewRays RandomRays(std::mt19937& random, const Box& box, bool perspective, double eyeDistance)
{
  ViewRays rays;
  rays.perspective = perspective;
  const Vec3 center = 0.5 * (box.lower + box.upper);
  const Vec3 toward = RandomUnit(random);
  rays.depthGradient = Uniform(random, 0.3, 3) * Normalize(toward + 0.4 * RandomUnit(random));
  if (Dot(rays.depthGradient, toward) <= 0.1)
  {
    rays.depthGradient = toward;
  }
  if (perspective)
  {
    rays.eye = center - eyeDistance * toward;
    rays.depthOffset = -Dot(rays.depthGradient, rays.eye);
  }
  else
  {
    rays.direction = Uniform(random, 0.5, 2) * toward;
    rays.depthOffset = Uniform(random, -10, 10);
  }
  return rays;
}

bool InRegion(const Vec3& p, const Box& box, const std::vector<HalfSpace>& clip)
{
  bool inside = p.x >= box.lower.x && p.x <= box.upper.x && p.y >= box.lower.y &&
    p.y <= box.upper.y && p.z >= box.lower.z && p.z <= box.upper.z;
  for (const HalfSpace& h : clip)
  {
    inside = inside && Dot(h.normal, p) + h.offset >= 0;
  }
  return inside;
}

Vec3 Project(const ViewRays& rays, const Vec3& p, double depth)
{
  if (rays.perspective)
  {
    return rays.eye + (p - rays.eye) * (depth / Depth(rays, p));
  }
  return p + rays.direction * ((depth - Depth(rays, p)) / Dot(rays.depthGradient, rays.direction));
}

// Signed distance of q outside the polygon's edges (<= 0 inside), requiring the winding to face
// the viewer: counterclockwise about -depthGradient.
double DistanceOutside(const Polygon& polygon, const Vec3& gradient, const Vec3& q)
{
  const Vec3 normal = -Normalize(gradient);
  double outside = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < polygon.size(); ++i)
  {
    const Vec3 edge = polygon[(i + 1) % polygon.size()] - polygon[i];
    outside = std::max(outside, -Dot(Cross(edge, q - polygon[i]), normal) / Length(edge));
  }
  return outside;
}

double DistanceToBoundary(const Polygon& polygon, const Vec3& q)
{
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < polygon.size(); ++i)
  {
    const Vec3 a = polygon[i], edge = polygon[(i + 1) % polygon.size()] - a;
    const double t = std::clamp(Dot(q - a, edge) / Dot(edge, edge), 0.0, 1.0);
    best = std::min(best, Length(a + edge * t - q));
  }
  return best;
}

// The ray through q (a point of the polygon) meets region ∩ {front <= depth <= back}, loosened
// by a small tolerance because hull vertices come from rays that only touch the region.
bool RayTouchesSlab(const Box& box, std::vector<HalfSpace> clip, const ViewRays& rays, double front,
  double back, const Vec3& q)
{
  const double slack = 1e-7;
  const Box loose{ box.lower - Vec3{ slack, slack, slack },
    box.upper + Vec3{ slack, slack, slack } };
  for (HalfSpace& h : clip)
  {
    h.offset += slack * Length(h.normal);
  }
  const double g = Length(rays.depthGradient);
  clip.push_back({ rays.depthGradient, rays.depthOffset - front + slack * g });
  clip.push_back({ -rays.depthGradient, back - rays.depthOffset + slack * g });
  const Vec3 origin = rays.perspective ? rays.eye : q;
  const Vec3 direction = rays.perspective ? q - rays.eye : rays.direction;
  double t0 = 0, t1 = 0;
  return IntersectRayRegion(origin, direction, loose, clip, t0, t1);
}

// Depth range of the region, from its boundary faces.
bool DepthRange(const Box& box, const std::vector<HalfSpace>& clip, const ViewRays& rays,
  double& low, double& high)
{
  low = std::numeric_limits<double>::infinity();
  high = -low;
  for (const Polygon& face : ComputeRegionBoundaryFaces(box, clip))
  {
    for (const Vec3& v : face)
    {
      low = std::min(low, Depth(rays, v));
      high = std::max(high, Depth(rays, v));
    }
  }
  return high > low;
}

TEST(SlabProxy, SingleSampleEqualsSlice)
{
  std::mt19937 random(11);
  int compared = 0;
  for (int trial = 0; trial < 300; ++trial)
  {
    const Box box = RandomBox(random);
    const std::vector<HalfSpace> clip = RandomClip(random, box);
    const ViewRays rays = RandomRays(random, box, trial % 2 == 0, Uniform(random, 8, 30));
    double low = 0, high = 0;
    if (!DepthRange(box, clip, rays, low, high))
    {
      continue;
    }
    const double depth = Uniform(random, low, high);
    const Polygon slab = ComputeSlabProxyPolygon(box, clip, rays, depth, depth);
    const Polygon slice =
      PlaneRegionPolygon(-rays.depthGradient, rays.depthOffset - depth, box, clip);
    ASSERT_EQ(slab.empty(), slice.empty());
    if (slice.empty())
    {
      continue;
    }
    ++compared;
    const double area = PolygonArea(slice);
    EXPECT_NEAR(PolygonArea(slab), area, 1e-9 * area);
    for (const Vec3& p : slab)
    {
      EXPECT_LT(DistanceToBoundary(slice, p), Tolerance);
      EXPECT_NEAR(Depth(rays, p), depth, Tolerance);
    }
    for (const Vec3& p : slice)
    {
      EXPECT_LT(DistanceToBoundary(slab, p), Tolerance);
    }
    // DistanceOutside also fails every vertex if the slab polygon winds away from the viewer.
    EXPECT_LE(DistanceOutside(slab, rays.depthGradient, slice[0]), Tolerance);
  }
  EXPECT_GT(compared, 200);
}

// Coverage and tightness for one slab: run for views at several eye distances.
void CheckSlabs(unsigned seed, double eyeDistanceLow, double eyeDistanceHigh)
{
  std::mt19937 random(seed);
  int checked = 0, covered = 0;
  for (int trial = 0; trial < 200; ++trial)
  {
    const Box box = RandomBox(random);
    const std::vector<HalfSpace> clip = RandomClip(random, box);
    const ViewRays rays =
      RandomRays(random, box, trial % 2 == 0, Uniform(random, eyeDistanceLow, eyeDistanceHigh));
    double low = 0, high = 0;
    if (!DepthRange(box, clip, rays, low, high))
    {
      continue;
    }
    double front = Uniform(random, low - 0.1 * (high - low), high);
    double back = front + Uniform(random, 0, 0.6) * (high - low);
    if (rays.perspective)
    {
      front = std::max(front, 1e-3);
      back = std::max(back, front);
    }
    const Polygon polygon = ComputeSlabProxyPolygon(box, clip, rays, front, back);
    for (int sample = 0; sample < 3000; ++sample)
    {
      const Vec3 p = RandomPoint(random, box);
      const double depth = Depth(rays, p);
      if (!InRegion(p, box, clip) || depth < front || depth > back)
      {
        continue;
      }
      ++covered;
      ASSERT_FALSE(polygon.empty()) << "trial " << trial;
      const Vec3 q = Project(rays, p, front);
      ASSERT_LE(DistanceOutside(polygon, rays.depthGradient, q), Tolerance) << "trial " << trial;
    }
    if (polygon.empty())
    {
      continue;
    }
    ++checked;
    Vec3 centroid;
    for (const Vec3& v : polygon)
    {
      EXPECT_NEAR(Depth(rays, v), front, Tolerance * (1 + std::abs(front)));
      EXPECT_TRUE(RayTouchesSlab(box, clip, rays, front, back, v)) << "trial " << trial;
      centroid = centroid + v * (1.0 / static_cast<double>(polygon.size()));
    }
    EXPECT_TRUE(RayTouchesSlab(box, clip, rays, front, back, centroid)) << "trial " << trial;
  }
  EXPECT_GT(checked, 100);
  EXPECT_GT(covered, 10000); // the coverage check must not pass vacuously
}

TEST(SlabProxy, CoversAndIsTightForDistantViews)
{
  CheckSlabs(21, 8, 40);
}

TEST(SlabProxy, EyeCloseToTheBox)
{
  // Eye distance from the centre 1.2 to 4: for the smaller boxes this is just outside a corner
  // (and sometimes inside the box, where fronts near the eye matter most).
  CheckSlabs(31, 1.2, 4);
}

TEST(SlabProxy, EmptyCases)
{
  const Box box{ { 0, 0, 0 }, { 1, 1, 1 } };
  ViewRays rays;
  rays.depthGradient = { 0, 0, 1 };
  rays.depthOffset = 5;
  rays.eye = { 0.5, 0.5, -5 };
  EXPECT_TRUE(ComputeSlabProxyPolygon(box, {}, rays, 7, 8).empty());     // beyond the box
  EXPECT_TRUE(ComputeSlabProxyPolygon(box, {}, rays, 5.6, 5.4).empty()); // back < front
  EXPECT_FALSE(ComputeSlabProxyPolygon(box, {}, rays, 4, 5.5).empty());
  EXPECT_TRUE(ComputeSlabProxyPolygon(Box{ { 0, 0, 0 }, { -1, 1, 1 } }, {}, rays, 5, 6).empty());
  const std::vector<HalfSpace> nothing = { { { 1, 0, 0 }, -2 } }; // x >= 2 misses the box
  EXPECT_TRUE(ComputeSlabProxyPolygon(box, nothing, rays, 5, 6).empty());
  EXPECT_TRUE(ComputeSlabProxyPolygons(box, nothing, rays, 0.1, 0, 4).polygons.empty());
  EXPECT_TRUE(
    ComputeSlabProxyPolygons(Box{ { 0, 0, 0 }, { -1, 1, 1 } }, {}, rays, 0.1, 0, 4).fronts.empty());
  EXPECT_TRUE(ComputeSlabProxyPolygons(box, {}, rays, 0, 0, 4).polygons.empty());
  EXPECT_TRUE(ComputeSlabProxyPolygons(box, {}, rays, 0.1, 0, 0).polygons.empty());
}

// Every sample depth phase + m * spacing strictly inside the region's depth range, at every point
// of the region there, is drawn by the slab holding sample m, and the stack goes back to front.
void CheckStack(unsigned seed, double eyeDistanceLow, double eyeDistanceHigh)
{
  std::mt19937 random(seed);
  for (int trial = 0; trial < 60; ++trial)
  {
    const Box box = RandomBox(random);
    const std::vector<HalfSpace> clip = RandomClip(random, box);
    const ViewRays rays =
      RandomRays(random, box, trial % 2 == 0, Uniform(random, eyeDistanceLow, eyeDistanceHigh));
    const double spacing = Uniform(random, 0.05, 0.5);
    const double phase = Uniform(random, -3, 3);
    const int perSlab = std::uniform_int_distribution<int>(1, 6)(random);
    const SlabStack stack = ComputeSlabProxyPolygons(box, clip, rays, spacing, phase, perSlab);
    ASSERT_EQ(stack.polygons.size(), stack.fronts.size());
    ASSERT_EQ(stack.polygons.size(), stack.depths.size());
    for (std::size_t i = 1; i < stack.fronts.size(); ++i)
    {
      EXPECT_GT(stack.fronts[i - 1], stack.fronts[i]);
    }
    // depths: the plane each polygon lies on (renderers sample there), the front unless raised.
    for (std::size_t i = 0; i < stack.polygons.size(); ++i)
    {
      const double eyeDepth = Depth(rays, rays.eye);
      if (!rays.perspective || stack.fronts[i] > eyeDepth)
      {
        EXPECT_EQ(stack.depths[i], stack.fronts[i]);
      }
      else
      {
        EXPECT_GT(stack.depths[i], eyeDepth);
      }
      for (const Vec3& v : stack.polygons[i])
      {
        EXPECT_NEAR(Depth(rays, v), stack.depths[i], Tolerance) << "trial " << trial;
      }
    }
    const SliceStack slices = ComputeViewAlignedSlices(
      box, clip, rays.depthGradient, rays.depthOffset, spacing, phase, SliceOrder::FrontToBack);
    for (std::size_t s = 0; s < slices.polygons.size(); ++s)
    {
      const double depth = slices.depths[s];
      if (rays.perspective && depth <= 0)
      {
        continue; // behind the eye: never visible
      }
      const long long m = std::llround((depth - phase) / spacing);
      const long long k = m >= 0 ? m / perSlab : -((-m + perSlab - 1) / perSlab);
      const double front = phase + static_cast<double>(k * perSlab) * spacing;
      const auto found = std::find(stack.fronts.begin(), stack.fronts.end(), front);
      ASSERT_NE(found, stack.fronts.end()) << "trial " << trial << " sample " << m;
      const Polygon& polygon = stack.polygons[found - stack.fronts.begin()];
      // Project onto the polygon's own plane, which differs from front only where a perspective
      // front behind the eye was raised.
      const double planeDepth = Depth(rays, polygon[0]);
      const Polygon& slice = slices.polygons[s];
      std::uniform_real_distribution<double> weight(0, 1);
      for (int sample = 0; sample < 40; ++sample)
      {
        // A random convex combination of the slice's vertices, its vertices included.
        Vec3 p = slice[sample % slice.size()];
        if (sample >= static_cast<int>(slice.size()))
        {
          double total = 0;
          p = Vec3{};
          for (const Vec3& v : slice)
          {
            const double w = weight(random);
            p = p + v * w;
            total += w;
          }
          p = p * (1.0 / total);
        }
        const Vec3 q = Project(rays, p, planeDepth);
        ASSERT_LE(DistanceOutside(polygon, rays.depthGradient, q), Tolerance)
          << "trial " << trial << " sample " << m;
      }
    }
  }
}

TEST(SlabProxy, StackCoversEverySample)
{
  CheckStack(41, 8, 40);
}

TEST(SlabProxy, StackWithEyeCloseToOrInsideTheBox)
{
  CheckStack(51, 0.3, 4);
}

// Culled slabs (non-empty boxes given): every sample of a slice through a non-empty box inside
// the region is still drawn by its slab, and no culled slab exceeds the unculled one.
TEST(SlabProxy, CulledStackCoversNonEmptySamples)
{
  std::mt19937 random(61);
  for (int trial = 0; trial < 60; ++trial)
  {
    const Box box = RandomBox(random);
    const std::vector<HalfSpace> clip = RandomClip(random, box);
    const ViewRays rays = RandomRays(random, box, trial % 2 == 0, Uniform(random, 8, 40));
    const double spacing = Uniform(random, 0.05, 0.5);
    const double phase = Uniform(random, -3, 3);
    const int perSlab = std::uniform_int_distribution<int>(2, 6)(random);
    std::vector<Box> nonEmpty;
    const int count = std::uniform_int_distribution<int>(0, 4)(random);
    for (int b = 0; b < count; ++b)
    {
      const Vec3 a = RandomPoint(random, box), c = RandomPoint(random, box);
      nonEmpty.push_back(Box{ { std::min(a.x, c.x), std::min(a.y, c.y), std::min(a.z, c.z) },
        { std::max(a.x, c.x), std::max(a.y, c.y), std::max(a.z, c.z) } });
    }
    const SlabStack full = ComputeSlabProxyPolygons(box, clip, rays, spacing, phase, perSlab);
    const SlabStack culled =
      ComputeSlabProxyPolygons(box, clip, rays, spacing, phase, perSlab, &nonEmpty);
    ASSERT_LE(culled.polygons.size(), full.polygons.size());
    for (std::size_t i = 0; i < culled.polygons.size(); ++i)
    {
      const auto found = std::find(full.fronts.begin(), full.fronts.end(), culled.fronts[i]);
      ASSERT_NE(found, full.fronts.end()) << "trial " << trial;
      EXPECT_LE(PolygonArea(culled.polygons[i]),
        PolygonArea(full.polygons[found - full.fronts.begin()]) * (1 + 1e-9) + 1e-12);
    }
    for (const Box& inner : nonEmpty)
    {
      const SliceStack slices = ComputeViewAlignedSlices(
        inner, clip, rays.depthGradient, rays.depthOffset, spacing, phase, SliceOrder::FrontToBack);
      for (std::size_t s = 0; s < slices.polygons.size(); ++s)
      {
        const long long m = std::llround((slices.depths[s] - phase) / spacing);
        const long long k = m >= 0 ? m / perSlab : -((-m + perSlab - 1) / perSlab);
        const double front = phase + static_cast<double>(k * perSlab) * spacing;
        if (rays.perspective && front <= Depth(rays, rays.eye))
        {
          continue; // a raised front: covered by StackWithEyeCloseToOrInsideTheBox
        }
        const auto found = std::find(culled.fronts.begin(), culled.fronts.end(), front);
        ASSERT_NE(found, culled.fronts.end()) << "trial " << trial << " sample " << m;
        const Polygon& polygon = culled.polygons[found - culled.fronts.begin()];
        for (const Vec3& p : slices.polygons[s])
        {
          EXPECT_LE(DistanceOutside(polygon, rays.depthGradient, Project(rays, p, front)),
            1e-7 * (1 + Length(p)))
            << "trial " << trial << " sample " << m;
        }
      }
    }
  }
}

} // namespace
