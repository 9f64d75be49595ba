// TestMinMaxOctreeBuild: min-max octree layout, Morton codes, builders vs brute force,
// determinism and NaN handling.
#include "MinMaxOctreeTestSupport.h"
#include "RandomGeometry.h"
#include "skipping/MinMaxOctree.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iostream>
#include <limits>
#include <random>
#include <string>
#include <thread>
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

constexpr float Infinity = std::numeric_limits<float>::infinity();
constexpr int LeafSizes[] = { 4, 8, 16 };
// Odd shapes: flat and thin volumes, sizes one past / short of leaf multiples.
constexpr int OddDimensions[][3] = { { 1, 7, 300 }, { 255, 97, 61 }, { 1, 1, 1 }, { 2, 3, 5 },
  { 17, 33, 9 } };
constexpr int TimingRepeats = 5;
constexpr int ClassifyRepeats = 100;

// Full-range integers; floats spread widely, and for double some values beyond float's range
// (so the outward rounding to float is exercised).
template <typename T>
std::vector<T> RandomVolume(std::mt19937& random, const int dims[3])
{
  std::vector<T> volume(VoxelCount(dims));
  if (std::is_integral<T>::value)
  {
    std::uniform_int_distribution<long long> values(
      std::numeric_limits<T>::lowest(), std::numeric_limits<T>::max());
    for (T& v : volume)
    {
      v = static_cast<T>(values(random));
    }
  }
  else
  {
    for (T& v : volume)
    {
      v = static_cast<T>(Uniform(random, -1e6, 1e6));
    }
    if (std::is_same<T, double>::value && volume.size() > 2)
    {
      volume[random() % volume.size()] = static_cast<T>(1e300);
      volume[random() % volume.size()] = static_cast<T>(-1e40);
    }
  }
  return volume;
}

// Checks that low is the largest float <= exact (and symmetric for high), defined directly
// rather than by the builder's rounding code.
void ExpectLowerBound(float low, double exact)
{
  if (std::isinf(exact))
  {
    EXPECT_EQ(static_cast<double>(low), exact);
    return;
  }
  EXPECT_LE(static_cast<double>(low), exact);
  EXPECT_GT(static_cast<double>(std::nextafter(low, Infinity)), exact);
}

void ExpectUpperBound(float high, double exact)
{
  ExpectLowerBound(-high, -exact);
}

// Every node against the min/max over its voxel range, computed here by plain loops.
template <typename T>
void ExpectMatchesBruteForce(
  const MinMaxOctree& octree, const std::vector<T>& volume, const int dims[3])
{
  const int leafSize = octree.GetLeafSize();
  for (int level = 0; level <= octree.GetDepth(); ++level)
  {
    const OctreeLevel& nodes = octree.GetLevel(level);
    ASSERT_EQ(nodes.minimum.size(), nodes.maximum.size());
    const long long span = static_cast<long long>(leafSize) << level;
    for (std::uint64_t index = 0; index < nodes.minimum.size(); ++index)
    {
      std::uint32_t c[3];
      MortonDecode(index, c[0], c[1], c[2]);
      long long first[3], last[3];
      bool padding = false;
      for (int axis = 0; axis < 3; ++axis)
      {
        first[axis] = c[axis] * span;
        last[axis] = std::min<long long>(first[axis] + span, dims[axis] - 1);
        padding =
          padding || first[axis] > dims[axis] - 1 || c[axis] >= unsigned(nodes.gridSize[axis]);
      }
      ASSERT_EQ(padding, octree.IsPadding(level, index));
      double low = std::numeric_limits<double>::infinity();
      double high = -low;
      if (!padding)
      {
        for (long long z = first[2]; z <= last[2]; ++z)
        {
          for (long long y = first[1]; y <= last[1]; ++y)
          {
            for (long long x = first[0]; x <= last[0]; ++x)
            {
              const double v = volume[(z * dims[1] + y) * dims[0] + x];
              if (!std::isnan(v))
              {
                low = std::min(low, v);
                high = std::max(high, v);
              }
            }
          }
        }
      }
      SCOPED_TRACE("level " + std::to_string(level) + " index " + std::to_string(index));
      ExpectLowerBound(nodes.minimum[index], low);
      ExpectUpperBound(nodes.maximum[index], high);
      if (::testing::Test::HasFailure())
      {
        return;
      }
    }
  }
}

// Bit-identical levels.
void ExpectIdentical(const MinMaxOctree& a, const MinMaxOctree& b)
{
  ASSERT_EQ(a.GetDepth(), b.GetDepth());
  for (int level = 0; level <= a.GetDepth(); ++level)
  {
    const OctreeLevel& x = a.GetLevel(level);
    const OctreeLevel& y = b.GetLevel(level);
    ASSERT_EQ(x.minimum.size(), y.minimum.size());
    EXPECT_EQ(0, std::memcmp(x.minimum.data(), y.minimum.data(), x.minimum.size() * sizeof(float)));
    EXPECT_EQ(0, std::memcmp(x.maximum.data(), y.maximum.data(), x.maximum.size() * sizeof(float)));
  }
}

template <typename T>
class MinMaxOctreeBuild : public ::testing::Test
{
};
using ScalarTypes = ::testing::Types<std::uint8_t, std::int16_t, std::uint16_t, float, std::int8_t,
  std::int32_t, double>;
TYPED_TEST_SUITE(MinMaxOctreeBuild, ScalarTypes);

TYPED_TEST(MinMaxOctreeBuild, BothBuildersMatchBruteForce)
{
  std::mt19937 random(7);
  for (const auto& dims : OddDimensions)
  {
    const std::vector<TypeParam> volume = RandomVolume<TypeParam>(random, dims);
    for (int leafSize : LeafSizes)
    {
      SCOPED_TRACE(std::to_string(dims[0]) + "x" + std::to_string(dims[1]) + "x" +
        std::to_string(dims[2]) + " L=" + std::to_string(leafSize));
      std::string error;
      MinMaxOctree reference, parallel;
      ASSERT_TRUE(reference.Configure(dims, leafSize, error)) << error;
      ASSERT_TRUE(parallel.Configure(dims, leafSize, error)) << error;
      ASSERT_TRUE(reference.BuildReference(View(volume, dims), error)) << error;
      ASSERT_TRUE(parallel.BuildParallel(View(volume, dims), SerialFor, error)) << error;
      ExpectMatchesBruteForce(reference, volume, dims);
      ExpectMatchesBruteForce(parallel, volume, dims);
      ExpectIdentical(reference, parallel);
    }
  }
}

TYPED_TEST(MinMaxOctreeBuild, ParallelIsDeterministic)
{
  std::mt19937 random(11);
  const int dims[3] = { 67, 45, 129 };
  const std::vector<TypeParam> volume = RandomVolume<TypeParam>(random, dims);
  std::string error;
  MinMaxOctree serial, shuffled, threaded;
  for (MinMaxOctree* octree : { &serial, &shuffled, &threaded })
  {
    ASSERT_TRUE(octree->Configure(dims, 4, error)) << error;
  }
  ASSERT_TRUE(serial.BuildParallel(View(volume, dims), SerialFor, error));
  ASSERT_TRUE(shuffled.BuildParallel(View(volume, dims), ShuffledFor(3), error));
  ASSERT_TRUE(threaded.BuildParallel(View(volume, dims), ThreadedFor(4), error));
  ExpectIdentical(serial, shuffled);
  ExpectIdentical(serial, threaded);
  // Upper levels alone (the GPU path): overwrite them, rebuild from the leaves.
  for (int level = 1; level <= threaded.GetDepth(); ++level)
  {
    std::fill(
      threaded.GetLevel(level).minimum.begin(), threaded.GetLevel(level).minimum.end(), 0.f);
    std::fill(
      threaded.GetLevel(level).maximum.begin(), threaded.GetLevel(level).maximum.end(), 0.f);
  }
  threaded.BuildUpperLevels(ThreadedFor(3));
  ExpectIdentical(serial, threaded);
}

template <typename T>
class MinMaxOctreeNaN : public ::testing::Test
{
};
using FloatingTypes = ::testing::Types<float, double>;
TYPED_TEST_SUITE(MinMaxOctreeNaN, FloatingTypes);

TYPED_TEST(MinMaxOctreeNaN, NaNIsIgnored)
{
  std::mt19937 random(5);
  const int dims[3] = { 21, 19, 18 };
  std::vector<TypeParam> volume = RandomVolume<TypeParam>(random, dims);
  for (TypeParam& v : volume)
  {
    if (random() % 3 == 0)
    {
      v = std::numeric_limits<TypeParam>::quiet_NaN();
    }
  }
  // A whole leaf of NaN (leaf (1, 1, 1) with L = 4 covers voxels 4..8) becomes empty.
  for (int z = 4; z <= 8; ++z)
  {
    for (int y = 4; y <= 8; ++y)
    {
      for (int x = 4; x <= 8; ++x)
      {
        volume[(z * dims[1] + y) * dims[0] + x] = std::numeric_limits<TypeParam>::quiet_NaN();
      }
    }
  }
  std::string error;
  MinMaxOctree reference, parallel;
  ASSERT_TRUE(reference.Configure(dims, 4, error));
  ASSERT_TRUE(parallel.Configure(dims, 4, error));
  ASSERT_TRUE(reference.BuildReference(View(volume, dims), error));
  ASSERT_TRUE(parallel.BuildParallel(View(volume, dims), ShuffledFor(1), error));
  ExpectMatchesBruteForce(reference, volume, dims);
  ExpectMatchesBruteForce(parallel, volume, dims);
  ExpectIdentical(reference, parallel);
  const std::uint64_t leaf = MortonEncode(1, 1, 1);
  EXPECT_EQ(parallel.GetLevel(0).minimum[leaf], Infinity);
  EXPECT_EQ(parallel.GetLevel(0).maximum[leaf], -Infinity);
}

TEST(MinMaxOctree, MortonRoundTrip)
{
  std::mt19937 random(1);
  const std::uint32_t axisMask = (1u << 21) - 1;
  for (int n = 0; n < 10000; ++n)
  {
    const std::uint32_t x = n == 0 ? axisMask : random() & axisMask;
    const std::uint32_t y = n == 0 ? axisMask : random() & axisMask;
    const std::uint32_t z = n == 0 ? axisMask : random() & axisMask;
    std::uint64_t expected = 0;
    for (int bit = 0; bit < 21; ++bit)
    {
      expected |= std::uint64_t((x >> bit) & 1) << (3 * bit);
      expected |= std::uint64_t((y >> bit) & 1) << (3 * bit + 1);
      expected |= std::uint64_t((z >> bit) & 1) << (3 * bit + 2);
    }
    const std::uint64_t code = MortonEncode(x, y, z);
    ASSERT_EQ(code, expected);
    std::uint32_t u, v, w;
    MortonDecode(code, u, v, w);
    ASSERT_EQ(u, x);
    ASSERT_EQ(v, y);
    ASSERT_EQ(w, z);
  }
}

TEST(MinMaxOctree, ConfigureLayout)
{
  std::string error;
  MinMaxOctree octree;
  const int dims[3] = { 255, 97, 61 };
  ASSERT_TRUE(octree.Configure(dims, 8, error)) << error;
  // Leaf grid ceil(254/8), ceil(96/8), ceil(60/8) = 32, 12, 8, so Depth 5.
  EXPECT_EQ(octree.GetDepth(), 5);
  const OctreeLevel& leaves = octree.GetLevel(0);
  EXPECT_EQ(leaves.gridSize[0], 32);
  EXPECT_EQ(leaves.gridSize[1], 12);
  EXPECT_EQ(leaves.gridSize[2], 8);
  EXPECT_EQ(leaves.minimum.size(), MortonEncode(31, 11, 7) + 1);
  std::size_t total = 0;
  for (int level = 0; level <= octree.GetDepth(); ++level)
  {
    const OctreeLevel& nodes = octree.GetLevel(level);
    const int expected[3] = { (32 + (1 << level) - 1) >> level, (12 + (1 << level) - 1) >> level,
      (8 + (1 << level) - 1) >> level };
    for (int axis = 0; axis < 3; ++axis)
    {
      EXPECT_EQ(nodes.gridSize[axis], expected[axis]);
    }
    total += nodes.minimum.size();
  }
  EXPECT_EQ(octree.GetLevel(5).minimum.size(), 1u);
  EXPECT_EQ(octree.GetNumberOfNodes(), total);
  // Boxes: a node spans L * 2^l voxels plus the overlap, clamped; padding boxes are empty.
  const Box root = octree.NodeBox(5, 0);
  EXPECT_EQ(root.upper.x, 254);
  EXPECT_EQ(root.upper.y, 96);
  EXPECT_EQ(root.upper.z, 60);
  const Box leaf = octree.NodeBox(0, MortonEncode(2, 11, 0));
  EXPECT_EQ(leaf.lower.x, 16);
  EXPECT_EQ(leaf.upper.x, 24);
  EXPECT_EQ(leaf.lower.y, 88);
  EXPECT_EQ(leaf.upper.y, 96);
  EXPECT_TRUE(octree.IsPadding(0, MortonEncode(0, 12, 0)));
  EXPECT_TRUE(octree.NodeBox(0, MortonEncode(0, 12, 0)).IsEmpty());
  // One voxel (and an exact leaf multiple plus one) give a single leaf, Depth 0.
  const int one[3] = { 1, 1, 1 };
  ASSERT_TRUE(octree.Configure(one, 64, error));
  EXPECT_EQ(octree.GetDepth(), 0);
  EXPECT_EQ(octree.GetNumberOfNodes(), 1u);
  const int nine[3] = { 9, 9, 9 };
  ASSERT_TRUE(octree.Configure(nine, 8, error));
  EXPECT_EQ(octree.GetDepth(), 0);
}

TEST(MinMaxOctree, ConfigureRejectsBadInput)
{
  std::string error;
  MinMaxOctree octree;
  const int dims[3] = { 10, 10, 10 };
  for (int leafSize : { 0, 1, 3, 12, 128 })
  {
    EXPECT_FALSE(octree.Configure(dims, leafSize, error)) << leafSize;
    EXPECT_FALSE(error.empty());
  }
  const int zero[3] = { 10, 0, 10 };
  EXPECT_FALSE(octree.Configure(zero, 8, error));
  const int huge[3] = { 1 << 30, 1 << 30, 1 << 30 };
  EXPECT_FALSE(octree.Configure(huge, 2, error));
  const int large[3] = { 2048 * 8, 2048 * 8, 2048 * 8 + 2 }; // needs 2049^3 leaves in Morton
  EXPECT_FALSE(octree.Configure(large, 8, error));
  // Building without (successful) configuration or with other dims fails.
  std::vector<std::uint8_t> volume(1000);
  EXPECT_FALSE(octree.BuildParallel(View(volume, dims), SerialFor, error));
  ASSERT_TRUE(octree.Configure(dims, 8, error));
  const int other[3] = { 10, 10, 9 };
  EXPECT_FALSE(octree.BuildReference(View(volume, other), error));
}

// Timing sanity print for a 256^3 uint8 volume (not an assertion: machines differ).
TEST(MinMaxOctree, TimingPrint)
{
  using Clock = std::chrono::steady_clock;
  const int dims[3] = { 256, 256, 256 };
  std::vector<std::uint8_t> volume(VoxelCount(dims));
  std::mt19937 random(2);
  for (std::size_t i = 0; i < volume.size(); ++i)
  {
    volume[i] = static_cast<std::uint8_t>((i * 2654435761u >> 13) & 0xff);
  }
  std::string error;
  MinMaxOctree octree;
  ASSERT_TRUE(octree.Configure(dims, 8, error));
  const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  auto milliseconds = [](Clock::time_point a, Clock::time_point b)
  { return std::chrono::duration<double, std::milli>(b - a).count(); };
  auto best = [&](const ParallelFor& parallel)
  {
    double fastest = std::numeric_limits<double>::infinity();
    for (int r = 0; r < TimingRepeats; ++r)
    {
      const auto start = Clock::now();
      EXPECT_TRUE(octree.BuildParallel(View(volume, dims), parallel, error));
      fastest = std::min(fastest, milliseconds(start, Clock::now()));
    }
    return fastest;
  };
  const double serial = best(SerialFor);
  const double threaded = best(ThreadedFor(threads));
  const auto referenceStart = Clock::now();
  MinMaxOctree reference;
  ASSERT_TRUE(reference.Configure(dims, 8, error));
  ASSERT_TRUE(reference.BuildReference(View(volume, dims), error));
  const double referenceTime = milliseconds(referenceStart, Clock::now());
  ExpectIdentical(reference, octree);
  std::vector<float> table(256, 0.f);
  for (std::size_t i = 200; i < table.size(); ++i)
  {
    table[i] = 0.5f;
  }
  const auto classifyStart = Clock::now();
  for (int r = 0; r < ClassifyRepeats; ++r)
  {
    octree.Classify(table, 0.0, 255.0);
  }
  const double classify = milliseconds(classifyStart, Clock::now()) / ClassifyRepeats;
  std::cout << "[ timing ] 256^3 uint8, L=8, " << octree.GetNumberOfNodes() << " nodes: "
            << "BuildParallel serial " << serial << " ms, " << threads << " threads " << threaded
            << " ms; BuildReference " << referenceTime << " ms; Classify " << classify << " ms\n";
}
}
