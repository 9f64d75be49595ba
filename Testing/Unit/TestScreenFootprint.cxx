// TestScreenFootprint: the screen footprint of the non-empty cells covers every pixel whose ray
// (the ray caster's own) crosses a non-empty cell, by exact traversal of the cell grid; it
// leaves pixels out; no footprint when a corner is behind the camera.
#include "RayCastEngineTestSupport.h"
#include "raycast/RayCastKernel.h"
#include "raycast/RayCastPixelRay.h"
#include "skipping/CellBricks.h"
#include "skipping/ScreenFootprint.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

namespace
{
using namespace accelvolume;
using namespace accelvolume_test::raycast_engine;

struct Grid
{
  int dims[3];                        // voxels
  int cellDims[3];                    // cells
  std::vector<std::uint8_t> nonEmpty; // per cell, row-major
  std::vector<std::uint8_t> distance; // CellBricks layout, 0 for the non-empty cells
  std::vector<std::uint16_t> packed;  // the same as the packed cell table's low byte
};

// `clusters` random boxes of non-empty cells (1 to 5 cells a side), and `corners` single cells,
// each at a random corner of a random 8-cell macro cell (the cells a footprint a voxel or a pixel
// short on any side would lose).
Grid MakeGrid(std::mt19937& random, const int dims[3], int clusters, int corners)
{
  Grid grid;
  for (int a = 0; a < 3; ++a)
  {
    grid.dims[a] = dims[a];
    grid.cellDims[a] = std::max(dims[a] - 1, 1);
  }
  const std::size_t cells =
    static_cast<std::size_t>(grid.cellDims[0]) * grid.cellDims[1] * grid.cellDims[2];
  grid.nonEmpty.assign(cells, 0);
  const auto set = [&grid](int x, int y, int z) {
    grid.nonEmpty[(static_cast<std::size_t>(z) * grid.cellDims[1] + y) * grid.cellDims[0] + x] = 1;
  };
  std::uniform_int_distribution<int> side(1, 5);
  for (int k = 0; k < clusters; ++k)
  {
    int from[3], to[3];
    for (int a = 0; a < 3; ++a)
    {
      from[a] = std::uniform_int_distribution<int>(0, grid.cellDims[a] - 1)(random);
      to[a] = std::min(from[a] + side(random), grid.cellDims[a]);
    }
    for (int z = from[2]; z < to[2]; ++z)
      for (int y = from[1]; y < to[1]; ++y)
        for (int x = from[0]; x < to[0]; ++x)
          set(x, y, z);
  }
  std::bernoulli_distribution high(0.5);
  for (int k = 0; k < corners; ++k)
  {
    int c[3];
    for (int a = 0; a < 3; ++a)
    {
      const int macro = std::uniform_int_distribution<int>(0, (grid.cellDims[a] - 1) / 8)(random);
      c[a] = std::min(8 * macro + (high(random) ? 7 : 0), grid.cellDims[a] - 1);
    }
    set(c[0], c[1], c[2]);
  }
  const CellBricks bricks(grid.cellDims);
  grid.distance.assign(bricks.Entries(), 1);
  grid.packed.assign(bricks.Entries(), 0x0301);
  std::size_t at = 0;
  for (int z = 0; z < grid.cellDims[2]; ++z)
  {
    for (int y = 0; y < grid.cellDims[1]; ++y)
    {
      for (int x = 0; x < grid.cellDims[0]; ++x, ++at)
      {
        if (grid.nonEmpty[at])
        {
          grid.distance[bricks.Index(x, y, z)] = 0;
          grid.packed[bricks.Index(x, y, z)] = 0x0500;
        }
      }
    }
  }
  return grid;
}

// Whether the ray meets the box [0, dims - 1] (never behind its origin), and whether it crosses
// a non-empty cell there, by exact grid traversal (Amanatides and Woo).
bool MeetsNonEmptyCell(const detail::IndexRay& ray, const Grid& grid, bool& inBox)
{
  double t0, t1;
  const Box box{ { 0, 0, 0 }, { grid.dims[0] - 1.0, grid.dims[1] - 1.0, grid.dims[2] - 1.0 } };
  inBox = IntersectRayRegion(ray.origin, ray.direction, box, {}, t0, t1) && std::max(t0, 0.0) <= t1;
  if (!inBox)
  {
    return false;
  }
  t0 = std::max(t0, 0.0);
  const double o[3] = { ray.origin.x, ray.origin.y, ray.origin.z };
  const double d[3] = { ray.direction.x, ray.direction.y, ray.direction.z };
  int c[3];
  double next[3], delta[3];
  for (int a = 0; a < 3; ++a)
  {
    const double p = o[a] + t0 * d[a];
    c[a] = std::min(std::max(static_cast<int>(std::floor(p)), 0), grid.cellDims[a] - 1);
    delta[a] = d[a] != 0 ? 1.0 / std::abs(d[a]) : std::numeric_limits<double>::infinity();
    next[a] = d[a] > 0
      ? (c[a] + 1 - o[a]) / d[a]
      : (d[a] < 0 ? (c[a] - o[a]) / d[a] : std::numeric_limits<double>::infinity());
  }
  for (;;)
  {
    if (grid
          .nonEmpty[(static_cast<std::size_t>(c[2]) * grid.cellDims[1] + c[1]) * grid.cellDims[0] +
            c[0]])
    {
      return true;
    }
    int a = next[0] < next[1] ? 0 : 1;
    a = next[2] < next[a] ? 2 : a;
    if (next[a] > t1)
    {
      return false;
    }
    c[a] += d[a] > 0 ? 1 : -1;
    if (c[a] < 0 || c[a] >= grid.cellDims[a])
    {
      return false;
    }
    next[a] += delta[a];
  }
}

void IndexToClip(const RayCastView& view, double out[4][4])
{
  Matrix clipToWorld{};
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      clipToWorld[r][c] = view.clipToWorld[r][c];
    }
  }
  const Matrix worldToClip = Invert(clipToWorld);
  // The test views' index space is world space.
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      out[r][c] = worldToClip[r][c];
    }
  }
}

TEST(ScreenFootprint, CoversEveryPixelWhoseRayMeetsANonEmptyCell)
{
  std::mt19937 random(7);
  const int dims[3] = { 45, 38, 29 };
  const Vec3 centre{ 22, 18.5, 14 };
  std::size_t meeting = 0, emptyInBox = 0, left = 0;
  for (int trial = 0; trial < 24; ++trial)
  {
    const Grid grid = MakeGrid(random, dims, trial % 3, 2 + trial % 3);
    MacroCells macro;
    ComputeMacroCells(grid.cellDims, grid.distance.data(), SerialFor, macro);
    MacroCells fromPacked;
    ComputeMacroCells(grid.cellDims, grid.packed.data(), ThreadedFor(3, 1), fromPacked);
    ASSERT_EQ(macro.nonEmpty, fromPacked.nonEmpty);
    Camera camera = RandomCamera(random, dims, trial % 2 == 0);
    if (trial % 3 == 1)
    {
      // Zoomed in: a voxel spans several pixel blocks, so a footprint a voxel short shows.
      camera.parallelScale *= 0.25;
      camera.viewAngleDegrees = 8;
    }
    if (trial % 3 == 2)
    {
      // Close, wide perspective views: the projection distorts most there.
      camera.parallel = false;
      camera.focalPoint = centre;
      const int k = trial / 3 % 4;
      camera.position = centre + Vec3{ 40.0 - 12 * k, 34.0, -20.0 + 9 * k };
      camera.viewAngleDegrees = 60 + 10 * k;
    }
    const int width = 123 + trial, height = 95 + 2 * trial;
    const RayCastView view = MakeView(camera, width, height, 0.5, 500.0);
    double indexToClip[4][4];
    IndexToClip(view, indexToClip);
    ScreenFootprint footprint;
    ASSERT_TRUE(ProjectFootprint(macro, dims, indexToClip, width, height, footprint));
    ASSERT_EQ(footprint.blocks[0], (width + 3) / 4);
    ASSERT_EQ(footprint.blocks[1], (height + 3) / 4);
    detail::KernelFrame frame;
    frame.view = &view;
    for (int j = 0; j < height; ++j)
    {
      for (int i = 0; i < width; ++i)
      {
        const bool covered =
          footprint.covered[static_cast<std::size_t>(j / 4) * footprint.blocks[0] + i / 4] != 0;
        const detail::IndexRay ray = detail::MakePixelRay(frame, i, j).index;
        bool inBox = false;
        if (MeetsNonEmptyCell(ray, grid, inBox))
        {
          ++meeting;
          EXPECT_TRUE(covered) << "trial " << trial << " pixel " << i << ", " << j;
        }
        else if (inBox)
        {
          ++emptyInBox;
          left += covered ? 0 : 1;
        }
      }
    }
  }
  EXPECT_GT(meeting, 1000u);
  // The footprint leaves most pixels whose rays meet only empty cells without a ray.
  EXPECT_GT(left, emptyInBox / 2);
}

TEST(ScreenFootprint, NoneWhenACornerIsBehindTheCamera)
{
  std::mt19937 random(8);
  const int dims[3] = { 30, 20, 25 };
  const Grid grid = MakeGrid(random, dims, 6, 4);
  MacroCells macro;
  ComputeMacroCells(grid.cellDims, grid.distance.data(), SerialFor, macro);
  Camera camera;
  camera.position = { 15, 10, 12 }; // inside the volume
  camera.focalPoint = { 15, 10, 30 };
  camera.viewUp = { 0, 1, 0 };
  camera.viewAngleDegrees = 90;
  const RayCastView view = MakeView(camera, 40, 30, 0.5, 500.0);
  double indexToClip[4][4];
  IndexToClip(view, indexToClip);
  ScreenFootprint footprint;
  EXPECT_FALSE(ProjectFootprint(macro, dims, indexToClip, 40, 30, footprint));
  EXPECT_TRUE(footprint.covered.empty());
}

// The corners projected in lanes give ProjectBox's pixels (and failures) to the bit: random
// projective maps (perspective ones with corners behind the eye, parallel ones, degenerate and
// huge entries) and boxes.
TEST(ScreenFootprint, BoxesProjectedInLanesMatchProjectBox)
{
  std::mt19937 random(19);
  std::uniform_real_distribution<double> entry(-2.0, 2.0), coordinate(-50.0, 300.0);
  std::uniform_int_distribution<int> kind(0, 9), size(1, 700);
  int succeeded = 0, failed = 0;
  for (int trial = 0; trial < 200000; ++trial)
  {
    double m[4][4];
    for (int r = 0; r < 4; ++r)
    {
      for (int c = 0; c < 4; ++c)
      {
        m[r][c] = entry(random);
      }
    }
    switch (kind(random))
    {
      case 0: // parallel: w = 1
        m[3][0] = m[3][1] = m[3][2] = 0.0;
        m[3][3] = 1.0;
        break;
      case 1: // in front of the eye for most boxes
        m[3][3] = 400.0;
        break;
      case 2: // an entry that overflows the division
        m[0][0] = 1.0e308;
        break;
      case 3: // w = 0 for every point
        m[3][0] = m[3][1] = m[3][2] = m[3][3] = 0.0;
        break;
      default:
        break;
    }
    Vec3 a{ coordinate(random), coordinate(random), coordinate(random) };
    Vec3 b{ coordinate(random), coordinate(random), coordinate(random) };
    const Box box{ { std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z) },
      { std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z) } };
    const int width = size(random), height = size(random);
    int expected[4] = { 7, 7, 7, 7 }, lanes[4] = { 7, 7, 7, 7 };
    const bool projects = ProjectBox(box, m, width, height, expected);
    ASSERT_EQ(ProjectBoxFast(box, m, width, height, lanes), projects) << "trial " << trial;
    if (projects)
    {
      ++succeeded;
      for (int k = 0; k < 4; ++k)
      {
        ASSERT_EQ(lanes[k], expected[k]) << "trial " << trial << " k " << k;
      }
    }
    else
    {
      ++failed;
    }
  }
  EXPECT_GT(succeeded, 20000);
  EXPECT_GT(failed, 20000);
}

TEST(ScreenFootprint, MacroCellsGrowToStayFew)
{
  std::mt19937 random(9);
  const int dims[3] = { 70, 50, 40 }; // 69 x 49 x 39 cells
  Grid grid = MakeGrid(random, dims, 0, 0);
  const int nonEmpty[3][3] = { { 7, 8, 0 }, { 68, 48, 38 }, { 40, 0, 17 } };
  const CellBricks bricks(grid.cellDims);
  for (const auto& c : nonEmpty)
  {
    grid.distance[bricks.Index(c[0], c[1], c[2])] = 0;
  }
  MacroCells macro;
  ComputeMacroCells(grid.cellDims, grid.distance.data(), SerialFor, macro);
  EXPECT_EQ(macro.shift, 3);
  EXPECT_EQ(macro.dims[0], 9);
  EXPECT_EQ(macro.dims[1], 7);
  EXPECT_EQ(macro.dims[2], 5);
  std::vector<std::uint8_t> expected(macro.nonEmpty.size(), 0);
  for (const auto& c : nonEmpty)
  {
    expected[(static_cast<std::size_t>(c[2] / 8) * 7 + c[1] / 8) * 9 + c[0] / 8] = 1;
  }
  EXPECT_EQ(macro.nonEmpty, expected);
  MacroCells few;
  ComputeMacroCells(grid.cellDims, grid.distance.data(), SerialFor, few, 40);
  EXPECT_EQ(few.shift, 5); // 16-cell macro cells would still be 5 x 4 x 3 = 60
  ASSERT_EQ(few.nonEmpty.size(), 3u * 2u * 2u);
  EXPECT_EQ(few.nonEmpty, (std::vector<std::uint8_t>{ 1, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1 }));
}

} // namespace
