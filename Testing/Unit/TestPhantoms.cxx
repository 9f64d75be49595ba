// TestPhantoms: unit tests for the procedural test volumes in Phantoms.h.
#include "reference/Phantoms.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <thread>

namespace
{

using accelvolume::GeneratePhantom;
using accelvolume::PhantomNames;
using accelvolume::PhantomVolume;

PhantomVolume Generate(const std::string& name, int x, int y, int z, double time = 0)
{
  const int dims[3] = { x, y, z };
  PhantomVolume volume;
  std::string error;
  EXPECT_TRUE(GeneratePhantom(name, dims, time, volume, error)) << error;
  EXPECT_TRUE(error.empty());
  return volume;
}

float At(const PhantomVolume& volume, int i, int j, int k)
{
  return volume.values[(static_cast<std::size_t>(k) * volume.dims[1] + j) * volume.dims[0] + i];
}

double MaximumDifference(const PhantomVolume& a, const PhantomVolume& b)
{
  double difference = 0;
  for (std::size_t i = 0; i < a.values.size(); ++i)
  {
    difference = std::max(difference, std::abs(double(a.values[i]) - b.values[i]));
  }
  return difference;
}

TEST(Phantoms, NamesListsAllWithVesselsFirst)
{
  const std::vector<std::string> expected = { "vessels", "shells", "blobs", "ramp", "box" };
  EXPECT_EQ(PhantomNames(), expected);
}

TEST(Phantoms, EverySizeAndRangeIsRight)
{
  for (const std::string& name : PhantomNames())
  {
    const PhantomVolume volume = Generate(name, 24, 20, 16, 0.3);
    EXPECT_EQ(volume.dims[0], 24);
    EXPECT_EQ(volume.dims[1], 20);
    EXPECT_EQ(volume.dims[2], 16);
    for (double s : volume.spacing)
    {
      EXPECT_EQ(s, 1.0);
    }
    ASSERT_EQ(volume.values.size(), 24u * 20u * 16u) << name;
    const auto range = std::minmax_element(volume.values.begin(), volume.values.end());
    EXPECT_GE(*range.first, 0.0f) << name;
    EXPECT_LE(*range.second, 1000.0f) << name;
    EXPECT_LT(*range.first, *range.second) << name << " should not be constant";
    EXPECT_TRUE(std::all_of(
      volume.values.begin(), volume.values.end(), [](float v) { return std::isfinite(v); }))
      << name;
  }
}

TEST(Phantoms, DeterministicAcrossRunsAndThreads)
{
  for (const std::string& name : PhantomNames())
  {
    const PhantomVolume first = Generate(name, 17, 13, 11, 0.4);
    const PhantomVolume second = Generate(name, 17, 13, 11, 0.4);
    EXPECT_EQ(first.values, second.values) << name;
    // Concurrent generation must give the same bits: there is no shared generator state.
    std::vector<PhantomVolume> results(4);
    std::vector<std::thread> threads;
    for (auto& result : results)
    {
      threads.emplace_back([&result, &name] { result = Generate(name, 17, 13, 11, 0.4); });
    }
    for (auto& thread : threads)
    {
      thread.join();
    }
    for (const auto& result : results)
    {
      EXPECT_EQ(result.values, first.values) << name;
    }
  }
}

TEST(Phantoms, TimeAnimatesSmoothlyAndPeriodically)
{
  for (const std::string& name : PhantomNames())
  {
    const PhantomVolume start = Generate(name, 32, 32, 32, 0.0);
    const PhantomVolume later = Generate(name, 32, 32, 32, 0.25);
    const PhantomVolume nearby = Generate(name, 32, 32, 32, 0.001);
    const PhantomVolume wrapped = Generate(name, 32, 32, 32, 1.0);
    EXPECT_GT(MaximumDifference(start, later), 1.0) << name << " does not change with time";
    EXPECT_LT(MaximumDifference(start, nearby), MaximumDifference(start, later) / 10)
      << name << " jumps for a tiny time step";
    EXPECT_LT(MaximumDifference(start, wrapped), 0.01) << name << " is not periodic in time";
  }
}

TEST(Phantoms, RampIsAnalyticAtTimeZero)
{
  const PhantomVolume ramp = Generate("ramp", 11, 3, 5);
  for (int k = 0; k < 5; ++k)
  {
    for (int j = 0; j < 3; ++j)
    {
      for (int i = 0; i < 11; ++i)
      {
        EXPECT_NEAR(At(ramp, i, j, k), 100.0 * i, 1e-3);
      }
    }
  }
  EXPECT_EQ(At(ramp, 0, 0, 0), 0.0f);
  EXPECT_EQ(At(ramp, 10, 2, 4), 1000.0f);
  EXPECT_EQ(Generate("ramp", 1, 4, 4).values, std::vector<float>(16, 0.0f));
}

TEST(Phantoms, BoxHasExactChords)
{
  const PhantomVolume box = Generate("box", 16, 12, 9);
  int chordX = 0, chordY = 0, chordZ = 0;
  for (int i = 0; i < 16; ++i)
  {
    chordX += At(box, i, 6, 4) > 0;
  }
  for (int j = 0; j < 12; ++j)
  {
    chordY += At(box, 8, j, 4) > 0;
  }
  for (int k = 0; k < 9; ++k)
  {
    chordZ += At(box, 8, 6, k) > 0;
  }
  EXPECT_EQ(chordX, 16 - 2 * 4);
  EXPECT_EQ(chordY, 12 - 2 * 3);
  EXPECT_EQ(chordZ, 9 - 2 * 2);
  EXPECT_EQ(At(box, 4, 3, 2), 1000.0f);
  EXPECT_EQ(At(box, 3, 3, 2), 0.0f);
  EXPECT_EQ(At(box, 11, 8, 6), 1000.0f);
  EXPECT_EQ(At(box, 12, 8, 6), 0.0f);
  for (float v : box.values)
  {
    EXPECT_TRUE(v == 0.0f || v == 1000.0f);
  }
}

TEST(Phantoms, ShapesSuitMaximumIntensityProjection)
{
  const PhantomVolume vessels = Generate("vessels", 64, 64, 64);
  std::vector<float> sorted = vessels.values;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_GT(sorted.back(), 700.0f) << "tubes should be bright";
  EXPECT_LT(sorted[sorted.size() / 2], 150.0f) << "background should be faint";
  EXPECT_GT(sorted[sorted.size() / 2], sorted[sorted.size() / 20]) << "background should vary";

  const PhantomVolume shells = Generate("shells", 65, 65, 65);
  EXPECT_LT(At(shells, 32, 32, 32), 50.0f) << "shells are hollow";
  float innermost = 0;
  for (int i = 32 + 6; i < 32 + 14; ++i)
  {
    innermost = std::max(innermost, At(shells, i, 32, 32));
  }
  EXPECT_GT(innermost, 900.0f) << "innermost shell near radius 0.16";

  const PhantomVolume blobs = Generate("blobs", 64, 64, 64);
  EXPECT_GT(*std::max_element(blobs.values.begin(), blobs.values.end()), 800.0f);
}

TEST(Phantoms, OddSizesWork)
{
  for (const std::string& name : PhantomNames())
  {
    const PhantomVolume thin = Generate(name, 1, 7, 300, 0.7);
    EXPECT_EQ(thin.values.size(), 7u * 300u) << name;
    const PhantomVolume single = Generate(name, 1, 1, 1);
    EXPECT_EQ(single.values.size(), 1u) << name;
  }
}

TEST(Phantoms, ErrorsLeaveOutputUntouched)
{
  PhantomVolume volume = Generate("ramp", 2, 2, 2);
  const std::vector<float> before = volume.values;
  std::string error;
  const int good[3] = { 4, 4, 4 };
  EXPECT_FALSE(GeneratePhantom("teapot", good, 0, volume, error));
  EXPECT_NE(error.find("unknown phantom 'teapot'"), std::string::npos) << error;
  EXPECT_NE(error.find("vessels"), std::string::npos) << "the error should list valid names";

  for (const auto& dims : { std::vector<int>{ 0, 4, 4 }, { 4, -1, 4 }, { 4, 4, 0 } })
  {
    error.clear();
    EXPECT_FALSE(GeneratePhantom("box", dims.data(), 0, volume, error));
    EXPECT_NE(error.find("at least 1"), std::string::npos) << error;
  }

  // 2048^3 is 2^33 voxels: refused from the arithmetic alone, without trying to allocate.
  const auto start = std::chrono::steady_clock::now();
  const int huge[3] = { 2048, 2048, 2048 };
  error.clear();
  EXPECT_FALSE(GeneratePhantom("vessels", huge, 0, volume, error));
  EXPECT_NE(error.find("2^31"), std::string::npos) << error;
  const int overflow[3] = { 2147483647, 2147483647, 2147483647 };
  EXPECT_FALSE(GeneratePhantom("vessels", overflow, 0, volume, error));
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(1));

  error.clear();
  EXPECT_FALSE(GeneratePhantom("ramp", good, std::nan(""), volume, error));
  EXPECT_FALSE(error.empty());
  EXPECT_EQ(volume.values, before);
}

} // namespace
