// TestDistanceMap: the chessboard distance map of non-empty cells, and the per-octant maps, vs
// brute-force oracles.
#include "MinMaxOctreeTestSupport.h"
#include "skipping/CellBricks.h"
#include "skipping/DistanceMap.h"
#include "skipping/OctantDistanceMap.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <random>
#include <vector>

namespace
{
using namespace accelvolume;

using accelvolume_test::ShuffledFor;
using accelvolume_test::ThreadedFor;

std::size_t CellCount(const int dims[3])
{
  return static_cast<std::size_t>(dims[0]) * dims[1] * dims[2];
}

// min over non-empty cells of the chessboard distance, capped; the cap when there are none.
std::vector<std::uint8_t> BruteForce(const int dims[3], const std::vector<std::uint8_t>& flags)
{
  std::vector<int> features;
  for (std::size_t i = 0; i < flags.size(); ++i)
  {
    if (flags[i])
    {
      features.push_back(static_cast<int>(i));
    }
  }
  std::vector<std::uint8_t> result(flags.size());
  for (int z = 0; z < dims[2]; ++z)
  {
    for (int y = 0; y < dims[1]; ++y)
    {
      for (int x = 0; x < dims[0]; ++x)
      {
        int best = DistanceMapSaturation;
        for (int f : features)
        {
          const int fx = f % dims[0];
          const int fy = (f / dims[0]) % dims[1];
          const int fz = f / (dims[0] * dims[1]);
          best = std::min(best, std::max({ std::abs(x - fx), std::abs(y - fy), std::abs(z - fz) }));
        }
        result[(static_cast<std::size_t>(z) * dims[1] + y) * dims[0] + x] =
          static_cast<std::uint8_t>(best);
      }
    }
  }
  return result;
}

std::vector<std::uint8_t> RandomFlags(const int dims[3], double density, std::mt19937& random)
{
  std::bernoulli_distribution flag(density);
  std::vector<std::uint8_t> flags(CellCount(dims));
  for (std::uint8_t& f : flags)
  {
    f = flag(random) ? 1 : 0;
  }
  return flags;
}

TEST(DistanceMap, MatchesBruteForceOnRandomGrids)
{
  std::mt19937 random(11);
  const int shapes[][3] = { { 1, 1, 1 }, { 1, 7, 1 }, { 13, 1, 1 }, { 1, 1, 9 }, { 5, 1, 9 },
    { 7, 6, 5 }, { 3, 17, 4 }, { 16, 15, 14 }, { 70, 3, 2 }, { 2, 66, 5 }, { 9, 4, 67 },
    { 131, 5, 1 } };
  const double densities[] = { 0.0, 0.002, 0.01, 0.05, 0.3, 0.9, 1.0 };
  for (const auto& dims : shapes)
  {
    for (double density : densities)
    {
      const std::vector<std::uint8_t> flags = RandomFlags(dims, density, random);
      const std::vector<std::uint8_t> expected = BruteForce(dims, flags);
      const std::vector<std::uint8_t> actual = ComputeDistanceMap(dims, flags, SerialFor);
      ASSERT_EQ(actual, expected) << dims[0] << "x" << dims[1] << "x" << dims[2] << " density "
                                  << density;
    }
  }
}

TEST(DistanceMap, SingleFeatures)
{
  // Every single-feature position of a small box: the map is the chessboard distance itself.
  const int dims[3] = { 6, 5, 4 };
  std::vector<std::uint8_t> flags(CellCount(dims), 0);
  for (std::size_t f = 0; f < flags.size(); ++f)
  {
    std::fill(flags.begin(), flags.end(), 0);
    flags[f] = 1;
    ASSERT_EQ(ComputeDistanceMap(dims, flags, SerialFor), BruteForce(dims, flags)) << f;
  }
}

TEST(DistanceMap, EmptyAndFull)
{
  const int dims[3] = { 9, 8, 7 };
  const std::vector<std::uint8_t> none(CellCount(dims), 0);
  const std::vector<std::uint8_t> all(CellCount(dims), 1);
  const std::vector<std::uint8_t> far = ComputeDistanceMap(dims, none, SerialFor);
  ASSERT_EQ(far.size(), none.size());
  for (std::uint8_t d : far)
  {
    ASSERT_EQ(d, DistanceMapSaturation);
  }
  for (std::uint8_t d : ComputeDistanceMap(dims, all, SerialFor))
  {
    ASSERT_EQ(d, 0);
  }
}

TEST(DistanceMap, SaturatesAlongEachAxis)
{
  // 300 cells along one axis with one feature at 10: min(|i - 10|, 255).
  for (int axis = 0; axis < 3; ++axis)
  {
    int dims[3] = { 1, 1, 1 };
    dims[axis] = 300;
    std::vector<std::uint8_t> flags(300, 0);
    flags[10] = 1;
    const std::vector<std::uint8_t> map = ComputeDistanceMap(dims, flags, SerialFor);
    ASSERT_EQ(map.size(), 300u);
    for (int i = 0; i < 300; ++i)
    {
      ASSERT_EQ(map[i], std::min(std::abs(i - 10), DistanceMapSaturation)) << axis << " " << i;
    }
  }
}

TEST(DistanceMap, SaturatesIn3D)
{
  // One feature in the corner of a 270 x 3 x 262 grid: distances reach past the cap along x and
  // z, and the corner feature is the only one.
  const int dims[3] = { 270, 3, 262 };
  std::vector<std::uint8_t> flags(CellCount(dims), 0);
  flags[0] = 1;
  const std::vector<std::uint8_t> map = ComputeDistanceMap(dims, flags, ThreadedFor(3));
  for (int z = 0; z < dims[2]; ++z)
  {
    for (int y = 0; y < dims[1]; ++y)
    {
      for (int x = 0; x < dims[0]; ++x)
      {
        const int expected = std::min(std::max({ x, y, z }), DistanceMapSaturation);
        ASSERT_EQ(map[(static_cast<std::size_t>(z) * dims[1] + y) * dims[0] + x], expected)
          << x << " " << y << " " << z;
      }
    }
  }
}

TEST(DistanceMap, ThreadCountIndependent)
{
  std::mt19937 random(5);
  const int dims[3] = { 61, 47, 23 };
  for (double density : { 0.0005, 0.01, 0.2 })
  {
    const std::vector<std::uint8_t> flags = RandomFlags(dims, density, random);
    const std::vector<std::uint8_t> serial = ComputeDistanceMap(dims, flags, SerialFor);
    EXPECT_EQ(ComputeDistanceMap(dims, flags, ThreadedFor(2)), serial);
    EXPECT_EQ(ComputeDistanceMap(dims, flags, ThreadedFor(5)), serial);
    EXPECT_EQ(ComputeDistanceMap(dims, flags, ShuffledFor(9)), serial);
  }
  // Large enough that every row loop runs its vectorized blocks, checked against the oracle.
  const int wide[3] = { 150, 70, 4 };
  const std::vector<std::uint8_t> flags = RandomFlags(wide, 0.001, random);
  EXPECT_EQ(ComputeDistanceMap(wide, flags, ThreadedFor(4)), BruteForce(wide, flags));
}

TEST(DistanceMap, ReusesTheOutputBuffer)
{
  std::mt19937 random(6);
  const int small[3] = { 5, 4, 3 }, large[3] = { 17, 9, 8 };
  std::vector<std::uint8_t> distance(3, 7); // stale contents of another size
  for (const auto* dims : { small, large, large, small })
  {
    const std::vector<std::uint8_t> flags = RandomFlags(dims, 0.03, random);
    ComputeDistanceMap(dims, flags, ThreadedFor(2), distance);
    ASSERT_EQ(distance, BruteForce(dims, flags));
  }
  const int bad[3] = { 0, 1, 1 };
  ComputeDistanceMap(bad, {}, SerialFor, distance);
  EXPECT_TRUE(distance.empty());
}

// Per octant: the largest empty cube with its corner at the cell, extending along the octant's
// signs (cells outside the grid empty), capped; searched side by side.
std::vector<std::uint8_t> OctantBruteForce(
  const int dims[3], const std::vector<std::uint8_t>& flags, int octant)
{
  const int sign[3] = { octant & 1 ? -1 : 1, octant & 2 ? -1 : 1, octant & 4 ? -1 : 1 };
  auto filled = [&](int x, int y, int z)
  {
    return x >= 0 && y >= 0 && z >= 0 && x < dims[0] && y < dims[1] && z < dims[2] &&
      flags[(static_cast<std::size_t>(z) * dims[1] + y) * dims[0] + x] != 0;
  };
  std::vector<std::uint8_t> result(flags.size());
  for (int z = 0; z < dims[2]; ++z)
  {
    for (int y = 0; y < dims[1]; ++y)
    {
      for (int x = 0; x < dims[0]; ++x)
      {
        // Cells inside the grid ahead of (x, y, z) along each axis: past them the cube only
        // grows over empty outside cells.
        const int ahead[3] = { sign[0] > 0 ? dims[0] - x : x + 1, sign[1] > 0 ? dims[1] - y : y + 1,
          sign[2] > 0 ? dims[2] - z : z + 1 };
        const int reach = std::max({ ahead[0], ahead[1], ahead[2] });
        int side = 0;
        // Grow the cube by its new shell while the shell is empty.
        while (side < DistanceMapSaturation)
        {
          if (side >= reach)
          {
            side = DistanceMapSaturation;
            break;
          }
          bool empty = true;
          for (int k = 0; k <= std::min(side, ahead[2] - 1) && empty; ++k)
          {
            for (int j = 0; j <= std::min(side, ahead[1] - 1) && empty; ++j)
            {
              for (int i = 0; i <= std::min(side, ahead[0] - 1) && empty; ++i)
              {
                if (std::max({ i, j, k }) == side &&
                  filled(x + sign[0] * i, y + sign[1] * j, z + sign[2] * k))
                {
                  empty = false;
                }
              }
            }
          }
          if (!empty)
          {
            break;
          }
          ++side;
        }
        result[(static_cast<std::size_t>(z) * dims[1] + y) * dims[0] + x] =
          static_cast<std::uint8_t>(side);
      }
    }
  }
  return result;
}

// ComputeOctantDistanceMap's result in row-major order (its input and output are bricked).
std::vector<std::uint8_t> OctantMap(
  const int dims[3], const std::vector<std::uint8_t>& flags, int octant)
{
  const CellBricks bricks(dims);
  std::vector<std::uint8_t> bricked;
  bricks.Reorder(dims, ComputeDistanceMap(dims, flags, SerialFor), bricked, SerialFor);
  std::vector<std::uint8_t> map;
  ComputeOctantDistanceMap(dims, bricked.data(), octant, map);
  EXPECT_EQ(map.size(), bricks.Entries());
  std::vector<std::uint8_t> rowMajor(flags.size());
  bricks.ForEachCell(dims, SerialFor,
    [&](std::size_t i, std::size_t brickedIndex) { rowMajor[i] = map[brickedIndex]; });
  return rowMajor;
}

TEST(OctantDistanceMap, MatchesBruteForceInEveryOctant)
{
  std::mt19937 random(17);
  const int shapes[][3] = { { 1, 1, 1 }, { 1, 7, 1 }, { 13, 1, 1 }, { 5, 1, 9 }, { 7, 6, 5 },
    { 3, 17, 4 }, { 16, 15, 14 }, { 21, 9, 10 } };
  for (const auto& dims : shapes)
  {
    for (double density : { 0.0, 0.01, 0.05, 0.3, 1.0 })
    {
      const std::vector<std::uint8_t> flags = RandomFlags(dims, density, random);
      const std::vector<std::uint8_t> chessboard = BruteForce(dims, flags);
      for (int octant = 0; octant < 8; ++octant)
      {
        const std::vector<std::uint8_t> map = OctantMap(dims, flags, octant);
        ASSERT_EQ(map, OctantBruteForce(dims, flags, octant))
          << dims[0] << "x" << dims[1] << "x" << dims[2] << " density " << density << " octant "
          << octant;
        // Never shorter than the chessboard map's leap: its cube holds the octant's.
        for (std::size_t i = 0; i < map.size(); ++i)
        {
          ASSERT_GE(map[i], chessboard[i]) << i;
        }
      }
    }
  }
}

TEST(OctantDistanceMap, SaturatesAndLooksOnlyAhead)
{
  // 300 cells along one axis with one non-empty cell at 10: ahead of it (towards it) the side
  // is the distance to it, behind it the cap; capped at 255.
  for (int axis = 0; axis < 3; ++axis)
  {
    int dims[3] = { 1, 1, 1 };
    dims[axis] = 300;
    std::vector<std::uint8_t> flags(300, 0);
    flags[10] = 1;
    for (int octant : { 0, 1 << axis })
    {
      const std::vector<std::uint8_t> map = OctantMap(dims, flags, octant);
      const bool forward = octant == 0;
      for (int i = 0; i < 300; ++i)
      {
        const int towards = forward ? (i <= 10 ? 10 - i : DistanceMapSaturation)
                                    : (i >= 10 ? i - 10 : DistanceMapSaturation);
        ASSERT_EQ(map[i], std::min(towards, DistanceMapSaturation)) << axis << " " << i;
      }
    }
  }
}

TEST(DistanceMap, RejectsBadInput)
{
  const int zero[3] = { 0, 4, 4 };
  EXPECT_TRUE(ComputeDistanceMap(zero, {}, SerialFor).empty());
  const int dims[3] = { 2, 2, 2 };
  EXPECT_TRUE(ComputeDistanceMap(dims, std::vector<std::uint8_t>(7, 0), SerialFor).empty());
}

}
