#include "common/Unorm16.h"

#include "common/Avx512.h"

#include <algorithm>

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
  for (std::size_t i = 0; i < count; ++i)
  {
    out[i] = ToUnorm16(in[i]);
  }
}

}
