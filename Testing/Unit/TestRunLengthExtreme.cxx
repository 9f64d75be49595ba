// RunLengthVolume: the MIP / MinIP encoding stores exactly the voxels kept by the threshold,
// dilated by their 3x3 in-slice neighbours, minus NaN voxels, with their quantized scalars
// (every scalar type, every principal axis, sparse and dense), identical for any parallel split.
#include "RunLengthTestSupport.h"

#include "shearwarp/RunLengthVolume.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

using namespace accelvolume;
using namespace accelvolume_test;

namespace
{

template <typename T>
void ExtremeTrial(std::mt19937& random, double low, double high, Totals& totals)
{
  const RandomVolume<T> volume(random, low, high);
  const bool maximum = random() % 2 == 0;
  const bool dense = random() % 4 == 0;
  const int axis = static_cast<int>(random() % 3);
  const auto threshold = static_cast<std::uint16_t>(random() % 65536);
  RunLengthVolume<ScalarVoxel> encoded;
  std::string error;
  ASSERT_TRUE(EncodeExtreme(volume.view, volume.rangeMin, volume.rangeMax, maximum, threshold, axis,
    dense, SerialParallelFor, encoded, error))
    << error;
  const std::vector<const ScalarVoxel*> decoded = Decode(encoded, axis, volume.view.dims, false);
  ASSERT_FALSE(decoded.empty());
  const int ni = encoded.sliceDims[0], nj = encoded.sliceDims[1], nk = encoded.sliceDims[2];
  const double scale = 65535.0 / (volume.rangeMax - volume.rangeMin);
  for (int k = 0; k < nk; ++k)
  {
    std::vector<int> quantized(static_cast<std::size_t>(ni) * nj, -1); // -1: NaN
    std::vector<char> kept(quantized.size(), 0);
    for (int j = 0; j < nj; ++j)
    {
      for (int i = 0; i < ni; ++i)
      {
        int p[3];
        SliceToObject(axis, i, j, k, p);
        const double s = volume.At(p);
        if (std::isnan(s))
        {
          continue;
        }
        const int q = static_cast<int>(
          std::lround(std::min(std::max((s - volume.rangeMin) * scale, 0.0), 65535.0)));
        quantized[j * ni + i] = q;
        kept[j * ni + i] = dense || (maximum ? q >= threshold : q <= threshold);
      }
    }
    for (int j = 0; j < nj; ++j)
    {
      for (int i = 0; i < ni; ++i)
      {
        bool near = false;
        for (int y = std::max(j - 1, 0); y <= std::min(j + 1, nj - 1); ++y)
        {
          for (int x = std::max(i - 1, 0); x <= std::min(i + 1, ni - 1); ++x)
          {
            near = near || kept[y * ni + x];
          }
        }
        const bool stored = near && quantized[j * ni + i] >= 0;
        const ScalarVoxel* got = decoded[(static_cast<std::size_t>(k) * nj + j) * ni + i];
        ASSERT_EQ(got != nullptr, stored)
          << "slice voxel " << i << " " << j << " " << k << " axis " << axis << " max " << maximum
          << " dense " << dense << " threshold " << threshold;
        if (stored)
        {
          ASSERT_EQ(static_cast<int>(*got), quantized[j * ni + i]);
          ++totals.stored;
        }
      }
    }
  }
  totals.total += decoded.size();
  totals.runs += encoded.runs.size();

  RunLengthVolume<ScalarVoxel> threaded;
  ASSERT_TRUE(EncodeExtreme(volume.view, volume.rangeMin, volume.rangeMax, maximum, threshold, axis,
    dense, UnevenThreadedFor(4), threaded, error));
  ExpectSameArrays(encoded, threaded, [](ScalarVoxel a, ScalarVoxel b) { return a == b; });
}

} // namespace

TEST(RunLengthVolume, ExtremeEncodingKeepsDilatedVisibleVoxels)
{
  std::mt19937 random(31337);
  Totals totals;
  for (int round = 0; round < 12; ++round)
  {
    EveryType(
      random,
      [](auto zero, double low, double high, std::mt19937& r, Totals& t)
      {
        using T = decltype(zero);
        ExtremeTrial<T>(r, low, high, t);
      },
      totals);
    if (HasFatalFailure())
    {
      return;
    }
  }
  EXPECT_GT(totals.stored, totals.total / 10);
  EXPECT_LT(totals.stored, totals.total * 9 / 10);
}
