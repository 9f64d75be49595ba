// ShearWarpCompositor: ExtremeScanline / ExtremeBand (MIP, MinIP) against a naive maximum /
// minimum over every bilinear sample written here: exact where the naive value is visible (at
// or beyond the encoding's threshold), never beyond it elsewhere; dense encodings, skip links
// and bands change nothing.
#include "ShearWarpTestSupport.h"

#include "shearwarp/RunLengthVolume.h"
#include "shearwarp/ShearWarpCompositor.h"
#include "shearwarp/ShearWarpFactorization.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

using namespace accelvolume;
using namespace accelvolume_test;

namespace
{

// A random float volume (object space) with NaN voxels, and its quantized values.
struct ExtremeScene
{
  int dims[3];
  std::vector<float> values;
  VolumeView view;
  double range[2] = { -0.2, 1.2 }; // values beyond clamp: plateaus at the extremes

  // Quantized value of slice voxel (i, j, k) for principal axis `axis`, or -1 when NaN or outside.
  int Quantized(int axis, int i, int j, int k, const int sliceDims[3]) const
  {
    if (i < 0 || j < 0 || k < 0 || i >= sliceDims[0] || j >= sliceDims[1] || k >= sliceDims[2])
    {
      return -1;
    }
    int p[3];
    SliceToObject(axis, i, j, k, p);
    const double s = this->values[p[0] + this->dims[0] * (p[1] + this->dims[1] * p[2])];
    if (std::isnan(s))
    {
      return -1;
    }
    const double q = (s - this->range[0]) * (65535.0 / (this->range[1] - this->range[0]));
    return static_cast<int>(std::lround(std::min(std::max(q, 0.0), 65535.0)));
  }
};

ExtremeScene RandomExtremeScene(std::mt19937& random)
{
  ExtremeScene scene;
  for (int& d : scene.dims)
  {
    d = 4 + static_cast<int>(random() % 18);
  }
  const double phase = Uniform(random, 0, 6);
  for (int z = 0; z < scene.dims[2]; ++z)
    for (int y = 0; y < scene.dims[1]; ++y)
      for (int x = 0; x < scene.dims[0]; ++x)
      {
        double s = 0.5 + 0.8 * std::sin(0.4 * x + phase) * std::cos(0.3 * y - 0.5 * z) +
          0.2 * Uniform(random, -1, 1);
        if (random() % 25 == 0)
        {
          s = std::numeric_limits<double>::quiet_NaN();
        }
        scene.values.push_back(static_cast<float>(s));
      }
  scene.view.data = scene.values.data();
  scene.view.type = ScalarType::Float32;
  std::copy(scene.dims, scene.dims + 3, scene.view.dims);
  return scene;
}

// Naive MIP / MinIP of scanline v over every slice and pixel: a sample counts when each corner
// it weighs is inside the volume and not NaN. The weights and the summation order are the
// compositor's (float, corners (i0, j0), (i0 + 1, j0), (i0, j0 + 1), (i0 + 1, j0 + 1)) so the
// values can be compared exactly. No sample: -inf (MIP) / +inf (MinIP).
std::vector<float> NaiveExtreme(
  const ExtremeScene& scene, const ShearWarpFactorization& f, bool maximum, int v)
{
  const int width = f.intermediateSize[0];
  const float none =
    maximum ? -std::numeric_limits<float>::infinity() : std::numeric_limits<float>::infinity();
  std::vector<float> value(static_cast<std::size_t>(width), none);
  const int axis = f.axes[2];
  for (int k = 0; k < f.sliceDims[2]; ++k) // the extreme does not depend on the order
  {
    const double offset[2] = { f.shear[0] * k + f.translate[0], f.shear[1] * k + f.translate[1] };
    const double fi = std::floor(offset[0]), fj = std::floor(offset[1]);
    const float aI = static_cast<float>(offset[0] - fi), aJ = static_cast<float>(offset[1] - fj);
    // Sample position (u - offset[0], v - offset[1]) lies in [i0, i0 + 1] x [j0, j0 + 1] with
    // the far corners weighted 1 - aI, 1 - aJ.
    const float w[4] = { aJ * aI, aJ * (1.0f - aI), (1.0f - aJ) * aI, (1.0f - aJ) * (1.0f - aI) };
    const int j0 = v - static_cast<int>(fj) - 1;
    for (int u = 0; u < width; ++u)
    {
      const int i0 = u - static_cast<int>(fi) - 1;
      const int corners[4][2] = { { i0, j0 }, { i0 + 1, j0 }, { i0, j0 + 1 }, { i0 + 1, j0 + 1 } };
      float sample = 0;
      bool valid = true;
      for (int c = 0; c < 4 && valid; ++c)
      {
        if (w[c] > 0)
        {
          const int q = scene.Quantized(axis, corners[c][0], corners[c][1], k, f.sliceDims);
          valid = q >= 0;
          sample += w[c] * static_cast<float>(q);
        }
      }
      if (valid)
      {
        value[u] = maximum ? std::max(value[u], sample) : std::min(value[u], sample);
      }
    }
  }
  return value;
}

} // namespace

TEST(ShearWarpCompositing, ExtremeScanlineEqualsNaiveWhereVisible)
{
  std::mt19937 random(4711);
  std::uint64_t visible = 0, hidden = 0, skipped = 0;
  for (int trial = 0; trial < 24; ++trial)
  {
    SCOPED_TRACE("trial " + std::to_string(trial));
    const ExtremeScene scene = RandomExtremeScene(random);
    const ShearWarpFactorization f = RandomFactorization(random, scene.dims);
    const bool maximum = trial % 2 == 0;
    const auto threshold =
      static_cast<std::uint16_t>(maximum ? 30000 + random() % 20000 : 10000 + random() % 20000);
    RunLengthVolume<ScalarVoxel> sparse, dense;
    std::string error;
    ASSERT_TRUE(EncodeExtreme(scene.view, scene.range[0], scene.range[1], maximum, threshold,
      f.axes[2], false, SerialParallelFor, sparse, error));
    ASSERT_TRUE(EncodeExtreme(scene.view, scene.range[0], scene.range[1], maximum, threshold,
      f.axes[2], true, SerialParallelFor, dense, error));
    float saturation = maximum ? 0.0f : 65535.0f;
    for (ScalarVoxel q : sparse.voxels)
    {
      saturation = maximum ? std::max(saturation, float(q)) : std::min(saturation, float(q));
    }
    const float none =
      maximum ? -std::numeric_limits<float>::infinity() : std::numeric_limits<float>::infinity();
    ScanlineWorkspace workspace;
    ScanlineCounters counters, skipCounters;
    const int width = f.intermediateSize[0];
    std::vector<float> image; // every scanline, skip links on
    for (int v = 0; v < f.intermediateSize[1]; ++v)
    {
      const std::vector<float> naive = NaiveExtreme(scene, f, maximum, v);
      std::vector<float> got(width, none), denseGot(width, none), skipGot(width, none);
      ExtremeScanline(sparse, f, maximum, saturation, false, v, got.data(), workspace, counters);
      ExtremeScanline(
        dense, f, maximum, saturation, false, v, denseGot.data(), workspace, counters);
      ExtremeScanline(
        sparse, f, maximum, saturation, true, v, skipGot.data(), workspace, skipCounters);
      // Dense: every sample, so exactly the naive value everywhere.
      EXPECT_TRUE(BitIdentical(denseGot, naive)) << "dense, scanline " << v;
      // Skip links stop only pixels at the volume's extreme: nothing changes.
      EXPECT_TRUE(BitIdentical(skipGot, got)) << "skip links, scanline " << v;
      image.insert(image.end(), skipGot.begin(), skipGot.end());
      for (int u = 0; u < width; ++u)
      {
        const bool show = maximum ? naive[u] >= threshold : naive[u] <= threshold;
        if (show)
        {
          ++visible;
          ASSERT_EQ(got[u], naive[u]) << "scanline " << v << " pixel " << u;
        }
        else
        {
          ++hidden;
          // Fewer samples, all true: never beyond the naive extreme, and still not visible.
          ASSERT_TRUE(maximum ? got[u] <= naive[u] : got[u] >= naive[u])
            << "scanline " << v << " pixel " << u << ": " << got[u] << " vs " << naive[u];
          ASSERT_FALSE(maximum ? got[u] >= threshold : got[u] <= threshold);
        }
      }
    }
    skipped += skipCounters.terminatedPixelVisits;
    // Bands (two voxel scanlines shared by consecutive rows), with and without skip links.
    for (bool links : { false, true })
    {
      ScanlineCounters bandCounters;
      const std::vector<float> banded = InRandomBands(random, f, width, none,
        [&](int v0, int v1, float* value, ScanlineWorkspace& ws, double* work) {
          ExtremeBand(sparse, f, maximum, saturation, links, v0, v1, value, ws, bandCounters, work);
        });
      EXPECT_TRUE(BitIdentical(banded, image)) << "bands, skip links " << links;
    }
  }
  EXPECT_GT(visible, 1000u);
  EXPECT_GT(hidden, 1000u);
  EXPECT_GT(skipped, 0u);
}
