#!/usr/bin/env bash
# Installs the Debian (bookworm) packages AccelVolume needs to build, test and render.
# Does nothing, quickly, when they are all installed already. Needs root or sudo otherwise.
#   ./scripts/setup.sh            install what is missing
#   ./scripts/setup.sh --check    only report; exit 1 when something is missing
set -euo pipefail

packages=(
  cmake g++ make                    # toolchain
  libvtk9-dev                       # VTK 9.1 (RenderingOpenGL2, RenderingVolumeOpenGL2, ...)
  libosmesa6-dev                    # headless backend: OSMesa
  libegl-dev libegl-mesa0           # headless backend: EGL (glvnd + Mesa vendor)
  libgl-dev libgl1-mesa-dri         # OpenGL headers, Mesa llvmpipe driver
  libgtest-dev libbenchmark-dev     # GoogleTest unit tests, Google Benchmark
  zlib1g-dev                        # gzipped volumes
  libvolpack1-dev                   # VolPack (Lacroute's shear-warp), the shear-warp benchmark's anchor
  openmpi-bin                       # mpirun for the MPI shear-warp tests
  xvfb xauth                        # X-window tests under xvfb-run
  python3-dev                       # Python wrapping (package accelvolume) for VTK's /usr/bin/python3
  paraview-dev                      # ParaView 5.11 plugin (its own VTK 9.2) and pvbatch
  python3-matplotlib                # charts of the benchmark report (BENCHMARKS.md)
)

missing=()
for pkg in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$pkg")
  fi
done

if [ "${#missing[@]}" -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages are installed"
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
