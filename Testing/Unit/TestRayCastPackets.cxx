// Ray packets (RayCastKernelPackets.inl): composite rays sixteen at a time, one per AVX-512
// lane, give the same bits as one ray at a time on every scalar type the packets load, shaded
// or not, with several lights, crops (rays of two intervals leave the packet), without early
// termination, over threads and on both one-ray walks.
#include "RayCastEngineTestSupport.h"

#include <gtest/gtest.h>

#include <random>
#include <utility>

namespace
{
using namespace accelvolume_test::raycast_engine;

bool CpuHasPackets()
{
#if (defined(__GNUC__) || defined(__clang__)) && defined(__x86_64__)
  return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq") &&
    __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512vl");
#else
  return false;
#endif
}

// A second, coloured directional light from the upper left, and VTK's headlight as a
// positional light at the eye (fixed along rays through the eye in perspective).
void AddLights(int trial, RayCastLighting& lighting)
{
  lighting.model.lights.emplace_back();
  if (trial % 3 == 1)
  {
    SceneLight side;
    const float axis[3] = { 0.48f, -0.6f, -0.64f };
    std::copy(axis, axis + 3, side.axis);
    const float diffuse[3] = { 0.9f, 0.6f, 0.3f };
    std::copy(diffuse, diffuse + 3, side.diffuse);
    side.ambient[0] = side.ambient[1] = side.ambient[2] = 0.2f;
    lighting.model.lights.push_back(side);
    lighting.model.twoSided = false;
  }
  if (trial % 3 == 2)
  {
    lighting.model.lights[0].positional = true;
    lighting.model.anyPositional = true;
    lighting.model.headlightOnly = true;
    lighting.model.specularPower = 35.0f;
  }
}

// One frame with the packets and one without, otherwise alike: the same image, and samples to
// compare. Returns both.
std::pair<Result, Result> CastWithAndWithoutPackets(const Scene& scene,
  const RayCastTransfer& transfer, const RayCastLighting& lighting, const RayCastView& view,
  RayCastSettings settings, int trial)
{
  settings.rayPackets = true;
  Result packets = Cast(scene, transfer, lighting, view, settings);
  EXPECT_GT(packets.counters.samples, 100u) << "trial " << trial;
  // Rays set up one by one: the same packets, so the same counts too (the opaque box's cut
  // included, which no image shows).
  settings.packetRaySetUp = false;
  const Result oneByOne = Cast(scene, transfer, lighting, view, settings);
  settings.packetRaySetUp = true;
  EXPECT_TRUE(Identical(packets.rgba, oneByOne.rgba)) << "trial " << trial << ": set-up";
  EXPECT_EQ(packets.counters.rays, oneByOne.counters.rays) << "trial " << trial;
  EXPECT_EQ(packets.counters.samples, oneByOne.counters.samples) << "trial " << trial;
  EXPECT_EQ(packets.counters.leapedDistance, oneByOne.counters.leapedDistance) << "trial " << trial;
  EXPECT_EQ(packets.counters.packetRays, oneByOne.counters.packetRays) << "trial " << trial;
  EXPECT_EQ(packets.counters.culledPixels, oneByOne.counters.culledPixels) << "trial " << trial;
  settings.rayPackets = false;
  Result alone = Cast(scene, transfer, lighting, view, settings);
  EXPECT_TRUE(Identical(packets.rgba, alone.rgba)) << "trial " << trial;
  return { std::move(packets), std::move(alone) };
}

} // namespace

TEST(RayCastPackets, SameImagesAsOneRayAtATime)
{
  std::mt19937 random(53);
  // Cells not a whole number of 4^3 bricks along any axis (the packets' cell index).
  const int dims[3] = { 47, 38, 43 };
  const Vec3 centre{ 23, 18.5, 21 };
  const ScalarType types[4] = { ScalarType::UInt8, ScalarType::UInt16, ScalarType::Int16,
    ScalarType::Float32 };
  std::uint64_t packetRays = 0;
  for (int trial = 0; trial < 12; ++trial)
  {
    const Scene scene = MakeScene(types[trial % 4], dims, 0.07 * trial);
    RayCastTransfer transfer;
    transfer.rgba = RandomTable(random, 256, false);
    if (trial % 5 == 1)
    {
      for (std::size_t i = 3; i < transfer.rgba.size(); i += 4)
      {
        transfer.rgba[i] = std::min(1.0f, 6.0f * transfer.rgba[i]); // nearly opaque
      }
    }
    else if (trial % 5 == 3 || trial % 5 == 4)
    {
      // Faint: long rays of many visible samples before early termination.
      for (std::size_t i = 3; i < transfer.rgba.size(); i += 4)
      {
        transfer.rgba[i] *= 0.15f;
      }
    }
    RayCastLighting lighting;
    lighting.shade = trial % 4 != 3;
    AddLights(trial, lighting);
    RayCastSettings settings = BaseSettings(dims, Blend::Composite);
    settings.leap = LeapMode::DistanceMap;
    settings.cellLeap = false;
    settings.earlyTermination = trial != 5;
    if (trial == 6 || trial == 7)
    {
      settings.regions = { { { 0, 0, 0 }, { 19, dims[1] - 1.0, dims[2] - 1.0 } },
        { { 30, 2, 3 }, { dims[0] - 1.0, dims[1] - 1.0, dims[2] - 1.0 } } };
    }
    Camera camera = RandomCamera(random, dims, trial % 2 == 0);
    if (trial >= 9)
    {
      // Close wide perspective views (rays of several octants), the last from inside.
      camera.parallel = false;
      camera.focalPoint = centre;
      camera.position = centre + Vec3{ 40.0 - 20 * (trial - 9), 35.0, -15.0 };
      camera.viewAngleDegrees = 70;
      if (trial == 11)
      {
        camera.position = centre + Vec3{ -3, -2, -4 };
      }
    }
    const RayCastView view = MakeView(camera, 71, 58, 0.5, 500.0);
    const auto [packets, alone] =
      CastWithAndWithoutPackets(scene, transfer, lighting, view, settings, trial);
    packetRays += packets.counters.packetRays;
    EXPECT_EQ(packets.counters.rays, alone.counters.rays) << "trial " << trial;
    EXPECT_EQ(alone.counters.packetRays, 0u) << "trial " << trial;
    settings.rayPackets = false;
    settings.batchedComposite = false;
    const Result perSample = Cast(scene, transfer, lighting, view, settings);
    EXPECT_TRUE(Identical(packets.rgba, perSample.rgba)) << "trial " << trial << ": per sample";
    settings.rayPackets = true;
    settings.batchedComposite = true;
    const Result threaded = Cast(scene, transfer, lighting, view, settings, ThreadedFor(3, 1));
    EXPECT_TRUE(Identical(packets.rgba, threaded.rgba)) << "trial " << trial << ": threads";
    EXPECT_EQ(packets.counters.packetRays, threaded.counters.packetRays) << "trial " << trial;
  }
  if (!CpuHasPackets())
  {
    GTEST_SKIP() << "no AVX-512 on this CPU: the images were compared, the packets never ran";
  }
  EXPECT_GT(packetRays, 12u * 1000u);
}

// 8-bit volumes take the interior cells' gradients from the voxels (PacketVoxelGradients) and
// the cells at the faces from the gradient words: a volume visible up to its faces (the blobs
// phantom plus noise everywhere) mixes both in one packet. Same images as one ray at a time.
TEST(RayCastPackets, VoxelGradientsMeetTheFaces)
{
  std::mt19937 random(71);
  const int dims[3] = { 29, 34, 23 };
  Scene scene = MakeScene(ScalarType::UInt8, dims, 0.3);
  std::uniform_int_distribution<int> noise(0, 90);
  for (std::uint8_t& v : scene.u8)
  {
    v = static_cast<std::uint8_t>(std::min(255, v + noise(random)));
  }
  std::uint64_t packetRays = 0;
  for (int trial = 0; trial < 6; ++trial)
  {
    RayCastTransfer transfer;
    transfer.rgba = RandomTable(random, 256, trial % 2 == 0);
    for (std::size_t i = 3; i < transfer.rgba.size(); i += 4)
    {
      transfer.rgba[i] *= 0.3f; // rays cross the faces and the inside
    }
    RayCastLighting lighting;
    lighting.shade = true;
    AddLights(trial, lighting);
    RayCastSettings settings = BaseSettings(dims, Blend::Composite);
    settings.leap = LeapMode::DistanceMap;
    settings.cellLeap = false;
    const Camera camera = RandomCamera(random, dims, trial % 2 == 1);
    const RayCastView view = MakeView(camera, 64, 52, 0.5, 500.0);
    packetRays += CastWithAndWithoutPackets(scene, transfer, lighting, view, settings, trial)
                    .first.counters.packetRays;
  }
  if (!CpuHasPackets())
  {
    GTEST_SKIP() << "no AVX-512 on this CPU: the images were compared, the packets never ran";
  }
  EXPECT_GT(packetRays, 6u * 1000u);
}

// Signed bytes (the packets' own corner loads, sign-extended), on a scene of its own: the
// blobs phantom shifted to [-128, 127].
TEST(RayCastPackets, SignedBytesGiveTheSameImages)
{
  std::mt19937 random(61);
  const int dims[3] = { 37, 30, 34 };
  const Scene unsignedScene = MakeScene(ScalarType::UInt8, dims, 0.2);
  std::vector<std::int8_t> values(unsignedScene.u8.size());
  for (std::size_t i = 0; i < values.size(); ++i)
  {
    values[i] = static_cast<std::int8_t>(static_cast<int>(unsignedScene.u8[i]) - 128);
  }
  Scene scene;
  scene.view = unsignedScene.view;
  scene.view.type = ScalarType::Int8;
  scene.view.data = values.data();
  scene.range[0] = -128;
  scene.range[1] = 127;
  std::uint64_t packetRays = 0;
  for (int trial = 0; trial < 4; ++trial)
  {
    RayCastTransfer transfer;
    transfer.rgba = RandomTable(random, 256, false);
    RayCastLighting lighting;
    lighting.shade = trial != 3;
    lighting.model.lights.emplace_back();
    RayCastSettings settings = BaseSettings(dims, Blend::Composite);
    settings.leap = LeapMode::DistanceMap;
    settings.cellLeap = false;
    const RayCastView view =
      MakeView(RandomCamera(random, dims, trial % 2 == 0), 53, 47, 0.5, 500.0);
    packetRays += CastWithAndWithoutPackets(scene, transfer, lighting, view, settings, trial)
                    .first.counters.packetRays;
  }
  if (CpuHasPackets())
  {
    EXPECT_GT(packetRays, 4u * 300u);
  }
}

// What the packets do not take goes the one-ray way, with the same images: cell leaping,
// nearest-voxel sampling, the baseline (SSE2) lanes.
TEST(RayCastPackets, OtherCasesTakeTheOneRayPaths)
{
  std::mt19937 random(59);
  const int dims[3] = { 33, 29, 31 };
  const Scene scene = MakeScene(ScalarType::UInt16, dims, 0.3);
  RayCastTransfer transfer;
  transfer.rgba = RandomTable(random, 256, false);
  RayCastLighting lighting;
  lighting.shade = true;
  lighting.model.lights.emplace_back();
  RayCastSettings settings = BaseSettings(dims, Blend::Composite);
  settings.leap = LeapMode::DistanceMap;
  settings.cellLeap = false;
  const RayCastView view = MakeView(RandomCamera(random, dims, false), 40, 36, 0.5, 500.0);
  const Result packets = Cast(scene, transfer, lighting, view, settings);
  // Rays whose samples all lie outside the box of possibly opaque cells count without a lane.
  EXPECT_LE(packets.counters.packetRays, packets.counters.rays);
  if (CpuHasPackets())
  {
    EXPECT_GT(packets.counters.packetRays, packets.counters.rays / 4);
  }
  settings.cellLeap = true;
  const Result cellLeap = Cast(scene, transfer, lighting, view, settings);
  EXPECT_EQ(cellLeap.counters.packetRays, 0u);
  EXPECT_TRUE(Identical(packets.rgba, cellLeap.rgba));
  settings.cellLeap = false;
  settings.nearest = true;
  EXPECT_EQ(Cast(scene, transfer, lighting, view, settings).counters.packetRays, 0u);
  settings.nearest = false;
  settings.baselineLanes = true;
  const Result baseline = Cast(scene, transfer, lighting, view, settings);
  EXPECT_EQ(baseline.counters.packetRays, 0u);
  EXPECT_TRUE(Identical(packets.rgba, baseline.rgba));
}
