// The ray caster's 32-bit precomputed gradients (EncodeGradient / DecodeGradient): exact for
// integer differences up to 511 units, otherwise within half a step of the shared exponent
// (half a unit while every component is within 511 units, else under 1/255 of the largest).
#include "raycast/RayCastSampler.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

using accelvolume::detail::DecodeGradient;
using accelvolume::detail::EncodeGradient;

TEST(RayCastGradients, SmallIntegerDifferencesAreExact)
{
  for (int x = -511; x <= 511; x += 7)
  {
    for (const int y : { -511, -256, -1, 0, 1, 300, 511 })
    {
      const float g[3] = { static_cast<float>(x), static_cast<float>(y), static_cast<float>(-x) };
      float back[3];
      DecodeGradient(EncodeGradient(g), back);
      for (int k = 0; k < 3; ++k)
      {
        EXPECT_EQ(back[k], g[k]) << x << " " << y;
      }
    }
  }
}

TEST(RayCastGradients, LargeValuesShareOneExponent)
{
  std::mt19937 random(7);
  std::uniform_real_distribution<float> component(-32767.0f, 32767.0f);
  std::uniform_real_distribution<float> shrink(0.0f, 1.0f);
  for (int trial = 0; trial < 20000; ++trial)
  {
    // Components of one gradient at different scales, as across an edge.
    const float scale = std::pow(shrink(random), 3.0f);
    const float g[3] = { component(random) * scale, component(random) * scale * shrink(random),
      component(random) };
    const float largest = std::max({ std::abs(g[0]), std::abs(g[1]), std::abs(g[2]) });
    int exponent = 0;
    while (exponent < 3 && largest > 511.0f * std::ldexp(1.0f, 2 * exponent))
    {
      ++exponent;
    }
    const float step = std::ldexp(1.0f, 2 * exponent);
    float back[3];
    DecodeGradient(EncodeGradient(g), back);
    for (int k = 0; k < 3; ++k)
    {
      // Half a step, or the clamp to 511 steps at the very top of the range.
      const float bound = std::max(0.5f * step, std::abs(g[k]) - 511.0f * step);
      EXPECT_LE(std::abs(back[k] - g[k]), bound) << "trial " << trial << " axis " << k;
      if (exponent > 0)
      {
        EXPECT_LE(std::abs(back[k] - g[k]), largest / 255.5f) << "trial " << trial;
      }
      // Signs survive, and zero stays zero.
      EXPECT_TRUE(back[k] == 0 || (back[k] > 0) == (g[k] > 0)) << "trial " << trial;
    }
  }
}

TEST(RayCastGradients, ExtremesDecodeWithinTheRange)
{
  const float extremes[3] = { 32767.0f, -32767.0f, 0.25f };
  float back[3];
  DecodeGradient(EncodeGradient(extremes), back);
  EXPECT_NEAR(back[0], 32767.0f, 64.0f);
  EXPECT_NEAR(back[1], -32767.0f, 64.0f);
  EXPECT_EQ(back[2], 0.0f);
  const float zero[3] = { 0, 0, 0 };
  EXPECT_EQ(EncodeGradient(zero), 0u);
}
