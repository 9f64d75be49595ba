#include "common/Unorm16.h"

#include "common/Avx512.h"

#include <algorithm>
#include <cstring>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace accelvolume
{

namespace
{

inline std::uint16_t ToUnorm16(float v)
{
  v = v > 0.0f ? std::min(v, 1.0f) : 0.0f; // NaN too
  return static_cast<std::uint16_t>(v * 65535.0f + 0.5f);
}

#if ACCELVOLUME_AVX512_BUILD
// This file never contracts v * 65535 + 0.5 into FMA (the CMake module's options), so the lanes
// round as the scalar code does.
ACCELVOLUME_AVX512 void ConvertInLanes(const float* in, std::size_t count, std::uint16_t* out)
{
  const __m512 zero = _mm512_setzero_ps(), one = _mm512_set1_ps(1.0f);
  std::size_t i = 0;
  for (; i + 16 <= count; i += 16)
  {
    // maxps(v, 0) is 0 for a NaN v (its second operand), as ToUnorm16's comparison gives.
    const __m512 v = _mm512_min_ps(_mm512_max_ps(_mm512_loadu_ps(in + i), zero), one);
    const __m512 scaled =
      _mm512_add_ps(_mm512_mul_ps(v, _mm512_set1_ps(65535.0f)), _mm512_set1_ps(0.5f));
    _mm256_storeu_si256(
      reinterpret_cast<__m256i*>(out + i), _mm512_cvtepi32_epi16(_mm512_cvttps_epi32(scaled)));
  }
  for (; i < count; ++i)
  {
    out[i] = ToUnorm16(in[i]);
  }
}
#endif

#if defined(__SSE2__)
// Every x86-64 CPU: 8 values a step. The truncated values lie in [0, 65535]; SSE2 packs 32-bit
// integers to 16 bits with signed saturation only, so they are packed less 32768 and the sign
// bit flipped back.
void ConvertInSse2Lanes(const float* in, std::size_t count, std::uint16_t* out)
{
  const __m128 zero = _mm_setzero_ps(), one = _mm_set1_ps(1.0f);
  const __m128 scale = _mm_set1_ps(65535.0f), half = _mm_set1_ps(0.5f);
  const __m128i bias = _mm_set1_epi32(32768);
  const __m128i signBit = _mm_set1_epi16(static_cast<short>(0x8000));
  const auto convert = [&](const float* four)
  {
    // maxps(v, 0) is 0 for a NaN v (its second operand), as ToUnorm16's comparison gives.
    const __m128 v = _mm_min_ps(_mm_max_ps(_mm_loadu_ps(four), zero), one);
    return _mm_sub_epi32(_mm_cvttps_epi32(_mm_add_ps(_mm_mul_ps(v, scale), half)), bias);
  };
  std::size_t i = 0;
  for (; i + 8 <= count; i += 8)
  {
    const __m128i packed = _mm_packs_epi32(convert(in + i), convert(in + i + 4));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out + i), _mm_xor_si128(packed, signBit));
  }
  for (; i < count; ++i)
  {
    out[i] = ToUnorm16(in[i]);
  }
}
#endif

// The first and last of `count` RGBA pixels (4 channels of 16 bits) that are not all zero;
// first > last when every pixel is zero.
void FindNonZeroPixels(const std::uint16_t* rgba, int count, int& first, int& last)
{
  const auto visible = [rgba](int i)
  {
    std::uint64_t bits;
    std::memcpy(&bits, rgba + 4 * static_cast<std::size_t>(i), sizeof bits);
    return bits != 0;
  };
  first = 0;
  while (first < count && !visible(first))
  {
    ++first;
  }
  last = count - 1;
  while (last > first && !visible(last))
  {
    --last;
  }
  if (first == count)
  {
    last = -1;
  }
}

} // namespace

void ConvertToUnorm16(const float* in, std::size_t count, std::uint16_t* out)
{
#if ACCELVOLUME_AVX512_BUILD
  if (CpuHasAvx512())
  {
    ConvertInLanes(in, count, out);
    return;
  }
#endif
#if defined(__SSE2__)
  ConvertInSse2Lanes(in, count, out);
#else
  for (std::size_t i = 0; i < count; ++i)
  {
    out[i] = ToUnorm16(in[i]);
  }
#endif
}

void ConvertRowsPadded(const float* image, int width, int v0, int v1, std::uint16_t* padded,
  int* rowFirst, int* rowLast)
{
  const std::size_t paddedValues = 4 * (static_cast<std::size_t>(width) + 1);
  for (int v = v0; v < v1; ++v)
  {
    std::uint16_t* row = padded + paddedValues * v;
    ConvertToUnorm16(image + 4 * static_cast<std::size_t>(width) * v, paddedValues - 4, row);
    std::fill(row + paddedValues - 4, row + paddedValues, std::uint16_t(0));
    FindNonZeroPixels(row, width, rowFirst[v], rowLast[v]);
  }
}

}
