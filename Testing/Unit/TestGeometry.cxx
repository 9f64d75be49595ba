// TestGeometry: checks slice proxy geometry against brute-force estimates.
#include "RandomGeometry.h"
#include "common/Geometry.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace
{
using namespace accelvolume;

constexpr double OnPlaneTolerance = 1e-9;
constexpr double Pi = 3.14159265358979323846;

using accelvolume_test::RandomBox;
using accelvolume_test::RandomPoint;
using accelvolume_test::RandomUnit;
using accelvolume_test::Uniform;

// A half-space whose plane passes through a random point of the box.
HalfSpace RandomHalfSpace(std::mt19937& random, const Box& box)
{
  const Vec3 normal = RandomUnit(random);
  return { normal, -Dot(normal, RandomPoint(random, box)) };
}

Vec3 Corner(const Box& box, int c)
{
  return { (c & 1) ? box.upper.x : box.lower.x, (c & 2) ? box.upper.y : box.lower.y,
    (c & 4) ? box.upper.z : box.lower.z };
}

bool Inside(const Vec3& p, const Box& box, const std::vector<HalfSpace>& clip, double tolerance)
{
  bool inside = p.x >= box.lower.x - tolerance && p.x <= box.upper.x + tolerance &&
    p.y >= box.lower.y - tolerance && p.y <= box.upper.y + tolerance &&
    p.z >= box.lower.z - tolerance && p.z <= box.upper.z + tolerance;
  for (const HalfSpace& h : clip)
  {
    inside = inside && Dot(h.normal, p) + h.offset >= -tolerance;
  }
  return inside;
}

Vec3 PolygonNormal(const Polygon& polygon)
{
  Vec3 sum;
  for (std::size_t i = 1; i + 1 < polygon.size(); ++i)
  {
    sum = sum + Cross(polygon[i] - polygon[0], polygon[i + 1] - polygon[0]);
  }
  return Normalize(sum);
}

// Every turn goes the same way around the expected normal: convex with consistent winding.
void ExpectConvexAround(const Polygon& polygon, const Vec3& normal)
{
  ASSERT_GE(polygon.size(), 3u);
  for (std::size_t i = 0; i < polygon.size(); ++i)
  {
    const Vec3& a = polygon[i];
    const Vec3& b = polygon[(i + 1) % polygon.size()];
    const Vec3& c = polygon[(i + 2) % polygon.size()];
    EXPECT_GT(Dot(Cross(b - a, c - b), normal), 0) << "vertex " << i;
  }
}

double Perimeter(const Polygon& polygon)
{
  double sum = 0;
  for (std::size_t i = 0; i < polygon.size(); ++i)
  {
    sum += Length(polygon[(i + 1) % polygon.size()] - polygon[i]);
  }
  return sum;
}

// Area of plane ∩ region counted on a fine grid of the plane.
double GridSectionArea(const Vec3& normal, double value, const Box& box,
  const std::vector<HalfSpace>& clip, int cells, double& cellSize)
{
  const Vec3 center = 0.5 * (box.lower + box.upper);
  const double radius = 0.5 * Length(box.upper - box.lower);
  const Vec3 origin = center + (value - Dot(normal, center)) * normal;
  const Vec3 u =
    Normalize(Cross(normal, std::abs(normal.x) < 0.9 ? Vec3{ 1, 0, 0 } : Vec3{ 0, 1, 0 }));
  const Vec3 v = Cross(normal, u);
  cellSize = 2 * radius / cells;
  int count = 0;
  for (int a = 0; a < cells; ++a)
  {
    for (int b = 0; b < cells; ++b)
    {
      const Vec3 p =
        origin + (-radius + (a + 0.5) * cellSize) * u + (-radius + (b + 0.5) * cellSize) * v;
      count += Inside(p, box, clip, 0) ? 1 : 0;
    }
  }
  return count * cellSize * cellSize;
}

// Plane crossings of the 12 box edges (corner pairs differing in one coordinate).
std::vector<Vec3> BoxEdgeIntersections(const Vec3& normal, double value, const Box& box)
{
  std::vector<Vec3> points;
  for (int c = 0; c < 8; ++c)
  {
    for (int bit : { 1, 2, 4 })
    {
      const Vec3 a = Corner(box, c), b = Corner(box, c | bit);
      const double da = Dot(normal, a) - value, db = Dot(normal, b) - value;
      if (!(c & bit) && (da < 0) != (db < 0))
      {
        points.push_back(a + (da / (da - db)) * (b - a));
      }
    }
  }
  return points;
}

bool Contains(const std::vector<Vec3>& points, const Vec3& p)
{
  return std::any_of(
    points.begin(), points.end(), [&](const Vec3& q) { return Length(p - q) < OnPlaneTolerance; });
}

TEST(Geometry, ClipPolygonBasics)
{
  const Polygon square = { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 } };
  EXPECT_EQ(ClipPolygon(square, { { 1, 0, 0 }, 5 }).size(), 4u);
  EXPECT_TRUE(ClipPolygon(square, { { 1, 0, 0 }, -5 }).empty());
  const Polygon half = ClipPolygon(square, { { -1, 0, 0 }, 0.5 });
  EXPECT_NEAR(PolygonArea(half), 0.5, 1e-12);
  // A diagonal cut through two vertices must not leave duplicated vertices.
  const Polygon triangle = ClipPolygon(square, { { -1, -1, 0 }, 1 });
  EXPECT_EQ(triangle.size(), 3u);
  EXPECT_NEAR(PolygonArea(triangle), 0.5, 1e-12);
  // Cutting at an edge leaves a segment, which is degenerate.
  EXPECT_TRUE(ClipPolygon(square, { { -1, 0, 0 }, 0 }).empty());
  EXPECT_TRUE(ClipPolygon({ { 0, 0, 0 }, { 1, 0, 0 } }, { { 1, 0, 0 }, 1 }).empty());
}

TEST(Geometry, PlaneSectionsMatchBruteForce)
{
  std::mt19937 random(7);
  for (int trial = 0; trial < 120; ++trial)
  {
    const Box box = RandomBox(random);
    std::vector<HalfSpace> clip;
    const int clipCount = trial % 3;
    for (int c = 0; c < clipCount; ++c)
    {
      clip.push_back(RandomHalfSpace(random, box));
    }
    const Vec3 normal = RandomUnit(random);
    const double value = Dot(normal, RandomPoint(random, box));
    const Polygon polygon = PlaneRegionPolygon(normal, value, box, clip);
    double cellSize = 0;
    const double gridArea = GridSectionArea(normal, value, box, clip, 300, cellSize);
    if (polygon.empty())
    {
      EXPECT_LT(gridArea, 1e-2) << "trial " << trial;
      continue;
    }
    for (const Vec3& v : polygon)
    {
      EXPECT_NEAR(Dot(normal, v), value, OnPlaneTolerance);
      EXPECT_TRUE(Inside(v, box, clip, OnPlaneTolerance));
    }
    ExpectConvexAround(polygon, normal);
    const double area = PolygonArea(polygon);
    EXPECT_NEAR(area, gridArea, std::max(0.03 * area, Perimeter(polygon) * cellSize))
      << "trial " << trial;
    if (clip.empty())
    {
      const std::vector<Vec3> expected = BoxEdgeIntersections(normal, value, box);
      EXPECT_EQ(polygon.size(), expected.size());
      for (const Vec3& v : polygon)
      {
        EXPECT_TRUE(Contains(expected, v));
      }
      for (const Vec3& p : expected)
      {
        EXPECT_TRUE(Contains(polygon, p));
      }
    }
  }
}

TEST(Geometry, PlaneMissingBoxIsEmpty)
{
  const Box box{ { 0, 0, 0 }, { 1, 1, 1 } };
  EXPECT_TRUE(PlaneRegionPolygon({ 1, 1, 1 }, 3.5, box, {}).empty());
  EXPECT_TRUE(PlaneRegionPolygon({ 0, 0, 1 }, -0.1, box, {}).empty());
  EXPECT_TRUE(PlaneRegionPolygon({ 0, 0, 0 }, 0.5, box, {}).empty());
  // Touching only a corner or an edge gives no area.
  EXPECT_TRUE(PlaneRegionPolygon({ 1, 1, 1 }, 3, box, {}).empty());
  EXPECT_TRUE(PlaneRegionPolygon({ 1, 1, 0 }, 2, box, {}).empty());
  // A clip plane removing the whole section.
  EXPECT_TRUE(PlaneRegionPolygon({ 0, 0, 1 }, 0.5, box, { { { 1, 0, 0 }, -2 } }).empty());
}

// Vertices of box ∩ clip by brute force: every point where three boundary planes meet, if inside.
std::vector<Vec3> RegionVertices(const Box& box, const std::vector<HalfSpace>& clip)
{
  std::vector<HalfSpace> planes = { { { 1, 0, 0 }, -box.lower.x }, { { -1, 0, 0 }, box.upper.x },
    { { 0, 1, 0 }, -box.lower.y }, { { 0, -1, 0 }, box.upper.y }, { { 0, 0, 1 }, -box.lower.z },
    { { 0, 0, -1 }, box.upper.z } };
  planes.insert(planes.end(), clip.begin(), clip.end());
  std::vector<Vec3> vertices;
  for (std::size_t a = 0; a < planes.size(); ++a)
    for (std::size_t b = a + 1; b < planes.size(); ++b)
      for (std::size_t c = b + 1; c < planes.size(); ++c)
      {
        const Vec3 &na = planes[a].normal, &nb = planes[b].normal, &nc = planes[c].normal;
        const double determinant = Dot(na, Cross(nb, nc));
        if (std::abs(determinant) < 1e-12)
        {
          continue;
        }
        // Cramer's rule for Dot(n, p) = -offset on the three planes.
        const Vec3 p = (1 / determinant) *
          (-planes[a].offset * Cross(nb, nc) - planes[b].offset * Cross(nc, na) -
            planes[c].offset * Cross(na, nb));
        if (Inside(p, box, clip, 1e-9))
        {
          vertices.push_back(p);
        }
      }
  return vertices;
}

TEST(Geometry, ViewAlignedSlices)
{
  std::mt19937 random(11);
  for (int trial = 0; trial < 40; ++trial)
  {
    const Box box = RandomBox(random);
    std::vector<HalfSpace> clip;
    if (trial % 2)
    {
      clip.push_back(RandomHalfSpace(random, box));
    }
    const Vec3 gradient = 0.5 * RandomUnit(random);
    const double offset = Uniform(random, -3, 3);
    const double spacing = Uniform(random, 0.05, 0.4);
    const double phase = Uniform(random, -10, 10);
    const SliceStack front = ComputeViewAlignedSlices(
      box, clip, gradient, offset, spacing, phase, SliceOrder::FrontToBack);
    const SliceStack back = ComputeViewAlignedSlices(
      box, clip, gradient, offset, spacing, phase, SliceOrder::BackToFront);
    ASSERT_EQ(front.polygons.size(), front.depths.size());
    ASSERT_EQ(front.depths.size(), back.depths.size());
    ASSERT_TRUE(!clip.empty() || !front.depths.empty()) << "trial " << trial;
    for (std::size_t n = 0; n < front.depths.size(); ++n)
    {
      EXPECT_EQ(front.depths[n], back.depths[back.depths.size() - 1 - n]);
      if (n > 0)
      {
        EXPECT_NEAR(front.depths[n] - front.depths[n - 1], spacing, 1e-9);
      }
      const double k = (front.depths[n] - phase) / spacing;
      EXPECT_NEAR(k, std::round(k), 1e-6);
      for (const Vec3& v : front.polygons[n])
      {
        EXPECT_NEAR(Dot(gradient, v) + offset, front.depths[n], OnPlaneTolerance);
        EXPECT_TRUE(Inside(v, box, clip, OnPlaneTolerance));
      }
      // Slices face the viewer, who looks along +gradient.
      ExpectConvexAround(front.polygons[n], -gradient);
    }
    // Count every phase + k * spacing strictly inside the depth range of the region's vertices.
    double low = 1e300, high = -1e300;
    for (const Vec3& vertex : RegionVertices(box, clip))
    {
      low = std::min(low, Dot(gradient, vertex) + offset);
      high = std::max(high, Dot(gradient, vertex) + offset);
    }
    std::size_t expected = 0;
    for (long k = -100000; k <= 100000; ++k)
    {
      const double depth = phase + k * spacing;
      expected += (depth > low && depth < high) ? 1 : 0;
    }
    EXPECT_EQ(front.depths.size(), expected) << "trial " << trial;
  }
}

TEST(Geometry, SlicesSpacingLargerThanBox)
{
  const Box box{ { 0, 0, 0 }, { 1, 1, 1 } };
  const Vec3 gradient{ 0, 0, 1 };
  // Only depth 0.5 = -9.5 + 1 * 10 lies inside (0, 1).
  SliceStack stack =
    ComputeViewAlignedSlices(box, {}, gradient, 0, 10, -9.5, SliceOrder::FrontToBack);
  ASSERT_EQ(stack.depths.size(), 1u);
  EXPECT_DOUBLE_EQ(stack.depths[0], 0.5);
  EXPECT_NEAR(PolygonArea(stack.polygons[0]), 1, 1e-12);
  stack = ComputeViewAlignedSlices(box, {}, gradient, 0, 10, 3, SliceOrder::FrontToBack);
  EXPECT_TRUE(stack.depths.empty());
  // Slices on the faces themselves are excluded: the range is open.
  stack = ComputeViewAlignedSlices(box, {}, gradient, 0, 0.5, 0, SliceOrder::FrontToBack);
  ASSERT_EQ(stack.depths.size(), 1u);
  EXPECT_TRUE(
    ComputeViewAlignedSlices(box, {}, gradient, 0, 0, 0, SliceOrder::FrontToBack).depths.empty());
  EXPECT_TRUE(ComputeViewAlignedSlices(box, {}, { 0, 0, 0 }, 0, 0.1, 0, SliceOrder::FrontToBack)
                .depths.empty());
}

double FacesArea(const std::vector<Polygon>& faces)
{
  double sum = 0;
  for (const Polygon& face : faces)
  {
    sum += PolygonArea(face);
  }
  return sum;
}

TEST(Geometry, BoundaryFacesOfBox)
{
  const Box box{ { -1, 2, 0.5 }, { 2, 3.5, 4 } };
  const std::vector<Polygon> faces = ComputeRegionBoundaryFaces(box, {});
  ASSERT_EQ(faces.size(), 6u);
  const Vec3 size = box.upper - box.lower;
  EXPECT_NEAR(FacesArea(faces), 2 * (size.x * size.y + size.y * size.z + size.z * size.x), 1e-12);
  const Vec3 center = 0.5 * (box.lower + box.upper);
  for (const Polygon& face : faces)
  {
    EXPECT_EQ(face.size(), 4u);
    const Vec3 centroid = 0.25 * (face[0] + face[1] + face[2] + face[3]);
    ExpectConvexAround(face, centroid - center); // wound counterclockwise seen from outside
  }
}

TEST(Geometry, BoundaryFacesWithClipPlanes)
{
  std::mt19937 random(3);
  const Box cube{ { 0, 0, 0 }, { 1, 1, 1 } };
  for (int trial = 0; trial < 20; ++trial)
  {
    std::vector<HalfSpace> clip = { RandomHalfSpace(random, cube) };
    if (trial >= 10)
    {
      clip.push_back(RandomHalfSpace(random, cube));
    }
    const std::vector<Polygon> faces = ComputeRegionBoundaryFaces(cube, clip);
    // Brute force: each cube face and each clip plane section measured on a fine grid.
    double expected = 0;
    const Vec3 axes[3] = { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } };
    for (int axis = 0; axis < 3; ++axis)
    {
      for (double value : { 0.0, 1.0 })
      {
        double cell = 0;
        expected += GridSectionArea(axes[axis], value, cube, clip, 400, cell);
      }
    }
    for (std::size_t a = 0; a < clip.size(); ++a)
    {
      std::vector<HalfSpace> others = clip;
      others.erase(others.begin() + a);
      double cell = 0;
      expected += GridSectionArea(clip[a].normal, -clip[a].offset, cube, others, 400, cell);
    }
    EXPECT_NEAR(FacesArea(faces), expected, std::max(0.01 * expected, 0.01)) << "trial " << trial;
    // Closed and outward: area-weighted normals cancel; the divergence theorem gives the volume.
    Vec3 normalSum;
    double volume = 0;
    for (const Polygon& face : faces)
    {
      const Vec3 normal = PolygonNormal(face);
      normalSum = normalSum + PolygonArea(face) * normal;
      volume += PolygonArea(face) * Dot(face[0], normal) / 3;
      for (const Vec3& v : face)
      {
        EXPECT_TRUE(Inside(v, cube, clip, OnPlaneTolerance));
      }
    }
    EXPECT_LT(Length(normalSum), 1e-9);
    int inside = 0;
    constexpr int Samples = 200000;
    for (int s = 0; s < Samples; ++s)
    {
      inside += Inside(RandomPoint(random, cube), cube, clip, 0) ? 1 : 0;
    }
    EXPECT_NEAR(volume, static_cast<double>(inside) / Samples, 0.01);
  }
}

TEST(Geometry, CoincidentClipPlaneAddsNoDuplicateFace)
{
  const Box cube{ { 0, 0, 0 }, { 1, 1, 1 } };
  const std::vector<Polygon> faces =
    ComputeRegionBoundaryFaces(cube, { { { 1, 0, 0 }, 0 }, { { 2, 0, 0 }, 0 } });
  EXPECT_EQ(faces.size(), 6u);
  EXPECT_NEAR(FacesArea(faces), 6, 1e-12);
  // A clip plane removing everything leaves no faces.
  EXPECT_TRUE(ComputeRegionBoundaryFaces(cube, { { { 1, 0, 0 }, -2 } }).empty());
}

TEST(Geometry, FlatBoxes)
{
  // A 1 x 7 x 300 volume: its index box has no thickness along x.
  const Box flat{ { 0, 0, 0 }, { 0, 6, 299 } };
  EXPECT_FALSE(flat.IsEmpty());
  const std::vector<Polygon> faces = ComputeRegionBoundaryFaces(flat, {});
  ASSERT_EQ(faces.size(), 2u); // the rectangle, once per winding
  EXPECT_NEAR(PolygonArea(faces[0]), 6 * 299, 1e-9);
  EXPECT_NEAR(Dot(PolygonNormal(faces[0]), PolygonNormal(faces[1])), -1, 1e-12);
  // No volume, hence no slices, from any direction.
  for (const Vec3& gradient : { Vec3{ 1, 0, 0 }, Vec3{ 0, 0, 1 }, Vec3{ 0.3, 0.5, 0.8 } })
  {
    EXPECT_TRUE(ComputeViewAlignedSlices(flat, {}, gradient, 0, 0.5, 0.25, SliceOrder::FrontToBack)
                  .polygons.empty());
  }
  // Rays cross it at a single parameter; rays inside its plane see its full chord.
  double t0 = 0, t1 = 0;
  ASSERT_TRUE(IntersectRayRegion({ -1, 3, 100 }, { 1, 0, 0 }, flat, {}, t0, t1));
  EXPECT_EQ(t0, 1);
  EXPECT_EQ(t1, 1);
  ASSERT_TRUE(IntersectRayRegion({ 0, 3, -1 }, { 0, 0, 1 }, flat, {}, t0, t1));
  EXPECT_DOUBLE_EQ(t1 - t0, 299);
  // Flat along two axes or a single point: no faces at all.
  EXPECT_TRUE(ComputeRegionBoundaryFaces({ { 0, 0, 0 }, { 0, 0, 5 } }, {}).empty());
  EXPECT_TRUE(ComputeRegionBoundaryFaces({ { 1, 1, 1 }, { 1, 1, 1 } }, {}).empty());
  EXPECT_TRUE(ComputeRegionBoundaryFaces({ { 1, 1, 1 }, { 0, 2, 2 } }, {}).empty());
}

bool VisibleByFlags(const Vec3& p, const double planes[6], int flags)
{
  const double coordinates[3] = { p.x, p.y, p.z };
  int bit = 0, scale = 1;
  for (int axis = 0; axis < 3; ++axis, scale *= 3)
  {
    const double low = std::min(planes[2 * axis], planes[2 * axis + 1]);
    const double high = std::max(planes[2 * axis], planes[2 * axis + 1]);
    bit += scale * (coordinates[axis] < low ? 0 : (coordinates[axis] > high ? 2 : 1));
  }
  return (flags >> bit) & 1;
}

double BoxVolume(const Box& box)
{
  const Vec3 size = box.upper - box.lower;
  return size.x * size.y * size.z;
}

// Random points are visible by the flags exactly when some box holds them; boxes do not overlap.
void ExpectCroppingMatches(
  const Box& volume, const double planes[6], int flags, std::mt19937& random)
{
  const std::vector<Box> boxes = CroppingRegionBoxes(volume, planes, flags);
  int visible = 0;
  constexpr int Samples = 20000;
  for (int s = 0; s < Samples; ++s)
  {
    const Vec3 p = RandomPoint(random, volume);
    const bool expected = VisibleByFlags(p, planes, flags);
    visible += expected ? 1 : 0;
    int holders = 0;
    for (const Box& box : boxes)
    {
      holders += Inside(p, box, {}, 0) ? 1 : 0;
    }
    EXPECT_EQ(holders, expected ? 1 : 0);
  }
  double total = 0;
  for (const Box& box : boxes)
  {
    EXPECT_FALSE(box.IsEmpty());
    total += BoxVolume(box);
  }
  EXPECT_NEAR(total / BoxVolume(volume), static_cast<double>(visible) / Samples, 0.02);
}

TEST(Geometry, CroppingRegionBoxes)
{
  std::mt19937 random(5);
  const Box volume{ { 0, 0, 0 }, { 10, 20, 30 } };
  const double planes[6] = { 2, 7, 5, 15, 10, 25 };
  constexpr int SubVolume = 0x0002000;
  constexpr int AllRegions = (1 << 27) - 1;
  std::vector<Box> boxes = CroppingRegionBoxes(volume, planes, SubVolume);
  ASSERT_EQ(boxes.size(), 1u);
  EXPECT_EQ(boxes[0].lower.x, 2);
  EXPECT_EQ(boxes[0].upper.z, 25);
  boxes = CroppingRegionBoxes(volume, planes, AllRegions);
  ASSERT_EQ(boxes.size(), 1u);
  EXPECT_EQ(BoxVolume(boxes[0]), BoxVolume(volume));
  EXPECT_TRUE(CroppingRegionBoxes(volume, planes, 0).empty());
  // Cross: the centre and its six face neighbours (VTK_CROP_CROSS = 0x0417410).
  constexpr int Cross = 0x0417410;
  boxes = CroppingRegionBoxes(volume, planes, Cross);
  EXPECT_EQ(boxes.size(), 5u); // a column through the centre plus four arms
  ExpectCroppingMatches(volume, planes, Cross, random);
  // Inverted planes behave as sorted ones.
  const double inverted[6] = { 7, 2, 15, 5, 25, 10 };
  ExpectCroppingMatches(volume, inverted, Cross, random);
  boxes = CroppingRegionBoxes(volume, inverted, SubVolume);
  ASSERT_EQ(boxes.size(), 1u);
  EXPECT_EQ(boxes[0].lower.y, 5);
  EXPECT_EQ(boxes[0].upper.y, 15);
  // Planes outside the volume are clamped: the outer regions vanish.
  const double outside[6] = { -5, 50, -1, 100, 30, -30 };
  boxes = CroppingRegionBoxes(volume, outside, SubVolume);
  ASSERT_EQ(boxes.size(), 1u);
  EXPECT_EQ(BoxVolume(boxes[0]), BoxVolume(volume));
  EXPECT_TRUE(CroppingRegionBoxes(volume, outside, AllRegions & ~SubVolume).empty());
  // Any mask.
  for (int trial = 0; trial < 30; ++trial)
  {
    const int flags = std::uniform_int_distribution<int>(0, AllRegions)(random);
    ExpectCroppingMatches(volume, planes, flags, random);
  }
}

TEST(Geometry, TriangleFan)
{
  Polygon pentagon;
  for (int n = 0; n < 5; ++n)
  {
    pentagon.push_back({ std::cos(n * 2 * Pi / 5), std::sin(n * 2 * Pi / 5), 1 });
  }
  std::vector<float> xyz = { 9 };
  AppendTriangleFan(pentagon, xyz);
  ASSERT_EQ(xyz.size(), 1u + 27u);
  double area = 0;
  for (std::size_t t = 1; t < xyz.size(); t += 9)
  {
    const Vec3 a{ xyz[t], xyz[t + 1], xyz[t + 2] }, b{ xyz[t + 3], xyz[t + 4], xyz[t + 5] },
      c{ xyz[t + 6], xyz[t + 7], xyz[t + 8] };
    EXPECT_GT(Cross(b - a, c - a).z, 0); // winding kept
    area += 0.5 * Length(Cross(b - a, c - a));
  }
  EXPECT_NEAR(area, PolygonArea(pentagon), 1e-6);
  AppendTriangleFan({ { 0, 0, 0 }, { 1, 0, 0 } }, xyz);
  EXPECT_EQ(xyz.size(), 28u);
}

TEST(Geometry, RayRegionMatchesBruteForce)
{
  std::mt19937 random(13);
  constexpr double Step = 1e-3;
  for (int trial = 0; trial < 60; ++trial)
  {
    const Box box = RandomBox(random);
    std::vector<HalfSpace> clip;
    for (int c = 0; c < trial % 3; ++c)
    {
      clip.push_back(RandomHalfSpace(random, box));
    }
    const Vec3 origin = RandomPoint(random, { { -10, -10, -10 }, { 10, 10, 10 } });
    // Aim near the box so that many rays hit.
    const Vec3 direction = Normalize(RandomPoint(random, box) + 0.5 * RandomUnit(random) - origin);
    double first = 1e300, last = -1e300;
    for (double t = -40; t <= 40; t += Step)
    {
      if (Inside(origin + t * direction, box, clip, 0))
      {
        first = std::min(first, t);
        last = std::max(last, t);
      }
    }
    double t0 = 0, t1 = 0;
    const bool hit = IntersectRayRegion(origin, direction, box, clip, t0, t1);
    if (first > last)
    {
      EXPECT_TRUE(!hit || t1 - t0 < Step) << "trial " << trial;
      continue;
    }
    ASSERT_TRUE(hit) << "trial " << trial;
    EXPECT_NEAR(t0, first, Step);
    EXPECT_NEAR(t1, last, Step);
  }
  double t0 = 0, t1 = 0;
  const Box cube{ { 0, 0, 0 }, { 1, 1, 1 } };
  EXPECT_FALSE(IntersectRayRegion({ 2, 0.5, 0.5 }, { 0, 1, 0 }, cube, {}, t0, t1));
  EXPECT_TRUE(IntersectRayRegion({ 0.5, 0.5, 0.5 }, { 0, 0, 0 }, cube, {}, t0, t1));
  EXPECT_TRUE(std::isinf(t0) && std::isinf(t1));
  EXPECT_FALSE(
    IntersectRayRegion({ 0.5, 0.5, 0.5 }, { 1, 0, 0 }, { { 1, 1, 1 }, { 0, 0, 0 } }, {}, t0, t1));
}

// The box's faces are narrowed with their dot products written out (IntersectRayRegion runs
// per ray): the same bits as the same faces passed as general half-spaces of a box that does
// not bound the ray, axis-parallel rays and rays starting on a face included.
TEST(Geometry, RayBoxFacesMatchTheirHalfSpacesExactly)
{
  std::mt19937 random(17);
  const Box everywhere{ { -1e30, -1e30, -1e30 }, { 1e30, 1e30, 1e30 } };
  int hits = 0;
  for (int trial = 0; trial < 2000; ++trial)
  {
    const Box box = RandomBox(random);
    Vec3 origin = RandomPoint(random, { { -10, -10, -10 }, { 10, 10, 10 } });
    Vec3 direction = Normalize(RandomPoint(random, box) + 0.3 * RandomUnit(random) - origin);
    if (trial % 5 == 1)
    {
      direction = { trial % 3 == 0 ? 1.0 : 0.0, trial % 3 == 1 ? -1.0 : 0.0,
        trial % 3 == 2 ? 1.0 : 0.0 };
    }
    if (trial % 7 == 2)
    {
      origin.x = box.lower.x; // on a face
    }
    double t0 = 0, t1 = 0, u0 = 0, u1 = 0;
    const bool hit = IntersectRayRegion(origin, direction, box, {}, t0, t1);
    const bool same = IntersectRayRegion(origin, direction, everywhere, BoxHalfSpaces(box), u0, u1);
    ASSERT_EQ(hit, same) << "trial " << trial;
    if (hit)
    {
      ++hits;
      EXPECT_EQ(t0, u0) << "trial " << trial;
      EXPECT_EQ(t1, u1) << "trial " << trial;
    }
  }
  EXPECT_GT(hits, 500);
}

} // namespace
