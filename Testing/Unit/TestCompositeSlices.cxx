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
