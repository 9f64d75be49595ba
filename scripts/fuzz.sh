#!/usr/bin/env bash
# Fuzzes the accelvolume CLI's input parsing for a bounded time: builds the libFuzzer targets in
# Testing/Fuzz (clang, -fsanitize=fuzzer,address,undefined; a project of its own, so the main gcc
# build is untouched) and runs each one with leak detection, a per-input timeout and a memory cap.
#   ./scripts/fuzz.sh
# Environment:
#   ACCELVOLUME_FUZZ_BUILD_DIR  build folder (default <repo>/build-fuzz); its corpus/ keeps growing
#                               across runs, artifacts/ holds the reproducers of findings
#   ACCELVOLUME_FUZZ_SECONDS    seconds of fuzzing per target (default 60)
#   ACCELVOLUME_FUZZ_CXX        the clang++ to build with (default clang++)
# Exits non-zero when a target crashes, leaks, times out, runs out of memory or breaks LoadVolume's
# contract and its reproducer fails again on replay; prints the reproducer's path and the command
# that replays it. A finding that passes on replay is reported but does not fail the run. Either
# way <build>/findings.txt keeps what was found (small reproducers base64-encoded), which
# scripts/test.sh repeats at the end of its output.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${ACCELVOLUME_FUZZ_BUILD_DIR:-$root/build-fuzz}"
seconds="${ACCELVOLUME_FUZZ_SECONDS:-60}"
jobs="$(nproc 2>/dev/null || echo 2)"
t0=$SECONDS

# What failed and what each failing target found, for scripts/test.sh to repeat at the end.
findings="$build/findings.txt"
mkdir -p "$build"
rm -f "$findings"

echo "=== configure + build ($build) ==="
if ! cmake -S "$root/Testing/Fuzz" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_COMPILER="${ACCELVOLUME_FUZZ_CXX:-clang++}" >/dev/null ||
  ! cmake --build "$build" -j"$jobs"; then
  echo "fuzz.sh: the fuzz targets did not build" | tee "$findings" >&2
  exit 1
fi
echo "fuzz build: $((SECONDS - t0)) s"

rm -rf "$build/seeds"
"$build/MakeBadInputs" --fuzz-seeds "$build/seeds"

# The targets' scratch folders (FuzzSupport.h) go under the build folder: libFuzzer ends a run
# with _Exit, so their atexit cleanup never runs and /tmp would collect one per run.
export TMPDIR="$build/tmp"
rm -rf "$TMPDIR"
mkdir -p "$TMPDIR"

# The fuzzers' sanitizer settings, for fuzzing and for replaying a reproducer alike.
fuzz_env() {
  ASAN_OPTIONS="detect_leaks=1:allocator_may_return_null=1" \
    LSAN_OPTIONS="suppressions=$root/Testing/Fuzz/lsan.supp:print_suppressions=0" \
    UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1" "$@"
}

# target, seed folder, dictionary, largest input in bytes
targets=(
  "FuzzRawVolume raw raw.dict 65536"
  "FuzzHeader header header.dict 16384"
)
# fuzz_target ENTRY: fuzzes one target, then replays what it found; prints its report and writes
# its findings to <build>/<target>.findings. Exit status 1: a finding that reproduces (or left no
# reproducer).
fuzz_target() {
  local target seeds dict max_len
  read -r target seeds dict max_len <<<"$1"
  local corpus="$build/corpus/$target" artifacts="$build/artifacts/$target"
  local found="$build/$target.findings" t=$SECONDS status=0
  mkdir -p "$corpus" "$artifacts"
  rm -f "$found"
  echo
  echo "=== $target: ${seconds} s ==="
  touch "$artifacts/.started"
  # halt_on_error: UBSan findings stop the run like ASan ones, leaving a reproducer. lsan.supp
  # names the one leak inside Debian's VTK that the fuzzer reaches (see the file).
  fuzz_env "$build/$target" "$corpus" "$build/seeds/$seeds" \
    -dict="$root/Testing/Fuzz/$dict" -max_len="$max_len" -max_total_time="$seconds" \
    -timeout=10 -rss_limit_mb=2048 -detect_leaks=1 -print_final_stats=1 \
    -artifact_prefix="$artifacts/" >"$build/$target.log" 2>&1 || status=$?
  grep -E "^(Done|stat::number_of_executed_units|stat::average_exec_per_sec|stat::peak_rss_mb)" \
    "$build/$target.log" || true
  echo "$target: exit $status after $((SECONDS - t)) s (log: $build/$target.log)"
  if [ "$status" -eq 0 ]; then
    return 0
  fi
  {
    echo "$target: exit $status"
    grep -E "^(==[0-9]+==ERROR|SUMMARY|LoadVolume broke)|runtime error|out-of-memory|timeout" \
      "$build/$target.log" | head -5 | cut -c1-200 || true
    # The stack's frames outside libFuzzer, the sanitizers and libc.
    grep -E "^ +#[0-9]+ " "$build/$target.log" |
      grep -v -E "fuzzer::|__sanitizer|libc\.so|libc_start|_start " | head -10 | cut -c1-200 || true
  } | tee -a "$found"
  # A finding fails the run when its reproducer fails again on replay (three times, with a
  # generous time limit). One that passes on replay (a stalled machine tripping the 10 s limit,
  # a nondeterministic leak report) is reported with its bytes but does not fail the run.
  local reproduced=0 reproducers=0 reproducer
  while IFS= read -r reproducer; do
    reproducers=$((reproducers + 1))
    echo "reproducer: $reproducer"
    echo "  replay:   $build/$target $reproducer"
    # CI keeps only the tail of its log: the reproducer itself, when small, travels in it.
    if [ "$(stat -c %s "$reproducer")" -le 4096 ]; then
      echo "reproducer $(basename "$reproducer") (base64): $(base64 -w0 "$reproducer")" >>"$found"
    fi
    if fuzz_env "$build/$target" "$reproducer" -runs=3 -timeout=60 -rss_limit_mb=2048 \
      -detect_leaks=1 >"$reproducer.replay.log" 2>&1; then
      echo "  passes on replay: not reproduced" | tee -a "$found"
    else
      echo "  fails on replay (log: $reproducer.replay.log)" | tee -a "$found"
      reproduced=1
    fi
  done < <(find "$artifacts" -maxdepth 1 -type f -newer "$artifacts/.started" \
    \( -name 'crash-*' -o -name 'leak-*' -o -name 'timeout-*' -o -name 'oom-*' \) \
    ! -name '*.replay.log' | sort)
  if [ "$reproduced" -eq 1 ] || [ "$reproducers" -eq 0 ]; then
    return 1
  fi
  echo "$target: no finding reproduced on replay; reported above, not failed" | tee -a "$found"
}

# The targets run side by side when there are cores for them (each fuzzer is one process on one
# core), else one after the other; their reports are printed in order either way.
failed=()
statuses=()
if [ "$jobs" -ge "${#targets[@]}" ]; then
  pids=()
  for entry in "${targets[@]}"; do
    read -r target _ <<<"$entry"
    fuzz_target "$entry" >"$build/$target.report" 2>&1 &
    pids+=("$!")
  done
  for pid in "${pids[@]}"; do
    status=0
    wait "$pid" || status=$?
    statuses+=("$status")
  done
else
  for entry in "${targets[@]}"; do
    read -r target _ <<<"$entry"
    status=0
    fuzz_target "$entry" >"$build/$target.report" 2>&1 || status=$?
    statuses+=("$status")
  done
fi
for n in "${!targets[@]}"; do
  read -r target _ <<<"${targets[$n]}"
  cat "$build/$target.report"
  if [ -f "$build/$target.findings" ]; then
    cat "$build/$target.findings" >>"$findings"
  fi
  if [ "${statuses[$n]}" -ne 0 ]; then
    failed+=("$target")
  fi
done

rm -rf "$TMPDIR"
echo
echo "fuzz.sh: total $((SECONDS - t0)) s"
if [ "${#failed[@]}" -ne 0 ]; then
  printf 'fuzz.sh: FAILED: %s\n' "${failed[@]}" >&2
  exit 1
fi
echo "fuzz.sh: no findings"
