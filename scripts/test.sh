#!/usr/bin/env bash
# One command: set up (when packages are missing), configure, build and run every test.
#   ./scripts/test.sh
# Environment: ACCELVOLUME_BUILD_DIR (default <repo>/build), ACCELVOLUME_SKIP_SETUP=1,
# CTEST_PARALLEL (default 2).
# Runs, in order:
#   1. all tests (ctest -j2) on the default headless backend, OSMesa (ACCELVOLUME_TEST_GL=osmesa);
#   2. the image tests (label "image") again on EGL (surfaceless Mesa or a GPU driver), but the
#      CPU mappers' exactness tests (CPU images, which the backend only displays);
#   3. the X-window tests (label "xwindow") under xvfb-run, when xvfb-run exists;
#   4. libFuzzer on the CLI's loaders for a bounded time (scripts/fuzz.sh; skip with
#      ACCELVOLUME_FUZZ=0; ACCELVOLUME_FUZZ_SECONDS per target, default 60);
#   5. ASan + UBSan and TSan builds over the Core unit tests and the CPU mappers' image tests
#      (scripts/sanitize.sh ci; skip with ACCELVOLUME_SANITIZERS=0).
# The build is always left configured for OSMesa. Exits non-zero if any run failed.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${ACCELVOLUME_BUILD_DIR:-$root/build}"
jobs="$(nproc 2>/dev/null || echo 2)"
ctest_jobs="${CTEST_PARALLEL:-2}"

if [ "${ACCELVOLUME_SKIP_SETUP:-0}" != "1" ]; then
  "$root/scripts/setup.sh"
fi

phase() { echo; echo "=== $* ==="; }
t0=$SECONDS

phase "configure ($build)"
# A new build folder uses Ninja when there is one: it keeps both cores busy across libraries
# (Make finishes a library before compiling the next one's sources). An existing folder keeps
# its generator.
generator=()
if [ ! -f "$build/CMakeCache.txt" ] && command -v ninja >/dev/null 2>&1; then
  generator=(-G Ninja)
fi
cmake -S "$root" -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING=ON \
  -DACCELVOLUME_TEST_GL=osmesa
phase "build (-j$jobs)"
cmake --build "$build" -j"$jobs"
echo "configure + build: $((SECONDS - t0)) s"

# Whatever happens below (failures, Ctrl-C), leave the tests configured for OSMesa.
set_test_gl() { cmake -DACCELVOLUME_TEST_GL="$1" "$build" >/dev/null; }
restore() { set_test_gl osmesa || echo "test.sh: could not restore ACCELVOLUME_TEST_GL=osmesa" >&2; }
trap restore EXIT

cd "$build"
failed=()

phase "all tests, OSMesa (ctest -j$ctest_jobs)"
t=$SECONDS
ctest --output-on-failure -j"$ctest_jobs" || failed+=("all tests (OSMesa)")
echo "OSMesa run: $((SECONDS - t)) s"

phase "image tests, EGL"
t=$SECONDS
if set_test_gl egl; then
  # Not the CPU mappers' exactness tests: they compare images computed on the CPU, which the
  # backend only displays (the other image tests cover EGL's display path).
  ctest -L image -E 'TestAccelVolume(RayCastExact|RayCastAgreement|ShearWarpExact|ShearWarpAgreement)$' \
    --output-on-failure -j"$ctest_jobs" || failed+=("image tests (EGL)")
else
  failed+=("configure for EGL")
fi
echo "EGL run: $((SECONDS - t)) s"

if command -v xvfb-run >/dev/null 2>&1; then
  phase "X-window tests under xvfb-run"
  t=$SECONDS
  if set_test_gl x; then
    ACCELVOLUME_GL=x xvfb-run -a ctest -L xwindow --no-tests=ignore --output-on-failure \
      || failed+=("xwindow tests (Xvfb)")
  else
    failed+=("configure for X")
  fi
  echo "Xvfb run: $((SECONDS - t)) s"
else
  echo "xvfb-run not found: skipping the xwindow tests"
fi

if [ "${ACCELVOLUME_FUZZ:-1}" != "0" ]; then
  phase "fuzzing the CLI's loaders (scripts/fuzz.sh)"
  t=$SECONDS
  ACCELVOLUME_FUZZ_BUILD_DIR="${ACCELVOLUME_FUZZ_BUILD_DIR:-$build-fuzz}" "$root/scripts/fuzz.sh" \
    || failed+=("fuzzing (scripts/fuzz.sh)")
  echo "fuzz run: $((SECONDS - t)) s"
fi

if [ "${ACCELVOLUME_SANITIZERS:-1}" != "0" ]; then
  phase "sanitizers: ASan + UBSan and TSan (scripts/sanitize.sh ci)"
  t=$SECONDS
  ACCELVOLUME_SKIP_SETUP=1 \
    ACCELVOLUME_SANITIZE_BUILD_DIR_ASAN="${ACCELVOLUME_SANITIZE_BUILD_DIR_ASAN:-$build-asan}" \
    ACCELVOLUME_SANITIZE_BUILD_DIR_TSAN="${ACCELVOLUME_SANITIZE_BUILD_DIR_TSAN:-$build-tsan}" \
    "$root/scripts/sanitize.sh" ci || failed+=("sanitizers (scripts/sanitize.sh ci)")
  echo "sanitizer run: $((SECONDS - t)) s"
fi

restore
trap - EXIT

echo
echo "test.sh: total $((SECONDS - t0)) s"
fuzz_findings="${ACCELVOLUME_FUZZ_BUILD_DIR:-$build-fuzz}/findings.txt"
if [ "${ACCELVOLUME_FUZZ:-1}" != "0" ] && [ -s "$fuzz_findings" ]; then
  echo "test.sh: the fuzzer's findings ($fuzz_findings):" >&2
  cat "$fuzz_findings" >&2
fi
if [ "${#failed[@]}" -ne 0 ]; then
  printf 'test.sh: FAILED: %s\n' "${failed[@]}" >&2
  exit 1
fi
echo "test.sh: all test runs passed"
