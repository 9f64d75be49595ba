// ShearWarpCompositor: CompositeScanline / CompositeBand against a naive dense compositor
// written here (every slice front to back, every pixel, bilinear resampling of the four corner
// voxels' premultiplied colours, voxels outside the volume transparent), for random views and
// random run layouts, with and without early termination, on sparse and dense encodings.
#include "ShearWarpTestSupport.h"

#include "shearwarp/RunLengthVolume.h"
#include "shearwarp/ShearWarpCompositor.h"
#include "shearwarp/ShearWarpFactorization.h"

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

// Slice-space grid (ni x nj x nk, i fastest) of optional voxels.
template <typename Voxel>
struct Grid
{
  int dims[3] = { 0, 0, 0 };
  std::vector<char> present;
  std::vector<Voxel> values;

  std::size_t Index(int i, int j, int k) const
  {
    return static_cast<std::size_t>(i) +
      static_cast<std::size_t>(this->dims[0]) * (j + static_cast<std::size_t>(this->dims[1]) * k);
  }
  // The voxel at (i, j, k), nullptr outside the volume or when absent.
  const Voxel* At(int i, int j, int k) const
  {
    if (i < 0 || j < 0 || k < 0 || i >= this->dims[0] || j >= this->dims[1] || k >= this->dims[2])
    {
      return nullptr;
    }
    const std::size_t at = this->Index(i, j, k);
    return this->present[at] ? &this->values[at] : nullptr;
  }
};

// The grid as a run-length encoding (runs of present voxels), or dense (every voxel, absent ones
// as `transparent`).
template <typename Voxel>
RunLengthVolume<Voxel> Encode(const Grid<Voxel>& grid, int axis, bool dense, Voxel transparent)
{
  RunLengthVolume<Voxel> e;
  e.axis = axis;
  e.dense = dense;
  std::copy(grid.dims, grid.dims + 3, e.sliceDims);
  e.rowStart.push_back(0);
  for (int k = 0; k < grid.dims[2]; ++k)
  {
    for (int j = 0; j < grid.dims[1]; ++j)
    {
      int i = 0;
      while (i < grid.dims[0])
      {
        if (!dense && !grid.present[grid.Index(i, j, k)])
        {
          ++i;
          continue;
        }
        VoxelRun run;
        run.begin = static_cast<std::uint32_t>(i);
        run.offset = e.voxels.size();
        while (i < grid.dims[0] && (dense || grid.present[grid.Index(i, j, k)]))
        {
          const std::size_t at = grid.Index(i, j, k);
          e.voxels.push_back(grid.present[at] ? grid.values[at] : transparent);
          ++i;
        }
        run.end = static_cast<std::uint32_t>(i);
        e.runs.push_back(run);
      }
      e.rowStart.push_back(e.runs.size());
    }
  }
  return e;
}

// Random blobs of classified voxels: runs of varied length, some scanlines empty.
Grid<ShadedVoxel> RandomShadedGrid(std::mt19937& random, const int dims[3], double opaqueness)
{
  Grid<ShadedVoxel> grid;
  std::copy(dims, dims + 3, grid.dims);
  const std::size_t count = static_cast<std::size_t>(dims[0]) * dims[1] * dims[2];
  grid.present.resize(count);
  grid.values.resize(count);
  const double centre[3] = { Uniform(random, 0, dims[0]), Uniform(random, 0, dims[1]),
    Uniform(random, 0, dims[2]) };
  const double radius = 0.45 * std::max({ dims[0], dims[1], dims[2] });
  for (int k = 0; k < dims[2]; ++k)
    for (int j = 0; j < dims[1]; ++j)
      for (int i = 0; i < dims[0]; ++i)
      {
        const double dx = i - centre[0], dy = j - centre[1], dz = k - centre[2];
        const double r = std::sqrt(dx * dx + dy * dy + dz * dz) / radius;
        const std::size_t at = grid.Index(i, j, k);
        grid.present[at] = r < 1.0 && Uniform(random, 0, 1) < 0.85;
        ShadedVoxel& v = grid.values[at];
        const double top = OpacityLevels - 1.0;
        v.opacity = static_cast<std::uint16_t>(
          1 + std::min(top, top * opaqueness * Uniform(random, 0.2, 1.0)));
        v.normal =
          random() % 10 == 0 ? NoNormal : static_cast<std::uint16_t>(random() % NormalCodes);
        for (int c = 0; c < 4; ++c)
        {
          v.colour[c] = static_cast<std::uint8_t>(random() % 256);
        }
      }
  return grid;
}

CompositeTables RandomTables(std::mt19937& random, bool shade)
{
  CompositeTables t;
  const double ratio = Uniform(random, 0.5, 2.0);
  t.opacity.resize(OpacityLevels + 1);
  for (int q = 0; q <= OpacityLevels; ++q)
  {
    t.opacity[q] = static_cast<float>(1.0 - std::pow(1.0 - q / double(OpacityLevels), ratio));
  }
  t.shade = shade;
  t.phong = false;
  if (shade)
  {
    // Coloured lights (a factor and a term per channel) or, every other table, white light
    // (one of each: the renderer's one-register shading).
    t.shadingStride = random() % 2 ? 6 : 2;
    const int channels = t.shadingStride / 2;
    t.shading.resize(t.shadingStride * (static_cast<std::size_t>(NormalCodes) + 1));
    for (std::size_t row = 0; row <= static_cast<std::size_t>(NormalCodes); ++row)
    {
      for (int c = 0; c < channels; ++c)
      {
        t.shading[t.shadingStride * row + c] = static_cast<float>(Uniform(random, 0.1, 1.3));
        t.shading[t.shadingStride * row + channels + c] =
          static_cast<float>(Uniform(random, 0.0, 0.3));
      }
    }
  }
  return t;
}

// Naive dense compositing of intermediate scanline v, in double: pixel u samples slice k at
// (u - offset_k[0], v - offset_k[1]) bilinearly from the premultiplied colours of its four
// corner voxels (absent or outside: transparent), slices front to back with the over operator.
// With a threshold <= 1 (early termination) a pixel stops once its opacity reaches it; `close`
// then flags the pixels whose opacity came within 1e-5 of the threshold, where float and double
// may decide differently.
struct NaiveScanline
{
  std::vector<double> rgba;
  std::vector<char> close;
};

NaiveScanline NaiveComposite(const Grid<ShadedVoxel>& grid, const ShearWarpFactorization& f,
  const CompositeTables& t, int v, double threshold = 2.0)
{
  const int width = f.intermediateSize[0];
  NaiveScanline result;
  result.rgba.assign(4 * static_cast<std::size_t>(width), 0.0);
  result.close.assign(static_cast<std::size_t>(width), 0);
  auto colour = [&](int i, int j, int k, double out[4])
  {
    const ShadedVoxel* voxel = grid.At(i, j, k);
    const double opacity = voxel ? t.opacity[voxel->opacity] : 0.0;
    for (int c = 0; c < 3; ++c)
    {
      double value = voxel ? voxel->colour[c] / 255.0 : 0.0;
      if (voxel && t.shade)
      {
        const std::size_t row = voxel->normal == NoNormal ? NormalCodes : voxel->normal;
        const int channels = t.shadingStride / 2;
        const float* shading = t.shading.data() + t.shadingStride * row;
        const int channel = channels == 3 ? c : 0;
        value = std::min(value * shading[channel] + shading[channels + channel], 1.0);
      }
      out[c] = value * opacity;
    }
    out[3] = opacity;
  };
  for (int s = 0; s < f.sliceDims[2]; ++s)
  {
    const int k = f.sliceStep > 0 ? s : f.sliceDims[2] - 1 - s;
    const double offset[2] = { f.shear[0] * k + f.translate[0], f.shear[1] * k + f.translate[1] };
    const double y = v - offset[1];
    const int j0 = static_cast<int>(std::floor(y));
    const double b = y - j0;
    for (int u = 0; u < width; ++u)
    {
      double* pixel = &result.rgba[4 * static_cast<std::size_t>(u)];
      if (pixel[3] >= threshold)
      {
        continue; // terminated
      }
      const double x = u - offset[0];
      const int i0 = static_cast<int>(std::floor(x));
      const double a = x - i0;
      double c00[4], c10[4], c01[4], c11[4];
      colour(i0, j0, k, c00);
      colour(i0 + 1, j0, k, c10);
      colour(i0, j0 + 1, k, c01);
      colour(i0 + 1, j0 + 1, k, c11);
      const double transmit = 1.0 - pixel[3];
      for (int c = 0; c < 4; ++c)
      {
        const double sample =
          (1 - a) * (1 - b) * c00[c] + a * (1 - b) * c10[c] + (1 - a) * b * c01[c] + a * b * c11[c];
        pixel[c] += transmit * sample;
      }
      if (std::abs(pixel[3] - threshold) < 1e-5)
      {
        result.close[u] = 1;
      }
    }
  }
  return result;
}

// Every scanline composited on its own (bands of one scanline).
std::vector<float> CompositeEachScanline(const RunLengthVolume<ShadedVoxel>& e,
  const ShearWarpFactorization& f, const CompositeTables& t, ScanlineCounters& counters)
{
  const std::size_t rowFloats = 4 * static_cast<std::size_t>(f.intermediateSize[0]);
  std::vector<float> rgba(rowFloats * f.intermediateSize[1], 0.0f);
  ScanlineWorkspace workspace;
  for (int v = 0; v < f.intermediateSize[1]; ++v)
  {
    CompositeScanline(e, f, t, v, rgba.data() + rowFloats * v, workspace, counters);
  }
  return rgba;
}

} // namespace

TEST(ShearWarpCompositing, CompositeScanlineEqualsNaiveCompositing)
{
  std::mt19937 random(8080);
  double worst = 0, worstTerminated = 0;
  std::uint64_t skipped = 0, sparseSamples = 0, denseSamples = 0, closePixels = 0;
  int palettes = 0;
  int whiteLightTables = 0, colouredLightTables = 0;
  for (int trial = 0; trial < 24; ++trial)
  {
    SCOPED_TRACE("trial " + std::to_string(trial));
    const int dims[3] = { 6 + static_cast<int>(random() % 18), 6 + static_cast<int>(random() % 18),
      1 + static_cast<int>(random() % 20) };
    const ShearWarpFactorization f = RandomFactorization(random, dims);
    // Saturating scenes (opaque voxels) every third trial, thin ones otherwise.
    const bool opaque = trial % 3 == 0;
    const Grid<ShadedVoxel> grid = RandomShadedGrid(random, f.sliceDims, opaque ? 1.0 : 0.15);
    CompositeTables t = RandomTables(random, trial % 2 == 1);
    if (t.shade)
    {
      ++(t.shadingStride == 2 ? whiteLightTables : colouredLightTables);
    }
    const RunLengthVolume<ShadedVoxel> sparse =
      Encode(grid, f.axes[2], false, ShadedVoxel{ 0, NoNormal, { 0, 0, 0, 0 } });
    const RunLengthVolume<ShadedVoxel> dense = Encode(grid, f.axes[2], true,
      ShadedVoxel{ 0, static_cast<std::uint16_t>(random() % NormalCodes), { 9, 9, 9, 9 } });
    const int height = f.intermediateSize[1];
    const std::size_t rowFloats = 4 * static_cast<std::size_t>(f.intermediateSize[0]);
    auto bands = [&](const RunLengthVolume<ShadedVoxel>& e, const CompositeTables& tables)
    {
      ScanlineCounters counters;
      return InRandomBands(random, f, rowFloats, 0.0f,
        [&](int v0, int v1, float* rgba, ScanlineWorkspace& workspace, double* work)
        { CompositeBand(e, f, tables, v0, v1, rgba, workspace, counters, work); });
    };

    // Brute force: no skip links, no early termination.
    t.earlyTermination = false;
    t.terminationLinks = false;
    ScanlineCounters plainCounters;
    const std::vector<float> plain = CompositeEachScanline(sparse, f, t, plainCounters);
    for (int v = 0; v < height; ++v)
    {
      const NaiveScanline naive = NaiveComposite(grid, f, t, v);
      for (std::size_t q = 0; q < rowFloats; ++q)
      {
        const double d = std::abs(plain[rowFloats * v + q] - naive.rgba[q]);
        worst = std::max(worst, d);
        ASSERT_LE(d, 1e-6) << "scanline " << v << " pixel " << q / 4 << " channel " << q % 4;
      }
    }
    EXPECT_EQ(plainCounters.terminatedPixelVisits, 0u);
    EXPECT_TRUE(BitIdentical(bands(sparse, t), plain)) << "bands";
    // Skip links alone (no termination) skip nothing; the dense encoding gives the same bits.
    t.terminationLinks = true;
    ScanlineCounters linkCounters, denseCounters;
    EXPECT_TRUE(BitIdentical(CompositeEachScanline(sparse, f, t, linkCounters), plain));
    EXPECT_TRUE(BitIdentical(CompositeEachScanline(dense, f, t, denseCounters), plain));
    EXPECT_TRUE(BitIdentical(bands(dense, t), plain)) << "dense bands";
    EXPECT_LE(plainCounters.samples, denseCounters.samples);
    sparseSamples += plainCounters.samples;
    denseSamples += denseCounters.samples;

    // Early termination: each pixel is the naive one stopped once its opacity reached the
    // threshold, so it moves by no more than what it had left to gain, 1 - threshold.
    t.earlyTermination = true;
    t.terminationThreshold = static_cast<float>(Uniform(random, 0.7, 0.99));
    ScanlineCounters terminatedCounters;
    const std::vector<float> terminated = CompositeEachScanline(sparse, f, t, terminatedCounters);
    for (int v = 0; v < height; ++v)
    {
      const NaiveScanline full = NaiveComposite(grid, f, t, v);
      const NaiveScanline stopped = NaiveComposite(grid, f, t, v, t.terminationThreshold);
      for (std::size_t q = 0; q < rowFloats; ++q)
      {
        const double got = terminated[rowFloats * v + q];
        const double d = std::abs(got - full.rgba[q]);
        worstTerminated = std::max(worstTerminated, d);
        ASSERT_LE(d, 1.0 - t.terminationThreshold + 1e-6) << "scanline " << v;
        if (!stopped.close[q / 4])
        {
          ASSERT_NEAR(got, stopped.rgba[q], 1e-6)
            << "scanline " << v << " pixel " << q / 4 << " channel " << q % 4;
        }
        closePixels += q % 4 == 0 && stopped.close[q / 4];
      }
    }
    EXPECT_LE(terminatedCounters.samples, plainCounters.samples);
    if (opaque)
    {
      EXPECT_GT(terminatedCounters.terminatedPixelVisits, 0u);
      EXPECT_LT(terminatedCounters.samples, plainCounters.samples);
    }
    skipped += terminatedCounters.terminatedPixelVisits;
    // Bands share voxel scanlines between their rows, also with termination: same bits.
    EXPECT_TRUE(BitIdentical(bands(sparse, t), terminated)) << "bands, early termination";
    // Termination without skip links (the dense baseline keeps compositing) is the naive image.
    t.terminationLinks = false;
    ScanlineCounters noLinks;
    EXPECT_TRUE(BitIdentical(CompositeEachScanline(sparse, f, t, noLinks), plain));
    if (!t.shade)
    {
      // Unshaded, the palette encoding (colours looked up by index, the renderer's way for
      // unshaded encodings) gives the same bits, terminated or not, on uneven threads too.
      RunLengthVolume<ShadedVoxel> paletted = sparse;
      for (ShadedVoxel& voxel : paletted.voxels)
      {
        voxel.normal = NoNormal; // unshaded encodings have none
      }
      ASSERT_TRUE(AssignPalette(paletted, UnevenThreadedFor(3)));
      CompositeTables withPalette = t;
      BuildPaletteColours(paletted.palette, withPalette, UnevenThreadedFor(3));
      EXPECT_EQ(withPalette.paletteColours.size(), 4 * paletted.palette.size());
      withPalette.terminationLinks = true;
      EXPECT_TRUE(BitIdentical(bands(paletted, withPalette), terminated)) << "palette";
      withPalette.earlyTermination = false;
      withPalette.terminationLinks = false;
      ScanlineCounters paletteCounters;
      EXPECT_TRUE(
        BitIdentical(CompositeEachScanline(paletted, f, withPalette, paletteCounters), plain))
        << "palette, no termination";
      // The palette encoding holds indices only (its voxels released); without the precomputed
      // colours each voxel's palette entry is converted as it is read (the code that converted
      // the palette's entries): the same bits again.
      EXPECT_TRUE(paletted.voxels.empty());
      withPalette.paletteColours.clear();
      withPalette.earlyTermination = true;
      withPalette.terminationLinks = true;
      ScanlineCounters convertedCounters;
      EXPECT_TRUE(BitIdentical(
        CompositeEachScanline(paletted, f, withPalette, convertedCounters), terminated))
        << "palette, colours converted per voxel";
      ++palettes;
    }
  }
  std::printf("[ measured ] composite scanline vs naive: max |difference| %.3g; with early "
              "termination %.3g from the full naive image; samples sparse %llu dense %llu; "
              "skipped %llu; %llu pixels too close to the threshold to compare exactly\n",
    worst, worstTerminated, static_cast<unsigned long long>(sparseSamples),
    static_cast<unsigned long long>(denseSamples), static_cast<unsigned long long>(skipped),
    static_cast<unsigned long long>(closePixels));
  EXPECT_LT(sparseSamples, denseSamples);
  EXPECT_GT(skipped, 0u);
  EXPECT_GT(palettes, 0);
  EXPECT_GT(whiteLightTables, 0);
  EXPECT_GT(colouredLightTables, 0);
}
