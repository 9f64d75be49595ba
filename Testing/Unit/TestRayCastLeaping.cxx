// RayCastEngine's leaping: every leaping mode (octree, distance map, octant maps, cell table,
// rays approaching together) gives bit-identical images to plain ray casting, on random volumes,
// transfer functions and views.
#include "raycast/RayCastEngine.h"

#include "RayCastEngineTestSupport.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

using namespace accelvolume;
using namespace accelvolume_test::raycast_engine;

TEST(RayCastEngine, LeapingIsPixelIdenticalOnRandomVolumesAndTransferFunctions)
{
  std::mt19937 random(20261125);
  const ScalarType types[] = { ScalarType::UInt8, ScalarType::UInt16, ScalarType::Int16,
    ScalarType::Float32 };
  std::uint64_t leapedOctree = 0, leapedDistance = 0, leapedCell = 0;
  for (int trial = 0; trial < 12; ++trial)
  {
    const int dims[3] = { 20 + trial % 5 * 3, 17 + trial % 3 * 5, 15 + trial % 4 * 4 };
    const Scene scene = MakeScene(types[trial % 4], dims, 0.1 * trial);
    RayCastTransfer transfer;
    transfer.rgba = RandomTable(random, 256, false);
    transfer.opacityUnitDistance = 2.0;
    RayCastLighting lighting;
    const bool shaded = trial % 3 == 1;
    if (shaded)
    {
      lighting.shade = true;
      lighting.model.lights.emplace_back(); // white, shining along -z
    }
    const Blend blend = trial % 4 == 3 ? Blend::Additive : Blend::Composite;
    RayCastSettings settings = BaseSettings(dims, blend);
    settings.earlyTermination = trial % 2 == 0;
    const RayCastView view =
      MakeView(RandomCamera(random, dims, trial % 5 == 2), 37, 29, 1.0, 500.0);
    settings.leap = LeapMode::None;
    settings.cellLeap = false;
    const Result plain = Cast(scene, transfer, lighting, view, settings);
    for (LeapMode leap : { LeapMode::None, LeapMode::Octree, LeapMode::DistanceMap })
    {
      for (bool cell : { false, true })
      {
        settings.leap = leap;
        settings.cellLeap = cell;
        const Result leaped = Cast(scene, transfer, lighting, view, settings);
        EXPECT_TRUE(Identical(plain.rgba, leaped.rgba))
          << "trial " << trial << " leap " << static_cast<int>(leap) << " cell " << cell;
        EXPECT_LE(leaped.counters.samples, plain.counters.samples);
        EXPECT_LE(leaped.counters.rays, plain.counters.rays); // leaping culls rays in image space
        leapedOctree += leaped.counters.leapedOctree;
        leapedDistance += leaped.counters.leapedDistance;
        leapedCell += leaped.counters.leapedCell;
      }
    }
  }
  // The comparison above must have exercised every mechanism.
  EXPECT_GT(leapedOctree, 1000u);
  EXPECT_GT(leapedDistance, 1000u);
  EXPECT_GT(leapedCell, 100u);
}

TEST(RayCastEngine, ExtremeLeapingIsExact)
{
  std::mt19937 random(7);
  for (int trial = 0; trial < 6; ++trial)
  {
    const int dims[3] = { 24, 21, 19 };
    const Scene scene =
      MakeScene(trial % 2 ? ScalarType::UInt16 : ScalarType::Float32, dims, 0.3 * trial);
    RayCastTransfer transfer;
    transfer.rgba = RandomTable(random, 128, true);
    RayCastSettings settings = BaseSettings(dims, trial % 3 == 2 ? Blend::Minimum : Blend::Maximum);
    const RayCastView view = MakeView(RandomCamera(random, dims, trial == 4), 31, 33, 1.0, 500.0);
    settings.leap = LeapMode::None;
    const Result plain = Cast(scene, transfer, RayCastLighting(), view, settings);
    settings.leap = LeapMode::Octree;
    const Result leaped = Cast(scene, transfer, RayCastLighting(), view, settings);
    EXPECT_TRUE(Identical(plain.rgba, leaped.rgba)) << "trial " << trial;
    if (settings.blend == Blend::Maximum)
    {
      EXPECT_GT(leaped.counters.leapedOctree, 0u);
    }
  }
}

// Composite rays leap the empty space before their first non-empty cell a group at a time
// (approachTogether); each ray then resumes its own walk where it would have arrived alone:
// the same bits as rays cast one by one and as no leaping, on both walks (batched for
// semi-transparent tables, per sample for opaque ones), with cell leaping, with two crop
// regions (rays of several intervals) and on perspective and parallel views.
TEST(RayCastEngine, RaysApproachingTogetherLeapAsAlone)
{
  std::mt19937 random(29);
  const int dims[3] = { 41, 27, 33 };
  for (int trial = 0; trial < 8; ++trial)
  {
    const Scene scene =
      MakeScene(trial % 2 ? ScalarType::UInt16 : ScalarType::Float32, dims, 0.1 * trial);
    RayCastTransfer transfer;
    transfer.rgba = RandomTable(random, 256, false);
    const bool opaque = trial % 4 >= 2;
    for (std::size_t i = 3; i < transfer.rgba.size(); i += 4)
    {
      transfer.rgba[i] = opaque ? std::min(1.0f, 4.0f * transfer.rgba[i]) : 0.3f * transfer.rgba[i];
    }
    RayCastLighting lighting;
    lighting.shade = trial % 3 != 0;
    lighting.model.lights.emplace_back();
    RayCastSettings settings = BaseSettings(dims, Blend::Composite);
    settings.leap = LeapMode::DistanceMap;
    settings.cellLeap = trial == 5;
    // Every pixel casts its ray, so the rays counted compare (the footprint that leaves some
    // without one: ScreenFootprintCullsRaysWithTheSameImage).
    settings.screenFootprint = false;
    if (trial >= 4)
    {
      // Two crop regions side by side along x: rays meet one or two intervals.
      settings.regions = { { { 0, 0, 0 }, { 15, dims[1] - 1.0, dims[2] - 1.0 } },
        { { 25, 2, 3 }, { dims[0] - 1.0, dims[1] - 1.0, dims[2] - 1.0 } } };
    }
    const RayCastView view =
      MakeView(RandomCamera(random, dims, trial % 2 == 1), 47, 39, 1.0, 500.0);
    const Result together = Cast(scene, transfer, lighting, view, settings);
    EXPECT_GT(together.counters.distanceLeaps, 100u) << "trial " << trial;
    EXPECT_GT(together.counters.samples, 20u) << "trial " << trial;
    settings.approachTogether = false;
    const Result alone = Cast(scene, transfer, lighting, view, settings);
    EXPECT_TRUE(Identical(together.rgba, alone.rgba)) << "trial " << trial;
    EXPECT_EQ(together.counters.rays, alone.counters.rays) << "trial " << trial;
    settings.leap = LeapMode::None;
    settings.cellLeap = false;
    const Result unleaped = Cast(scene, transfer, lighting, view, settings);
    EXPECT_TRUE(Identical(together.rgba, unleaped.rgba)) << "trial " << trial;
    if (!opaque)
    {
      settings.leap = LeapMode::DistanceMap;
      settings.approachTogether = true;
      settings.batchedComposite = false;
      const Result perSample = Cast(scene, transfer, lighting, view, settings);
      EXPECT_TRUE(Identical(together.rgba, perSample.rgba)) << "trial " << trial << ": per sample";
    }
  }
}

// Distance-map leaping reads per ray its direction octant's map (octantDistanceMaps): the same
// bits as the chessboard map alone and as no leaping, with fewer leaps, on views whose rays head
// into one octant (parallel), four (straight down the z axis) and more (the eye inside the
// volume, a wide view), on both walks; the frame builds the maps of exactly those octants.
TEST(RayCastEngine, OctantDistanceMapsLeapFartherWithTheSameImage)
{
  std::mt19937 random(41);
  const int dims[3] = { 41, 27, 33 };
  const Vec3 centre{ 20, 13, 16 };
  // One octant's map in CellBricks layout: 10 x 7 x 8 bricks of 64 cells.
  const std::size_t octantBytes = 10 * 7 * 8 * 64;
  for (int trial = 0; trial < 6; ++trial)
  {
    const Scene scene =
      MakeScene(trial % 2 ? ScalarType::UInt16 : ScalarType::UInt8, dims, 0.1 * trial);
    RayCastTransfer transfer;
    transfer.rgba = RandomTable(random, 256, false);
    const bool opaque = trial % 2 == 1;
    for (std::size_t i = 3; i < transfer.rgba.size(); i += 4)
    {
      transfer.rgba[i] = opaque ? std::min(1.0f, 4.0f * transfer.rgba[i]) : 0.3f * transfer.rgba[i];
    }
    RayCastLighting lighting;
    lighting.shade = true;
    lighting.model.lights.emplace_back();
    RayCastSettings settings = BaseSettings(dims, Blend::Composite);
    settings.leap = LeapMode::DistanceMap;
    settings.cellLeap = false; // the octant maps replace the chessboard map read alone
    Camera camera = RandomCamera(random, dims, true);
    std::size_t octants = 1;
    if (trial >= 2)
    {
      camera.parallel = false;
      camera.focalPoint = centre;
      camera.position = centre + Vec3{ 0, 0, 70 };
      camera.viewUp = { 0, 1, 0 };
      camera.viewAngleDegrees = 50;
      octants = 4;
    }
    if (trial >= 4)
    {
      camera.position = centre + Vec3{ -4, -3, -2 };
      camera.focalPoint = centre + Vec3{ 6, 6, 6 };
      camera.viewUp = { 0, 0, 1 };
      camera.viewAngleDegrees = 120;
      octants = 0; // counted below: more than four
    }
    const RayCastView view = MakeView(camera, 45, 37, 0.5, 500.0);
    const Result withOctants = Cast(scene, transfer, lighting, view, settings);
    settings.octantDistanceMaps = false;
    const Result chessboard = Cast(scene, transfer, lighting, view, settings);
    const std::size_t built =
      (withOctants.accelerationBytes - chessboard.accelerationBytes) / octantBytes;
    if (octants > 0)
    {
      EXPECT_EQ(built, octants) << "trial " << trial;
    }
    else
    {
      EXPECT_GT(built, 4u) << "trial " << trial;
    }
    EXPECT_TRUE(Identical(withOctants.rgba, chessboard.rgba)) << "trial " << trial;
    EXPECT_GT(chessboard.counters.distanceLeaps, 100u) << "trial " << trial;
    EXPECT_LT(withOctants.counters.distanceLeaps, chessboard.counters.distanceLeaps)
      << "trial " << trial;
    EXPECT_GT(withOctants.counters.samples, 20u) << "trial " << trial;
    // With cell leaping the distance comes from the octant maps too.
    settings.cellLeap = true;
    const Result cellLeapAlone = Cast(scene, transfer, lighting, view, settings);
    settings.octantDistanceMaps = true;
    const Result cellLeap = Cast(scene, transfer, lighting, view, settings);
    EXPECT_TRUE(Identical(withOctants.rgba, cellLeap.rgba)) << "trial " << trial;
    EXPECT_LT(cellLeap.counters.distanceLeaps, cellLeapAlone.counters.distanceLeaps)
      << "trial " << trial;
    settings.cellLeap = false;
    settings.batchedComposite = false;
    const Result perSample = Cast(scene, transfer, lighting, view, settings);
    EXPECT_TRUE(Identical(withOctants.rgba, perSample.rgba)) << "trial " << trial << ": per sample";
    settings.leap = LeapMode::None;
    const Result unleaped = Cast(scene, transfer, lighting, view, settings);
    EXPECT_TRUE(Identical(withOctants.rgba, unleaped.rgba)) << "trial " << trial;
  }
  // One caster, the view from inside (more than four maps), then a parallel view: at most four
  // maps stay, the new view's among them, and its image is a fresh caster's.
  const Scene scene = MakeScene(ScalarType::UInt8, dims, 0.2);
  RayCastTransfer transfer;
  transfer.rgba = RandomTable(random, 256, false);
  RayCastLighting lighting;
  RayCastSettings settings = BaseSettings(dims, Blend::Composite);
  settings.leap = LeapMode::DistanceMap;
  settings.cellLeap = false;
  Camera inside = RandomCamera(random, dims, false);
  inside.position = centre + Vec3{ -4, -3, -2 };
  inside.focalPoint = centre + Vec3{ 6, 6, 6 };
  inside.viewAngleDegrees = 120;
  RayCaster caster;
  const Result first = Cast(
    scene, transfer, lighting, MakeView(inside, 45, 37, 0.5, 500.0), settings, SerialFor, &caster);
  const RayCastView parallelView = MakeView(RandomCamera(random, dims, true), 45, 37, 0.5, 500.0);
  const Result second = Cast(scene, transfer, lighting, parallelView, settings, SerialFor, &caster);
  EXPECT_LT(second.accelerationBytes, first.accelerationBytes);
  settings.octantDistanceMaps = false;
  const Result chessboard = Cast(scene, transfer, lighting, parallelView, settings);
  EXPECT_LE(second.accelerationBytes - chessboard.accelerationBytes, 4 * octantBytes);
  EXPECT_TRUE(Identical(second.rgba, chessboard.rgba));
  EXPECT_LT(second.counters.distanceLeaps, chessboard.counters.distanceLeaps);
}

// Pixels outside the screen footprint of the non-empty cells get no ray, with the same image as
// casting every ray (any thread count, both walks, with and without cell leaping); a view from
// inside the volume has no footprint (every ray is cast).
TEST(RayCastEngine, ScreenFootprintCullsRaysWithTheSameImage)
{
  std::mt19937 random(43);
  const int dims[3] = { 57, 43, 49 };
  const Vec3 centre{ 28, 21, 24 };
  std::uint64_t culled = 0;
  for (int trial = 0; trial < 10; ++trial)
  {
    const Scene scene =
      MakeScene(trial % 2 ? ScalarType::UInt16 : ScalarType::UInt8, dims, 0.1 * trial);
    RayCastTransfer transfer;
    transfer.rgba = RandomTable(random, 256, false);
    if (trial % 2 == 1)
    {
      for (std::size_t i = 3; i < transfer.rgba.size(); i += 4)
      {
        transfer.rgba[i] = std::min(1.0f, 6.0f * transfer.rgba[i]);
      }
    }
    RayCastLighting lighting;
    lighting.shade = trial % 3 != 2;
    lighting.model.lights.emplace_back();
    RayCastSettings settings = BaseSettings(dims, Blend::Composite);
    settings.leap = LeapMode::DistanceMap;
    settings.cellLeap = trial % 4 == 3;
    if (trial == 4 || trial == 5)
    {
      // Two crop regions: rays meet one or two intervals.
      settings.regions = { { { 0, 0, 0 }, { 20, dims[1] - 1.0, dims[2] - 1.0 } },
        { { 33, 2, 3 }, { dims[0] - 1.0, dims[1] - 1.0, dims[2] - 1.0 } } };
    }
    Camera camera = RandomCamera(random, dims, trial % 2 == 0);
    const bool inside = trial == 9;
    if (trial >= 6)
    {
      // Close perspective views (wide angles: the projection distorts most), one from inside.
      camera.parallel = false;
      camera.focalPoint = centre;
      camera.position = centre + Vec3{ 45.0 - 15 * (trial - 6), 38.0, -18.0 + 6 * (trial - 6) };
      camera.viewAngleDegrees = 60 + 10 * (trial - 6);
      if (inside)
      {
        camera.position = centre + Vec3{ -4, -3, -2 };
      }
    }
    const RayCastView view = MakeView(camera, 96, 80, 0.5, 500.0);
    const Result footprint = Cast(scene, transfer, lighting, view, settings);
    settings.screenFootprint = false;
    const Result everyRay = Cast(scene, transfer, lighting, view, settings);
    EXPECT_TRUE(Identical(footprint.rgba, everyRay.rgba)) << "trial " << trial;
    EXPECT_EQ(everyRay.counters.culledPixels, 0u) << "trial " << trial;
    EXPECT_LE(footprint.counters.rays, everyRay.counters.rays) << "trial " << trial;
    EXPECT_GT(everyRay.counters.samples, 20u) << "trial " << trial;
    if (inside)
    {
      EXPECT_EQ(footprint.counters.culledPixels, 0u);
    }
    culled += footprint.counters.culledPixels;
    settings.screenFootprint = true;
    const Result threaded = Cast(scene, transfer, lighting, view, settings, ThreadedFor(3, 1));
    EXPECT_TRUE(Identical(footprint.rgba, threaded.rgba)) << "trial " << trial << ": threads";
    settings.batchedComposite = false;
    const Result perSample = Cast(scene, transfer, lighting, view, settings);
    EXPECT_TRUE(Identical(footprint.rgba, perSample.rgba)) << "trial " << trial << ": per sample";
  }
  // Most views leave a good part of the projected box without a ray.
  EXPECT_GT(culled, 45u * 37u);
}
