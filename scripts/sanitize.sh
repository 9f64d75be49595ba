#!/usr/bin/env bash
# Sanitizer runs: builds AccelVolume with AddressSanitizer + UndefinedBehaviorSanitizer, and with
# ThreadSanitizer, each in a build folder of its own, and runs the tests there. Any finding fails
# the run. What runs and why: docs/sanitizers.md.
#   ./scripts/sanitize.sh [asan|tsan|all|ci]  (default: all)
#
# ci: the subset CI runs (scripts/test.sh, so .ci/run): ASan + UBSan over the self-tests, the
#   Core unit tests and the CPU mappers' image tests (ray caster, shear-warp, octree; with
#   ACCELVOLUME_TEST_SUBSET=sanitizer as the tsan run; not the loaders' tests, which fuzz.sh
#   runs under ASan + UBSan), then the
#   tsan run below as it is. The slice mapper's image tests, the CLI and MPI tests run only in
#   the full asan mode (time: the whole of .ci/run must stay under 30 minutes on 2 cores). The
#   ci and tsan builds compile only the image tests they run (ACCELVOLUME_IMAGE_TESTS=sanitizer-ci).
#
# asan: -DACCELVOLUME_SANITIZE="address;undefined" (UBSan with float-cast-overflow, no recovery;
#   LeakSanitizer on, Testing/Sanitizers/lsan.supp), GL tests on EGL (Mesa surfaceless: nothing
#   there leaks; OSMesa leaks per context, see lsan.supp). Builds the module, the GoogleTest
#   executables, both image test drivers, the CLI and the self-test (not the benchmarks and the
#   technique examples), and runs
#     ctest -L '^sanitizer$'                          the self-tests (each error must be caught)
#     ctest -L '^(unit|image|cli)$' -LE '^mpi$' -E "$timing_tests"
#         every GoogleTest, VTK image test and CLI test but the MPI ones and two timing tests
#     ASAN_OPTIONS=detect_leaks=0 ctest -L '^mpi$'   the MPI image and CLI tests, without leak
#         checking (Open MPI's own allocations cannot be told apart; docs/sanitizers.md)
#   Not run: python, install, report, paraview (uninstrumented interpreters or a second build),
#   xwindow (needs X), example (the same mappers as the image tests).
# tsan: -DACCELVOLUME_SANITIZE=thread (Testing/Sanitizers/tsan.supp, empty). Builds the module,
#   the core GoogleTest executable (the threaded suites' files only), the image test driver (the
#   image tests below only) and the self-test, and runs
#     ctest -L '^sanitizer$'                          (a race in a vtkSMPTools loop must be caught)
#     ctest -L '^unit$' -R "$tsan_unit_regex" -E "$timing_tests"
#         the GoogleTests that start threads: ray caster engine, shear-warp engine, run-length
#         encoding, partition, min-max octree parallel build and classification, distance map,
#         cell classification, reference renderers, progress, phantoms (2-7 threads each)
#     ACCELVOLUME_TEST_SUBSET=sanitizer ctest -L '^image$' -LE '^mpi$' -R "$tsan_image_regex"
#         (for time, RayCastExact then checks every third multi-component case and
#         ShearWarpExact 2 threads only) the image tests whose vtkSMPTools loops vary the
#         thread count or cover a loop no other test does: ray caster (exact, modes, sample
#         distances), shear-warp (exact, modes), min-max octree, progress, shaded slice
#         composite (gradients); 1-3 threads asked, as many as cores used. Left to the ASan run, for time: the agreement, smart
#         mapper and mixed-geometry tests (the same loops as the tests above).
#   In this build vtkSMPTools runs on its STDThread backend (Debian's default, TBB, is not
#   instrumented: every loop would be reported) and llvmpipe on the calling thread
#   (LP_NUM_THREADS=0); AccelVolumeSanitizerOptions.cxx sets both. STDThread uses one thread
#   per core, so TSan needs at least 2 cores to see the image tests' loops run in parallel (the
#   script warns otherwise; the GoogleTests start their own threads anyway).
#
# Sanitizer options come with the binaries (Testing/Sanitizers/AccelVolumeSanitizerOptions.cxx),
# so a plain `ctest` in either build folder reproduces a run; a finding exits with code 86.
#
# Environment: ACCELVOLUME_SANITIZE_BUILD_DIR_ASAN (default <repo>/build-asan),
# ACCELVOLUME_SANITIZE_BUILD_DIR_TSAN (default <repo>/build-tsan), CTEST_PARALLEL (default 2),
# ACCELVOLUME_SKIP_SETUP=1 (do not run scripts/setup.sh first).
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
mode="${1:-all}"
case "$mode" in
  asan | tsan | all | ci) ;;
  -h | --help)
    sed -n '2,/^set -euo/p' "${BASH_SOURCE[0]}" | sed '$d; s/^# \{0,1\}//'
    exit 0
    ;;
  *)
    echo "sanitize.sh: unknown mode '$mode' (asan, tsan, all or ci)" >&2
    exit 2
    ;;
esac
jobs="$(nproc 2>/dev/null || echo 2)"
ctest_jobs="${CTEST_PARALLEL:-2}"

if [ "${ACCELVOLUME_SKIP_SETUP:-0}" != "1" ]; then
  "$root/scripts/setup.sh"
fi

# Test selections (ctest names: GoogleTest cases are "Suite.Case", image tests
# "VTK::RenderingAccelVolumeCxx-TestAccelVolume<Name>").
# Timing tests measure speed, which a sanitizer build does not have.
timing_tests='^(ReferenceRenderer\.Speed|MinMaxOctree\.TimingPrint)$'
tsan_unit_regex='^((RayCastEngine|ShearWarpEngine|ShearWarpPartition|RunLengthVolume|ReferenceRenderer|ReferenceComposite|Progress|ClassifyCells|ClassifyCellsTyped)\.|MinMaxOctreeBuild\.ParallelIsDeterministic|MinMaxOctree\.ClassifyDegenerateRange$|DistanceMap\.(SaturatesIn3D|ThreadCountIndependent|ReusesTheOutputBuffer)$|Phantoms\.DeterministicAcrossRunsAndThreads$)'
# The CPU mappers' image tests (ci mode's ASan run).
cpu_image_regex='TestAccelVolume(RayCast[A-Za-z]*|ShearWarp(Agreement|Exact|Modes)|MinMaxOctree|Progress)$'
tsan_image_regex='TestAccelVolume(RayCastExact|RayCastModes|RayCastSampleDistances|ShearWarpExact|ShearWarpModes|MinMaxOctree|Progress|CompositeShaded)$'

phase() { echo; echo "=== $* ==="; }
failed=()
t_all=$SECONDS

# configure DIR SANITIZERS GL IMAGE_TESTS [UNIT_TESTS]: a RelWithDebInfo build at -O1 with line
# tables (enough for symbolized reports; -O2 -g compiles half as fast), without Python wrapping
# and the ParaView plugin, the tests on headless backend GL; IMAGE_TESTS all or sanitizer-ci
# (only the image tests the ci and tsan runs select are compiled: Testing/Cxx/CMakeLists.txt,
# which must match cpu_image_regex and tsan_image_regex above); UNIT_TESTS all (default) or
# threaded (only the files of the suites tsan_unit_regex selects: Testing/Unit/CMakeLists.txt). A new build folder uses Ninja when there is one
# (a long translation unit then no longer holds back the next library's).
configure() {
  local generator=()
  if [ ! -f "$1/CMakeCache.txt" ] && command -v ninja >/dev/null 2>&1; then
    generator=(-G Ninja)
  fi
  cmake -S "$root" -B "$1" "${generator[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG" \
    "-DCMAKE_C_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG" \
    -DBUILD_TESTING=ON "-DACCELVOLUME_TEST_GL=$3" -DACCELVOLUME_WRAP_PYTHON=OFF \
    -DACCELVOLUME_BUILD_PARAVIEW_PLUGIN=OFF "-DACCELVOLUME_SANITIZE=$2" \
    "-DACCELVOLUME_IMAGE_TESTS=$4" "-DACCELVOLUME_UNIT_TESTS=${5:-all}"
}

# run_ctest NAME ARGS...: one ctest run in the current build folder, recorded on failure.
run_ctest() {
  local name="$1"
  shift
  ctest --output-on-failure -j"$ctest_jobs" "$@" || failed+=("$name")
}

run_asan() {
  local build="${ACCELVOLUME_SANITIZE_BUILD_DIR_ASAN:-$root/build-asan}" t=$SECONDS
  phase "ASan + UBSan: configure and build ($build)"
  configure "$build" "address;undefined" egl all || { failed+=("asan: configure"); return; }
  cmake --build "$build" -j"$jobs" --target SanitizerSelfTest CellLeapTableShared AccelVolumeUnitTests \
    AccelVolumeCellLeapTests AccelVolumeVolumeIOTests vtkRenderingAccelVolumeCxxTests \
    vtkRenderingAccelVolumeCxxTests-MPI accelvolume || { failed+=("asan: build"); return; }
  echo "asan: configure + build $((SECONDS - t)) s"
  phase "ASan + UBSan: tests"
  local tt=$SECONDS
  pushd "$build" >/dev/null
  run_ctest "asan: self-tests" -L '^sanitizer$'
  run_ctest "asan: unit, image and CLI tests" -L '^(unit|image|cli)$' -LE '^mpi$' -E "$timing_tests"
  ASAN_OPTIONS=detect_leaks=0 run_ctest "asan: MPI tests" -L '^mpi$'
  popd >/dev/null
  echo "asan: tests $((SECONDS - tt)) s, total $((SECONDS - t)) s"
}

# The ci subset of run_asan: Core unit tests and the CPU mappers' image tests.
run_asan_ci() {
  local build="${ACCELVOLUME_SANITIZE_BUILD_DIR_ASAN:-$root/build-asan}" t=$SECONDS
  phase "ASan + UBSan (ci subset): configure and build ($build)"
  configure "$build" "address;undefined" egl sanitizer-ci || { failed+=("asan: configure"); return; }
  # Not AccelVolumeVolumeIOTests: fuzz.sh runs the same loaders under ASan + UBSan.
  cmake --build "$build" -j"$jobs" --target SanitizerSelfTest CellLeapTableShared AccelVolumeUnitTests \
    AccelVolumeCellLeapTests vtkRenderingAccelVolumeCxxTests \
    || { failed+=("asan: build"); return; }
  echo "asan: configure + build $((SECONDS - t)) s"
  phase "ASan + UBSan (ci subset): tests"
  local tt=$SECONDS
  pushd "$build" >/dev/null
  run_ctest "asan: self-tests" -L '^sanitizer$'
  run_ctest "asan: unit tests" -L '^unit$' -E "$timing_tests|^AccelVolumeVolumeIOTests_NOT_BUILT$"
  ACCELVOLUME_TEST_SUBSET=sanitizer run_ctest "asan: CPU mapper image tests" -L '^image$' -LE '^mpi$' \
    -R "$cpu_image_regex"
  popd >/dev/null
  echo "asan: tests $((SECONDS - tt)) s, total $((SECONDS - t)) s"
}

run_tsan() {
  local build="${ACCELVOLUME_SANITIZE_BUILD_DIR_TSAN:-$root/build-tsan}" t=$SECONDS
  if [ "$jobs" -lt 2 ]; then
    echo "sanitize.sh: warning: $jobs core(s): vtkSMPTools runs the image tests' loops on one" \
      "thread here, so TSan cannot see races in them (the GoogleTests still start threads)" >&2
  fi
  phase "TSan: configure and build ($build)"
  configure "$build" thread osmesa sanitizer-ci threaded || { failed+=("tsan: configure"); return; }
  cmake --build "$build" -j"$jobs" --target SanitizerSelfTest CellLeapTableShared AccelVolumeUnitTests \
    vtkRenderingAccelVolumeCxxTests || { failed+=("tsan: build"); return; }
  echo "tsan: configure + build $((SECONDS - t)) s"
  phase "TSan: tests"
  local tt=$SECONDS
  pushd "$build" >/dev/null
  run_ctest "tsan: self-tests" -L '^sanitizer$'
  run_ctest "tsan: unit tests" -L '^unit$' -R "$tsan_unit_regex" -E "$timing_tests"
  ACCELVOLUME_TEST_SUBSET=sanitizer run_ctest "tsan: image tests" -L '^image$' -LE '^mpi$' \
    -R "$tsan_image_regex"
  popd >/dev/null
  echo "tsan: tests $((SECONDS - tt)) s, total $((SECONDS - t)) s"
}

case "$mode" in
  asan) run_asan ;;
  tsan) run_tsan ;;
  all)
    run_asan
    run_tsan
    ;;
  ci)
    run_asan_ci
    run_tsan
    ;;
esac

echo
echo "sanitize.sh: $mode took $((SECONDS - t_all)) s"
if [ "${#failed[@]}" -ne 0 ]; then
  printf 'sanitize.sh: FAILED: %s\n' "${failed[@]}" >&2
  exit 1
fi
echo "sanitize.sh: no findings"
