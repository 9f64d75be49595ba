#!/usr/bin/env bash
# VTK 9.1's own volume-rendering tests with our class names swapped in, each run twice (VTK's
# mapper, ours) on the same data under Xvfb; the two pictures are compared (compare.py).
#
#   Testing/VTKCompat/run.sh <VTK 9.1 source tree or git dir> [work dir] [build dir]
#
# The VTK tree gives Rendering/Volume/Testing/Cxx and Rendering/VolumeOpenGL2/Testing/Cxx
# (a git directory is read at tag v9.1.0). VTK's test data are not in it: make_data.py writes
# stand-ins of the same names and types from ../shared/data (headsq, ironProt, HeadMRVolume are
# the real ones; the vase, tooth, atlas and rectilinear grid are substitutes), so the pictures
# are not VTK's baselines but the two mappers always see the same input. Needs the module built
# in <build dir> (default: build), xvfb, python3-vtk9. Not part of CI (about 25 minutes on 2
# cores); docs/drop-in.md has the last table. ACCELVOLUME_VTKCOMPAT_TESTS=<regex> runs only the
# tests whose names match.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd)
vtk=${1:?usage: run.sh <VTK 9.1 source tree or git dir> [work dir] [build dir]}
work=$(mkdir -p "${2:-/tmp/accelvolume-vtkcompat}" && cd "${2:-/tmp/accelvolume-vtkcompat}" && pwd)
build=$(cd "${3:-$root/build}" && pwd)
data=${ACCELVOLUME_DATA_DIR:-$root/../shared/data}
mkdir -p "$work/src" "$work/bin" "$work/log" "$work/out/orig" "$work/out/accel"

rename='s/vtkOpenGLGPUVolumeRayCastMapper/vtkAccelVolumeSliceMapper/g;
  s/vtkGPUVolumeRayCastMapper/vtkAccelVolumeSliceMapper/g;
  s/vtkSmartVolumeMapper/vtkAccelVolumeSmartMapper/g;
  s/vtkFixedPointVolumeRayCastMapper/vtkAccelVolumeRayCastMapper/g'
for dir in Rendering/Volume/Testing/Cxx Rendering/VolumeOpenGL2/Testing/Cxx; do
  if [ -d "$vtk/$dir" ]; then
    files=$(cd "$vtk/$dir" && ls ./*.cxx)
    show() { cat "$vtk/$dir/$1"; }
  else
    files=$(git --git-dir="$vtk" ls-tree --name-only v9.1.0 "$dir/" | grep '\.cxx$' | xargs -n1 basename)
    show() { git --git-dir="$vtk" show "v9.1.0:$dir/$1"; }
  fi
  for f in $files; do
    f=$(basename "$f")
    show "$f" > "$work/src/${f%.cxx}.orig"
    sed -e "$rename" "$work/src/${f%.cxx}.orig" > "$work/src/$f"
  done
done
# Unstructured-grid tests use no mapper of ours; UserShader2 needs a generated header.
(cd "$work/src" && grep -l AccelVolume ./*.cxx | xargs -n1 basename | sed 's/\.cxx$//' |
  grep -v UserShader2 | grep -E "${ACCELVOLUME_VTKCOMPAT_TESTS:-.}") > "$work/tests.txt"
/usr/bin/python3 "$here/make_data.py" "$data" "$work/data"

flags="-std=c++17 -O0 -w -I$build/Module -I$root/Module -I$root/Rendering/AccelVolume
  -I$root/Rendering/Core -isystem /usr/include/vtk-9.1
  -isystem /usr/lib/x86_64-linux-gnu/openmpi/include"
libs="-Wl,-rpath,$build/lib $build/lib/libvtkRenderingAccelVolume.so -Wl,--as-needed
  $(ls /usr/lib/x86_64-linux-gnu/libvtk*-9.1.so | grep -v -i 'java\|python' | tr '\n' ' ') -lGL"
build_one() {
  local n=$1 v s
  for v in orig accel; do
    s="$work/src/$n.cxx"
    [ "$v" = orig ] && s="$work/src/$n.orig"
    sed "s/TESTNAME/$n/" "$here/driver.cxx.in" > "$work/bin/${n}_$v.main.cxx"
    # shellcheck disable=SC2086
    c++ $flags -x c++ "$s" -x none "$work/bin/${n}_$v.main.cxx" -o "$work/bin/${n}_$v" $libs \
      2> "$work/log/${n}_$v.build.err" || echo "BUILD FAILED: $n $v"
  done
}
run_one() {
  local n=$1 v
  for v in orig accel; do
    DISPLAY=:$display timeout 90 "$work/bin/${n}_$v" -D "$work/data" -T "$work/out/$v" \
      -V "/nonexistent/$n.png" > "$work/log/${n}_$v.run.log" 2>&1 || true
  done
}
export -f build_one run_one
export work here flags libs
display=$((200 + $$ % 500))
Xvfb ":$display" -screen 0 1280x1024x24 > /dev/null 2>&1 &
xvfb=$!
trap 'kill $xvfb' EXIT
export display
xargs -P2 -n1 bash -c 'build_one "$0"' < "$work/tests.txt"
xargs -P2 -n1 bash -c 'run_one "$0"' < "$work/tests.txt"
/usr/bin/python3 "$here/compare.py" "$work" | tee "$work/table.txt"
