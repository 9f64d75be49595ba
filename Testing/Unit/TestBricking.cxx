// Brick layouts cover the volume exactly, respect the texture limit and the budget, carry the
// one-voxel overlap, and come in an order that no ray contradicts.
#include "slicing/Bricking.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace
{
using accelvolume::Brick;
using accelvolume::BrickLayout;
using accelvolume::BrickRequest;

BrickLayout Layout(int nx, int ny, int nz, int limit, std::uint64_t bytes, std::uint64_t budget)
{
  BrickRequest request;
  request.dimensions = { { nx, ny, nz } };
  request.maximumTextureSize = limit;
  request.bytesPerVoxel = bytes;
  request.budgetBytes = budget;
  BrickLayout layout;
  std::string error;
  EXPECT_TRUE(accelvolume::ComputeBrickLayout(request, layout, error)) << error;
  return layout;
}

// Every point sample of the volume has exactly one owner, whose texture holds the 2x2x2 (and
// the central-difference) texels it reads.
void ExpectExactCover(const BrickLayout& layout, const std::array<int, 3>& dims)
{
  std::mt19937 random(7);
  for (int n = 0; n < 4000; ++n)
  {
    double p[3];
    for (int a = 0; a < 3; ++a)
    {
      std::uniform_real_distribution<double> along(0.0, std::max(0, dims[a] - 1));
      p[a] = along(random);
    }
    int owners = 0;
    for (const Brick& brick : layout.bricks)
    {
      bool owns = true;
      for (int a = 0; a < 3; ++a)
      {
        owns = owns && (brick.firstOnAxis[a] || p[a] >= brick.pointLower[a]) &&
          (brick.lastOnAxis[a] || p[a] < brick.pointUpper[a]);
      }
      if (!owns)
      {
        continue;
      }
      ++owners;
      for (int a = 0; a < 3; ++a)
      {
        const int low = std::max(0, static_cast<int>(std::floor(p[a])) - 1);
        const int high = std::min(dims[a] - 1, static_cast<int>(std::floor(p[a])) + 2);
        EXPECT_LE(brick.textureOrigin[a], low);
        EXPECT_GE(brick.textureOrigin[a] + brick.textureSize[a] - 1, high);
      }
    }
    EXPECT_EQ(owners, 1);
  }
}
}

TEST(Bricking, FittingVolumeIsOneBrick)
{
  const BrickLayout layout = Layout(256, 256, 128, 2048, 1, 0);
  ASSERT_TRUE(layout.Single());
  EXPECT_EQ(layout.bricks[0].textureSize, (std::array<int, 3>{ { 256, 256, 128 } }));
  EXPECT_EQ(layout.totalBytes, 256u * 256u * 128u);
}

TEST(Bricking, LongAxisIsSplitUnderTheTextureLimit)
{
  const BrickLayout layout = Layout(2100, 64, 64, 2048, 1, 0);
  ASSERT_EQ(layout.bricks.size(), 2u);
  for (const Brick& brick : layout.bricks)
  {
    EXPECT_LE(brick.textureSize[0], 2048);
    EXPECT_EQ(brick.textureSize[1], 64);
  }
  // The shared face and one more point on each side of it.
  EXPECT_EQ(layout.bricks[0].pointUpper[0], layout.bricks[1].pointLower[0]);
  EXPECT_EQ(layout.bricks[0].textureOrigin[0] + layout.bricks[0].textureSize[0] - 1,
    layout.bricks[0].pointUpper[0] + 1);
  EXPECT_EQ(layout.bricks[1].textureOrigin[0], layout.bricks[1].pointLower[0] - 1);
  ExpectExactCover(layout, { { 2100, 64, 64 } });
}

TEST(Bricking, BudgetSplitsIntoShares)
{
  const std::uint64_t budget = 16u << 20;
  const BrickLayout layout = Layout(512, 512, 275, 2048, 2, budget);
  EXPECT_GT(layout.bricks.size(), 8u);
  EXPECT_LE(layout.largestBrickBytes, budget / accelvolume::BudgetShare);
  ExpectExactCover(layout, { { 512, 512, 275 } });
}

TEST(Bricking, FlatAndTinyAxes)
{
  const BrickLayout layout = Layout(1, 300, 2, 40, 4, 0);
  EXPECT_EQ(layout.gridSize[0], 1);
  EXPECT_EQ(layout.gridSize[2], 1);
  EXPECT_GT(layout.gridSize[1], 1);
  ExpectExactCover(layout, { { 1, 300, 2 } });
}

TEST(Bricking, ImpossibleRequestsAreErrors)
{
  BrickRequest request;
  request.dimensions = { { 128, 128, 128 } };
  request.budgetBytes = 100;
  BrickLayout layout;
  std::string error;
  EXPECT_FALSE(accelvolume::ComputeBrickLayout(request, layout, error));
  EXPECT_NE(error.find("smaller than one brick"), std::string::npos);
  request.budgetBytes = 0;
  request.maximumTextureSize = 3;
  EXPECT_FALSE(accelvolume::ComputeBrickLayout(request, layout, error));
  request.maximumTextureSize = 64;
  request.dimensions = { { 0, 5, 5 } };
  EXPECT_FALSE(accelvolume::ComputeBrickLayout(request, layout, error));
}

// Marching along random rays, the bricks met come in non-decreasing order positions.
TEST(Bricking, VisibilityOrderHoldsAlongEveryRay)
{
  const std::array<int, 3> dims{ { 90, 70, 50 } };
  const BrickLayout layout = Layout(dims[0], dims[1], dims[2], 20, 1, 0);
  const accelvolume::Box volume{ { 0, 0, 0 }, { 89, 69, 49 } };
  std::mt19937 random(3);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int trial = 0; trial < 120; ++trial)
  {
    const bool perspective = trial % 2 == 0;
    // Eyes inside and outside the volume; directions any way.
    const accelvolume::Vec3 eye{ 45 + 80 * unit(random), 35 + 60 * unit(random),
      25 + 50 * unit(random) };
    const accelvolume::Vec3 direction =
      accelvolume::Normalize(accelvolume::Vec3{ unit(random), unit(random), unit(random) });
    const std::vector<int> order =
      accelvolume::BrickVisibilityOrder(layout, perspective, eye, direction);
    std::vector<int> position(order.size());
    for (size_t i = 0; i < order.size(); ++i)
    {
      position[order[i]] = static_cast<int>(i);
    }
    for (int ray = 0; ray < 10; ++ray)
    {
      const accelvolume::Vec3 along = perspective
        ? accelvolume::Normalize(accelvolume::Vec3{ unit(random), unit(random), unit(random) })
        : direction;
      const accelvolume::Vec3 start = perspective
        ? eye
        : accelvolume::Vec3{ 45 + 40 * unit(random), 35 + 30 * unit(random),
            25 + 20 * unit(random) } - 200.0 * direction;
      int last = -1;
      for (double t = 0; t < 400; t += 0.37)
      {
        const accelvolume::Vec3 p = start + t * along;
        for (size_t b = 0; b < layout.bricks.size(); ++b)
        {
          const accelvolume::Box owned = accelvolume::BrickOwnedBox(layout.bricks[b], volume);
          if (p.x >= owned.lower.x && p.x < owned.upper.x && p.y >= owned.lower.y &&
            p.y < owned.upper.y && p.z >= owned.lower.z && p.z < owned.upper.z)
          {
            EXPECT_GE(position[b], last) << "trial " << trial << " ray " << ray;
            last = std::max(last, position[b]);
          }
        }
      }
    }
  }
}
