// Progress: reporting parallel loops cover every item once and report in order from the calling
// thread only; the ray caster and the shear-warp renderer report monotone progress ending at 1,
// only on the calling thread, and render bit-identical images with and without it.
#include "ShearWarpEngineTestSupport.h"

#include "common/Progress.h"

#include <gtest/gtest.h>

#include <atomic>
#include <memory>
#include <thread>
#include <vector>

using namespace accelvolume;
using namespace accelvolume_test;

namespace
{

// Records every report, and whether any came from another thread than the test's.
struct Recorder
{
  std::vector<double> values;
  std::thread::id owner = std::this_thread::get_id();
  bool foreignThread = false;

  ProgressFunction Function()
  {
    return [this](double fraction)
    {
      this->foreignThread = this->foreignThread || std::this_thread::get_id() != this->owner;
      this->values.push_back(fraction);
    };
  }
};

void ExpectMonotoneToOne(const std::vector<double>& values)
{
  ASSERT_FALSE(values.empty());
  for (std::size_t i = 0; i < values.size(); ++i)
  {
    EXPECT_GE(values[i], 0.0) << i;
    EXPECT_LE(values[i], 1.0) << i;
    if (i > 0)
    {
      EXPECT_GE(values[i], values[i - 1]) << i;
    }
  }
  EXPECT_EQ(values.back(), 1.0);
}

RayCastSettings CompositeSettings(const Scene& scene, LeapMode leap)
{
  RayCastSettings settings;
  settings.sampleDistance = 0.7;
  settings.leap = leap;
  settings.regions.push_back(
    Box{ Vec3{ 0, 0, 0 }, Vec3{ scene.dims[0] - 1.0, scene.dims[1] - 1.0, scene.dims[2] - 1.0 } });
  return settings;
}

}

TEST(Progress, ReportingParallelForCoversEveryItemOnceAndReportsFromTheCaller)
{
  const ParallelFor threaded = UnevenThreadedFor(3);
  for (std::size_t count : { 1000u, 37u, 5u, 1u, 0u })
  {
    for (int serial = 0; serial < 2; ++serial)
    {
      SCOPED_TRACE(std::to_string(count) + " items, " + (serial ? "serial" : "3 threads"));
      std::unique_ptr<std::atomic<int>[]> visits(new std::atomic<int>[count + 1]);
      for (std::size_t i = 0; i <= count; ++i)
      {
        visits[i] = 0;
      }
      Recorder recorder;
      const ParallelFor reporting = ReportingParallelFor(
        serial ? ParallelFor(SerialParallelFor) : threaded, recorder.Function(), 16);
      reporting(count,
        [&](std::size_t begin, std::size_t end)
        {
          for (std::size_t i = begin; i < end; ++i)
          {
            ++visits[i];
          }
        });
      for (std::size_t i = 0; i < count; ++i)
      {
        ASSERT_EQ(visits[i].load(), 1) << "item " << i;
      }
      EXPECT_FALSE(recorder.foreignThread);
      ExpectMonotoneToOne(recorder.values);
      EXPECT_LE(recorder.values.size(), 16u);
      if (serial)
      {
        // Every 1/16 of the items once (fewer steps than items: one report per item) and 1.
        EXPECT_EQ(recorder.values.size(), count >= 16 ? 16u : std::max<std::size_t>(count, 1));
      }
    }
  }
  // Without a report the loop is the given one: a single call over the whole range.
  int calls = 0;
  const ParallelFor counting =
    [&](std::size_t count, const std::function<void(std::size_t, std::size_t)>& body)
  {
    ++calls;
    body(0, count);
  };
  ReportingParallelFor(counting, ProgressFunction())(1000, [](std::size_t, std::size_t) {});
  EXPECT_EQ(calls, 1);
}

TEST(Progress, RangeMapsAndClamps)
{
  Recorder recorder;
  const ProgressFunction range = ProgressRange(recorder.Function(), 0.2, 0.6);
  range(0.0);
  range(0.5);
  range(1.0);
  range(2.0);
  range(-1.0);
  ASSERT_EQ(recorder.values.size(), 5u);
  EXPECT_DOUBLE_EQ(recorder.values[0], 0.2);
  EXPECT_DOUBLE_EQ(recorder.values[1], 0.4);
  EXPECT_DOUBLE_EQ(recorder.values[2], 0.6);
  EXPECT_DOUBLE_EQ(recorder.values[3], 0.6);
  EXPECT_DOUBLE_EQ(recorder.values[4], 0.2);
  EXPECT_FALSE(ProgressRange(ProgressFunction(), 0, 1));
}

TEST(Progress, RayCasterReportsWithoutChangingTheImage)
{
  const int dims[3] = { 40, 32, 24 };
  const Scene scene = MakeScene(dims, false);
  const RayCastTransfer tf = MakeTransfer(0.3f);
  const ViewSetup camera = MakeCamera(scene, 200, -35, Isotropic, 160, 128, 25, true);
  const ParallelFor threaded = UnevenThreadedFor(3);
  for (LeapMode leap : { LeapMode::None, LeapMode::Octree, LeapMode::DistanceMap })
  {
    SCOPED_TRACE(static_cast<int>(leap));
    const RayCastSettings settings = CompositeSettings(scene, leap);
    RayCaster plain;
    RayCaster reporting;
    Recorder recorder;
    reporting.SetProgressFunction(recorder.Function());
    // Two frames: the first rebuilds the leaping structures, the second reuses them.
    for (int frame = 0; frame < 2; ++frame)
    {
      SCOPED_TRACE("frame " + std::to_string(frame));
      std::vector<float> expected, actual;
      RayCastCounters expectedCounters, actualCounters;
      std::string error;
      ASSERT_TRUE(plain.Render(scene.view, scene.range[0], scene.range[1], 1, tf, 1,
        camera.lighting, camera.rc, settings, threaded, expected, expectedCounters, error))
        << error;
      recorder.values.clear();
      ASSERT_TRUE(reporting.Render(scene.view, scene.range[0], scene.range[1], 1, tf, 1,
        camera.lighting, camera.rc, settings, threaded, actual, actualCounters, error))
        << error;
      EXPECT_TRUE(BitIdentical(expected, actual));
      EXPECT_EQ(expectedCounters.samples, actualCounters.samples);
      EXPECT_EQ(expectedCounters.rays, actualCounters.rays);
      EXPECT_FALSE(recorder.foreignThread);
      ExpectMonotoneToOne(recorder.values);
      // At most 16 tile reports and the final 1; frame 0 also rebuilds the shading gradients
      // and the leaping structures (one report each, within the first quarter).
      if (frame == 0)
      {
        EXPECT_GE(recorder.values.size(), 2u);
        EXPECT_LE(recorder.values.size(), 20u);
        EXPECT_LE(recorder.values.front(), 0.25);
      }
      else
      {
        EXPECT_LE(recorder.values.size(), 16u);
      }
    }
  }
}

TEST(Progress, RayCasterReportsEverySixteenthOfTheTilesOnOneThread)
{
  const int dims[3] = { 40, 32, 24 };
  const Scene scene = MakeScene(dims, false);
  const ViewSetup camera = MakeCamera(scene, 200, -35, Isotropic, 160, 128, 25, false);
  RayCaster caster;
  Recorder recorder;
  caster.SetProgressFunction(recorder.Function());
  RayCastSettings settings = CompositeSettings(scene, LeapMode::None);
  settings.cellLeap = false;
  std::vector<float> rgba;
  RayCastCounters counters;
  std::string error;
  ASSERT_TRUE(caster.Render(scene.view, scene.range[0], scene.range[1], 1, MakeTransfer(0.3f), 1,
    camera.lighting, camera.rc, settings, SerialParallelFor, rgba, counters, error))
    << error;
  // Nothing to rebuild (no leaping, no shading): 80 tiles, a report per 1/16 of them, then 1.
  ExpectMonotoneToOne(recorder.values);
  ASSERT_EQ(recorder.values.size(), 16u);
  EXPECT_DOUBLE_EQ(recorder.values.front(), 5.0 / 80.0);
}

TEST(Progress, ShearWarpReportsEncodingAndPhasesWithoutChangingTheImage)
{
  const int dims[3] = { 40, 32, 48 };
  const Scene scene = MakeScene(dims, false);
  const RayCastTransfer tf = MakeTransfer(0.3f);
  const ViewSetup camera = MakeCamera(scene, 20, 15, Isotropic, 90, 70, 25, true);
  const ParallelFor threaded = UnevenThreadedFor(3);
  for (Blend blend : { Blend::Composite, Blend::Maximum })
  {
    SCOPED_TRACE(BlendName(blend));
    ShearWarpSettings settings;
    settings.blend = blend;
    settings.bands = 3;
    ShearWarpRenderer plain;
    ShearWarpRenderer reporting;
    Recorder recorder;
    reporting.SetProgressFunction(recorder.Function());
    for (int frame = 0; frame < 2; ++frame)
    {
      SCOPED_TRACE("frame " + std::to_string(frame));
      const Frame expected = RenderFrame(plain, scene, tf, camera, settings, threaded);
      recorder.values.clear();
      const Frame actual = RenderFrame(reporting, scene, tf, camera, settings, threaded);
      EXPECT_TRUE(BitIdentical(expected.rgba, actual.rgba));
      EXPECT_EQ(expected.stats.samples, actual.stats.samples);
      EXPECT_FALSE(recorder.foreignThread);
      ExpectMonotoneToOne(recorder.values);
      ASSERT_GE(recorder.values.size(), 2u);
      EXPECT_DOUBLE_EQ(recorder.values[recorder.values.size() - 2], 0.95); // compositing done
      if (frame == 0)
      {
        // The encoding (its slices as they finish) up to 0.8, then the phases.
        EXPECT_GE(recorder.values.size(), 3u);
        EXPECT_DOUBLE_EQ(recorder.values[recorder.values.size() - 3], 0.8);
      }
      else
      {
        EXPECT_EQ(recorder.values.size(), 2u); // the encoding is reused
      }
    }
  }
  // BeginFrame alone reports its encoding 0..1, and nothing when it reuses the encoding.
  ShearWarpRenderer phased;
  Recorder recorder;
  phased.SetProgressFunction(recorder.Function());
  ShearWarpSettings settings;
  for (int frame = 0; frame < 2; ++frame)
  {
    ShearWarpStats stats;
    std::string error;
    recorder.values.clear();
    ASSERT_TRUE(phased.BeginFrame(scene.view, scene.range[0], scene.range[1], 1, tf, 1,
      camera.lighting, camera.sw, settings, SerialParallelFor, stats, error))
      << error;
    if (frame == 0)
    {
      // One thread: every 1/16 of the 48 slices, then 1.
      ExpectMonotoneToOne(recorder.values);
      EXPECT_EQ(recorder.values.size(), 16u);
    }
    else
    {
      EXPECT_TRUE(recorder.values.empty());
    }
  }
}
