// Default run-time options of the sanitizers, compiled into every executable of a build
// configured with ACCELVOLUME_SANITIZE (cmake/AccelVolumeSanitizers.cmake), so that ctest, the
// CLI and the benchmarks of that build all run the same way as scripts/sanitize.sh. The
// sanitizer run-times call these hooks at start-up; the environment variables (ASAN_OPTIONS,
// UBSAN_OPTIONS, LSAN_OPTIONS, TSAN_OPTIONS) are read afterwards and override them.
//
// exitcode=86: a finding must never look like an expected exit status (the CLI tests expect 1
// or 2 for bad input, ctest skips on 125).

#ifndef ACCELVOLUME_SANITIZER_DIR
#error "ACCELVOLUME_SANITIZER_DIR (the folder of the suppression files) must be defined"
#endif

#define ACCELVOLUME_SANITIZER_EXPORT extern "C" __attribute__((visibility("default"), used))

ACCELVOLUME_SANITIZER_EXPORT const char* __asan_default_options()
{
  // detect_leaks: leaks fail like any other finding (suppressions below).
  return "detect_leaks=1:check_initialization_order=1:strict_init_order=1:exitcode=86";
}

ACCELVOLUME_SANITIZER_EXPORT const char* __lsan_default_options()
{
  // One-time allocations inside uninstrumented Mesa / Open MPI / VTK; each entry says why.
  return "suppressions=" ACCELVOLUME_SANITIZER_DIR "/lsan.supp:print_suppressions=0:exitcode=86";
}

ACCELVOLUME_SANITIZER_EXPORT const char* __ubsan_default_options()
{
  return "print_stacktrace=1:halt_on_error=1:exitcode=86";
}

ACCELVOLUME_SANITIZER_EXPORT const char* __tsan_default_options()
{
  return "suppressions=" ACCELVOLUME_SANITIZER_DIR "/tsan.supp:halt_on_error=1:"
         "second_deadlock_stack=1:print_suppressions=0:exitcode=86";
}

#if defined(__SANITIZE_THREAD__)
#define ACCELVOLUME_THREAD_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define ACCELVOLUME_THREAD_SANITIZER 1
#endif
#endif

#if defined(ACCELVOLUME_THREAD_SANITIZER)
#include <cstdlib>

namespace
{
// Two environment defaults of this build, set before main and before any static initializer of
// the program (priority 101); an explicit setting in the environment wins.
//
// VTK_SMP_BACKEND_IN_USE=STDThread: vtkSMPTools' default backend in Debian's VTK 9.1 is TBB.
// libtbb is not instrumented and hands work to its threads through its own atomics and futexes,
// which TSan cannot see, so the TBB partitioner state written by the calling thread and read by
// a worker is reported as a race (verified: docs/sanitizers.md). The STDThread backend, also in
// Debian's build, starts, feeds and joins its threads with pthread mutexes, condition variables
// and joins, which TSan intercepts: only races in the loop bodies, ours, are left.
// vtkSMPTools reads the variable when it is first used.
//
// LP_NUM_THREADS=0: Mesa's llvmpipe rasterizes on the calling thread instead of its own
// threads. Mesa is not instrumented and not under test; its threads destroy and lock the same
// mutexes under synchronisation TSan cannot see (a report inside libOSMesa in every image test
// otherwise). Suppressing reports by library would also hide a real race between our worker
// threads and a GL upload that reads our image, so the threads are switched off instead; the
// pictures do not change.
__attribute__((constructor(101))) void AccelVolumeThreadSanitizerEnvironment()
{
  setenv("VTK_SMP_BACKEND_IN_USE", "STDThread", 0);
  setenv("LP_NUM_THREADS", "0", 0);
}
}
#endif
