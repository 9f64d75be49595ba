#!/usr/bin/env bash
# One command for the benchmark report: build the benchmark programs and the CLI, run every
# benchmark with JSON output, render the gallery (our mappers next to VTK's, same transfer
# function and camera), then write BENCHMARKS.md with tables and charts
# (scripts/benchmark_report.py, Debian's python3-matplotlib).
#
#   ./scripts/bench.sh [--quick] [--out DIR] [--skip-run] [--skip-build] [--only LIST]
#
#   --quick        one small case per benchmark, 1 frame, small images: about a minute; checks
#                  that everything runs (the report says its timings mean nothing)
#   --out DIR      write DIR/BENCHMARKS.md and DIR/report/ (default: BENCHMARKS.md at the
#                  repository root and docs/benchmarks/report/)
#   --skip-run     only regenerate the report from the results already in <report>/results
#   --skip-build   use the programs already built in the build folder
#   --only LIST    comma-separated subset of composite,raycast,octree,shearwarp,cropping,gallery
#                  (the report still covers every benchmark whose results are present)
#
# Environment: ACCELVOLUME_BUILD_DIR (default <repo>/build), ACCELVOLUME_DATA_DIR (default: the
# programs' built-in data folder, ../shared/data beside the repository), ACCELVOLUME_GL (headless
# backend, default egl), ACCELVOLUME_SKIP_SETUP=1 (do not run scripts/setup.sh).
#
# The full run takes about 20 minutes on a 2-core machine with Mesa llvmpipe; run it on an
# otherwise idle machine, since every number is a timing. Exit status: 0 when every step
# succeeded, 1 when a benchmark, a render or the report failed (the report is still written,
# with notes), 2 on bad arguments.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${ACCELVOLUME_BUILD_DIR:-$root/build}"
gl="${ACCELVOLUME_GL:-egl}"
# Debian's Python has python3-matplotlib (a python3 first on PATH may not); -B keeps __pycache__
# out of the source tree.
python=/usr/bin/python3

quick=0
skip_run=0
skip_build=0
out=""
only="composite,raycast,octree,shearwarp,cropping,gallery"
usage() { sed -n '2,25p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; }
while [ $# -gt 0 ]; do
  case "$1" in
    --quick) quick=1 ;;
    --skip-run) skip_run=1 ;;
    --skip-build) skip_build=1 ;;
    --out)
      [ $# -ge 2 ] || { echo "bench.sh: --out needs a folder" >&2; exit 2; }
      out="$2"; shift ;;
    --only)
      [ $# -ge 2 ] || { echo "bench.sh: --only needs a list" >&2; exit 2; }
      only="$2"; shift ;;
    -h|--help) usage; exit 0 ;;
    *) echo "bench.sh: unknown option $1 (see --help)" >&2; exit 2 ;;
  esac
  shift
done
for step in ${only//,/ }; do
  case "$step" in
    composite|raycast|octree|shearwarp|cropping|gallery) ;;
    *) echo "bench.sh: unknown step '$step' in --only" >&2; exit 2 ;;
  esac
done
wanted() { [[ ",$only," == *",$1,"* ]]; }

if [ -n "$out" ]; then
  mkdir -p "$out"
  out="$(cd "$out" && pwd)"
  markdown="$out/BENCHMARKS.md"
  assets="$out/report"
else
  markdown="$root/BENCHMARKS.md"
  assets="$root/docs/benchmarks/report"
fi
results="$assets/results"
bin="$build/bin"
data_args=()
if [ -n "${ACCELVOLUME_DATA_DIR:-}" ]; then
  data_args=(--data "$ACCELVOLUME_DATA_DIR")
fi
data_dir="${ACCELVOLUME_DATA_DIR:-$(cd "$root/.." && pwd)/shared/data}"
failed=()

report() {
  echo "bench.sh: writing the report"
  if ! "$python" -B "$root/scripts/benchmark_report.py" --results "$results" \
    --markdown "$markdown" --assets "$assets"; then
    failed+=(report)
  fi
}

finish() {
  if [ "${#failed[@]}" -gt 0 ]; then
    echo "bench.sh: failed: ${failed[*]} (see $results/*.log and the report's notes)" >&2
    exit 1
  fi
  echo "bench.sh: done: $markdown"
}

if [ "$skip_run" = 1 ]; then
  [ -d "$results" ] || { echo "bench.sh: no results in $results to report on" >&2; exit 1; }
  report
  finish
  exit 0
fi

if [ "$skip_build" = 0 ]; then
  if [ "${ACCELVOLUME_SKIP_SETUP:-0}" != "1" ]; then
    "$root/scripts/setup.sh"
  fi
  cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release
  cmake --build "$build" -j"$(nproc 2>/dev/null || echo 2)" --target accelvolume \
    accelvolume_benchmark_composite accelvolume_benchmark_raycast accelvolume_benchmark_octree \
    accelvolume_benchmark_shearwarp accelvolume_benchmark_cropping
fi

# Open MPI refuses to start as root unless told; the shear-warp benchmark's MPI rows launch it.
if [ "$(id -u)" = 0 ]; then
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
fi
export OMPI_MCA_rmaps_base_oversubscribe=1

mkdir -p "$results"
mode=full
[ "$quick" = 1 ] && mode=quick
"$python" -B "$root/scripts/benchmark_report.py" --collect-machine "$results/machine.json" \
  --mode "$mode"
# runs.tsv: one line per step; with --only, the lines of the steps not rerun are kept.
runs_kept=""
if [ -f "$results/runs.tsv" ]; then
  while IFS= read -r line; do
    case "$line" in
      "#"*) ;;
      *) wanted "${line%%$'\t'*}" || runs_kept+="$line"$'\n' ;;
    esac
  done < "$results/runs.tsv"
fi
{ printf '# name\texit\tseconds\tcommand\n'; printf '%s' "$runs_kept"; } > "$results/runs.tsv"

# Settings. Full: frame counts chosen so that the whole run takes about 20 minutes on an idle
# 2-core machine with llvmpipe. Estimates from earlier runs (fixed cost + per-frame cost):
# composite ~4 min (5/3 frames took 2.5 min), raycast ~6 (68 s + 15 s per frame), octree ~1.5,
# shear-warp ~6 (171 s + 15 s per frame), cropping ~1, gallery ~0.5. Quick: one small case each,
# one frame, small images.
if [ "$quick" = 1 ]; then
  composite_args=(--datasets engine --tfs tf2 --sizes 128 --frames 1 --large-frames 0 --noop-frames 10)
  raycast_args=(--quick --frames 1)
  octree_args=(--datasets engine,vessels --repeat 1 --frames 1 --phantom-size 64)
  shearwarp_args=(--datasets cthead --tfs tf2 --sizes 128 --frames 1)
  cropping_args=(--datasets cthead --size 128 128 --frames 1 --reference-frames 1)
  gallery_specs=(engine:tf2)
  gallery_size=128
else
  composite_args=(--frames 10 --large-frames 5)
  raycast_args=(--frames 20)
  octree_args=(--repeat 7)
  shearwarp_args=(--frames 12)
  cropping_args=(--frames 20)
  gallery_specs=(engine:tf2 cthead:tf1 aneurism:tf2 boston_teapot:tf1)
  gallery_size=256
fi

# run NAME PROGRAM ARGS...: runs bin/PROGRAM with --json results/NAME.json, its output in
# results/NAME.log, and records exit status and time in runs.tsv. An old JSON is removed first so
# that a failed run cannot leave stale numbers in the report.
run() {
  local name="$1" program="$2"
  shift 2
  local args=("$@" --gl "$gl" --json "$results/$name.json" "${data_args[@]}")
  rm -f "$results/$name.json"
  echo "bench.sh: [$name] $program ${args[*]}"
  local start=$SECONDS status=0
  "$bin/$program" "${args[@]}" > "$results/$name.log" 2>&1 || status=$?
  local seconds=$((SECONDS - start))
  # The command as recorded: paths relative to the results folder / build, for the report.
  local shown="$program ${args[*]}"
  shown="${shown//"$results/"/}"
  printf '%s\t%s\t%s\t%s\n' "$name" "$status" "$seconds" "$shown" >> "$results/runs.tsv"
  echo "bench.sh: [$name] exit $status after ${seconds} s"
  if [ "$status" != 0 ]; then
    failed+=("$name")
    tail -n 5 "$results/$name.log" >&2 || true
  fi
}

if wanted composite; then
  run composite accelvolume_benchmark_composite "${composite_args[@]}"
fi
if wanted raycast; then
  run raycast accelvolume_benchmark_raycast "${raycast_args[@]}"
fi
if wanted octree; then
  run octree accelvolume_benchmark_octree "${octree_args[@]}"
fi
if wanted shearwarp; then
  rm -rf "$results/images/shearwarp"
  run shearwarp accelvolume_benchmark_shearwarp "${shearwarp_args[@]}" \
    --images "$results/images/shearwarp"
fi
if wanted cropping; then
  rm -rf "$results/images/cropping"
  run cropping accelvolume_benchmark_cropping "${cropping_args[@]}" \
    --images "$results/images/cropping"
fi

# The gallery: every mapper of `accelvolume render` on the same volume, transfer function and
# camera (parallel projection, which the shear-warp mapper requires), shaded composite.
if wanted gallery; then
  gallery="$results/gallery"
  rm -rf "$gallery"
  mkdir -p "$gallery"
  common=(--blend composite --shade on --parallel --azimuth 30 --elevation 20 --zoom 1.4
    --size "$gallery_size" "$gallery_size" --frames 1 --gl "$gl" --quiet)
  printf '# args: --input FILE --mapper M --tf TF %s\n' "${common[*]}" > "$gallery/gallery.tsv"
  start=$SECONDS
  gallery_failed=0
  for spec in "${gallery_specs[@]}"; do
    dataset="${spec%%:*}"
    tf="${spec##*:}"
    file="$(ls "$data_dir/${dataset}"_*x*x*_*.raw* 2>/dev/null | head -n 1 || true)"
    for mapper in slice raycast shearwarp vtk-gpu vtk-fixed; do
      stem="${dataset}_${tf}_${mapper}"
      status=0
      if [ -z "$file" ]; then
        echo "bench.sh: [gallery] no file for dataset $dataset in $data_dir" >&2
        status=1
      else
        "$bin/accelvolume" render --input "$file" --mapper "$mapper" --tf "$tf" "${common[@]}" \
          --out "$gallery/$stem.png" --stats "$gallery/$stem.json" \
          >> "$gallery/gallery.log" 2>&1 || status=$?
      fi
      printf '%s\t%s\t%s\t%s\t%s\t%s\n' "$dataset" "$tf" "$mapper" "$status" "$stem.png" \
        "$stem.json" >> "$gallery/gallery.tsv"
      if [ "$status" != 0 ]; then
        failed+=("gallery:$stem")
        gallery_failed=1
      fi
    done
  done
  printf '%s\t%s\t%s\t%s\n' gallery "$gallery_failed" "$((SECONDS - start))" \
    "accelvolume render (see gallery/gallery.tsv)" >> "$results/runs.tsv"
  echo "bench.sh: [gallery] ${#gallery_specs[@]} volume(s) x 5 mappers in $((SECONDS - start)) s"
fi

report
finish
