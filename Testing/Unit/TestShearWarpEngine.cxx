// ShearWarpRenderer: images independent of bands, balancing, threads and the order the phases
// composite scanline ranges; run-length encoding exact against the dense baseline; Phong against
// the shading table; encodings cached per axis and version; bad arguments fail cleanly.
#include "ShearWarpEngineTestSupport.h"

#include "common/Unorm16.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

using namespace accelvolume;
using namespace accelvolume_test;

namespace
{
// BeginFrame on one thread: the first of the phases MPI ranks use.
::testing::AssertionResult BeginPhases(ShearWarpRenderer& renderer, const Scene& scene,
  const RayCastTransfer& tf, const ViewSetup& camera, const ShearWarpSettings& settings)
{
  ShearWarpStats stats;
  std::string error;
  if (renderer.BeginFrame(scene.view, scene.range[0], scene.range[1], 1, tf, 1, camera.lighting,
        camera.sw, settings, SerialParallelFor, stats, error))
  {
    return ::testing::AssertionSuccess();
  }
  return ::testing::AssertionFailure() << error;
}
}

TEST(ShearWarpEngine, ImagesIgnoreBandsBalancingAndThreads)
{
  const int dims[3] = { 40, 32, 24 };
  const ParallelFor threaded = UnevenThreadedFor(3);
  for (Blend blend :
    { Blend::Composite, Blend::Maximum, Blend::Minimum })
  {
    SCOPED_TRACE(BlendName(blend));
    const bool minimum = blend == Blend::Minimum;
    const Scene scene = MakeScene(dims, false, minimum ? Content::Inverted : Content::SphereAndBar);
    const RayCastTransfer tf = MakeTransfer(0.3f, minimum);
    const ViewSetup camera = MakeCamera(scene, 200, -35, Isotropic, 90, 70, 25, true);
    ShearWarpSettings settings;
    settings.blend = blend;
    ShearWarpRenderer reference;
    const Frame base = RenderFrame(reference, scene, tf, camera, settings);
    ExpectTransparentOutside(base, 90, 70);
    double alpha = 0;
    for (std::size_t p = 3; p < base.rgba.size(); p += 4)
    {
      alpha += base.rgba[p];
    }
    EXPECT_GT(alpha, 50.0); // something visible
    // The phases by hand, as MPI ranks use them: scanline ranges composited in any order.
    {
      ShearWarpRenderer phased;
      ASSERT_TRUE(BeginPhases(phased, scene, tf, camera, settings));
      const int rows = phased.GetFactorization().intermediateSize[1];
      for (int v1 = rows; v1 > 0; v1 -= 5)
      {
        phased.CompositeRows(std::max(0, v1 - 5), v1);
      }
      Frame frame;
      phased.Warp(SerialParallelFor, frame.rgba, frame.rectangle);
      EXPECT_TRUE(BitIdentical(frame.rgba, base.rgba)) << "phases";
      ASSERT_EQ(phased.GetScanlineSeconds().size(), static_cast<std::size_t>(rows));
      for (double seconds : phased.GetScanlineSeconds())
      {
        EXPECT_GE(seconds, 0.0);
      }
    }
    ShearWarpRenderer renderer; // one renderer: balancing learns from the frames before
    for (int bands : { 1, 2, 3, 7 })
    {
      for (bool balance : { false, true })
      {
        for (int p = 0; p < 2; ++p)
        {
          settings.bands = bands;
          settings.balance = balance;
          const Frame frame = RenderFrame(
            renderer, scene, tf, camera, settings, p ? threaded : ParallelFor(SerialParallelFor));
          EXPECT_TRUE(BitIdentical(frame.rgba, base.rgba))
            << bands << " bands, balance " << balance << ", threads " << p;
          // Several workers take BandsPerWorker bands each, dynamically.
          const int parts = bands > 1 ? bands * BandsPerWorker : 1;
          ASSERT_EQ(frame.stats.bandBounds.size(), static_cast<std::size_t>(parts) + 1);
          EXPECT_EQ(frame.stats.bandBounds.front(), 0);
          EXPECT_EQ(frame.stats.bandBounds.back(), frame.stats.intermediateSize[1]);
          EXPECT_TRUE(std::is_sorted(frame.stats.bandBounds.begin(), frame.stats.bandBounds.end()));
          EXPECT_EQ(frame.stats.samples, base.stats.samples);
          EXPECT_EQ(std::vector<int>(frame.rectangle, frame.rectangle + 4),
            std::vector<int>(base.rectangle, base.rectangle + 4));
        }
      }
    }
  }
}

TEST(ShearWarpEngine, OneWorkerSplitsLargeImagesIntoCacheSizedBands)
{
  // An intermediate image of several BandCacheBytes: even one worker composites it band by
  // band, and the image is the one of a single band over every scanline.
  const int dims[3] = { 180, 160, 20 };
  const Scene scene = MakeScene(dims, false, Content::SphereAndBar);
  const RayCastTransfer tf = MakeTransfer(0.3f, false);
  const ViewSetup camera = MakeCamera(scene, 200, -35, Isotropic, 240, 220, 25, true);
  for (Blend blend : { Blend::Composite, Blend::Maximum })
  {
    SCOPED_TRACE(BlendName(blend));
    ShearWarpSettings settings;
    settings.blend = blend;
    ShearWarpRenderer renderer;
    const Frame frame = RenderFrame(renderer, scene, tf, camera, settings);
    const int width = frame.stats.intermediateSize[0];
    const int rows = frame.stats.intermediateSize[1];
    const std::size_t pixelBytes = blend == Blend::Composite ? 16 : 4;
    const std::size_t bytes = pixelBytes * static_cast<std::size_t>(width) * rows;
    const std::size_t expected = (bytes + BandCacheBytes - 1) / BandCacheBytes;
    if (blend == Blend::Composite)
    {
      ASSERT_GT(expected, 1u); // the scene is large enough to need several bands
    }
    EXPECT_EQ(frame.stats.bandBounds.size(), expected + 1);

    ShearWarpRenderer single;
    ASSERT_TRUE(BeginPhases(single, scene, tf, camera, settings));
    single.CompositeRows(0, rows);
    Frame whole;
    single.Warp(SerialParallelFor, whole.rgba, whole.rectangle);
    EXPECT_TRUE(BitIdentical(whole.rgba, frame.rgba));
  }
}

TEST(ShearWarpEngine, BandWorkersConvertTheDisplayPixels)
{
  // Without the warp, Render's band workers convert their rows for display: the values of
  // converting the intermediate image afterwards, a zero column and row past it, each row's
  // visible span, whatever the bands and threads; the phases (MPI) leave them unset.
  const int dims[3] = { 40, 32, 24 };
  const Scene scene = MakeScene(dims, false, Content::SphereAndBar);
  const RayCastTransfer tf = MakeTransfer(0.3f, false);
  const ViewSetup camera = MakeCamera(scene, 200, -35, Isotropic, 90, 70, 25, true);
  for (Blend blend : { Blend::Composite, Blend::Maximum })
  {
    SCOPED_TRACE(BlendName(blend));
    ShearWarpSettings settings;
    settings.blend = blend;
    settings.warp = false;
    ShearWarpRenderer renderer;
    Frame frame = RenderFrame(renderer, scene, tf, camera, settings);
    EXPECT_EQ(renderer.GetDisplayPixels().rgba, nullptr) << "not asked for";
    settings.displayPixels = true;
    for (int bands : { 1, 3 })
    {
      settings.bands = bands;
      frame = RenderFrame(renderer, scene, tf, camera, settings,
        bands > 1 ? UnevenThreadedFor(3) : ParallelFor(SerialParallelFor));
      const ShearWarpDisplayPixels display = renderer.GetDisplayPixels();
      const int width = frame.stats.intermediateSize[0], rows = frame.stats.intermediateSize[1];
      ASSERT_NE(display.rgba, nullptr);
      ASSERT_EQ(display.width, width + 1);
      ASSERT_EQ(display.height, rows + 1);
      const float* intermediate = renderer.GetIntermediateImage();
      int visibleRows = 0;
      for (int v = 0; v <= rows; ++v)
      {
        const std::uint16_t* row = display.rgba + 4 * static_cast<std::size_t>(width + 1) * v;
        std::vector<std::uint16_t> expected(4 * static_cast<std::size_t>(width + 1), 0);
        if (v < rows)
        {
          ConvertToUnorm16(intermediate + 4 * static_cast<std::size_t>(width) * v,
            4 * static_cast<std::size_t>(width), expected.data());
        }
        ASSERT_TRUE(std::equal(expected.begin(), expected.end(), row)) << "row " << v;
        if (v == rows)
        {
          break;
        }
        int first = width, last = -1;
        for (int u = 0; u < width; ++u)
        {
          if (row[4 * u] || row[4 * u + 1] || row[4 * u + 2] || row[4 * u + 3])
          {
            first = std::min(first, u);
            last = u;
          }
        }
        if (last < 0)
        {
          EXPECT_GT(display.rowFirst[v], display.rowLast[v]) << "row " << v;
          continue;
        }
        ++visibleRows;
        EXPECT_EQ(display.rowFirst[v], first) << "row " << v;
        EXPECT_EQ(display.rowLast[v], last) << "row " << v;
      }
      EXPECT_GT(visibleRows, rows / 4);
      EXPECT_LT(visibleRows, rows); // a transparent margin too
    }
    ASSERT_TRUE(BeginPhases(renderer, scene, tf, camera, settings));
    EXPECT_EQ(renderer.GetDisplayPixels().rgba, nullptr) << "phases";
  }
}

TEST(ShearWarpEngine, RunLengthEncodingIsExactAgainstTheDenseVolume)
{
  const int dims[3] = { 36, 30, 26 };
  const Scene scene = MakeScene(dims, true);
  const Scene inverted = MakeScene(dims, true, Content::Inverted);
  const RayCastTransfer tf = MakeTransfer(0.6f);
  // MIP / MinIP: coarse tables whose opacity jumps between entries, so the visibility threshold
  // the renderer derives (which voxels the encoding may leave out) must be exactly right.
  RayCastTransfer high;
  high.rgba = { 0.1f, 0.2f, 0.3f, 0.0f, 0.2f, 0.3f, 0.4f, 0.0f, 0.3f, 0.9f, 0.5f, 0.8f, 0.4f, 0.5f,
    0.6f, 0.8f, 0.5f, 0.6f, 0.7f, 0.9f, 0.6f, 0.7f, 0.8f, 1.0f };
  RayCastTransfer low = high;
  for (int e = 0; e < 6; ++e)
  {
    std::copy(&high.rgba[4 * (5 - e)], &high.rgba[4 * (5 - e)] + 4, &low.rgba[4 * e]);
  }
  // Views down each axis from both sides, and oblique ones, so every principal axis and slice
  // order is exercised.
  const double views[][2] = { { 0, 0 }, { 180, 3 }, { 93, 5 }, { -88, -7 }, { 20, 70 },
    { 160, -65 }, { 35, 25 } };
  const double spacing[3] = { 1.0, 1.25, 0.8 };
  for (const auto& v : views)
  {
    for (int mode = 0; mode < 5; ++mode)
    {
      const Blend blend = mode < 3 ? Blend::Composite
        : mode == 3                         ? Blend::Maximum
                                            : Blend::Minimum;
      SCOPED_TRACE("view " + std::to_string(v[0]) + " " + std::to_string(v[1]) + " mode " +
        std::to_string(mode));
      const ViewSetup camera =
        MakeCamera(scene, v[0], v[1], spacing, 80, 64, 30, mode >= 1 && mode <= 2);
      ShearWarpSettings settings;
      settings.blend = blend;
      settings.shading = mode == 2 ? ShearWarpShading::Phong : ShearWarpShading::LookupTable;
      settings.earlyTermination = false;
      const bool minimum = blend == Blend::Minimum;
      const Scene& volume = minimum ? inverted : scene;
      const RayCastTransfer& table = minimum ? low : blend == Blend::Maximum ? high : tf;
      ShearWarpRenderer renderer;
      const Frame rle = RenderFrame(renderer, volume, table, camera, settings);
      settings.runLengthEncoding = false;
      const Frame dense = RenderFrame(renderer, volume, table, camera, settings);
      double alpha = 0;
      for (std::size_t q = 3; q < rle.rgba.size(); q += 4)
      {
        alpha += rle.rgba[q];
      }
      EXPECT_GT(alpha, 50.0);
      EXPECT_TRUE(BitIdentical(rle.rgba, dense.rgba));
      EXPECT_LT(rle.stats.storedVoxels, dense.stats.storedVoxels);
      EXPECT_LT(rle.stats.samples, dense.stats.samples);
      EXPECT_EQ(rle.stats.principalAxis, dense.stats.principalAxis);
      if (blend == Blend::Composite)
      {
        // Early termination moves no channel by more than 1 - threshold.
        settings.runLengthEncoding = true;
        settings.earlyTermination = true;
        settings.terminationThreshold = 0.95;
        const Frame terminated = RenderFrame(renderer, scene, tf, camera, settings);
        double worst = 0;
        for (std::size_t q = 0; q < rle.rgba.size(); ++q)
        {
          worst = std::max(worst, double(std::abs(terminated.rgba[q] - rle.rgba[q])));
        }
        EXPECT_LE(worst, 0.05 + 1e-5);
      }
    }
  }
}

// Bands skip the scanlines of each slice outside its first and last stored one, and the pairs
// of scanlines without stored voxels: single voxels on the first and last scanlines of slices,
// and empty slices, must still composite exactly as the dense volume.
TEST(ShearWarpEngine, RunLengthEncodingIsExactOnVoxelsAtTheSliceEdges)
{
  const int dims[3] = { 23, 19, 29 };
  const Scene scene = MakeScene(dims, false, Content::Edges);
  const RayCastTransfer tf = MakeTransfer(0.9f);
  const double views[][2] = { { 0, 0 }, { 180, 2 }, { 91, 4 }, { -89, -3 }, { 15, 80 },
    { 170, -75 }, { 40, 30 }, { -130, 25 } };
  for (const auto& v : views)
  {
    for (const Blend blend : { Blend::Composite, Blend::Maximum })
    {
      SCOPED_TRACE("view " + std::to_string(v[0]) + " " + std::to_string(v[1]));
      const ViewSetup camera = MakeCamera(scene, v[0], v[1], Isotropic, 70, 66, 24, false);
      ShearWarpSettings settings;
      settings.blend = blend;
      settings.earlyTermination = false;
      ShearWarpRenderer renderer;
      const Frame rle = RenderFrame(renderer, scene, tf, camera, settings);
      settings.runLengthEncoding = false;
      const Frame dense = RenderFrame(renderer, scene, tf, camera, settings);
      ASSERT_EQ(rle.rgba.size(), dense.rgba.size());
      double alpha = 0;
      for (std::size_t q = 3; q < rle.rgba.size(); q += 4)
      {
        alpha += blend == Blend::Composite ? rle.rgba[q] : 0;
      }
      EXPECT_TRUE(blend != Blend::Composite || alpha > 1.0);
      EXPECT_TRUE(BitIdentical(rle.rgba, dense.rgba));
      EXPECT_LT(rle.stats.samples, dense.stats.samples / 10);
    }
  }
}

TEST(ShearWarpEngine, PhongMatchesTheShadingTable)
{
  const int dims[3] = { 32, 28, 24 };
  const Scene scene = MakeScene(dims, false);
  const RayCastTransfer tf = MakeTransfer(0.6f);
  const ViewSetup camera = MakeCamera(scene, 55, 20, Isotropic, 64, 60, 22, true);
  ShearWarpSettings settings;
  ShearWarpRenderer renderer;
  const Frame table = RenderFrame(renderer, scene, tf, camera, settings);
  settings.shading = ShearWarpShading::Phong;
  const Frame phong = RenderFrame(renderer, scene, tf, camera, settings);
  double worst = 0;
  for (std::size_t q = 0; q < table.rgba.size(); ++q)
  {
    worst = std::max(worst, double(std::abs(table.rgba[q] - phong.rgba[q])));
  }
  EXPECT_LE(worst, 1e-4); // the same formulas, per code or per voxel
  // Shading must change the image.
  ShearWarpRenderer plainRenderer;
  ViewSetup unshaded = camera;
  unshaded.lighting.shade = false;
  const Frame plain = RenderFrame(plainRenderer, scene, tf, unshaded, settings);
  EXPECT_FALSE(BitIdentical(plain.rgba, table.rgba));
}

TEST(ShearWarpEngine, EncodingsAreCachedPerAxisAndVersion)
{
  const int dims[3] = { 30, 26, 22 };
  const Scene scene = MakeScene(dims, false);
  const RayCastTransfer tf = MakeTransfer();
  const RayCastTransfer other = MakeTransfer(0.9f);
  const ViewSetup alongZ = MakeCamera(scene, 10, 5, Isotropic, 48, 40, 20, false);
  const ViewSetup alongX = MakeCamera(scene, 80, 5, Isotropic, 48, 40, 20, false);
  for (Blend blend : { Blend::Composite, Blend::Maximum })
  {
    SCOPED_TRACE(BlendName(blend));
    ShearWarpSettings settings;
    settings.blend = blend;
    settings.backgroundEncodings = false; // each axis encoded when needed (see the next test)
    ShearWarpRenderer renderer;
    const Frame first = RenderFrame(renderer, scene, tf, alongZ, settings);
    EXPECT_GT(first.stats.encodeSeconds, 0.0);
    EXPECT_EQ(first.stats.principalAxis, 2);
    const Frame second = RenderFrame(renderer, scene, tf, alongZ, settings);
    EXPECT_EQ(second.stats.encodeSeconds, 0.0);
    EXPECT_TRUE(BitIdentical(first.rgba, second.rgba));
    // Another principal axis: a second encoding; back to the first: reused.
    const Frame x = RenderFrame(renderer, scene, tf, alongX, settings);
    EXPECT_EQ(x.stats.principalAxis, 0);
    EXPECT_GT(x.stats.encodeSeconds, 0.0);
    EXPECT_GT(x.stats.encodedBytes, first.stats.encodedBytes);
    EXPECT_EQ(RenderFrame(renderer, scene, tf, alongZ, settings).stats.encodeSeconds, 0.0);
    // Same versions, other table: the cached encoding is what the versions promise.
    const Frame stale = RenderFrame(renderer, scene, other, alongZ, settings, SerialParallelFor, 1);
    EXPECT_EQ(stale.stats.encodeSeconds, 0.0);
    // A new transfer version re-encodes and drops the encodings of the old one.
    const Frame changed =
      RenderFrame(renderer, scene, other, alongZ, settings, SerialParallelFor, 2);
    EXPECT_GT(changed.stats.encodeSeconds, 0.0);
    EXPECT_FALSE(BitIdentical(changed.rgba, first.rgba));
    EXPECT_EQ(RenderFrame(renderer, scene, other, alongZ, settings, SerialParallelFor, 2)
                .stats.encodeSeconds,
      0.0);
    // A new volume version re-encodes too.
    EXPECT_GT(RenderFrame(renderer, scene, other, alongZ, settings, SerialParallelFor, 2, 7)
                .stats.encodeSeconds,
      0.0);
    ShearWarpRenderer fresh;
    const Frame freshFrame =
      RenderFrame(fresh, scene, other, alongZ, settings, SerialParallelFor, 2);
    EXPECT_TRUE(BitIdentical(changed.rgba, freshFrame.rgba));
    // The encodings of the old transfer function (both axes) were dropped: only the new one is
    // held, as in a renderer that never saw the old one.
    EXPECT_EQ(changed.stats.encodedBytes, freshFrame.stats.encodedBytes);
  }
  // Turning shading on needs normals: a new encoding.
  ShearWarpRenderer renderer;
  ShearWarpSettings settings;
  settings.backgroundEncodings = false;
  RenderFrame(renderer, scene, tf, alongZ, settings);
  ViewSetup shaded = alongZ;
  shaded.lighting.shade = true;
  EXPECT_GT(RenderFrame(renderer, scene, tf, shaded, settings).stats.encodeSeconds, 0.0);
}

TEST(ShearWarpEngine, BackgroundEncodingsGiveTheSameImages)
{
  // Composite, shaded and not, RLE and dense: the other axes' encodings built in the background
  // from the first frame's give the images of encodings built from the volume, whichever axis a
  // later view needs and whenever the job finishes; after a frame on another axis (which waits
  // for the job when its axis is not ready yet) all three encodings are held.
  const int dims[3] = { 30, 26, 22 };
  const Scene scene = MakeScene(dims, false);
  const RayCastTransfer tf = MakeTransfer();
  const ViewSetup alongZ = MakeCamera(scene, 10, 5, Isotropic, 48, 40, 20, false);
  const ViewSetup alongX = MakeCamera(scene, 80, 5, Isotropic, 48, 40, 20, false);
  const ViewSetup alongY = MakeCamera(scene, 10, 80, Isotropic, 48, 40, 20, false);
  for (bool shade : { false, true })
  {
    for (bool rle : { true, false })
    {
      SCOPED_TRACE(std::string(shade ? "shaded" : "unshaded") + (rle ? ", RLE" : ", dense"));
      ShearWarpSettings background;
      background.runLengthEncoding = rle;
      ShearWarpSettings direct = background;
      direct.backgroundEncodings = false;
      ShearWarpRenderer withJob;
      ShearWarpRenderer without;
      std::size_t allAxes = 0;
      std::vector<int> axes;
      for (ViewSetup view : { alongZ, alongX, alongY, alongZ })
      {
        view.lighting.shade = shade;
        const Frame a = RenderFrame(withJob, scene, tf, view, background);
        const Frame b = RenderFrame(without, scene, tf, view, direct);
        EXPECT_TRUE(BitIdentical(a.rgba, b.rgba)) << "principal axis " << a.stats.principalAxis;
        EXPECT_EQ(a.stats.principalAxis, b.stats.principalAxis);
        axes.push_back(a.stats.principalAxis);
        allAxes = b.stats.encodedBytes; // the renderer without the job holds the axes seen
        if (axes.size() > 2)
        {
          EXPECT_EQ(a.stats.encodedBytes, allAxes); // every axis held by both now
        }
      }
      EXPECT_EQ(axes, (std::vector<int>{ 2, 0, 1, 2 }));
    }
  }
}

TEST(ShearWarpEngine, BadArgumentsFail)
{
  const int dims[3] = { 8, 8, 8 };
  const Scene scene = MakeScene(dims, false);
  const RayCastTransfer tf = MakeTransfer();
  const ViewSetup camera = MakeCamera(scene, 30, 20, Isotropic, 16, 16, 8, false);
  ShearWarpSettings settings;
  ShearWarpRenderer renderer;
  std::vector<float> rgba;
  int rectangle[4];
  ShearWarpStats stats;
  auto fails = [&](const VolumeView& volume, double rangeMin, const RayCastTransfer& transfer,
                 const ShearWarpView& view, const ShearWarpSettings& s, const char* what)
  {
    std::string error;
    EXPECT_FALSE(renderer.Render(volume, rangeMin, 255, 1, transfer, 1, camera.lighting, view, s,
      SerialParallelFor, rgba, rectangle, stats, error))
      << what;
    EXPECT_FALSE(error.empty()) << what;
  };
  VolumeView empty;
  fails(empty, 0, tf, camera.sw, settings, "no data");
  VolumeView flat = scene.view;
  flat.dims[2] = 0;
  fails(flat, 0, tf, camera.sw, settings, "zero dims");
  ShearWarpView noWidth = camera.sw;
  noWidth.width = 0;
  fails(scene.view, 0, tf, noWidth, settings, "width 0");
  ShearWarpView noHeight = camera.sw;
  noHeight.height = -2;
  fails(scene.view, 0, tf, noHeight, settings, "height -2");
  RayCastTransfer shortTable;
  shortTable.rgba = { 1, 1, 1, 1 };
  fails(scene.view, 0, shortTable, camera.sw, settings, "one-entry table");
  shortTable.rgba = { 1, 1, 1, 1, 1, 1 };
  fails(scene.view, 0, shortTable, camera.sw, settings, "ragged table");
  RayCastTransfer noDistance = tf;
  noDistance.opacityUnitDistance = 0;
  fails(scene.view, 0, noDistance, camera.sw, settings, "opacity unit distance 0");
  fails(scene.view, std::nan(""), tf, camera.sw, settings, "NaN range");
  ShearWarpSettings noBands = settings;
  noBands.bands = 0;
  fails(scene.view, 0, tf, camera.sw, noBands, "0 bands");
  // Every ray through one point (what the affine part of a perspective map degenerates to):
  // the depth row is a combination of the others.
  ShearWarpView singular = camera.sw;
  for (int c = 0; c < 4; ++c)
  {
    singular.voxelToImage[2][c] = singular.voxelToImage[0][c] - 2 * singular.voxelToImage[1][c];
  }
  fails(scene.view, 0, tf, singular, settings, "singular map");
  ShearWarpView zero = camera.sw;
  for (auto& row : zero.voxelToImage)
    for (double& value : row)
      value = 0;
  fails(scene.view, 0, tf, zero, settings, "zero map");
  // The renderer still works afterwards.
  std::string error;
  EXPECT_TRUE(renderer.Render(scene.view, 0, 255, 1, tf, 1, camera.lighting, camera.sw, settings,
    SerialParallelFor, rgba, rectangle, stats, error))
    << error;
  EXPECT_EQ(rgba.size(), 4u * 16 * 16);
}
