// Avx512: the one place that decides whether code may use AVX-512. A build on x86-64 with GCC
// or Clang compiles functions marked ACCELVOLUME_AVX512 for it (the default build targets any
// x86-64); CpuHasAvx512 tells at run time whether this CPU may run them.
#ifndef accelvolume_Avx512_h
#define accelvolume_Avx512_h

#if (defined(__GNUC__) || defined(__clang__)) && defined(__x86_64__)
#define ACCELVOLUME_AVX512_BUILD 1
#include <immintrin.h>
#define ACCELVOLUME_AVX512 __attribute__((target("avx512f,avx512dq,avx512bw,avx512vl")))
#else
#define ACCELVOLUME_AVX512_BUILD 0
#endif

namespace accelvolume
{

#if ACCELVOLUME_AVX512_BUILD
// AVX-512 F, DQ, BW and VL (every AVX-512 server and desktop CPU since 2017).
inline bool CpuHasAvx512()
{
  static const bool avx512 = __builtin_cpu_supports("avx512f") &&
    __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512bw") &&
    __builtin_cpu_supports("avx512vl");
  return avx512;
}
#endif

}

#endif
