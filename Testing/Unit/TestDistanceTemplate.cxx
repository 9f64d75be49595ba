// TestDistanceTemplate: the distance template's step counts never leave the box and are close
// to the exact count.
#include "RandomGeometry.h"
#include "skipping/DistanceTemplate.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

namespace
{
using namespace accelvolume;

using accelvolume_test::Uniform;

// Samples checked one by one; past this, the last sample stands for the rest (coordinates are
// monotone in j, also in floating point).
constexpr std::int64_t CheckedSamples = 20000;
constexpr std::int64_t StepCap = std::int64_t(1) << 30;

double& At(Vec3& v, int axis)
{
  return axis == 0 ? v.x : (axis == 1 ? v.y : v.z);
}

double At(const Vec3& v, int axis)
{
  return axis == 0 ? v.x : (axis == 1 ? v.y : v.z);
}

bool Inside(const Box& box, const Vec3& p)
{
  for (int a = 0; a < 3; ++a)
  {
    if (!(At(p, a) >= At(box.lower, a) && At(p, a) <= At(box.upper, a)))
    {
      return false;
    }
  }
  return true;
}

// position + j * step, evaluated directly as the contract states.
Vec3 Sample(const Vec3& position, const Vec3& step, std::int64_t j)
{
  return position + static_cast<double>(j) * step;
}

// Every sample 1..count lies in the box.
::testing::AssertionResult AllInside(
  const Box& box, const Vec3& position, const Vec3& step, std::int64_t count)
{
  const std::int64_t checked = std::min(count, CheckedSamples);
  for (std::int64_t j = 1; j <= checked; ++j)
  {
    if (!Inside(box, Sample(position, step, j)))
    {
      return ::testing::AssertionFailure() << "sample " << j << " of " << count << " outside";
    }
  }
  if (count > checked && !Inside(box, Sample(position, step, count)))
  {
    return ::testing::AssertionFailure() << "last sample " << count << " outside";
  }
  return ::testing::AssertionSuccess();
}

// min over moving axes of floor(m_a / |s_a|), in double; -1 when no axis moves.
std::int64_t ExactCount(const Box& box, const Vec3& position, const Vec3& step)
{
  std::int64_t result = -1;
  for (int a = 0; a < 3; ++a)
  {
    const double s = At(step, a);
    if (s == 0)
    {
      continue;
    }
    const double m =
      s > 0 ? At(box.upper, a) - At(position, a) : At(position, a) - At(box.lower, a);
    const std::int64_t count = static_cast<std::int64_t>(std::floor(m / std::fabs(s)));
    result = result < 0 ? count : std::min(result, count);
  }
  return result;
}

// A random step component: zero sometimes, else a log-uniform magnitude in [0.02, 3].
double RandomStep(std::mt19937& random)
{
  if (random() % 5 == 0)
  {
    return 0.0;
  }
  const double magnitude = std::exp(Uniform(random, std::log(0.02), std::log(3.0)));
  return random() % 2 ? magnitude : -magnitude;
}

struct Trial
{
  Box box;
  Vec3 position, step;
  double maximumStep[3];
  int maximumDistance = 1;
};

// Random box (some axes flat), a position inside (some coordinates on a face), mixed steps.
Trial RandomTrial(std::mt19937& random, double offset, bool exactMaximum)
{
  Trial t;
  double largest = 0;
  for (int a = 0; a < 3; ++a)
  {
    const double lower = offset + Uniform(random, -100, 100);
    const double extent = random() % 10 == 0 ? 0.0 : Uniform(random, 0, 40);
    At(t.box.lower, a) = lower;
    At(t.box.upper, a) = lower + extent;
    largest = std::max(largest, extent);
    const int where = static_cast<int>(random() % 6);
    At(t.position, a) =
      where == 0 ? lower : (where == 1 ? lower + extent : lower + Uniform(random, 0, extent));
    At(t.step, a) = RandomStep(random);
    const double size = std::fabs(At(t.step, a));
    t.maximumStep[a] = exactMaximum ? size : size * Uniform(random, 1, 2);
    if (size == 0 && random() % 2)
    {
      t.maximumStep[a] = Uniform(random, 0, 2); // a tile whose other rays move along a
    }
  }
  t.maximumDistance =
    std::max(1, static_cast<int>(std::ceil(largest)) + static_cast<int>(random() % 3));
  return t;
}

TEST(DistanceTemplate, NeverOverestimates)
{
  std::mt19937 random(21);
  for (int i = 0; i < 20000; ++i)
  {
    Trial t = RandomTrial(random, 0.0, i % 2 == 0);
    if (i % 7 == 0)
    {
      t.maximumDistance = 1 + static_cast<int>(random() % 4); // template smaller than the box
    }
    DistanceTemplate distance;
    distance.Build(t.maximumStep, t.maximumDistance);
    ASSERT_EQ(distance.GetMaximumDistance(), t.maximumDistance);
    const std::int64_t count = distance.StepsInside(t.box, t.position, t.step);
    ASSERT_GE(count, 0);
    if (ExactCount(t.box, t.position, t.step) >= 0)
    {
      ASSERT_TRUE(AllInside(t.box, t.position, t.step, count)) << "trial " << i;
    }
  }
}

TEST(DistanceTemplate, CloseToExactWhenStepIsTheMaximum)
{
  std::mt19937 random(22);
  for (int i = 0; i < 20000; ++i)
  {
    const Trial t = RandomTrial(random, 0.0, true);
    DistanceTemplate distance;
    distance.Build(t.maximumStep, t.maximumDistance);
    const std::int64_t count = distance.StepsInside(t.box, t.position, t.step);
    const std::int64_t exact = ExactCount(t.box, t.position, t.step);
    if (exact < 0)
    {
      continue;
    }
    // The whole-cell lookup loses less than one cell of distance per axis: at most
    // floor(1 / |s|) + 1 samples, one sample for steps longer than a cell.
    std::int64_t allowed = 0;
    for (int a = 0; a < 3; ++a)
    {
      const double s = std::fabs(At(t.step, a));
      if (s > 0)
      {
        allowed = std::max(allowed, static_cast<std::int64_t>(std::floor(1.0 / s)) + 1);
      }
    }
    ASSERT_LE(count, exact) << "trial " << i;
    ASSERT_GE(count, exact - allowed) << "trial " << i;
  }
}

TEST(DistanceTemplate, LongStepsLoseAtMostOneSample)
{
  std::mt19937 random(23);
  for (int i = 0; i < 5000; ++i)
  {
    Trial t = RandomTrial(random, 0.0, true);
    for (int a = 0; a < 3; ++a)
    {
      // Steps of more than a cell (a little above 1, so that rounding cannot matter).
      const double size = Uniform(random, 1.001, 3);
      At(t.step, a) = random() % 2 ? size : -size;
      t.maximumStep[a] = size;
    }
    DistanceTemplate distance;
    distance.Build(t.maximumStep, t.maximumDistance);
    const std::int64_t count = distance.StepsInside(t.box, t.position, t.step);
    const std::int64_t exact = ExactCount(t.box, t.position, t.step);
    ASSERT_LE(count, exact);
    ASSERT_GE(count, exact - 1) << "trial " << i;
  }
}

TEST(DistanceTemplate, LargeCoordinatesAndInexactSteps)
{
  std::mt19937 random(24);
  for (int i = 0; i < 5000; ++i)
  {
    Trial t = RandomTrial(random, 1e6, i % 2 == 0);
    for (int a = 0; a < 3 && i % 3 == 0; ++a)
    {
      // Decimal steps that binary cannot hold, from positions on the entry face.
      const double steps[] = { 0.1, 0.3, 0.7, 1.1 };
      const double s = steps[random() % 4];
      At(t.step, a) = random() % 2 ? s : -s;
      At(t.position, a) = At(t.step, a) > 0 ? At(t.box.lower, a) : At(t.box.upper, a);
      t.maximumStep[a] = s;
    }
    DistanceTemplate distance;
    distance.Build(t.maximumStep, t.maximumDistance);
    const std::int64_t count = distance.StepsInside(t.box, t.position, t.step);
    if (ExactCount(t.box, t.position, t.step) >= 0)
    {
      ASSERT_TRUE(AllInside(t.box, t.position, t.step, count)) << "trial " << i;
    }
  }
}

TEST(DistanceTemplate, ExactCountsOnAUnitGrid)
{
  // From the lower corner of [0, 10]^3 along +x: floor(9 / s) samples (the lookup uses the
  // whole cells below the safety margin, 9 of the 10), each still inside.
  const Box box{ { 0, 0, 0 }, { 10, 10, 10 } };
  for (double s : { 0.25, 0.5, 1.0, 2.0, 3.0, 0.1, 1.0 / 3.0 })
  {
    const double maximumStep[3] = { s, s, s };
    DistanceTemplate distance;
    distance.Build(maximumStep, 10);
    const Vec3 step{ s, 0, 0 };
    const std::int64_t count = distance.StepsInside(box, { 0, 5, 5 }, step);
    EXPECT_LE(static_cast<double>(count) * s, 9.0) << s;
    EXPECT_GE(count, static_cast<std::int64_t>(9.0 / s) - 1) << s;
    EXPECT_TRUE(AllInside(box, { 0, 5, 5 }, step, count));
    // From a fractional position the same whole-cell lookup applies: m = 9.5 -> 9 cells.
    EXPECT_EQ(distance.StepsInside(box, { 0.5, 5, 5 }, step), count) << s;
  }
}

TEST(DistanceTemplate, ZeroStepsSaturate)
{
  const Box box{ { 0, 0, 0 }, { 4, 4, 4 } };
  const Vec3 still{ 0, 0, 0 };
  DistanceTemplate distance;
  const double steps[3] = { 0.5, 1.0, 2.0 };
  distance.Build(steps, 10);
  // No axis moves: the largest entry, floor(10 / 0.5).
  EXPECT_EQ(distance.StepsInside(box, { 1, 2, 3 }, still), 20);
  const double none[3] = { 0, 0, 0 };
  distance.Build(none, 10);
  EXPECT_EQ(distance.StepsInside(box, { 1, 2, 3 }, still), StepCap);
  // Axes with step 0 impose no limit, even when the template's maximum there is larger.
  distance.Build(steps, 10);
  EXPECT_EQ(distance.StepsInside(box, { 0, 2, 3 }, { 0.5, 0, 0 }), 6); // floor(3 / 0.5)
}

TEST(DistanceTemplate, StepsLargerThanTheMaximumFallBackToExact)
{
  std::mt19937 random(25);
  for (int i = 0; i < 5000; ++i)
  {
    Trial t = RandomTrial(random, 0.0, true);
    for (double& m : t.maximumStep)
    {
      m *= Uniform(random, 0.1, 0.99); // the caller broke the contract
    }
    DistanceTemplate distance;
    distance.Build(t.maximumStep, t.maximumDistance);
    const std::int64_t count = distance.StepsInside(t.box, t.position, t.step);
    const std::int64_t exact = ExactCount(t.box, t.position, t.step);
    if (exact >= 0)
    {
      ASSERT_TRUE(AllInside(t.box, t.position, t.step, count)) << "trial " << i;
      ASSERT_GE(count, exact - 1) << "trial " << i; // no table rounding on exact division
    }
  }
}

TEST(DistanceTemplate, DegenerateInputs)
{
  const Box box{ { 0, 0, 0 }, { 4, 4, 4 } };
  const double steps[3] = { 1, 1, 1 };
  DistanceTemplate distance;
  // Unbuilt: exact division, and the cap when nothing moves.
  EXPECT_EQ(distance.StepsInside(box, { 1, 1, 1 }, { 1, 0.5, 0 }), 2);
  EXPECT_EQ(distance.StepsInside(box, { 1, 1, 1 }, { 0, 0, 0 }), StepCap);
  distance.Build(steps, 4);
  // Outside the box, or a NaN / infinite step: nothing is certain.
  EXPECT_EQ(distance.StepsInside(box, { -0.5, 1, 1 }, { 1, 0, 0 }), 0);
  EXPECT_EQ(distance.StepsInside(box, { 1, 1, 4.5 }, { 1, 0, 0 }), 0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(distance.StepsInside(box, { 1, 1, 1 }, { nan, 0, 0 }), 0);
  EXPECT_EQ(distance.StepsInside(box, { 1, 1, 1 }, { 0, -inf, 0 }), 0);
  EXPECT_EQ(distance.StepsInside(box, { nan, 1, 1 }, { 1, 0, 0 }), 0);
  // On the exit face: no sample left.
  EXPECT_EQ(distance.StepsInside(box, { 4, 1, 1 }, { 1, 0, 0 }), 0);
  // A flat box: only steps along its other axes.
  const Box flat{ { 0, 0, 2 }, { 4, 4, 2 } };
  EXPECT_EQ(distance.StepsInside(flat, { 0, 0, 2 }, { 1, 1, 0 }), 3);
  EXPECT_EQ(distance.StepsInside(flat, { 0, 0, 2 }, { 1, 1, 0.5 }), 0);
}

}
