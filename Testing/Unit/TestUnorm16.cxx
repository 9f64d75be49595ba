// TestUnorm16: the displayed images' 16-bit conversion gives the scalar formula's values in its
// SIMD lanes, for every count (the lanes' tail) and for the special values.
#include "common/Unorm16.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

namespace
{

std::uint16_t Expected(float v)
{
  if (!(v > 0.0f))
  {
    return 0; // negative, zero or NaN
  }
  const float clamped = v < 1.0f ? v : 1.0f;
  return static_cast<std::uint16_t>(clamped * 65535.0f + 0.5f);
}

TEST(Unorm16, LanesGiveTheScalarValues)
{
  std::mt19937 random(16);
  std::uniform_real_distribution<float> value(-0.25f, 1.25f);
  std::vector<float> in(4099);
  for (float& v : in)
  {
    v = value(random);
  }
  // Values whose scaled product lies next to k + 0.5 (the rounding edges).
  for (int k = 0; k < 600; ++k)
  {
    in[static_cast<std::size_t>(k)] = std::nextafter((k + 0.5f) / 65535.0f, k % 2 ? 1.0f : 0.0f);
  }
  const float special[] = { 0.0f, -0.0f, 1.0f, -1.0f, std::numeric_limits<float>::infinity(),
    -std::numeric_limits<float>::infinity(), std::numeric_limits<float>::quiet_NaN(),
    std::numeric_limits<float>::denorm_min(), std::nextafter(1.0f, 2.0f),
    std::nextafter(1.0f, 0.0f), 0.5f / 65535.0f };
  std::memcpy(in.data() + 700, special, sizeof(special));
  for (std::size_t count : { std::size_t(0), std::size_t(1), std::size_t(15), std::size_t(16),
         std::size_t(17), std::size_t(4099) })
  {
    std::vector<std::uint16_t> out(count + 1, 7);
    accelvolume::ConvertToUnorm16(in.data(), count, out.data());
    for (std::size_t i = 0; i < count; ++i)
    {
      ASSERT_EQ(out[i], Expected(in[i])) << "value " << in[i] << " at " << i << " of " << count;
    }
    EXPECT_EQ(out[count], 7) << "wrote past the end, count " << count;
  }
}

}
