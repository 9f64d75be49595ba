// Random volumes of every scalar type and a checked decoder of run-length encodings, shared by
// the RunLengthVolume tests.
#ifndef accelvolume_test_RunLengthTestSupport_h
#define accelvolume_test_RunLengthTestSupport_h

#include "ShearWarpTestSupport.h"

#include "shearwarp/RunLengthVolume.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <type_traits>
#include <vector>

namespace accelvolume_test
{
using namespace accelvolume;

template <typename T>
ScalarType TypeOf();
template <>
inline ScalarType TypeOf<std::int8_t>()
{
  return ScalarType::Int8;
}
template <>
inline ScalarType TypeOf<std::uint8_t>()
{
  return ScalarType::UInt8;
}
template <>
inline ScalarType TypeOf<std::int16_t>()
{
  return ScalarType::Int16;
}
template <>
inline ScalarType TypeOf<std::uint16_t>()
{
  return ScalarType::UInt16;
}
template <>
inline ScalarType TypeOf<std::int32_t>()
{
  return ScalarType::Int32;
}
template <>
inline ScalarType TypeOf<float>()
{
  return ScalarType::Float32;
}
template <>
inline ScalarType TypeOf<double>()
{
  return ScalarType::Float64;
}

// A random small volume of T: values over [low, high], with NaN / infinite voxels for floats,
// and a range [rangeMin, rangeMax] inside the data range so classification clamps.
template <typename T>
struct RandomVolume
{
  std::vector<T> values;
  VolumeView view;
  double rangeMin = 0, rangeMax = 1;

  RandomVolume(std::mt19937& random, double low, double high)
  {
    std::uniform_int_distribution<int> size(1, 13);
    for (int& d : this->view.dims)
    {
      d = size(random);
    }
    if (random() % 4 == 0)
    {
      this->view.dims[random() % 3] = 1; // a one-voxel axis: zero gradient across it
    }
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const std::size_t count =
      static_cast<std::size_t>(this->view.dims[0]) * this->view.dims[1] * this->view.dims[2];
    // A smooth field plus noise, so runs have some length.
    const double phase[3] = { 6 * unit(random), 6 * unit(random), 6 * unit(random) };
    for (std::size_t n = 0; n < count; ++n)
    {
      const int x = static_cast<int>(n % this->view.dims[0]);
      const int y = static_cast<int>(n / this->view.dims[0] % this->view.dims[1]);
      const int z =
        static_cast<int>(n / (static_cast<std::size_t>(this->view.dims[0]) * this->view.dims[1]));
      const double smooth = 0.5 + 0.25 * std::sin(0.7 * x + phase[0]) +
        0.25 * std::sin(0.5 * y + phase[1]) * std::cos(0.6 * z + phase[2]);
      const double t = std::min(1.0, std::max(0.0, smooth + 0.3 * (unit(random) - 0.5)));
      double value = low + t * (high - low);
      if (std::is_integral<T>::value)
      {
        value = std::round(value);
      }
      else
      {
        const double special = unit(random);
        if (special < 0.06)
        {
          value = std::numeric_limits<double>::quiet_NaN();
        }
        else if (special < 0.07)
        {
          value = special < 0.065 ? std::numeric_limits<double>::infinity()
                                  : -std::numeric_limits<double>::infinity();
        }
      }
      this->values.push_back(static_cast<T>(value));
    }
    this->view.data = this->values.data();
    this->view.type = TypeOf<T>();
    this->rangeMin = low + 0.1 * unit(random) * (high - low);
    this->rangeMax = high - 0.1 * unit(random) * (high - low);
  }

  double At(const int p[3]) const
  {
    return static_cast<double>(this->values[p[0] +
      static_cast<std::size_t>(this->view.dims[0]) *
        (p[1] + static_cast<std::size_t>(this->view.dims[1]) * p[2])]);
  }
};

// Checks the run structure and decodes it into one entry per slice voxel (nullptr: not stored).
// Dense composite encodings hold one run per scanline; dense extreme encodings leave NaN voxels
// out (they are never kept), so they may have more.
template <typename Voxel>
std::vector<const Voxel*> Decode(
  const RunLengthVolume<Voxel>& e, int axis, const int dims[3], bool denseHasOneRun)
{
  std::vector<const Voxel*> decoded;
  EXPECT_EQ(e.axis, axis);
  EXPECT_EQ(e.sliceDims[0], dims[(axis + 1) % 3]);
  EXPECT_EQ(e.sliceDims[1], dims[(axis + 2) % 3]);
  EXPECT_EQ(e.sliceDims[2], dims[axis]);
  const int ni = e.sliceDims[0], nj = e.sliceDims[1], nk = e.sliceDims[2];
  const std::size_t rows = static_cast<std::size_t>(nj) * nk;
  if (e.rowStart.size() != rows + 1)
  {
    ADD_FAILURE() << "rowStart has " << e.rowStart.size() << " entries, want " << rows + 1;
    return decoded;
  }
  EXPECT_EQ(e.rowStart.front(), 0u);
  EXPECT_EQ(e.rowStart.back(), e.runs.size());
  decoded.assign(rows * ni, nullptr);
  std::uint64_t expectedOffset = 0; // runs pack their voxels in scanline order
  for (int k = 0; k < nk; ++k)
  {
    for (int j = 0; j < nj; ++j)
    {
      const std::size_t row = e.Row(j, k);
      EXPECT_LE(e.rowStart[row], e.rowStart[row + 1]) << "rowStart not monotone at " << row;
      if (e.rowStart[row] > e.rowStart[row + 1] || e.rowStart[row + 1] > e.runs.size())
      {
        return {};
      }
      std::int64_t previousEnd = -1;
      for (const VoxelRun* run = e.RunsBegin(j, k); run != e.RunsEnd(j, k); ++run)
      {
        EXPECT_LT(run->begin, run->end) << "empty run";
        EXPECT_LE(run->end, static_cast<std::uint32_t>(ni));
        // Sorted, non-overlapping and maximal (adjacent runs would have been one).
        EXPECT_GT(static_cast<std::int64_t>(run->begin), previousEnd) << "row " << row;
        EXPECT_EQ(run->offset, expectedOffset);
        if (run->end > static_cast<std::uint32_t>(ni) ||
          run->offset + (run->end - run->begin) > e.StoredVoxels() || run->begin >= run->end)
        {
          return {};
        }
        for (std::uint32_t i = run->begin; i < run->end; ++i)
        {
          decoded[row * ni + i] = &e.StoredVoxel(run->offset + (i - run->begin));
          EXPECT_EQ(FindVoxel(e, static_cast<int>(i), j, k), decoded[row * ni + i]);
        }
        previousEnd = run->end;
        expectedOffset = run->offset + (run->end - run->begin);
      }
      if (e.dense && denseHasOneRun)
      {
        EXPECT_EQ(e.rowStart[row + 1] - e.rowStart[row], 1u) << "dense: one run per scanline";
      }
    }
  }
  EXPECT_EQ(expectedOffset, e.StoredVoxels());
  return decoded;
}

template <typename Voxel, typename Same>
void ExpectSameArrays(const RunLengthVolume<Voxel>& a, const RunLengthVolume<Voxel>& b, Same same)
{
  EXPECT_EQ(a.rowStart, b.rowStart);
  ASSERT_EQ(a.runs.size(), b.runs.size());
  for (std::size_t r = 0; r < a.runs.size(); ++r)
  {
    EXPECT_EQ(a.runs[r].begin, b.runs[r].begin);
    EXPECT_EQ(a.runs[r].end, b.runs[r].end);
    EXPECT_EQ(a.runs[r].offset, b.runs[r].offset);
  }
  ASSERT_EQ(a.StoredVoxels(), b.StoredVoxels());
  for (std::size_t v = 0; v < a.StoredVoxels(); ++v)
  {
    ASSERT_TRUE(same(a.StoredVoxel(v), b.StoredVoxel(v))) << "voxel " << v;
  }
}

struct Totals
{
  std::uint64_t stored = 0, total = 0, runs = 0, nanVoxels = 0;
};

template <typename Trial>
void EveryType(std::mt19937& random, Trial trial, Totals& totals)
{
  trial(std::int8_t(), -120.0, 120.0, random, totals);
  trial(std::uint8_t(), 0.0, 255.0, random, totals);
  trial(std::int16_t(), -3000.0, 3000.0, random, totals);
  trial(std::uint16_t(), 0.0, 60000.0, random, totals);
  trial(std::int32_t(), -2.0e6, 2.0e6, random, totals);
  trial(float(), -1.0, 2.0, random, totals);
  trial(double(), -1.0, 2.0, random, totals);
}

}

#endif
