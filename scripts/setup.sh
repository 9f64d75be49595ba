#!/usr/bin/env bash
# Installs the Debian (bookworm) packages AccelVolume needs to build, test and render.
# Does nothing, quickly, when they are all installed already. Needs root or sudo otherwise.
#   ./scripts/setup.sh            install what is missing
#   ./scripts/setup.sh --check    only report; exit 1 when something is missing
set -euo pipefail

packages=(
  cmake g++ make ninja-build        # toolchain (Ninja: scripts/test.sh and sanitize.sh builds)
  libvtk9-dev                       # VTK 9.1 (RenderingOpenGL2, RenderingVolumeOpenGL2, ...)
  libosmesa6-dev                    # headless backend: OSMesa
  libegl-dev libegl-mesa0           # headless backend: EGL (glvnd + Mesa vendor)
  libgl-dev libgl1-mesa-dri         # OpenGL headers, Mesa llvmpipe driver
  libgtest-dev libbenchmark-dev     # GoogleTest unit tests, Google Benchmark
  zlib1g-dev                        # gzipped volumes
  libcli11-dev                      # CLI11, the accelvolume command line's options (header-only)
  nlohmann-json3-dev                # nlohmann::json: every JSON read and written (header-only)
  libvolpack1-dev                   # VolPack (Lacroute's shear-warp), the shear-warp benchmark's anchor
  openmpi-bin                       # mpirun for the MPI shear-warp tests
  xvfb xauth                        # X-window tests under xvfb-run
  python3-dev                       # Python wrapping (package accelvolume) for VTK's /usr/bin/python3
  paraview-dev                      # ParaView 5.11 plugin (its own VTK 9.2) and pvbatch
  python3-matplotlib                # charts of the benchmark report (BENCHMARKS.md)
  clang libclang-rt-14-dev          # libFuzzer targets of the CLI's loaders (scripts/fuzz.sh)
)

# --- ParaView's Python package for the plugin test (pvbatch) -------------------------------------
# Debian's python3-paraview conflicts with python3-vtk9 (both ship a vtkmodules package), which the
# Python wrapping needs: installing it would remove libvtk9-dev. pvbatch only needs it on its
# PYTHONPATH (and the plugin build uses its wrap hierarchy files), so unpack it with dpkg -x into
# a folder of its own, the default of CMake's ACCELVOLUME_PARAVIEW_PYTHON_ROOT. Runs only when
# paraview-dev is installed; quick when the folder holds the matching version already.
paraview_python_root=/usr/local/lib/accelvolume/paraview-python
setup_paraview_python() {
  local version marker tmp
  version=$(dpkg-query -W -f='${Version}' paraview-dev 2>/dev/null) || return 0
  dpkg-query -W -f='${Status}' paraview-dev 2>/dev/null | grep -q "install ok installed" || return 0
  marker="$paraview_python_root/usr/lib/python3/dist-packages/paraview/simple.py"
  if [ -f "$marker" ] && [ "$(cat "$paraview_python_root/VERSION" 2>/dev/null)" = "$version" ]; then
    echo "setup: ParaView's Python package $version is unpacked in $paraview_python_root"
    return 0
  fi
  echo "setup: ParaView's Python package $version is not unpacked in $paraview_python_root"
  if [ "${1:-}" = "--check" ]; then
    return 1
  fi
  local sudo=()
  if [ "$(id -u)" -ne 0 ]; then
    if ! command -v sudo >/dev/null 2>&1; then
      echo "setup: run as root (or install sudo) to unpack python3-paraview into" \
        "$paraview_python_root, or unpack it elsewhere with 'apt-get download python3-paraview'" \
        "and 'dpkg -x' and configure with -DACCELVOLUME_PARAVIEW_PYTHON_ROOT=<folder>" >&2
      return 1
    fi
    sudo=(sudo)
  fi
  tmp=$(mktemp -d)
  if [ "$(id -u)" -eq 0 ] && id _apt >/dev/null 2>&1; then
    chown _apt "$tmp" # as root, apt downloads as its _apt user (else it warns)
  fi
  if ! (cd "$tmp" && apt-get download "python3-paraview=$version"); then
    "${sudo[@]}" apt-get update
    (cd "$tmp" && apt-get download "python3-paraview=$version") || {
      echo "setup: could not download python3-paraview $version (it must match paraview-dev)" >&2
      rm -rf "$tmp"
      return 1
    }
  fi
  dpkg -x "$tmp"/python3-paraview_*.deb "$tmp/root"
  echo "$version" >"$tmp/root/VERSION"
  "${sudo[@]}" rm -rf "$paraview_python_root"
  "${sudo[@]}" mkdir -p "$(dirname "$paraview_python_root")"
  "${sudo[@]}" cp -a "$tmp/root" "$paraview_python_root"
  rm -rf "$tmp"
  echo "setup: unpacked python3-paraview $version into $paraview_python_root"
}
# --- end of ParaView's Python package ------------------------------------------------------------

missing=()
for pkg in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$pkg")
  fi
done

if [ "${#missing[@]}" -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages are installed"
  if [ "${1:-}" = "--check" ]; then
    setup_paraview_python --check
    exit $?
  fi
  setup_paraview_python || echo "setup: warning: python3-paraview not unpacked; the ParaView plugin test will be skipped" >&2
  exit 0
fi
echo "setup: missing packages: ${missing[*]}"
if [ "${1:-}" = "--check" ]; then
  exit 1
fi

if [ "$(id -u)" -eq 0 ]; then
  sudo=()
elif command -v sudo >/dev/null 2>&1; then
  sudo=(sudo)
else
  echo "setup: run as root (or install sudo) to install: ${missing[*]}" >&2
  exit 1
fi

export DEBIAN_FRONTEND=noninteractive
start=$SECONDS
"${sudo[@]}" apt-get update
# Install the whole list (not only the missing ones) so apt resolves them together.
"${sudo[@]}" apt-get install -y --no-install-recommends "${packages[@]}"
echo "setup: installed in $((SECONDS - start)) s"
setup_paraview_python || echo "setup: warning: python3-paraview not unpacked; the ParaView plugin test will be skipped" >&2
