// TestReferenceRenderer: analytic checks of the CPU projection oracle.
#include "ReferenceTestSupport.h"
#include "reference/ReferenceRenderer.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <functional>
#include <random>

namespace
{
using namespace accelvolume;
constexpr double Pi = 3.14159265358979323846;

using accelvolume_test::IndexBox;
using accelvolume_test::MakeVolume;

// Parallel rays along +x through the middle of a 21 x 11 x 11 index box: chord length 20.
Camera AlongX()
{
  Camera camera;
  camera.position = { -5, 5, 5 };
  camera.focalPoint = { 10, 5, 5 };
  camera.viewUp = { 0, 0, 1 };
  camera.parallel = true;
  camera.parallelScale = 2;
  return camera;
}

constexpr int Size = 6;

ReferenceOptions Options(Blend blend)
{
  ReferenceOptions options;
  options.blend = blend;
  return options;
}

void ExpectAll(const std::vector<ReferencePixel>& pixels, float value, double tolerance)
{
  ASSERT_EQ(pixels.size(), static_cast<std::size_t>(Size * Size));
  for (const ReferencePixel& pixel : pixels)
  {
    EXPECT_TRUE(pixel.hit);
    EXPECT_NEAR(pixel.value, value, tolerance);
  }
}

const OpacityTable Opaque{ { 1, 1 } };

TEST(ReferenceRenderer, ConstantVolumeAdditiveAndAverage)
{
  const ScalarVolume volume = MakeVolume(21, 11, 11, [](int, int, int) { return 0.5f; });
  ReferenceOptions options = Options(Blend::Additive);
  options.additiveUnitDistance = 2;
  const std::vector<Box> regions = { IndexBox(volume) };
  ExpectAll(RenderReference(volume, regions, {}, Opaque, AlongX(), Size, Size, options), 5, 1e-5);
  options.blend = Blend::Average;
  ExpectAll(RenderReference(volume, regions, {}, Opaque, AlongX(), Size, Size, options), 0.5, 1e-6);
  // A clip half-space x <= 10 halves the chord.
  options.blend = Blend::Additive;
  const std::vector<HalfSpace> clip = { { { -1, 0, 0 }, 10 } };
  ExpectAll(
    RenderReference(volume, regions, clip, Opaque, AlongX(), Size, Size, options), 2.5, 1e-5);
  // Opaque geometry 10 units from the camera plane leaves 5 units inside the volume.
  const std::vector<double> ends(Size * Size, 10.0);
  ExpectAll(
    RenderReference(volume, regions, {}, Opaque, AlongX(), Size, Size, options, &ends), 1.25, 1e-5);
  const std::vector<double> wrongSize(3, 1.0);
  EXPECT_THROW(
    RenderReference(volume, regions, {}, Opaque, AlongX(), Size, Size, options, &wrongSize),
    std::invalid_argument);
}

TEST(ReferenceRenderer, CroppingShortensChord)
{
  const ScalarVolume volume = MakeVolume(21, 11, 11, [](int, int, int) { return 0.5f; });
  const ReferenceOptions options = Options(Blend::Additive);
  const double planes[6] = { 4, 15, 1, 9, 1, 9 };
  constexpr int SubVolume = 0x0002000;
  std::vector<Box> regions = CroppingRegionBoxes(IndexBox(volume), planes, SubVolume);
  ExpectAll(
    RenderReference(volume, regions, {}, Opaque, AlongX(), Size, Size, options), 0.5 * 11, 1e-5);
  // Only the regions below and above the x planes in the centre column: chords 4 + 5.
  constexpr int OuterX = (1 << (0 + 3 + 9)) | (1 << (2 + 3 + 9));
  regions = CroppingRegionBoxes(IndexBox(volume), planes, OuterX);
  ASSERT_EQ(regions.size(), 2u);
  ExpectAll(
    RenderReference(volume, regions, {}, Opaque, AlongX(), Size, Size, options), 0.5 * 9, 1e-5);
}

TEST(ReferenceRenderer, RampExtremaOverCroppedRange)
{
  const ScalarVolume ramp = MakeVolume(21, 11, 11, [](int i, int, int) { return i / 20.0f; });
  const double planes[6] = { 4, 15, 0, 10, 0, 10 };
  const std::vector<Box> regions = CroppingRegionBoxes(IndexBox(ramp), planes, 0x0002000);
  ExpectAll(RenderReference(
              ramp, regions, {}, Opaque, AlongX(), Size, Size, Options(Blend::Maximum)),
    15 / 20.0f, 1e-6);
  ExpectAll(RenderReference(
              ramp, regions, {}, Opaque, AlongX(), Size, Size, Options(Blend::Minimum)),
    4 / 20.0f, 1e-6);
  // Opacity(s) = s turns the raysum into the integral of (x / 20)^2 over [0, 20] = 20 / 3.
  const OpacityTable linear{ { 0, 1 } };
  ExpectAll(RenderReference(ramp, { IndexBox(ramp) }, {}, linear, AlongX(), Size, Size,
              Options(Blend::Additive)),
    20 / 3.0f, 1e-3);
}

TEST(ReferenceRenderer, AverageRange)
{
  const ScalarVolume step =
    MakeVolume(21, 11, 11, [](int i, int, int) { return i < 10 ? 0.2f : 0.8f; });
  ReferenceOptions options = Options(Blend::Average);
  options.averageRangeMin = 0.5;
  // Counted: x in [9.5, 10] where s rises from 0.5 to 0.8 (mean 0.65), then 0.8 up to x = 20.
  ExpectAll(RenderReference(step, { IndexBox(step) }, {}, Opaque, AlongX(), Size, Size, options),
    (0.65 * 0.5 + 0.8 * 10) / 10.5, 5e-3);
  options.averageRangeMin = 0.9;
  for (const ReferencePixel& pixel :
    RenderReference(step, { IndexBox(step) }, {}, Opaque, AlongX(), Size, Size, options))
  {
    EXPECT_FALSE(pixel.hit);
    EXPECT_EQ(pixel.value, 0);
  }
}

TEST(ReferenceRenderer, RaysMissingVolumeAreNotHit)
{
  const ScalarVolume volume = MakeVolume(21, 11, 11, [](int, int, int) { return 0.5f; });
  Camera camera = AlongX();
  camera.parallelScale = 10; // the image spans y, z in [-5, 15]; the volume [0, 10]
  constexpr int Pixels = 20;
  for (Blend blend : { Blend::Maximum, Blend::Minimum,
         Blend::Additive, Blend::Average })
  {
    const std::vector<ReferencePixel> pixels = RenderReference(
      volume, { IndexBox(volume) }, {}, Opaque, camera, Pixels, Pixels, Options(blend));
    for (int j = 0; j < Pixels; ++j)
    {
      for (int i = 0; i < Pixels; ++i)
      {
        const Ray ray = PixelRay(camera, Pixels, Pixels, i, j);
        const bool inside =
          ray.origin.y >= 0 && ray.origin.y <= 10 && ray.origin.z >= 0 && ray.origin.z <= 10;
        EXPECT_EQ(pixels[i + j * Pixels].hit, inside);
        EXPECT_EQ(pixels[i + j * Pixels].value, inside ? pixels[i + j * Pixels].value : 0.0f);
      }
    }
  }
}

TEST(ReferenceRenderer, PixelRays)
{
  Camera camera;
  camera.position = { 1, 2, 3 };
  camera.focalPoint = { 4, -2, 3 };
  camera.viewUp = { 0, 0, 1 };
  camera.viewAngleDegrees = 40;
  const Vec3 forward = Normalize(camera.focalPoint - camera.position);
  // Odd sizes put a pixel centre on the view axis.
  Ray centre = PixelRay(camera, 5, 3, 2, 1);
  EXPECT_NEAR(Length(centre.origin - camera.position), 0, 1e-12);
  EXPECT_NEAR(Dot(centre.direction, forward), 1, 1e-12);
  // Top-middle pixel: NDC y = 2/3, so tan(angle to axis) = 2/3 * tan(20 degrees), tilted upward.
  const Ray top = PixelRay(camera, 5, 3, 2, 2);
  EXPECT_NEAR(Length(top.direction), 1, 1e-12);
  EXPECT_NEAR(
    std::tan(std::acos(Dot(top.direction, forward))), 2.0 / 3 * std::tan(20 * Pi / 180), 1e-12);
  EXPECT_GT(top.direction.z, 0);
  // Right-middle pixel: NDC x = 0.8 times the aspect 5/3, tilted to the right of the view.
  const Ray right = PixelRay(camera, 5, 3, 4, 1);
  EXPECT_NEAR(std::tan(std::acos(Dot(right.direction, forward))),
    0.8 * 5 / 3 * std::tan(20 * Pi / 180), 1e-12);
  EXPECT_GT(Dot(right.direction, Cross(forward, camera.viewUp)), 0);

  camera.parallel = true;
  camera.parallelScale = 3;
  centre = PixelRay(camera, 5, 3, 2, 1);
  EXPECT_NEAR(Length(centre.origin - camera.position), 0, 1e-12);
  for (int j = 0; j < 3; ++j)
  {
    for (int i = 0; i < 5; ++i)
    {
      const Ray ray = PixelRay(camera, 5, 3, i, j);
      EXPECT_NEAR(Length(ray.direction - forward), 0, 1e-12);
      EXPECT_NEAR(Dot(ray.origin - camera.position, forward), 0, 1e-12);
    }
  }
  // The top pixel centre sits at NDC 2/3 of the half-height.
  EXPECT_NEAR(PixelRay(camera, 5, 3, 2, 2).origin.z - camera.position.z, 2.0, 1e-12);
}

TEST(ReferenceRenderer, NonuniformSpacingIntegratesWorldLength)
{
  ScalarVolume volume = MakeVolume(21, 11, 11, [](int, int, int) { return 0.5f; });
  // Spacing (2, 0.5, 1): the index box spans 40 x 5 x 10 world units.
  volume.indexToWorld = Affine::Identity();
  volume.indexToWorld.m[0][0] = 2;
  volume.indexToWorld.m[1][1] = 0.5;
  Camera camera = AlongX();
  camera.position = { -5, 2.5, 5 };
  camera.focalPoint = { 10, 2.5, 5 };
  ReferenceOptions options = Options(Blend::Additive);
  ExpectAll(RenderReference(volume, { IndexBox(volume) }, {}, Opaque, camera, Size, Size, options),
    0.5 * 40, 1e-4);
  camera.position = { 20, -5, 5 };
  camera.focalPoint = { 20, 2.5, 5 };
  ExpectAll(RenderReference(volume, { IndexBox(volume) }, {}, Opaque, camera, Size, Size, options),
    0.5 * 5, 1e-5);
  // Rotated by 90 degrees about z and translated: index x runs along world y.
  volume.indexToWorld = { { { 0, -0.5, 0, 100 }, { 2, 0, 0, -7 }, { 0, 0, 1, 3 } } };
  camera.position = { 100 - 2.5, -50, 8 };
  camera.focalPoint = { 100 - 2.5, 0, 8 };
  ExpectAll(RenderReference(volume, { IndexBox(volume) }, {}, Opaque, camera, Size, Size, options),
    0.5 * 40, 1e-4);
}

TEST(ReferenceRenderer, AffineInverse)
{
  const Affine affine{ { { 0.3, -1, 2, 5 }, { 1.5, 0.2, 0, -1 }, { 0, 0.7, 1.1, 2 } } };
  const Affine inverse = affine.Inverse();
  const Vec3 p{ 0.4, -3, 7 };
  const Vec3 back = inverse.Apply(affine.Apply(p));
  EXPECT_NEAR(Length(back - p), 0, 1e-12);
  EXPECT_NEAR(Length(inverse.ApplyLinear(affine.ApplyLinear(p)) - p), 0, 1e-12);
  const Affine singular{ { { 1, 0, 0, 0 }, { 0, 0, 0, 0 }, { 0, 0, 1, 0 } } };
  EXPECT_THROW(singular.Inverse(), std::domain_error);
}

TEST(ReferenceRenderer, ThreadCountDoesNotChangeResults)
{
  std::mt19937 random(1);
  std::uniform_real_distribution<float> uniform(0, 1);
  const ScalarVolume noise = MakeVolume(17, 13, 11, [&](int, int, int) { return uniform(random); });
  Camera camera;
  camera.position = { -10, -14, 20 };
  camera.focalPoint = { 8, 6, 5 };
  camera.viewUp = { 0, 0, 1 };
  const OpacityTable ramp{ { 0.1f, 0.9f, 0.4f, 1 } };
  const std::vector<HalfSpace> clip = { { Normalize({ 1, 1, -1 }), 1 } };
  for (Blend blend :
    { Blend::Maximum, Blend::Additive, Blend::Average })
  {
    ReferenceOptions options = Options(blend);
    options.averageRangeMin = 0.2;
    options.threads = 1;
    const auto one =
      RenderReference(noise, { IndexBox(noise) }, clip, ramp, camera, 31, 17, options);
    options.threads = 4;
    const auto four =
      RenderReference(noise, { IndexBox(noise) }, clip, ramp, camera, 31, 17, options);
    ASSERT_EQ(one.size(), four.size());
    int hits = 0;
    for (std::size_t n = 0; n < one.size(); ++n)
    {
      EXPECT_EQ(one[n].hit, four[n].hit);
      EXPECT_EQ(one[n].value, four[n].value); // bitwise
      hits += one[n].hit ? 1 : 0;
    }
    EXPECT_GT(hits, 50);
  }
}

TEST(ReferenceRenderer, Sampling)
{
  auto linear = [](double x, double y, double z) { return 0.1 + 0.03 * x + 0.02 * y + 0.01 * z; };
  const ScalarVolume volume =
    MakeVolume(8, 6, 5, [&](int i, int j, int k) { return static_cast<float>(linear(i, j, k)); });
  std::mt19937 random(2);
  std::uniform_real_distribution<double> coordinate(-3, 10);
  for (int n = 0; n < 1000; ++n)
  {
    const Vec3 p{ coordinate(random), coordinate(random), coordinate(random) };
    // Clamp-to-edge: outside points take the value at the clamped point; inside is exact.
    const double x = std::clamp(p.x, 0.0, 7.0), y = std::clamp(p.y, 0.0, 5.0),
                 z = std::clamp(p.z, 0.0, 4.0);
    EXPECT_NEAR(volume.SampleTrilinear(p), linear(x, y, z), 1e-6);
    EXPECT_NEAR(volume.SampleNearest(p),
      linear(std::floor(x + 0.5), std::floor(y + 0.5), std::floor(z + 0.5)), 1e-6);
  }
  EXPECT_FLOAT_EQ(volume.SampleTrilinear({ 7, 5, 4 }), volume.Value(7, 5, 4));
  EXPECT_FLOAT_EQ(volume.SampleNearest({ 2.49, 0.5, 3.51 }), volume.Value(2, 1, 4));

  const OpacityTable table{ { 0, 1, 0.5f } };
  EXPECT_FLOAT_EQ(table.Lookup(0.25f), 0.5f);
  EXPECT_FLOAT_EQ(table.Lookup(0.75f), 0.75f);
  EXPECT_FLOAT_EQ(table.Lookup(-1), 0);
  EXPECT_FLOAT_EQ(table.Lookup(2), 0.5f);
  EXPECT_FLOAT_EQ(OpacityTable{}.Lookup(0.3f), 1);
  EXPECT_FLOAT_EQ(OpacityTable{ { 0.25f } }.Lookup(0.3f), 0.25f);
}

TEST(ReferenceRenderer, Speed)
{
  const ScalarVolume volume =
    MakeVolume(64, 64, 64, [](int i, int j, int k) { return ((i ^ j ^ k) & 63) / 63.0f; });
  // World extent 1 per axis, viewed obliquely.
  ScalarVolume scaled = volume;
  scaled.indexToWorld = Affine::Identity();
  for (int axis = 0; axis < 3; ++axis)
  {
    scaled.indexToWorld.m[axis][axis] = 1.0 / 63;
  }
  Camera camera;
  camera.position = { 2, 1.5, 2.5 };
  camera.focalPoint = { 0.5, 0.5, 0.5 };
  camera.viewUp = { 0, 0, 1 };
  ReferenceOptions options = Options(Blend::Additive);
  options.stepWorld = 0.05 / 63; // as fine in voxels as step 0.05 at unit spacing
  const auto start = std::chrono::steady_clock::now();
  const auto pixels =
    RenderReference(scaled, { IndexBox(scaled) }, {}, Opaque, camera, 128, 128, options);
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cout << "128x128 of 64^3 at 20 samples per voxel: " << seconds << " s\n";
  EXPECT_EQ(pixels.size(), 128u * 128u);
  EXPECT_LT(seconds, 10.0); // generous: shared machines; the expected time is well under 1 s
}

} // namespace
