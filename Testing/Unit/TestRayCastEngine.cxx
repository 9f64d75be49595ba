// RayCastEngine: results ignore the thread count and the SIMD target; images agree with the CPU
// reference oracles; depth, eye lights and fixed-point locating; bad arguments fail cleanly (its
// leaping: TestRayCastLeaping.cxx).
#include "raycast/RayCastEngine.h"
#include "raycast/RayCastSampler.h"
#include "reference/ReferenceComposite.h"

#include "RayCastEngineTestSupport.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <random>
#include <stdexcept>
#include <thread>
#include <vector>

using namespace accelvolume;
using namespace accelvolume_test::raycast_engine;

TEST(RayCastEngine, ResultsIgnoreTheThreadCount)
{
  std::mt19937 random(3);
  const int dims[3] = { 32, 28, 24 };
  const Scene scene = MakeScene(ScalarType::UInt16, dims, 0.2);
  RayCastTransfer transfer;
  transfer.rgba = RandomTable(random, 512, false);
  RayCastSettings settings = BaseSettings(dims, Blend::Composite);
  settings.leap = LeapMode::Octree;
  const RayCastView view = MakeView(RandomCamera(random, dims, false), 61, 47, 1.0, 500.0);
  const Result serial = Cast(scene, transfer, RayCastLighting(), view, settings);
  for (int threads : { 2, 3, 7 })
  {
    for (std::size_t chunk : { std::size_t(1), std::size_t(5) })
    {
      const Result parallel =
        Cast(scene, transfer, RayCastLighting(), view, settings, ThreadedFor(threads, chunk));
      EXPECT_TRUE(Identical(serial.rgba, parallel.rgba)) << threads << " threads";
      EXPECT_EQ(serial.counters.samples, parallel.counters.samples);
      EXPECT_EQ(serial.counters.leapedOctree, parallel.counters.leapedOctree);
    }
  }
}

// The batched composite kernel (distance map or no leaping, with and without cell leaping,
// shaded by fixed lights) against itself: every thread count (FixedThreadsParallelFor, the
// mappers' set thread count, and uneven chunks) and both builds of its lane loops (x86-64
// baseline and AVX2, where the CPU has it) give the same bits.
TEST(RayCastEngine, BatchedCompositeIgnoresThreadsAndSimdTarget)
{
  std::mt19937 random(11);
  const int dims[3] = { 34, 29, 23 };
  for (int trial = 0; trial < 4; ++trial)
  {
    const Scene scene =
      MakeScene(trial % 2 ? ScalarType::UInt16 : ScalarType::UInt8, dims, 0.15 * trial);
    RayCastTransfer transfer;
    transfer.rgba = RandomTable(random, 256, false);
    for (std::size_t i = 3; i < transfer.rgba.size(); i += 4)
    {
      transfer.rgba[i] *= 0.4f; // semi-transparent: the batched kernel's case
    }
    RayCastLighting lighting;
    lighting.shade = true;
    lighting.model.lights.emplace_back();
    lighting.model.lights.emplace_back();
    lighting.model.lights.back().axis[0] = 0.6f; // a second, oblique light
    lighting.model.lights.back().axis[2] = -0.8f;
    if (trial >= 1)
    {
      // A positional light: at the eye (fixed along perspective rays, not along parallel
      // ones), or elsewhere and attenuated (never fixed).
      SceneLight& positional = lighting.model.lights.back();
      positional.positional = true;
      if (trial == 1)
      {
        positional.position[0] = 30.0f;
        positional.position[2] = 10.0f;
        positional.attenuation[1] = 0.01f;
      }
      lighting.model.anyPositional = true;
      // Eye space = index space shifted back along z: the eye in front of the volume.
      lighting.indexToEyeOffset[2] = -200.0;
    }
    lighting.model.twoSided = trial % 2 == 0;
    RayCastSettings settings = BaseSettings(dims, Blend::Composite);
    settings.leap = trial < 2 ? LeapMode::DistanceMap : LeapMode::None;
    settings.cellLeap = trial % 2 == 1;
    const RayCastView view =
      MakeView(RandomCamera(random, dims, trial == 3), 53, 41, 1.0, 500.0);
    const Result serial = Cast(scene, transfer, lighting, view, settings);
    EXPECT_GT(serial.counters.samples, trial % 2 ? 50u : 1000u) << "trial " << trial;
    for (int threads : { 2, 3 })
    {
      const Result fixed =
        Cast(scene, transfer, lighting, view, settings, FixedThreadsParallelFor(threads));
      EXPECT_TRUE(Identical(serial.rgba, fixed.rgba)) << "trial " << trial << ", " << threads;
      const Result uneven =
        Cast(scene, transfer, lighting, view, settings, ThreadedFor(threads, 3));
      EXPECT_TRUE(Identical(serial.rgba, uneven.rgba)) << "trial " << trial << ", " << threads;
    }
    settings.baselineLanes = true;
    const Result baseline = Cast(scene, transfer, lighting, view, settings);
    EXPECT_TRUE(Identical(serial.rgba, baseline.rgba)) << "trial " << trial << ": SIMD targets";
    // And the generic per-sample walk agrees with the batched one, with octree leaping in
    // either (the batched walk leaps the octree too).
    settings.leap = LeapMode::Octree;
    const Result octree = Cast(scene, transfer, lighting, view, settings);
    EXPECT_TRUE(Identical(serial.rgba, octree.rgba)) << "trial " << trial << ": octree";
    EXPECT_GT(octree.counters.octreeLeaps, 0u) << "trial " << trial;
    settings.batchedComposite = false;
    const Result generic = Cast(scene, transfer, lighting, view, settings);
    EXPECT_TRUE(Identical(serial.rgba, generic.rgba)) << "trial " << trial << ": per sample";
    settings.leap = LeapMode::DistanceMap;
    const Result genericDistance = Cast(scene, transfer, lighting, view, settings);
    EXPECT_TRUE(Identical(serial.rgba, genericDistance.rgba)) << "trial " << trial;
  }
}

TEST(RayCastEngine, FixedThreadsParallelForCoversEveryItemOnce)
{
  for (int threads : { 1, 2, 5 })
  {
    for (std::size_t count : { std::size_t(0), std::size_t(1), std::size_t(7), std::size_t(1000) })
    {
      std::vector<std::atomic<int>> hits(count);
      FixedThreadsParallelFor(threads)(count,
        [&](std::size_t begin, std::size_t end)
        {
          for (std::size_t i = begin; i < end; ++i)
          {
            hits[i].fetch_add(1);
          }
        });
      for (std::size_t i = 0; i < count; ++i)
      {
        EXPECT_EQ(hits[i].load(), 1) << threads << " threads, item " << i << " of " << count;
      }
    }
  }
  // An exception in one worker reaches the caller after every worker stopped.
  EXPECT_THROW(FixedThreadsParallelFor(3)(100,
                 [](std::size_t begin, std::size_t)
                 {
                   if (begin >= 50)
                   {
                     throw std::runtime_error("worker failed");
                   }
                 }),
    std::runtime_error);
}

TEST(RayCastEngine, CompositeAgreesWithTheReferenceOracle)
{
  const int dims[3] = { 30, 26, 22 };
  const Scene scene = MakeScene(ScalarType::Float32, dims, 0.0);
  std::mt19937 random(11);
  RayCastTransfer transfer;
  transfer.rgba = RandomTable(random, 256, false);
  transfer.opacityUnitDistance = 1.0;
  Camera camera = RandomCamera(random, dims, false);
  const int width = 40, height = 36;
  RayCastView view = MakeView(camera, width, height, 1.0, 500.0);
  RayCastSettings settings = BaseSettings(dims, Blend::Composite);
  settings.sampleDistance = 0.05;
  settings.earlyTermination = false;
  const Result ours = Cast(scene, transfer, RayCastLighting(), view, settings);

  ScalarVolume volume;
  std::copy(dims, dims + 3, volume.dims);
  for (float v : scene.f32)
    volume.values.push_back(v / 1000.0f);
  std::vector<float> colours;
  OpacityTable opacity;
  for (int i = 0; i < 256; ++i)
  {
    colours.insert(colours.end(), &transfer.rgba[4 * i], &transfer.rgba[4 * i] + 3);
    opacity.values.push_back(transfer.rgba[4 * i + 3]);
  }
  CompositeOptions options;
  options.stepWorld = 0.05;
  // The oracle's rays start at the camera; ours at the near plane (1 unit ahead): same rays.
  const std::vector<CompositePixel> reference = RenderReferenceComposite(
    volume, settings.regions, {}, colours, opacity, camera, width, height, options);
  double total = 0;
  double worst = 0;
  for (std::size_t p = 0; p < reference.size(); ++p)
  {
    for (int c = 0; c < 4; ++c)
    {
      const double d = std::abs(reference[p].rgba[c] - ours.rgba[4 * p + c]);
      total += d;
      worst = std::max(worst, d);
    }
  }
  EXPECT_LT(total / (4.0 * reference.size()), 2.0e-3);
  EXPECT_LT(worst, 0.03);
}

TEST(RayCastEngine, DepthStopsTheRays)
{
  const int dims[3] = { 24, 24, 24 };
  const Scene scene = MakeScene(ScalarType::UInt8, dims, 0.0);
  RayCastTransfer transfer;
  transfer.rgba.assign(4 * 4, 0.5f);
  Camera camera;
  camera.position = { 11.5, 11.5, 80 };
  camera.focalPoint = { 11.5, 11.5, 11.5 };
  RayCastView view = MakeView(camera, 16, 16, 1.0, 200.0);
  std::vector<float> depth(16 * 16, 1.0f);
  depth[0] = 0.0f; // geometry on the near plane hides the volume at pixel 0
  view.depth = &depth;
  RayCastSettings settings = BaseSettings(dims, Blend::Maximum);
  const Result result = Cast(scene, transfer, RayCastLighting(), view, settings);
  EXPECT_EQ(result.rgba[3], 0.0f);
  EXPECT_GT(result.rgba[4 * (8 * 16 + 8) + 3], 0.0f);
}

TEST(RayCastEngine, BadArgumentsFail)
{
  const int dims[3] = { 4, 4, 4 };
  const Scene scene = MakeScene(ScalarType::UInt8, dims, 0.0);
  RayCastTransfer transfer;
  transfer.rgba.assign(8, 1.0f);
  std::mt19937 random(1);
  RayCastView view = MakeView(RandomCamera(random, dims, false), 8, 8, 1, 100);
  RayCastSettings settings = BaseSettings(dims, Blend::Composite);
  RayCaster caster;
  std::vector<float> rgba;
  RayCastCounters counters;
  std::string error;
  VolumeView empty;
  EXPECT_FALSE(caster.Render(empty, 0, 1, 1, transfer, 1, RayCastLighting(), view, settings,
    SerialFor, rgba, counters, error));
  EXPECT_FALSE(error.empty());
  RayCastTransfer shortTable;
  shortTable.rgba.assign(4, 1.0f);
  EXPECT_FALSE(caster.Render(scene.view, 0, 255, 1, shortTable, 1, RayCastLighting(), view,
    settings, SerialFor, rgba, counters, error));
  settings.sampleDistance = 0;
  EXPECT_FALSE(caster.Render(scene.view, 0, 255, 1, transfer, 1, RayCastLighting(), view, settings,
    SerialFor, rgba, counters, error));
  settings.sampleDistance = 1;
  settings.octreeLeafSize = 3;
  EXPECT_FALSE(caster.Render(scene.view, 0, 255, 1, transfer, 1, RayCastLighting(), view, settings,
    SerialFor, rgba, counters, error));
  std::vector<float> wrongDepth(3, 1.0f);
  view.depth = &wrongDepth;
  settings.octreeLeafSize = 4;
  EXPECT_FALSE(caster.Render(scene.view, 0, 255, 1, transfer, 1, RayCastLighting(), view, settings,
    SerialFor, rgba, counters, error));
}

// The walks place samples in 32.32 fixed point (FixedSteps) and locate them with integer
// operations: the cells and fractions must be Locate's for the same point, bit for bit, inside,
// on the faces, outside (clamped) and on one-voxel axes.
TEST(RayCastEngine, LocateFixedMatchesLocate)
{
  using detail::FixedSteps;
  using detail::SampleCell;
  std::vector<std::uint16_t> voxels(7 * 5 * 9);
  for (const auto& dims :
    { std::array<int, 3>{ 7, 5, 9 }, std::array<int, 3>{ 1, 5, 9 }, std::array<int, 3>{ 7, 1, 1 } })
  {
    VolumeView volume;
    volume.data = voxels.data();
    volume.type = ScalarType::UInt16;
    volume.dims[0] = dims[0];
    volume.dims[1] = dims[1];
    volume.dims[2] = dims[2];
    const detail::Sampler<std::uint16_t> sampler(volume);
    std::mt19937_64 random(7);
    std::uniform_real_distribution<double> position(-2.0, 11.0);
    int checked = 0;
    for (int i = 0; i < 20000; ++i)
    {
      std::int64_t q[3];
      for (int a = 0; a < 3; ++a)
      {
        // Random points, and exact voxel faces now and then.
        const double x = i % 5 == 0 ? std::floor(position(random)) : position(random);
        q[a] = FixedSteps::ToFixed(x) + (i % 7 == 0 ? -1 : 0);
      }
      double p[3];
      FixedSteps::ToPoint(q, p);
      SampleCell fromDouble, fromFixed;
      sampler.Locate(p, fromDouble);
      sampler.LocateFixed(q, fromFixed);
      ASSERT_EQ(fromDouble.base, fromFixed.base);
      ASSERT_EQ(fromDouble.cell, fromFixed.cell);
      for (int a = 0; a < 3; ++a)
      {
        ASSERT_EQ(fromDouble.offset[a], fromFixed.offset[a]);
        ASSERT_EQ(fromDouble.f[a], fromFixed.f[a]) << "axis " << a << " at " << p[a];
      }
      ++checked;
    }
    EXPECT_EQ(checked, 20000);
  }
  // Sample k is start + k * step exactly, however it is reached.
  detail::IndexRay ray{ Vec3{ 0.25, -1.0, 3.5 }, Normalize(Vec3{ 0.3, 0.9, -0.2 }), 100.0 };
  const FixedSteps steps(ray, 0.75, 0.37);
  std::int64_t walked[3] = { steps.start[0], steps.start[1], steps.start[2] };
  for (std::int64_t k = 0; k < 300; ++k)
  {
    std::int64_t q[3];
    steps.At(k, q);
    for (int a = 0; a < 3; ++a)
    {
      ASSERT_EQ(q[a], walked[a]);
      walked[a] += steps.step[a];
    }
  }
}

// A light at the eye on rays that do not pass through it (parallel projection) shines along
// each ray from one direction, taken at the ray's entry into the volume (as
// vtkGPUVolumeRayCastMapper does): the picture equals a directional light from the eye towards
// that entry point, and differs from one aimed at the exit point. One pixel, one ray along -x
// through the volume's centre; the eye (the light) off that ray, so a per-sample direction
// would vary along it. Batched and per-sample paths both.
TEST(RayCastEngine, EyeLightOnParallelRaysIsTakenAtTheEntryPoint)
{
  const int dims[3] = { 34, 29, 23 };
  const Scene scene = MakeScene(ScalarType::UInt16, dims, 0.3);
  RayCastTransfer transfer;
  transfer.rgba.resize(4 * 256);
  for (int i = 0; i < 256; ++i)
  {
    const float s = i / 255.0f;
    const float rgba[4] = { 0.9f, 0.5f + 0.5f * s, 0.3f, i > 40 ? 0.15f : 0.0f };
    std::copy(rgba, rgba + 4, transfer.rgba.begin() + 4 * i);
  }
  const Vec3 centre{ (dims[0] - 1) / 2.0, (dims[1] - 1) / 2.0, (dims[2] - 1) / 2.0 };
  Camera camera;
  camera.focalPoint = centre;
  camera.position = centre + Vec3{ 100.0, 0.0, 0.0 };
  camera.viewUp = { 0, 0, 1 };
  camera.parallel = true;
  camera.parallelScale = 20.0;
  const RayCastView view = MakeView(camera, 1, 1, 1.0, 500.0);
  // Eye space: index space translated so that the eye sits at `eye`, off the ray.
  const double eye[3] = { 45.0, centre.y + 25.0, centre.z - 12.0 };
  RayCastLighting lighting;
  lighting.shade = true;
  lighting.model.specular = 0.5f;
  lighting.model.anyPositional = true;
  for (int r = 0; r < 3; ++r)
  {
    lighting.indexToEyeOffset[r] = -eye[r];
  }
  SceneLight atEye;
  atEye.positional = true; // at the eye origin, unattenuated, no cone: VTK's headlight
  // A directional light from the eye towards `target` (eye space).
  auto towards = [&](const double target[3])
  {
    double d[3];
    for (int r = 0; r < 3; ++r)
    {
      d[r] = target[r] - eye[r];
    }
    const double length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    SceneLight light;
    for (int r = 0; r < 3; ++r)
    {
      light.axis[r] = static_cast<float>(d[r] / length);
    }
    return light;
  };
  const double entry[3] = { dims[0] - 1.0, centre.y, centre.z };
  const double exit[3] = { 0.0, centre.y, centre.z };
  for (const LeapMode leap : { LeapMode::DistanceMap, LeapMode::Octree })
  {
    RayCastSettings settings = BaseSettings(dims, Blend::Composite);
    settings.leap = leap; // batched lanes, and the generic per-sample walk
    auto render = [&](const SceneLight& light)
    {
      RayCastLighting l = lighting;
      l.model.lights = { light };
      const Result result = Cast(scene, transfer, l, view, settings);
      EXPECT_GT(result.counters.samples, 10u);
      return std::array<float, 3>{ result.rgba[0], result.rgba[1], result.rgba[2] };
    };
    const std::array<float, 3> headlight = render(atEye);
    const std::array<float, 3> fromEntry = render(towards(entry));
    const std::array<float, 3> fromExit = render(towards(exit));
    double entryDifference = 0, exitDifference = 0;
    for (int c = 0; c < 3; ++c)
    {
      entryDifference = std::max(entryDifference, std::abs(double(headlight[c]) - fromEntry[c]));
      exitDifference = std::max(exitDifference, std::abs(double(headlight[c]) - fromExit[c]));
    }
    EXPECT_GT(headlight[0], 0.05f);
    EXPECT_LT(entryDifference, 1.0e-5) << "leap " << static_cast<int>(leap);
    EXPECT_GT(exitDifference, 1.0e-2) << "leap " << static_cast<int>(leap);
  }
}
