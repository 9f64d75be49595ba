// CompositeSlices: ordering and exact culling of composite slices by non-empty boxes.
#include "RandomGeometry.h"
#include "slicing/CompositeSlices.h"

#include <gtest/gtest.h>

#include <random>

namespace
{
using namespace accelvolume;
using accelvolume_test::RandomBox;
using accelvolume_test::RandomPoint;
using accelvolume_test::RandomUnit;

// Whether a point of a slice plane lies in the (convex, ordered) polygon.
bool InsidePolygon(const Polygon& polygon, const Vec3& normal, const Vec3& p)
{
  if (polygon.size() < 3)
  {
    return false;
  }
  double sign = 0;
  for (size_t i = 0; i < polygon.size(); ++i)
  {
    const Vec3& a = polygon[i];
    const Vec3& b = polygon[(i + 1) % polygon.size()];
    const double side = Dot(Cross(b - a, p - a), normal);
    if (std::fabs(side) < 1e-9)
    {
      continue;
    }
    if (sign == 0)
    {
      sign = side;
    }
    else if (side * sign < 0)
    {
      return false;
    }
  }
  return true;
}
}

TEST(CompositeSlices, OrderedFrontToBackAndBack)
{
  Box region;
  region.upper = { 10, 8, 6 };
  const Vec3 gradient = Normalize({ 0.3, -0.5, 0.8 });
  const auto front = ComputeCompositeSlices({ region }, {}, gradient, 2.0, 0.7, 0.0, true, nullptr);
  const auto back = ComputeCompositeSlices({ region }, {}, gradient, 2.0, 0.7, 0.0, false, nullptr);
  ASSERT_GT(front.slices.size(), 5u);
  ASSERT_EQ(front.slices.size(), back.slices.size());
  for (size_t k = 1; k < front.slices.size(); ++k)
  {
    EXPECT_LT(front.slices[k - 1].first, front.slices[k].first);
    EXPECT_GT(back.slices[k - 1].first, back.slices[k].first);
  }
  EXPECT_DOUBLE_EQ(front.keptAreaFraction, 1.0);
}

TEST(CompositeSlices, CullingKeepsEveryNonEmptyPoint)
{
  std::mt19937 random(11);
  for (int trial = 0; trial < 30; ++trial)
  {
    Box region;
    region.upper = { 20, 16, 12 };
    std::vector<Box> nonEmpty;
    for (int b = 0; b < 3; ++b)
    {
      Box box = RandomBox(random);
      box.lower = box.lower + Vec3{ 10, 8, 6 };
      box.upper = box.upper + Vec3{ 10, 8, 6 };
      nonEmpty.push_back(box);
    }
    const Vec3 gradient = RandomUnit(random);
    const auto culled =
      ComputeCompositeSlices({ region }, {}, gradient, 0.0, 0.5, 0.1, true, &nonEmpty);
    EXPECT_LT(culled.keptAreaFraction, 1.0);
    // Points of the non-empty boxes on a slice plane must stay covered by that slice.
    for (const auto& slice : culled.slices)
    {
      for (int n = 0; n < 40; ++n)
      {
        const Box& box = nonEmpty[n % nonEmpty.size()];
        Vec3 p = RandomPoint(random, box);
        p = p + (slice.first - Dot(gradient, p)) * gradient; // onto the plane
        const bool inBox = p.x >= box.lower.x && p.x <= box.upper.x && p.y >= box.lower.y &&
          p.y <= box.upper.y && p.z >= box.lower.z && p.z <= box.upper.z;
        const bool inRegion =
          p.x >= 0 && p.x <= 20 && p.y >= 0 && p.y <= 16 && p.z >= 0 && p.z <= 12;
        if (inBox && inRegion)
        {
          EXPECT_TRUE(InsidePolygon(slice.second, gradient, p));
        }
      }
    }
  }
}

namespace
{
// The slow definition SliceBoundsTable replaces: every box tested at the slice's depth.
Box BruteForceBounds(
  const std::vector<Box>& boxes, const Vec3& gradient, double offset, double depth)
{
  Box bounds;
  bounds.lower = { 1e300, 1e300, 1e300 };
  bounds.upper = { -1e300, -1e300, -1e300 };
  for (Box box : boxes)
  {
    for (auto axis : { std::make_pair(&box.lower.x, &box.upper.x),
           std::make_pair(&box.lower.y, &box.upper.y), std::make_pair(&box.lower.z, &box.upper.z) })
    {
      if (*axis.first == *axis.second)
      {
        *axis.first -= 0.5;
        *axis.second += 0.5;
      }
    }
    double low = 1e300;
    double high = -1e300;
    for (int corner = 0; corner < 8; ++corner)
    {
      const Vec3 p{ corner & 1 ? box.upper.x : box.lower.x, corner & 2 ? box.upper.y : box.lower.y,
        corner & 4 ? box.upper.z : box.lower.z };
      low = std::min(low, Dot(gradient, p) + offset);
      high = std::max(high, Dot(gradient, p) + offset);
    }
    if (low <= depth && depth <= high)
    {
      bounds.lower = { std::min(bounds.lower.x, box.lower.x), std::min(bounds.lower.y, box.lower.y),
        std::min(bounds.lower.z, box.lower.z) };
      bounds.upper = { std::max(bounds.upper.x, box.upper.x), std::max(bounds.upper.y, box.upper.y),
        std::max(bounds.upper.z, box.upper.z) };
    }
  }
  return bounds;
}
}

TEST(CompositeSlices, BoundsTableEqualsEveryBoxTested)
{
  std::mt19937 random(5);
  for (int trial = 0; trial < 40; ++trial)
  {
    std::vector<Box> boxes;
    for (int b = 0; b < 12; ++b)
    {
      Box box = RandomBox(random);
      if (b % 4 == 0)
      {
        box.upper.z = box.lower.z; // flat, as an octree box of a one-voxel axis
      }
      boxes.push_back(box);
    }
    const Vec3 gradient = RandomUnit(random);
    const double offset = 3.25 * (trial % 3) - 2.0;
    const double spacing = 0.25 + 0.1 * (trial % 5);
    const double phase = 0.37 * (trial % 7) - 1.0;
    const SliceBoundsTable table(boxes, gradient, offset, spacing, phase);
    for (long long k = -200; k <= 200; ++k)
    {
      const Box expected =
        BruteForceBounds(boxes, gradient, offset, phase + static_cast<double>(k) * spacing);
      const Box actual = table.At(k);
      ASSERT_EQ(expected.IsEmpty(), actual.IsEmpty()) << "k " << k;
      if (!expected.IsEmpty())
      {
        EXPECT_EQ(expected.lower.x, actual.lower.x);
        EXPECT_EQ(expected.lower.y, actual.lower.y);
        EXPECT_EQ(expected.lower.z, actual.lower.z);
        EXPECT_EQ(expected.upper.x, actual.upper.x);
        EXPECT_EQ(expected.upper.y, actual.upper.y);
        EXPECT_EQ(expected.upper.z, actual.upper.z);
      }
    }
  }
}

// The GPU-generated slices (a plane's section of a box) are the CPU polygons: same depths in
// the same order, the same area (the CPU path drops slivers only).
TEST(CompositeSlices, SliceBoxesAreTheClippedPolygons)
{
  std::mt19937 random(23);
  Box region;
  region.upper = { 20, 16, 12 };
  for (int trial = 0; trial < 30; ++trial)
  {
    std::vector<Box> nonEmpty;
    for (int b = 0; b < 4; ++b)
    {
      Box box = RandomBox(random);
      box.lower = box.lower + Vec3{ 10, 8, 6 };
      box.upper = box.upper + Vec3{ 10, 8, 6 };
      nonEmpty.push_back(box);
    }
    const Vec3 gradient = RandomUnit(random);
    const bool frontToBack = trial % 2 == 0;
    const std::vector<Box>* culling = trial % 3 == 0 ? nullptr : &nonEmpty;
    const CompositeSlices cpu =
      ComputeCompositeSlices({ region }, {}, gradient, 1.5, 0.5, 0.1, frontToBack, culling);
    const std::vector<SliceBox> gpu =
      ComputeSliceBoxes(region, gradient, 1.5, 0.5, 0.1, frontToBack, culling);
    size_t g = 0;
    double cpuArea = 0;
    double gpuArea = 0;
    for (const auto& slice : cpu.slices)
    {
      // GPU slices the CPU dropped as slivers (or empty sections) come in between.
      while (g < gpu.size() && gpu[g].depth != slice.first)
      {
        EXPECT_LT(PlaneBoxSectionArea(gradient, 1.5, gpu[g].depth, gpu[g].box), 1e-6);
        ++g;
      }
      ASSERT_LT(g, gpu.size());
      const double area = PlaneBoxSectionArea(gradient, 1.5, gpu[g].depth, gpu[g].box);
      EXPECT_NEAR(area, PolygonArea(slice.second), 1e-9 * (1 + area));
      cpuArea += PolygonArea(slice.second);
      gpuArea += area;
      ++g;
    }
    EXPECT_NEAR(cpuArea, gpuArea, 1e-6 * (1 + cpuArea));
    // Every generated slice has a section; only slivers separate the two counts.
    for (; g < gpu.size(); ++g)
    {
      EXPECT_LT(PlaneBoxSectionArea(gradient, 1.5, gpu[g].depth, gpu[g].box), 1e-6);
    }
    size_t withSection = 0;
    for (const SliceBox& slice : gpu)
    {
      withSection += PlaneBoxSectionArea(gradient, 1.5, slice.depth, slice.box) > 1e-6 ? 1 : 0;
    }
    EXPECT_EQ(withSection, cpu.slices.size());
  }
}
