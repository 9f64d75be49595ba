// TestMinMaxOctreeQueries: min-max octree classification and empty-space queries vs brute force.
#include "MinMaxOctreeTestSupport.h"
#include "RandomGeometry.h"
#include "skipping/MinMaxOctree.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace
{
using namespace accelvolume;

using accelvolume_test::RandomUnit;
using accelvolume_test::ThreadedFor;
using accelvolume_test::Uniform;
using accelvolume_test::View;
using accelvolume_test::VoxelCount;

// Allowed error of the ray-query answers relative to the exact oracle (index units of t).
constexpr double QueryTolerance = 1e-7;
// Fine sampling of the transfer function over a node's value range.
constexpr int TransferSamples = 400;

// --- Classification ---

// Opacity at table position p (clamped), linearly interpolated.
double Interpolate(const std::vector<float>& table, double p)
{
  const double last = static_cast<double>(table.size() - 1);
  p = std::min(std::max(p, 0.0), last);
  const std::size_t i = std::min(static_cast<std::size_t>(p), table.size() - 2);
  const double f = p - static_cast<double>(i);
  return (1 - f) * table[i] + f * table[i + 1];
}

double Position(double v, const std::vector<float>& table, double rangeMin, double rangeMax)
{
  // Same arithmetic as Classify, so the rule check below is exact at table entries.
  return (v - rangeMin) * (static_cast<double>(table.size() - 1) / (rangeMax - rangeMin));
}

std::vector<float> RandomTable(std::mt19937& random)
{
  const std::size_t sizes[] = { 2, 3, 17, 256 };
  std::vector<float> table(sizes[random() % 4]);
  for (float& opacity : table)
  {
    // Mostly zero, so that many nodes are transparent.
    opacity = random() % 3 == 0 ? static_cast<float>(Uniform(random, 0, 1)) : 0.f;
  }
  return table;
}

TEST(MinMaxOctree, ClassifyMatchesBruteForce)
{
  std::mt19937 random(3);
  const int dims[3] = { 37, 29, 23 };
  std::vector<std::int16_t> volume(VoxelCount(dims));
  // Smooth-ish data (a few hundred values) so nodes have narrow and wide ranges.
  for (int z = 0; z < dims[2]; ++z)
  {
    for (int y = 0; y < dims[1]; ++y)
    {
      for (int x = 0; x < dims[0]; ++x)
      {
        volume[(z * dims[1] + y) * dims[0] + x] = static_cast<std::int16_t>(
          200 * std::sin(0.2 * x) * std::cos(0.15 * y) + 3 * z + random() % 7);
      }
    }
  }
  std::string error;
  MinMaxOctree octree;
  ASSERT_TRUE(octree.Configure(dims, 4, error));
  ASSERT_TRUE(octree.BuildParallel(View(volume, dims), SerialFor, error));
  for (int trial = 0; trial < 60; ++trial)
  {
    const std::vector<float> table = RandomTable(random);
    double rangeMin = Uniform(random, -300, 100);
    double rangeMax = Uniform(random, 0, 300);
    if (trial % 5 == 0)
    {
      std::swap(rangeMin, rangeMax); // decreasing map
    }
    const float threshold = trial % 2 ? 0.f : 0.25f;
    octree.Classify(table, rangeMin, rangeMax, threshold);
    ASSERT_TRUE(octree.IsClassified());
    for (int level = 0; level <= octree.GetDepth(); ++level)
    {
      const OctreeLevel& nodes = octree.GetLevel(level);
      for (std::uint64_t n = 0; n < nodes.minimum.size(); ++n)
      {
        const bool transparent = octree.IsTransparent(level, n);
        if (octree.IsPadding(level, n))
        {
          ASSERT_TRUE(transparent);
          continue;
        }
        const double low = nodes.minimum[n];
        const double high = nodes.maximum[n];
        // Fine sampling of the interpolated function over [low, high]: visible => kept.
        double sampled = 0;
        for (int s = 0; s <= TransferSamples; ++s)
        {
          const double v = low + (high - low) * s / TransferSamples;
          sampled = std::max(sampled, Interpolate(table, Position(v, table, rangeMin, rangeMax)));
        }
        if (sampled > threshold)
        {
          ASSERT_FALSE(transparent) << "visible node skipped, level " << level;
        }
        // Exact maximum: the end points and the table entries strictly between them.
        double a = Position(low, table, rangeMin, rangeMax);
        double b = Position(high, table, rangeMin, rangeMax);
        const double last = static_cast<double>(table.size() - 1);
        a = std::min(std::max(a, 0.0), last);
        b = std::min(std::max(b, 0.0), last);
        if (a > b)
        {
          std::swap(a, b);
        }
        double exact = std::max(Interpolate(table, a), Interpolate(table, b));
        bool ruleVisible = false;
        for (std::size_t m = 0; m < table.size(); ++m)
        {
          if (m > a && m < b)
          {
            exact = std::max(exact, static_cast<double>(table[m]));
          }
          if (m >= std::floor(a) && m <= std::ceil(b) && table[m] > threshold)
          {
            ruleVisible = true;
          }
        }
        ASSERT_EQ(!transparent, ruleVisible);
        if (threshold == 0.f)
        {
          // Exact for threshold 0 with non-negative opacities.
          ASSERT_EQ(!transparent, exact > 0);
        }
      }
    }
    // Each node judged on its own range: transparency passes down to the children.
    for (int level = 1; level <= octree.GetDepth(); ++level)
    {
      for (std::uint64_t p = 0; p < octree.GetLevel(level).minimum.size(); ++p)
      {
        for (std::uint64_t c = 8 * p; c < 8 * p + 8 && octree.IsTransparent(level, p); ++c)
        {
          ASSERT_TRUE(octree.IsTransparent(level - 1, c));
        }
      }
    }
  }
}

TEST(MinMaxOctree, ClassifyDegenerateRange)
{
  const int dims[3] = { 9, 9, 9 };
  std::vector<float> volume(VoxelCount(dims), 5.f);
  volume[0] = 1.f; // leaf (0,0,0) spans [1, 5]; the others are exactly 5
  std::string error;
  MinMaxOctree octree;
  ASSERT_TRUE(octree.Configure(dims, 4, error));
  ASSERT_TRUE(octree.BuildParallel(View(volume, dims), SerialFor, error));
  const std::uint64_t first = 0, other = MortonEncode(1, 1, 1);
  // Step at 5: below gives entry 0, above the last entry, 5 itself the whole table.
  octree.Classify({ 0.f, 0.f, 1.f }, 5.0, 5.0);
  EXPECT_FALSE(octree.IsTransparent(0, first));
  EXPECT_FALSE(octree.IsTransparent(0, other));
  octree.Classify({ 0.f, 0.f, 1.f }, 7.0, 7.0); // all values below the step
  EXPECT_TRUE(octree.IsTransparent(0, first));
  octree.Classify({ 0.f, 0.f, 1.f }, 0.5, 0.5); // all values above the step
  EXPECT_FALSE(octree.IsTransparent(0, first));
  octree.Classify({ 0.3f }, 0.0, 1.0); // one entry: constant
  EXPECT_FALSE(octree.IsTransparent(0, other));
  octree.Classify({}, 0.0, 1.0); // no table: nothing visible
  EXPECT_TRUE(octree.IsTransparent(0, other));
  // Rebuilding drops the classification.
  ASSERT_TRUE(octree.BuildParallel(View(volume, dims), SerialFor, error));
  EXPECT_FALSE(octree.IsClassified());
}

// --- Queries ---

// A mostly zero uint8 volume with a few random blobs; classified with opacity 0 at value 0 and
// positive above, so a leaf is non-transparent exactly when it covers a nonzero voxel.
struct SparseScene
{
  int dims[3];
  std::vector<std::uint8_t> volume;
  MinMaxOctree octree;
  std::vector<bool> visibleLeaf; // by Morton index, from the voxels directly
  // visibleBelow[l][n]: some leaf of node n at level l is visible (the leaves of a node are a
  // contiguous Morton range, so this is an OR over children)
  std::vector<std::vector<bool>> visibleBelow;
};

void MakeSparseScene(
  std::mt19937& random, const int dims[3], int leafSize, int blobs, SparseScene& scene)
{
  std::copy(dims, dims + 3, scene.dims);
  scene.volume.assign(VoxelCount(dims), 0);
  for (int b = 0; b < blobs; ++b)
  {
    int lower[3], upper[3];
    for (int axis = 0; axis < 3; ++axis)
    {
      lower[axis] = static_cast<int>(random() % dims[axis]);
      upper[axis] = std::min(dims[axis] - 1, lower[axis] + static_cast<int>(random() % 6));
    }
    for (int z = lower[2]; z <= upper[2]; ++z)
    {
      for (int y = lower[1]; y <= upper[1]; ++y)
      {
        for (int x = lower[0]; x <= upper[0]; ++x)
        {
          scene.volume[(static_cast<std::size_t>(z) * dims[1] + y) * dims[0] + x] =
            static_cast<std::uint8_t>(1 + random() % 255);
        }
      }
    }
  }
  std::string error;
  ASSERT_TRUE(scene.octree.Configure(dims, leafSize, error)) << error;
  ASSERT_TRUE(scene.octree.BuildParallel(View(scene.volume, dims), ThreadedFor(2), error));
  scene.octree.Classify({ 0.f, 1.f }, 0.0, 255.0);
  const OctreeLevel& leaves = scene.octree.GetLevel(0);
  scene.visibleLeaf.assign(leaves.minimum.size(), false);
  for (std::uint64_t n = 0; n < leaves.minimum.size(); ++n)
  {
    if (scene.octree.IsPadding(0, n))
    {
      continue;
    }
    std::uint32_t c[3];
    MortonDecode(n, c[0], c[1], c[2]);
    bool visible = false;
    for (int z = c[2] * leafSize; z <= std::min<int>((c[2] + 1) * leafSize, dims[2] - 1); ++z)
    {
      for (int y = c[1] * leafSize; y <= std::min<int>((c[1] + 1) * leafSize, dims[1] - 1); ++y)
      {
        for (int x = c[0] * leafSize; x <= std::min<int>((c[0] + 1) * leafSize, dims[0] - 1); ++x)
        {
          visible =
            visible || scene.volume[(static_cast<std::size_t>(z) * dims[1] + y) * dims[0] + x];
        }
      }
    }
    scene.visibleLeaf[n] = visible;
    ASSERT_EQ(visible, !scene.octree.IsTransparent(0, n));
  }
  scene.visibleBelow = { scene.visibleLeaf };
  for (int level = 1; level <= scene.octree.GetDepth(); ++level)
  {
    const std::vector<bool>& children = scene.visibleBelow.back();
    std::vector<bool> parents(scene.octree.GetLevel(level).minimum.size(), false);
    for (std::size_t c = 0; c < children.size(); ++c)
    {
      parents[c / 8] = parents[c / 8] || children[c];
    }
    scene.visibleBelow.push_back(parents);
  }
}

bool Contains(const Box& box, const Vec3& p)
{
  return p.x >= box.lower.x && p.x <= box.upper.x && p.y >= box.lower.y && p.y <= box.upper.y &&
    p.z >= box.lower.z && p.z <= box.upper.z;
}

bool ContainsBox(const Box& outer, const Box& inner)
{
  return Contains(outer, inner.lower) && Contains(outer, inner.upper);
}

// Closed-box ray interval; false when the ray misses.
bool RayBox(const Vec3& o, const Vec3& d, const Box& box, double& ta, double& tb)
{
  ta = -std::numeric_limits<double>::infinity();
  tb = std::numeric_limits<double>::infinity();
  const double origin[3] = { o.x, o.y, o.z }, direction[3] = { d.x, d.y, d.z };
  const double lower[3] = { box.lower.x, box.lower.y, box.lower.z };
  const double upper[3] = { box.upper.x, box.upper.y, box.upper.z };
  for (int axis = 0; axis < 3; ++axis)
  {
    if (direction[axis] == 0)
    {
      if (origin[axis] < lower[axis] || origin[axis] > upper[axis])
      {
        return false;
      }
      continue;
    }
    double a = (lower[axis] - origin[axis]) / direction[axis];
    double b = (upper[axis] - origin[axis]) / direction[axis];
    if (a > b)
    {
      std::swap(a, b);
    }
    ta = std::max(ta, a);
    tb = std::min(tb, b);
  }
  return ta <= tb;
}

const int QueryDimensions[][3] = { { 61, 47, 33 }, { 255, 97, 61 }, { 1, 7, 300 }, { 2, 3, 5 },
  { 40, 40, 40 } };

TEST(MinMaxOctree, LargestEmptyNodeAtMatchesBruteForce)
{
  std::mt19937 random(21);
  for (const auto& dims : QueryDimensions)
  {
    for (int leafSize : { 2, 4, 8 })
    {
      SparseScene scene;
      MakeSparseScene(random, dims, leafSize, 6, scene);
      const MinMaxOctree& octree = scene.octree;
      const Box volumeBox{ { 0, 0, 0 }, { dims[0] - 1.0, dims[1] - 1.0, dims[2] - 1.0 } };
      for (int n = 0; n < 3000; ++n)
      {
        Vec3 p = accelvolume_test::RandomPoint(random, volumeBox);
        if (n % 3 == 0)
        {
          // On leaf faces.
          p.x = std::min(dims[0] - 1.0, leafSize * std::floor(p.x / leafSize));
          p.z = std::min(dims[2] - 1.0, leafSize * std::floor(p.z / leafSize));
        }
        int level = -1;
        std::uint64_t index = 0;
        const int leaf[3] = { std::min<int>(static_cast<int>(p.x / leafSize),
                                octree.GetLevel(0).gridSize[0] - 1),
          std::min<int>(static_cast<int>(p.y / leafSize), octree.GetLevel(0).gridSize[1] - 1),
          std::min<int>(static_cast<int>(p.z / leafSize), octree.GetLevel(0).gridSize[2] - 1) };
        const std::uint64_t leafIndex = MortonEncode(leaf[0], leaf[1], leaf[2]);
        const bool found = octree.LargestEmptyNodeAt(p, level, index);
        ASSERT_EQ(found, !scene.visibleLeaf[leafIndex]);
        if (!found)
        {
          continue;
        }
        ASSERT_TRUE(Contains(octree.NodeBox(level, index), p));
        ASSERT_EQ(index, leafIndex >> (3 * level)) << "not an ancestor of the point's leaf";
        // Brute force: every leaf below is invisible, and some leaf below the parent is visible.
        ASSERT_FALSE(scene.visibleBelow[level][index]);
        if (level < octree.GetDepth())
        {
          ASSERT_TRUE(scene.visibleBelow[level + 1][index / 8]) << "a larger empty node exists";
        }
      }
      int level;
      std::uint64_t index;
      EXPECT_FALSE(octree.LargestEmptyNodeAt({ -0.5, 0, 0 }, level, index));
      EXPECT_FALSE(octree.LargestEmptyNodeAt({ 0, dims[1] - 0.5, 0 }, level, index));
    }
  }
}

TEST(MinMaxOctree, NextNonEmptyNeverSkipsVisibleLeaves)
{
  std::mt19937 random(8);
  for (const auto& dims : QueryDimensions)
  {
    for (int leafSize : { 2, 4, 8 })
    {
      SparseScene scene;
      MakeSparseScene(random, dims, leafSize, 4, scene);
      const MinMaxOctree& octree = scene.octree;
      std::vector<Box> visibleBoxes;
      for (std::uint64_t n = 0; n < scene.visibleLeaf.size(); ++n)
      {
        if (scene.visibleLeaf[n])
        {
          visibleBoxes.push_back(octree.NodeBox(0, n));
        }
      }
      const Box around{ { -10, -10, -10 }, { dims[0] + 10.0, dims[1] + 10.0, dims[2] + 10.0 } };
      for (int n = 0; n < 400; ++n)
      {
        const Vec3 origin = accelvolume_test::RandomPoint(random, around);
        Vec3 direction = RandomUnit(random) * Uniform(random, 0.1, 10);
        if (n % 10 == 0)
        {
          direction.y = 0; // parallel to faces
        }
        if (n % 20 == 0)
        {
          direction.x = 0;
        }
        const double t0 = Uniform(random, -50, 50);
        const double t1 = n % 4 == 0 ? t0 : t0 + Uniform(random, 0, 400);
        const double result = octree.NextNonEmpty(origin, direction, t0, t1);
        // Exact oracle: first entry into a visible leaf box within [t0, t1].
        double expected = t1;
        for (const Box& box : visibleBoxes)
        {
          double ta, tb;
          if (RayBox(origin, direction, box, ta, tb) && std::max(ta, t0) <= std::min(tb, t1))
          {
            expected = std::min(expected, std::max(ta, t0));
          }
        }
        const double tolerance = QueryTolerance * (1 + std::abs(expected));
        ASSERT_NEAR(result, expected, tolerance) << "ray " << n;
        // Stepping oracle: no sample before the answer lies in a visible leaf.
        const int steps = 2000;
        for (int s = 0; s <= steps && t1 > t0; ++s)
        {
          const double t = t0 + (t1 - t0) * s / steps;
          if (t >= result)
          {
            break;
          }
          const Vec3 p = origin + t * direction;
          for (const Box& box : visibleBoxes)
          {
            ASSERT_FALSE(Contains(box, p)) << "skipped a visible leaf at t " << t;
          }
        }
      }
    }
  }
}

TEST(MinMaxOctree, NonEmptyBoxesCoverVisibleLeavesExactly)
{
  std::mt19937 random(4);
  for (const auto& dims : QueryDimensions)
  {
    for (int leafSize : { 2, 4, 8 })
    {
      for (int blobs : { 0, 3, 40, 400 })
      {
        SparseScene scene;
        MakeSparseScene(random, dims, leafSize, blobs, scene);
        const MinMaxOctree& octree = scene.octree;
        const std::vector<Box> boxes = octree.NonEmptyBoxes();
        std::size_t leavesCovered = 0;
        for (const Box& box : boxes)
        {
          // Each box is a node box made only of visible leaves (the union is then exact): find
          // the node from the box's lower corner, the smallest level whose box matches.
          int level = 0;
          std::uint64_t node = 0;
          for (; level <= octree.GetDepth(); ++level)
          {
            const double span = static_cast<double>(leafSize << level);
            node = MortonEncode(static_cast<std::uint32_t>(box.lower.x / span),
              static_cast<std::uint32_t>(box.lower.y / span),
              static_cast<std::uint32_t>(box.lower.z / span));
            const Box candidate = octree.NodeBox(level, node);
            if (!octree.IsPadding(level, node) && candidate.lower.x == box.lower.x &&
              candidate.lower.y == box.lower.y && candidate.lower.z == box.lower.z &&
              candidate.upper.x == box.upper.x && candidate.upper.y == box.upper.y &&
              candidate.upper.z == box.upper.z)
            {
              break;
            }
          }
          ASSERT_LE(level, octree.GetDepth()) << "not a node box";
          // The node's leaves are the contiguous Morton range node * 8^level ...
          const std::uint64_t span = std::uint64_t(1) << (3 * level);
          for (std::uint64_t n = node * span; n < (node + 1) * span && n < scene.visibleLeaf.size();
               ++n)
          {
            if (!octree.IsPadding(0, n))
            {
              ASSERT_TRUE(ContainsBox(box, octree.NodeBox(0, n)));
              ASSERT_TRUE(scene.visibleLeaf[n]) << "box covers an empty leaf";
              ++leavesCovered;
            }
          }
        }
        std::size_t visible = 0;
        for (std::uint64_t n = 0; n < scene.visibleLeaf.size(); ++n)
        {
          visible += scene.visibleLeaf[n];
        }
        // Boxes are disjoint node boxes, so covered leaves are counted once each.
        EXPECT_EQ(leavesCovered, visible);
        if (blobs == 0)
        {
          EXPECT_TRUE(boxes.empty());
        }
      }
    }
  }
  // Unclassified: everything is non-empty, the root box.
  MinMaxOctree octree;
  std::string error;
  const int dims[3] = { 30, 20, 10 };
  ASSERT_TRUE(octree.Configure(dims, 4, error));
  const std::vector<Box> boxes = octree.NonEmptyBoxes();
  ASSERT_EQ(boxes.size(), 1u);
  EXPECT_EQ(boxes[0].upper.x, 29);
}
}
