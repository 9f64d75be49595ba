// TestCellClassification: OpacityRange against the interpolated table and ClassifyCells
// against a per-cell brute force, over every scalar type.
#include "MinMaxOctreeTestSupport.h"
#include "RandomGeometry.h"
#include "skipping/CellClassification.h"
#include "skipping/OpacityRange.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <type_traits>
#include <vector>

namespace
{
using namespace accelvolume;

using accelvolume_test::ShuffledFor;
using accelvolume_test::ThreadedFor;
using accelvolume_test::Uniform;
using accelvolume_test::View;
using accelvolume_test::VoxelCount;

constexpr double Infinity = std::numeric_limits<double>::infinity();
constexpr double NotANumber = std::numeric_limits<double>::quiet_NaN();
// Dense sampling of the interpolated table over a value range.
constexpr int TransferSamples = 300;

// --- OpacityRange ---

struct Transfer
{
  std::vector<float> table;
  double rangeMin = 0, rangeMax = 1;
  float threshold = 0;
};

// Runs of zeros between random opacities (sometimes all zero or all opaque).
std::vector<float> RandomTable(std::mt19937& random)
{
  const std::size_t sizes[] = { 1, 2, 3, 17, 256 };
  std::vector<float> table(sizes[random() % 5]);
  const int mode = static_cast<int>(random() % 8);
  std::size_t i = 0;
  while (i < table.size())
  {
    const std::size_t run = 1 + random() % 12;
    const bool zero = mode == 0 || (mode != 1 && random() % 2 == 0);
    for (std::size_t r = 0; r < run && i < table.size(); ++r, ++i)
    {
      table[i] = zero ? 0.f : static_cast<float>(Uniform(random, 0.01, 1));
    }
  }
  return table;
}

// Opacity at table position p (clamped), linearly interpolated.
double Interpolate(const std::vector<float>& table, double p)
{
  if (table.size() == 1)
  {
    return table[0];
  }
  const double last = static_cast<double>(table.size() - 1);
  p = std::min(std::max(p, 0.0), last);
  const std::size_t i = std::min(static_cast<std::size_t>(p), table.size() - 2);
  const double f = p - static_cast<double>(i);
  return (1 - f) * table[i] + f * table[i + 1];
}

// Same arithmetic as MinMaxOctree::Classify, so the rule check is exact at table entries.
double Position(const Transfer& t, double v)
{
  return (v - t.rangeMin) * (static_cast<double>(t.table.size() - 1) / (t.rangeMax - t.rangeMin));
}

// The documented rule, written out case by case.
bool RuleMayBeOpaque(const Transfer& t, double low, double high)
{
  const std::size_t n = t.table.size();
  if (!(low <= high) || n == 0)
  {
    return false;
  }
  std::size_t first = 0, last = n - 1;
  if (n >= 2 && std::isfinite(t.rangeMax - t.rangeMin))
  {
    if (t.rangeMin == t.rangeMax) // below: entry 0, above: entry N-1, on it: all
    {
      first = low > t.rangeMin ? n - 1 : 0;
      last = high < t.rangeMin ? 0 : n - 1;
    }
    else
    {
      double a = Position(t, low), b = Position(t, high);
      if (a > b)
      {
        std::swap(a, b);
      }
      a = std::min(std::max(a, 0.0), static_cast<double>(n - 1));
      b = std::min(std::max(b, 0.0), static_cast<double>(n - 1));
      first = static_cast<std::size_t>(std::floor(a));
      last = static_cast<std::size_t>(std::ceil(b));
    }
  }
  for (std::size_t m = first; m <= last; ++m)
  {
    if (t.table[m] > t.threshold)
    {
      return true;
    }
  }
  return false;
}

Transfer RandomTransfer(std::mt19937& random)
{
  Transfer t;
  t.table = RandomTable(random);
  t.rangeMin = Uniform(random, -300, 100);
  t.rangeMax = Uniform(random, 0, 300);
  const int shape = static_cast<int>(random() % 10);
  if (shape == 0)
  {
    std::swap(t.rangeMin, t.rangeMax); // decreasing (or at least arbitrary) order
  }
  else if (shape == 1)
  {
    t.rangeMax = t.rangeMin; // step
  }
  else if (shape == 2)
  {
    t.rangeMin = std::round(t.rangeMin); // integer range: positions land on entries
    t.rangeMax = t.rangeMin + static_cast<double>(t.table.size() > 1 ? t.table.size() - 1 : 1);
  }
  t.threshold = random() % 2 ? 0.f : static_cast<float>(Uniform(random, 0, 0.5));
  return t;
}

// A query bound: inside or around the map's range, on a table position, or non-finite.
double RandomBound(std::mt19937& random, const Transfer& t)
{
  const double low = std::min(t.rangeMin, t.rangeMax), high = std::max(t.rangeMin, t.rangeMax);
  const double span = std::max(high - low, 1.0);
  switch (random() % 12)
  {
    case 0:
      return -Infinity;
    case 1:
      return Infinity;
    case 2:
      return t.rangeMin;
    case 3:
    {
      // Exactly on table position m (as the map computes it), when there is one.
      const double m = static_cast<double>(random() % std::max<std::size_t>(t.table.size(), 1));
      return t.table.size() > 1 ? t.rangeMin + m * (t.rangeMax - t.rangeMin) / (t.table.size() - 1)
                                : t.rangeMin;
    }
    default:
      return Uniform(random, low - 0.3 * span, high + 0.3 * span);
  }
}

TEST(OpacityRange, MatchesRuleAndInterpolation)
{
  std::mt19937 random(31);
  for (int trial = 0; trial < 400; ++trial)
  {
    const Transfer t = RandomTransfer(random);
    const OpacityRange range(t.table, t.rangeMin, t.rangeMax, t.threshold);
    std::vector<double> lows, highs;
    for (int q = 0; q < 200; ++q)
    {
      double low = RandomBound(random, t), high = RandomBound(random, t);
      if (q % 10 != 0 && low > high)
      {
        std::swap(low, high); // mostly proper ranges, some empty ones
      }
      if (q % 37 == 0)
      {
        low = NotANumber;
      }
      lows.push_back(low);
      highs.push_back(high);
      const bool opaque = range.MayBeOpaque(low, high);
      ASSERT_EQ(opaque, RuleMayBeOpaque(t, low, high))
        << "trial " << trial << " [" << low << ", " << high << "]";
      const bool mapped = t.table.size() >= 2 && t.rangeMin != t.rangeMax;
      if (!mapped || !std::isfinite(low) || !std::isfinite(high) || !(low <= high))
      {
        continue;
      }
      // Visible somewhere => kept (sampling the function itself, not the rule).
      double sampled = 0;
      for (int s = 0; s <= TransferSamples; ++s)
      {
        const double v = low + (high - low) * s / TransferSamples;
        sampled = std::max(sampled, Interpolate(t.table, Position(t, v)));
      }
      if (sampled > t.threshold)
      {
        ASSERT_TRUE(opaque) << "visible range judged transparent, trial " << trial;
      }
      if (t.threshold == 0.f)
      {
        // Exact for threshold 0: the maximum over [a, b] is at the ends or an entry inside.
        double a = std::min(std::max(Position(t, low), 0.0), double(t.table.size() - 1));
        double b = std::min(std::max(Position(t, high), 0.0), double(t.table.size() - 1));
        if (a > b)
        {
          std::swap(a, b);
        }
        double exact = std::max(Interpolate(t.table, a), Interpolate(t.table, b));
        for (std::size_t m = 0; m < t.table.size(); ++m)
        {
          if (m > a && m < b)
          {
            exact = std::max(exact, static_cast<double>(t.table[m]));
          }
        }
        ASSERT_EQ(opaque, exact > 0) << "trial " << trial;
      }
    }
    // The batch call agrees with the single one.
    std::vector<std::uint8_t> batch(lows.size());
    range.MayBeOpaque(lows.data(), highs.data(), lows.size(), batch.data());
    for (std::size_t q = 0; q < lows.size(); ++q)
    {
      ASSERT_EQ(batch[q] != 0, range.MayBeOpaque(lows[q], highs[q])) << q;
    }
  }
}

TEST(OpacityRange, DegenerateTables)
{
  EXPECT_FALSE(OpacityRange({}, 0, 1).MayBeOpaque(-Infinity, Infinity));
  EXPECT_TRUE(OpacityRange({ 0.5f }, 0, 1).MayBeOpaque(7, 7)); // constant
  EXPECT_FALSE(OpacityRange({ 0.5f }, 0, 1, 0.6f).MayBeOpaque(7, 7));
  const OpacityRange step({ 0.f, 0.f, 1.f }, 5, 5);
  EXPECT_FALSE(step.MayBeOpaque(1, 4.5)); // below: entry 0
  EXPECT_TRUE(step.MayBeOpaque(5, 5));    // on it: the whole table
  EXPECT_TRUE(step.MayBeOpaque(6, 9));    // above: the last entry
  const OpacityRange unmapped({ 0.f, 1.f }, -Infinity, 3);
  EXPECT_TRUE(unmapped.MayBeOpaque(-10, -9)); // no usable map: the whole table
  EXPECT_FALSE(step.MayBeOpaque(3, 2));       // empty range
  EXPECT_FALSE(step.MayBeOpaque(NotANumber, 9));
  // A denormal range overflows the scale: conservative, and no undefined conversion.
  const OpacityRange tiny({ 0.f, 0.f, 1.f }, 0, 1e-320);
  EXPECT_TRUE(tiny.MayBeOpaque(0, 0));
}

// --- TransparentBelow ---

TEST(OpacityRange, TransparentBelow)
{
  std::mt19937 random(32);
  for (int trial = 0; trial < 2000; ++trial)
  {
    Transfer t = RandomTransfer(random);
    if (t.table.size() >= 2 && !(t.rangeMin < t.rangeMax))
    {
      continue; // decreasing maps and steps: below
    }
    const OpacityRange range(t.table, t.rangeMin, t.rangeMax, t.threshold);
    const double below = range.TransparentBelow();
    std::size_t firstOpaque = t.table.size();
    for (std::size_t m = 0; m < t.table.size() && firstOpaque == t.table.size(); ++m)
    {
      firstOpaque = t.table[m] > t.threshold ? m : firstOpaque;
    }
    if (firstOpaque == t.table.size())
    {
      ASSERT_EQ(below, Infinity) << trial;
      continue;
    }
    if (firstOpaque == 0)
    {
      ASSERT_EQ(below, -Infinity) << trial;
      continue;
    }
    ASSERT_TRUE(std::isfinite(below)) << trial;
    // Everything below is transparent, by the rule and by the interpolated table ...
    ASSERT_FALSE(range.MayBeOpaque(-Infinity, below)) << trial;
    for (int s = 0; s <= TransferSamples; ++s)
    {
      const double v = below - (below - t.rangeMin + 1) * s / TransferSamples;
      ASSERT_LE(Interpolate(t.table, Position(t, v)), t.threshold) << trial;
    }
    // ... it sits on the table position just before the first opaque entry ...
    ASSERT_NEAR(Position(t, below), static_cast<double>(firstOpaque - 1), 1e-9) << trial;
    ASSERT_GT(t.table[firstOpaque], t.threshold);
    // ... and it is the largest such value under the rule.
    ASSERT_TRUE(range.MayBeOpaque(-Infinity, std::nextafter(below, Infinity))) << trial;
  }
}

TEST(OpacityRange, TransparentBelowSpecialMaps)
{
  EXPECT_EQ(OpacityRange({}, 0, 1).TransparentBelow(), Infinity);
  EXPECT_EQ(OpacityRange({ 0.f, 0.f }, 0, 1).TransparentBelow(), Infinity);
  EXPECT_EQ(OpacityRange({ 0.5f }, 0, 1).TransparentBelow(), -Infinity); // constant opaque
  EXPECT_EQ(OpacityRange({ 0.f }, 0, 1).TransparentBelow(), Infinity);   // constant clear
  EXPECT_EQ(OpacityRange({ 0.f, 1.f }, 4, 4).TransparentBelow(), 4.0);   // step: entry 0 below
  EXPECT_EQ(OpacityRange({ 1.f, 0.f }, 4, 4).TransparentBelow(), -Infinity);
  EXPECT_EQ(OpacityRange({ 0.f, 1.f }, 9, 2).TransparentBelow(), -Infinity); // decreasing
  EXPECT_EQ(OpacityRange({ 0.f, 0.f }, 9, 2).TransparentBelow(), Infinity);
  // An 8-bit ramp: entries 0..9 transparent, 10 opaque -> values below 9 are clear.
  std::vector<float> ramp(256, 0.f);
  std::fill(ramp.begin() + 10, ramp.end(), 0.5f);
  EXPECT_EQ(OpacityRange(ramp, 0, 255).TransparentBelow(), 9.0);
}

// --- ClassifyCells ---

// The per-cell brute force of the header's definition.
template <typename T>
CellClassification BruteClassify(
  const std::vector<T>& volume, const int dims[3], const OpacityRange& opacity, double threshold)
{
  CellClassification result;
  for (int a = 0; a < 3; ++a)
  {
    result.cellDims[a] = std::max(dims[a] - 1, 1);
  }
  for (int k = 0; k < result.cellDims[2]; ++k)
  {
    for (int j = 0; j < result.cellDims[1]; ++j)
    {
      for (int i = 0; i < result.cellDims[0]; ++i)
      {
        int configuration = 0;
        double low = Infinity, high = -Infinity;
        for (int c = 0; c < 8; ++c)
        {
          const int x = std::min(i + (c & 1), dims[0] - 1);
          const int y = std::min(j + ((c >> 1) & 1), dims[1] - 1);
          const int z = std::min(k + ((c >> 2) & 1), dims[2] - 1);
          const double v =
            static_cast<double>(volume[(static_cast<std::size_t>(z) * dims[1] + y) * dims[0] + x]);
          if (std::isnan(v))
          {
            continue;
          }
          configuration |= v >= threshold ? 1 << c : 0;
          low = std::min(low, v);
          high = std::max(high, v);
        }
        result.configuration.push_back(static_cast<std::uint8_t>(configuration));
        result.nonEmpty.push_back(opacity.MayBeOpaque(low, high) ? 1 : 0);
      }
    }
  }
  return result;
}

// A value in [low, high] of type T (clamped to the type); floats are sometimes NaN or +-inf.
template <typename T>
T RandomScalar(std::mt19937& random, double low, double high)
{
  using Limits = std::numeric_limits<T>;
  if constexpr (std::is_floating_point<T>::value)
  {
    const int kind = static_cast<int>(random() % 40);
    return kind < 2 ? Limits::quiet_NaN()
                    : (kind == 2 ? (random() % 2 ? 1 : -1) * Limits::infinity()
                                 : static_cast<T>(Uniform(random, low, high)));
  }
  else
  {
    double lowest = std::max(std::ceil(low), double(Limits::lowest()));
    double highest = std::min(std::floor(high), double(Limits::max()));
    if (highest < lowest)
    {
      lowest = double(Limits::lowest()); // the range misses the type
      highest = double(Limits::max());
    }
    return static_cast<T>(std::uniform_int_distribution<std::int64_t>(
      static_cast<std::int64_t>(lowest), static_cast<std::int64_t>(highest))(random));
  }
}

template <typename T>
class ClassifyCellsTyped : public ::testing::Test
{
};
using ScalarTypes = ::testing::Types<std::int8_t, std::uint8_t, std::int16_t, std::uint16_t,
  std::int32_t, float, double>;
TYPED_TEST_SUITE(ClassifyCellsTyped, ScalarTypes);

TYPED_TEST(ClassifyCellsTyped, MatchesBruteForce)
{
  using T = TypeParam;
  std::mt19937 random(40 + 2 * sizeof(T) + (std::is_signed<T>::value ? 1 : 0) +
    (std::is_floating_point<T>::value ? 20 : 0));
  const int shapes[][3] = { { 1, 1, 1 }, { 2, 2, 2 }, { 1, 5, 7 }, { 6, 1, 4 }, { 9, 8, 1 },
    { 13, 11, 7 }, { 70, 3, 3 }, { 131, 2, 4 }, { 1, 1, 6 } };
  for (int trial = 0; trial < 90; ++trial)
  {
    const auto& dims = shapes[trial % (sizeof(shapes) / sizeof(shapes[0]))];
    // Data around the transfer function's range, sometimes over the type's whole range.
    Transfer t = RandomTransfer(random);
    double low = std::min(t.rangeMin, t.rangeMax) - 40;
    double high = std::max(t.rangeMin, t.rangeMax) + 40;
    if (std::is_integral<T>::value && random() % 4 == 0)
    {
      low = double(std::numeric_limits<T>::lowest());
      high = double(std::numeric_limits<T>::max());
    }
    std::vector<T> volume(VoxelCount(dims));
    for (std::size_t i = 0; i < volume.size(); ++i)
    {
      // Runs of equal values, so that many cells have narrow ranges, plus noise.
      volume[i] = i > 0 && random() % 3 == 0 ? volume[i - 1] : RandomScalar<T>(random, low, high);
    }
    const OpacityRange opacity(t.table, t.rangeMin, t.rangeMax, t.threshold);
    double threshold = opacity.TransparentBelow();
    const int pick = static_cast<int>(random() % 5);
    if (pick == 0 || pick == 1)
    {
      // Anywhere, or halfway between integers.
      threshold =
        pick == 0 ? Uniform(random, low, high) : std::floor(Uniform(random, low, high)) + 0.5;
    }
    else if (pick == 2)
    {
      threshold = random() % 3 == 0 ? NotANumber : (random() % 2 ? Infinity : -Infinity);
    }
    const CellClassification expected = BruteClassify(volume, dims, opacity, threshold);
    for (const ParallelFor& parallel :
      { ParallelFor(SerialFor), ThreadedFor(3), ShuffledFor(trial) })
    {
      const CellClassification actual =
        ClassifyCells(View(volume, dims), opacity, threshold, parallel);
      for (int a = 0; a < 3; ++a)
      {
        ASSERT_EQ(actual.cellDims[a], expected.cellDims[a]);
      }
      ASSERT_EQ(actual.configuration, expected.configuration)
        << "trial " << trial << " threshold " << threshold;
      ASSERT_EQ(actual.nonEmpty, expected.nonEmpty) << "trial " << trial;
    }
  }
}

TEST(ClassifyCells, SixteenBitTablesMatchTheRule)
{
  // The 16-bit path answers emptiness from per-value tables; stress it with fine tables (many
  // entries per value), coarse ones, fractional and decreasing ranges over the full range.
  std::mt19937 random(48);
  const int dims[3] = { 67, 5, 4 };
  std::vector<std::uint16_t> volume(VoxelCount(dims));
  for (int trial = 0; trial < 40; ++trial)
  {
    const double center = Uniform(random, 0, 65535);
    const double width = trial % 2 ? Uniform(random, 0.5, 20) : Uniform(random, 100, 70000);
    for (std::uint16_t& v : volume)
    {
      v = static_cast<std::uint16_t>(
        std::min(65535.0, std::max(0.0, std::floor(center + Uniform(random, -width, width)))));
    }
    std::vector<float> table = RandomTable(random);
    double rangeMin = center + Uniform(random, -width, width);
    double rangeMax = rangeMin + (trial % 3 ? 1 : -1) * Uniform(random, 0.3, 2 * width);
    const OpacityRange opacity(table, rangeMin, rangeMax);
    const CellClassification actual = ClassifyCells(View(volume, dims), opacity, center, SerialFor);
    ASSERT_EQ(actual.nonEmpty, BruteClassify(volume, dims, opacity, center).nonEmpty) << trial;
  }
}

TEST(ClassifyCells, ThresholdsBetweenRepresentableValues)
{
  // A threshold just above a voxel value must not count it as opaque, just below must; the
  // typed comparisons round the threshold, so check both sides of a float and of an integer.
  const int dims[3] = { 2, 1, 1 };
  const OpacityRange opacity({ 0.f, 1.f }, 0, 1);
  const std::vector<float> floats = { 0.1f, 1e30f };
  for (double v : { double(floats[0]), double(floats[1]) })
  {
    const std::uint8_t bit = v == double(floats[0]) ? 0x55 : 0xaa; // corners of x = 0 or 1
    EXPECT_EQ(ClassifyCells(View(floats, dims), opacity, std::nextafter(v, Infinity), SerialFor)
                .configuration[0] &
        bit,
      0);
    EXPECT_EQ(ClassifyCells(View(floats, dims), opacity, std::nextafter(v, -Infinity), SerialFor)
                .configuration[0] &
        bit,
      bit);
  }
  // Beyond float's range: only +inf passes 1e39, everything but -inf passes -1e39.
  const std::vector<float> extremes = { std::numeric_limits<float>::max(),
    std::numeric_limits<float>::infinity() };
  EXPECT_EQ(ClassifyCells(View(extremes, dims), opacity, 1e39, SerialFor).configuration[0], 0xaa);
  const std::vector<float> low = { -std::numeric_limits<float>::infinity(),
    -std::numeric_limits<float>::max() };
  EXPECT_EQ(ClassifyCells(View(low, dims), opacity, -1e39, SerialFor).configuration[0], 0xaa);
  const std::vector<std::int16_t> shorts = { 7, 8 };
  EXPECT_EQ(ClassifyCells(View(shorts, dims), opacity, 7.5, SerialFor).configuration[0], 0xaa);
  EXPECT_EQ(ClassifyCells(View(shorts, dims), opacity, 7.0, SerialFor).configuration[0], 0xff);
  EXPECT_EQ(ClassifyCells(View(shorts, dims), opacity, 8.0001, SerialFor).configuration[0], 0);
  EXPECT_EQ(ClassifyCells(View(shorts, dims), opacity, -1e300, SerialFor).configuration[0], 0xff);
}

TEST(ClassifyCells, ReusesTheResult)
{
  std::mt19937 random(49);
  const int small[3] = { 4, 3, 2 }, large[3] = { 70, 5, 3 };
  const OpacityRange opacity({ 0.f, 0.f, 1.f }, 0, 100);
  CellClassification result;
  for (const auto* dims : { small, large, large, small })
  {
    std::vector<std::int16_t> volume(VoxelCount(dims));
    for (std::int16_t& v : volume)
    {
      v = RandomScalar<std::int16_t>(random, -20, 120);
    }
    ClassifyCells(View(volume, dims), opacity, 50.0, ThreadedFor(2), result);
    const CellClassification expected = BruteClassify(volume, dims, opacity, 50.0);
    ASSERT_EQ(result.configuration, expected.configuration);
    ASSERT_EQ(result.nonEmpty, expected.nonEmpty);
    ASSERT_EQ(result.cellDims[0], expected.cellDims[0]);
  }
  ClassifyCells(VolumeView(), opacity, 50.0, SerialFor, result);
  EXPECT_TRUE(result.nonEmpty.empty());
  EXPECT_EQ(result.cellDims[0], 0);
}

TEST(ClassifyCells, AllNaNAndNoData)
{
  const int dims[3] = { 3, 4, 2 };
  const std::vector<float> volume(VoxelCount(dims), std::numeric_limits<float>::quiet_NaN());
  const OpacityRange everything({ 1.f }, 0, 1); // constant opaque
  const CellClassification cells = ClassifyCells(View(volume, dims), everything, 0.5, SerialFor);
  ASSERT_EQ(cells.nonEmpty.size(), 6u);
  for (std::size_t c = 0; c < cells.nonEmpty.size(); ++c)
  {
    EXPECT_EQ(cells.nonEmpty[c], 0); // NaN cells are empty, even under a constant opacity
    EXPECT_EQ(cells.configuration[c], 0);
  }
  VolumeView none;
  const CellClassification empty = ClassifyCells(none, everything, 0.5, SerialFor);
  EXPECT_TRUE(empty.configuration.empty());
  EXPECT_TRUE(empty.nonEmpty.empty());
}

}
