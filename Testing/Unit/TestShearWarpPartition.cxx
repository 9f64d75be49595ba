// ShearWarpPartition: balanced scanline bands (bounds well formed, no band over its share by more
// than one scanline's cost), equal bands, cost resampling and the imbalance measure.
#include "shearwarp/ShearWarpPartition.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <string>
#include <vector>

using namespace accelvolume;

namespace
{

// parts + 1 non-decreasing bounds from 0 to count.
void ExpectWellFormed(const std::vector<int>& bounds, int count, int parts)
{
  ASSERT_EQ(bounds.size(), static_cast<std::size_t>(parts) + 1);
  EXPECT_EQ(bounds.front(), 0);
  EXPECT_EQ(bounds.back(), count);
  for (std::size_t b = 1; b < bounds.size(); ++b)
  {
    EXPECT_LE(bounds[b - 1], bounds[b]) << "bound " << b;
  }
}

std::vector<double> BandCosts(const std::vector<double>& cost, const std::vector<int>& bounds)
{
  std::vector<double> bands;
  for (std::size_t b = 0; b + 1 < bounds.size(); ++b)
  {
    double sum = 0;
    for (int v = bounds[b]; v < bounds[b + 1]; ++v)
    {
      sum += cost[v] > 0 ? cost[v] : 0.0;
    }
    bands.push_back(sum);
  }
  return bands;
}

} // namespace

TEST(ShearWarpPartition, BalancedBandsStayWithinOneScanlineOfTheirShare)
{
  std::mt19937 random(12);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 500; ++trial)
  {
    const int count = static_cast<int>(random() % 300);
    const int parts = 1 + static_cast<int>(random() % 17);
    std::vector<double> cost(count);
    const int shape = trial % 4;
    for (int v = 0; v < count; ++v)
    {
      switch (shape)
      {
        case 0:
          cost[v] = unit(random);
          break; // noise
        case 1:
          cost[v] = std::exp(8 * unit(random));
          break; // heavy tail
        case 2:
          cost[v] = v > count / 3 && v < count / 2 ? 10 * unit(random) : 0.0;
          break; // one lump
        default:
          cost[v] = unit(random) < 0.1 ? 100.0 : 0.01;
          break; // spikes
      }
    }
    const std::vector<int> bounds = BalanceBands(cost, parts);
    SCOPED_TRACE("trial " + std::to_string(trial) + " count " + std::to_string(count) + " parts " +
      std::to_string(parts));
    ExpectWellFormed(bounds, count, parts);
    if (count == 0)
    {
      continue;
    }
    const double total = std::accumulate(cost.begin(), cost.end(), 0.0);
    const double largest = *std::max_element(cost.begin(), cost.end());
    for (double band : BandCosts(cost, bounds))
    {
      EXPECT_LE(band, total / parts + largest + 1e-9 * total);
    }
  }
}

TEST(ShearWarpPartition, EqualCostsGiveEqualBands)
{
  for (int count : { 1, 2, 7, 64, 100, 333 })
  {
    for (int parts : { 1, 2, 3, 5, 8, 13 })
    {
      for (double c : { 1.0, 0.37, 1e6 })
      {
        const std::vector<int> bounds = BalanceBands(std::vector<double>(count, c), parts);
        ExpectWellFormed(bounds, count, parts);
        int smallest = count, largest = 0;
        for (int b = 0; b < parts; ++b)
        {
          smallest = std::min(smallest, bounds[b + 1] - bounds[b]);
          largest = std::max(largest, bounds[b + 1] - bounds[b]);
        }
        EXPECT_LE(largest - smallest, 1) << count << " scanlines, " << parts << " parts";
      }
    }
  }
}

TEST(ShearWarpPartition, ZeroNegativeAndNaNCosts)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // All zero: equal bands.
  {
    const std::vector<int> bounds = BalanceBands(std::vector<double>(10, 0.0), 3);
    ExpectWellFormed(bounds, 10, 3);
    EXPECT_EQ(bounds, EqualBands(10, 3));
  }
  // Negative and NaN count as zero: the cost lies in scanlines 6..9 only.
  {
    std::vector<double> cost = { -5, nan, -1, nan, -100, nan, 1, 1, 1, 1 };
    const std::vector<int> bounds = BalanceBands(cost, 2);
    ExpectWellFormed(bounds, 10, 2);
    EXPECT_EQ(bounds[1], 8);
    cost.assign(10, nan);
    EXPECT_EQ(BalanceBands(cost, 4), EqualBands(10, 4));
    cost.assign(10, -1.0);
    EXPECT_EQ(BalanceBands(cost, 4), EqualBands(10, 4));
  }
  // Infinite cost: still well formed.
  {
    std::vector<double> cost(12, 1.0);
    cost[5] = std::numeric_limits<double>::infinity();
    ExpectWellFormed(BalanceBands(cost, 3), 12, 3);
  }
  // More parts than scanlines, and no scanlines at all.
  ExpectWellFormed(BalanceBands({ 1, 2, 3 }, 8), 3, 8);
  ExpectWellFormed(BalanceBands({}, 4), 0, 4);
  ExpectWellFormed(EqualBands(0, 4), 0, 4);
  // A single expensive scanline ends up alone in a band of its own share.
  const std::vector<int> bounds = BalanceBands({ 1, 1, 1, 1, 100, 1, 1, 1, 1 }, 3);
  ExpectWellFormed(bounds, 9, 3);
  for (double band : BandCosts({ 1, 1, 1, 1, 100, 1, 1, 1, 1 }, bounds))
  {
    EXPECT_LE(band, 108.0 / 3 + 100);
  }
}

TEST(ShearWarpPartition, EqualBandsDifferByAtMostOne)
{
  for (int count = 0; count < 200; count += 7)
  {
    for (int parts = 1; parts < 20; ++parts)
    {
      const std::vector<int> bounds = EqualBands(count, parts);
      ExpectWellFormed(bounds, count, parts);
      for (int b = 0; b < parts; ++b)
      {
        const int size = bounds[b + 1] - bounds[b];
        EXPECT_GE(size, count / parts);
        EXPECT_LE(size, (count + parts - 1) / parts);
      }
    }
  }
}

TEST(ShearWarpPartition, ResampledCostsKeepTheirTotalAndShape)
{
  std::mt19937 random(77);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 200; ++trial)
  {
    const int old = 1 + static_cast<int>(random() % 150);
    const int count = 1 + static_cast<int>(random() % 150);
    std::vector<double> cost(old);
    for (double& c : cost)
    {
      c = unit(random) < 0.3 ? 0.0 : unit(random);
    }
    const std::vector<double> resampled = ResampleCosts(cost, count);
    ASSERT_EQ(resampled.size(), static_cast<std::size_t>(count));
    const double total = std::accumulate(cost.begin(), cost.end(), 0.0);
    EXPECT_NEAR(std::accumulate(resampled.begin(), resampled.end(), 0.0), total, 1e-9 * (1 + total))
      << old << " -> " << count;
    for (double c : resampled)
    {
      EXPECT_GE(c, 0.0);
    }
    // The cost stays where it was: the first half of the old scanlines maps to the first half.
    if (old % 2 == 0 && count % 2 == 0)
    {
      const double half = std::accumulate(cost.begin(), cost.begin() + old / 2, 0.0);
      EXPECT_NEAR(std::accumulate(resampled.begin(), resampled.begin() + count / 2, 0.0), half,
        1e-9 * (1 + total));
    }
  }
  // Same count: unchanged; upsampling by 2 halves each cost.
  const std::vector<double> cost = { 1, 4, 0, 2 };
  const std::vector<double> same = ResampleCosts(cost, 4);
  for (int v = 0; v < 4; ++v)
  {
    EXPECT_NEAR(same[v], cost[v], 1e-12);
  }
  const std::vector<double> doubled = ResampleCosts(cost, 8);
  for (int v = 0; v < 8; ++v)
  {
    EXPECT_NEAR(doubled[v], cost[v / 2] / 2, 1e-12);
  }
  EXPECT_TRUE(ResampleCosts({}, 5) == std::vector<double>(5, 0.0));
  EXPECT_TRUE(ResampleCosts(cost, 0).empty());
}

TEST(ShearWarpPartition, Imbalance)
{
  EXPECT_DOUBLE_EQ(Imbalance({ 2, 2, 2, 2 }), 1.0);
  EXPECT_DOUBLE_EQ(Imbalance({ 1, 3 }), 1.5);
  EXPECT_DOUBLE_EQ(Imbalance({ 0, 0, 4, 0 }), 4.0);
  EXPECT_DOUBLE_EQ(Imbalance({ 0, 0 }), 1.0);
  EXPECT_DOUBLE_EQ(Imbalance({}), 1.0);
  EXPECT_DOUBLE_EQ(Imbalance({ 5 }), 1.0);
}
