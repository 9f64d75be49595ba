#!/usr/bin/env bash
# One command: set up (when packages are missing), configure, build the command-line tool and
# render the built-in volume to a PNG, headless.
#   ./scripts/render.sh [extra 'accelvolume render' options]
# Environment: ACCELVOLUME_BUILD_DIR (default <repo>/build), ACCELVOLUME_OUT (default
# ./accelvolume.png), ACCELVOLUME_SKIP_SETUP=1.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${ACCELVOLUME_BUILD_DIR:-$root/build}"
out="${ACCELVOLUME_OUT:-accelvolume.png}"

if [ "${ACCELVOLUME_SKIP_SETUP:-0}" != "1" ]; then
  "$root/scripts/setup.sh"
fi

cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release
cmake --build "$build" --target accelvolume -j"$(nproc 2>/dev/null || echo 2)"

"$build/bin/accelvolume" render --out "$out" "$@"

case "$out" in
  /*) abs="$out" ;;
  *) abs="$PWD/$out" ;;
esac
if [ ! -s "$abs" ]; then
  echo "render.sh: accelvolume did not write $abs" >&2
  exit 1
fi
echo "render.sh: wrote $abs"
