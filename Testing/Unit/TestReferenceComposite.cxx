// TestReferenceComposite: analytic checks of the CPU composite (direct volume rendering) oracle.
#include "ReferenceTestSupport.h"
#include "reference/ReferenceComposite.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>
#include <stdexcept>

namespace
{
using namespace accelvolume;

using accelvolume_test::IndexBox;
using accelvolume_test::MakeVolume;

// Parallel rays along +x (or -x) through the middle of a 21 x 11 x 11 index box: chord length 20,
// entered 5 world units from the ray origins.
Camera AlongX(bool reversed = false)
{
  Camera camera;
  camera.position = { reversed ? 25.0 : -5.0, 5, 5 };
  camera.focalPoint = { 10, 5, 5 };
  camera.viewUp = { 0, 0, 1 };
  camera.parallel = true;
  camera.parallelScale = 2;
  return camera;
}

constexpr int Size = 6;
const std::vector<float> White = { 1, 1, 1, 1, 1, 1 };

CompositeOptions Options(double step, double unit)
{
  CompositeOptions options;
  options.stepWorld = step;
  options.opacityUnitDistance = unit;
  return options;
}

void ExpectAll(const std::vector<CompositePixel>& pixels, const float (&rgba)[4], double tolerance)
{
  ASSERT_EQ(pixels.size(), static_cast<std::size_t>(Size * Size));
  for (const CompositePixel& pixel : pixels)
  {
    for (int c = 0; c < 4; ++c)
    {
      EXPECT_NEAR(pixel.rgba[c], rgba[c], tolerance) << "channel " << c;
    }
  }
}

// A smooth non-constant field, so region splits and sampling positions matter.
ScalarVolume WavyVolume()
{
  return MakeVolume(21, 11, 11,
    [](int i, int j, int k) {
      return static_cast<float>(0.5 + 0.3 * std::sin(0.4 * i) + 0.15 * std::cos(0.5 * j + 0.3 * k));
    });
}

const std::vector<float> Rainbow = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
const OpacityTable Ramp{ { 0.05f, 0.2f, 0.6f } };

TEST(ReferenceComposite, ConstantVolumeIsStepIndependent)
{
  const ScalarVolume volume = MakeVolume(21, 11, 11, [](int, int, int) { return 0.5f; });
  const double a0 = 0.3, unit = 10;
  const OpacityTable opacity{ { static_cast<float>(a0), static_cast<float>(a0) } };
  const std::vector<float> colour = { 0.2f, 0.4f, 0.8f, 0.2f, 0.4f, 0.8f };
  const float alpha = static_cast<float>(1 - std::pow(1 - a0, 20 / unit));
  const float expected[4] = { 0.2f * alpha, 0.4f * alpha, 0.8f * alpha, alpha };
  for (double step : { 0.05, 0.3, 0.7, 1.0, 3.0, 25.0 })
  {
    SCOPED_TRACE(step);
    ExpectAll(RenderReferenceComposite(volume, { IndexBox(volume) }, {}, colour, opacity, AlongX(),
                Size, Size, Options(step, unit)),
      expected, 1e-5);
  }
}

TEST(ReferenceComposite, VaryingOpacityConvergesToAnalyticTransmittance)
{
  // s = x / 20 along the chord and table opacity 0.6 s: alpha = 1 - exp(integral ln(1 - 0.03 x)
  // dx / unit), with the integral -(u ln u - u) / 0.03 between u = 1 and u = 0.4.
  const ScalarVolume volume = MakeVolume(21, 11, 11, [](int i, int, int) { return i / 20.0f; });
  const OpacityTable opacity{ { 0.0f, 0.6f } };
  const double unit = 10;
  const double integral = -((0.4 * std::log(0.4) - 0.4) - (-1.0)) / 0.03;
  const float alpha = static_cast<float>(1 - std::exp(integral / unit));
  const float expected[4] = { alpha, alpha, alpha, alpha };
  ExpectAll(RenderReferenceComposite(volume, { IndexBox(volume) }, {}, White, opacity, AlongX(),
              Size, Size, Options(0.05, unit)),
    expected, 1e-4);
  ExpectAll(RenderReferenceComposite(volume, { IndexBox(volume) }, {}, White, opacity, AlongX(),
              Size, Size, Options(0.5, unit)),
    expected, 1e-3);
}

TEST(ReferenceComposite, FrontLayerDominates)
{
  // Red (s = 0) for x < 9.5, blue (s = 1) beyond; the same opacity everywhere.
  const ScalarVolume volume =
    MakeVolume(21, 11, 11, [](int i, int, int) { return i < 10 ? 0.0f : 1.0f; });
  const std::vector<float> colour = { 1, 0, 0, 0, 0, 1 };
  const OpacityTable opacity{ { 0.5f, 0.5f } };
  const float alpha = static_cast<float>(1 - std::pow(0.5, 20 / 10.0));
  for (bool reversed : { false, true })
  {
    SCOPED_TRACE(reversed);
    const auto pixels = RenderReferenceComposite(volume, { IndexBox(volume) }, {}, colour, opacity,
      AlongX(reversed), Size, Size, Options(0.05, 10));
    for (const CompositePixel& pixel : pixels)
    {
      const float front = reversed ? pixel.rgba[2] : pixel.rgba[0];
      const float back = reversed ? pixel.rgba[0] : pixel.rgba[2];
      // The front layer (about half the chord) takes about 1 - 0.5^0.95 = 0.48; the back one only
      // what the front lets through.
      EXPECT_GT(front, 0.45f);
      EXPECT_LT(back, 0.28f);
      EXPECT_GT(back, 0.2f);
      EXPECT_EQ(pixel.rgba[1], 0.0f);
      EXPECT_NEAR(pixel.rgba[0] + pixel.rgba[2], pixel.rgba[3], 1e-6);
      EXPECT_NEAR(pixel.rgba[3], alpha, 1e-5);
    }
  }
}

TEST(ReferenceComposite, OpacityUnitDistanceScaling)
{
  const ScalarVolume volume = MakeVolume(21, 11, 11, [](int, int, int) { return 0.5f; });
  const double a0 = 0.2;
  const OpacityTable opacity{ { static_cast<float>(a0), static_cast<float>(a0) } };
  for (double unit : { 1.0, 4.0, 20.0, 50.0 })
  {
    SCOPED_TRACE(unit);
    const float alpha = static_cast<float>(1 - std::pow(1 - a0, 20 / unit));
    const float expected[4] = { alpha, alpha, alpha, alpha };
    ExpectAll(RenderReferenceComposite(volume, { IndexBox(volume) }, {}, White, opacity, AlongX(),
                Size, Size, Options(0.1, unit)),
      expected, 1e-5);
  }
  // Scaling the world (spacing 2.5) and the unit distance together leaves the image unchanged.
  const ScalarVolume wavy = WavyVolume();
  ScalarVolume scaled = wavy;
  scaled.indexToWorld = { { { 2.5, 0, 0, 0 }, { 0, 2.5, 0, 0 }, { 0, 0, 2.5, 0 } } };
  Camera camera = AlongX();
  Camera scaledCamera = camera;
  scaledCamera.position = 2.5 * camera.position;
  scaledCamera.focalPoint = 2.5 * camera.focalPoint;
  scaledCamera.parallelScale = 2.5 * camera.parallelScale;
  const auto reference = RenderReferenceComposite(
    wavy, { IndexBox(wavy) }, {}, Rainbow, Ramp, camera, Size, Size, Options(0.1, 3));
  const auto scaledPixels = RenderReferenceComposite(
    scaled, { IndexBox(scaled) }, {}, Rainbow, Ramp, scaledCamera, Size, Size, Options(0.25, 7.5));
  ASSERT_EQ(reference.size(), scaledPixels.size());
  for (std::size_t n = 0; n < reference.size(); ++n)
    for (int c = 0; c < 4; ++c)
      EXPECT_NEAR(reference[n].rgba[c], scaledPixels[n].rgba[c], 1e-5);
}

TEST(ReferenceComposite, SplitRegionsMatchOneBox)
{
  const ScalarVolume volume = WavyVolume();
  const Box whole = IndexBox(volume);
  const Box front = { { 0, 0, 0 }, { 8, 10, 10 } };
  const Box back = { { 8, 0, 0 }, { 20, 10, 10 } };
  // Along x with step 0.5 both boxes hold whole steps, so the samples coincide with the single
  // box's; listing the back box first checks the regions are composited in ray order.
  const auto one = RenderReferenceComposite(
    volume, { whole }, {}, Rainbow, Ramp, AlongX(), Size, Size, Options(0.5, 2));
  const auto two = RenderReferenceComposite(
    volume, { back, front }, {}, Rainbow, Ramp, AlongX(), Size, Size, Options(0.5, 2));
  ASSERT_EQ(one.size(), two.size());
  for (std::size_t n = 0; n < one.size(); ++n)
  {
    EXPECT_GT(one[n].rgba[3], 0.1f);
    for (int c = 0; c < 4; ++c)
      EXPECT_NEAR(one[n].rgba[c], two[n].rgba[c], 1e-6);
  }
  // Oblique perspective rays split anywhere: the samples differ but converge to the same image.
  Camera camera;
  camera.position = { -15, -8, 20 };
  camera.focalPoint = { 10, 5, 5 };
  camera.viewAngleDegrees = 25;
  const auto oneOblique =
    RenderReferenceComposite(volume, { whole }, {}, Rainbow, Ramp, camera, 9, 7, Options(0.02, 2));
  const auto twoOblique = RenderReferenceComposite(
    volume, { back, front }, {}, Rainbow, Ramp, camera, 9, 7, Options(0.02, 2));
  for (std::size_t n = 0; n < oneOblique.size(); ++n)
    for (int c = 0; c < 4; ++c)
      EXPECT_NEAR(oneOblique[n].rgba[c], twoOblique[n].rgba[c], 1e-4);
}

TEST(ReferenceComposite, RaysEndTruncates)
{
  const ScalarVolume volume = MakeVolume(21, 11, 11, [](int, int, int) { return 0.5f; });
  const double a0 = 0.3, unit = 5;
  const OpacityTable opacity{ { static_cast<float>(a0), static_cast<float>(a0) } };
  // The chord starts 5 from the ray origins: an end at 15 keeps 10 of it.
  std::vector<double> ends(Size * Size, 15.0);
  const float alpha = static_cast<float>(1 - std::pow(1 - a0, 10 / unit));
  const float expected[4] = { alpha, alpha, alpha, alpha };
  ExpectAll(RenderReferenceComposite(volume, { IndexBox(volume) }, {}, White, opacity, AlongX(),
              Size, Size, Options(0.3, unit), &ends),
    expected, 1e-5);
  // Opaque geometry before the volume hides it entirely.
  std::fill(ends.begin(), ends.end(), 3.0);
  const float zero[4] = { 0, 0, 0, 0 };
  ExpectAll(RenderReferenceComposite(volume, { IndexBox(volume) }, {}, White, opacity, AlongX(),
              Size, Size, Options(0.3, unit), &ends),
    zero, 0);
  ends.pop_back();
  EXPECT_THROW(RenderReferenceComposite(volume, { IndexBox(volume) }, {}, White, opacity, AlongX(),
                 Size, Size, Options(0.3, unit), &ends),
    std::invalid_argument);
}

TEST(ReferenceComposite, ThreadCountDoesNotChangeResults)
{
  std::mt19937 random(7);
  std::uniform_real_distribution<float> uniform(0, 1);
  const ScalarVolume volume = MakeVolume(13, 9, 11, [&](int, int, int) { return uniform(random); });
  Camera camera;
  camera.position = { -10, 20, 25 };
  camera.focalPoint = { 6, 4, 5 };
  camera.viewAngleDegrees = 35;
  const std::vector<HalfSpace> clip = { { { 1, 1, 0 }, -3 } };
  const std::vector<Box> regions = { { { 0, 0, 0 }, { 5, 8, 10 } },
    { { 5, 0, 0 }, { 12, 8, 10 } } };
  CompositeOptions options = Options(0.1, 1.5);
  std::vector<std::vector<CompositePixel>> results;
  for (int threads : { 1, 4, 0 })
  {
    options.threads = threads;
    results.push_back(
      RenderReferenceComposite(volume, regions, clip, Rainbow, Ramp, camera, 23, 17, options));
  }
  bool anyHit = false;
  for (std::size_t n = 0; n < results[0].size(); ++n)
  {
    anyHit = anyHit || results[0][n].rgba[3] > 0;
    for (int c = 0; c < 4; ++c)
    {
      EXPECT_EQ(results[0][n].rgba[c], results[1][n].rgba[c]);
      EXPECT_EQ(results[0][n].rgba[c], results[2][n].rgba[c]);
    }
  }
  EXPECT_TRUE(anyHit);
}

TEST(ReferenceComposite, MissingRaysGiveZero)
{
  const ScalarVolume volume = MakeVolume(21, 11, 11, [](int, int, int) { return 0.5f; });
  const OpacityTable opacity{ { 0.4f, 0.4f } };
  // A wide parallel view: only the pixels whose rays cross y, z in [0, 10] hit.
  Camera camera = AlongX();
  camera.parallelScale = 12;
  const int size = 12;
  const auto pixels = RenderReferenceComposite(
    volume, { IndexBox(volume) }, {}, White, opacity, camera, size, size, Options(0.1, 1));
  int hits = 0, misses = 0;
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i)
    {
      const Ray ray = PixelRay(camera, size, size, i, j);
      const bool inside =
        ray.origin.y >= 0 && ray.origin.y <= 10 && ray.origin.z >= 0 && ray.origin.z <= 10;
      const CompositePixel& pixel = pixels[i + j * size];
      if (inside)
      {
        ++hits;
        EXPECT_GT(pixel.rgba[3], 0.9f);
      }
      else
      {
        ++misses;
        for (float channel : pixel.rgba)
          EXPECT_EQ(channel, 0.0f);
      }
    }
  EXPECT_GT(hits, 0);
  EXPECT_GT(misses, 0);
  // The volume behind the camera: no t >= 0 part of any ray meets it.
  Camera away = AlongX();
  away.focalPoint = { -20, 5, 5 };
  const float zero[4] = { 0, 0, 0, 0 };
  ExpectAll(RenderReferenceComposite(
              volume, { IndexBox(volume) }, {}, White, opacity, away, Size, Size, Options(0.1, 1)),
    zero, 0);
}

TEST(ReferenceComposite, RejectsBadArguments)
{
  const ScalarVolume volume = MakeVolume(3, 3, 3, [](int, int, int) { return 0.5f; });
  const OpacityTable opacity{ { 0.4f, 0.4f } };
  EXPECT_THROW(RenderReferenceComposite(
                 volume, { IndexBox(volume) }, {}, White, opacity, AlongX(), 2, 2, Options(0, 1)),
    std::invalid_argument);
  EXPECT_THROW(RenderReferenceComposite(
                 volume, { IndexBox(volume) }, {}, White, opacity, AlongX(), 2, 2, Options(0.1, 0)),
    std::invalid_argument);
  EXPECT_THROW(RenderReferenceComposite(volume, { IndexBox(volume) }, {}, { 1, 1 }, opacity,
                 AlongX(), 2, 2, Options(0.1, 1)),
    std::invalid_argument);
  EXPECT_TRUE(RenderReferenceComposite(
    volume, { IndexBox(volume) }, {}, White, opacity, AlongX(), 0, 2, Options(0.1, 1))
                .empty());
}
} // namespace
