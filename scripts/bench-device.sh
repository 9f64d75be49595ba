#!/usr/bin/env bash
# The GPU check of the slice mapper (issue 17) on a lent device machine, with no build there:
# the programs built here travel with the libraries they load and the volumes they read.
#
#   scripts/bench-device.sh prepare         here: fill .device/ (ignored by git) with bin/,
#                                           lib.tar.xz (the programs' shared-library closure,
#                                           minus glibc and the GL / EGL loaders the machine
#                                           brings, OSMesa as a stub) and
#                                           data/ (the matrix's volumes); prints its size
#   scripts/bench-device.sh run [--quick]   there (or here, as a dry run on Mesa): the composite
#                                           matrix (ours vs vtkGPUVolumeRayCastMapper; engine,
#                                           cthead, bonsai, aneurism; tf1 / tf2; 256-1024^2), the
#                                           cropped-MIP benchmark and the GPU image tests; JSON
#                                           and a log under $OUT (or $ACCELVOLUME_DEVICE_OUT)
#
# The device call (GL loader packages as /work/.library/device/README.md says, in .gl/):
#   run(command="for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig; bash scripts/bench-device.sh run",
#       carry=[".gl", ".device"], timeout_s=420)
# Budget: the full run is sized for under 5 minutes on an H200; --quick takes one case each.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bundle="$root/.device"
build="${ACCELVOLUME_BUILD_DIR:-$root/build}"
data_src="${ACCELVOLUME_DATA_DIR:-$root/../shared/data}"
datasets="engine,cthead,bonsai_hazeremoved,aneurism"
bundled_data="$datasets,cta_avm"
programs=(accelvolume accelvolume_benchmark_composite accelvolume_benchmark_cropping
  vtkRenderingAccelVolumeCxxTests)
# GPU image tests: the slice mapper against its CPU reference and VTK's GPU mapper.
image_tests=(TestAccelVolumeSliceMapperReference TestAccelVolumeVsGPURayCast
  TestAccelVolumeVsGPURayCastFeatures TestAccelVolumeEarlyRayTermination
  TestAccelVolumeEmptySpaceSkipping TestAccelVolumeSlabSamples TestAccelVolumeCompositeSlabs
  TestAccelVolumeBricking
  TestAccelVolumeCompositeReference TestAccelVolumeMIP TestAccelVolumeMinIP)

prepare() {
  rm -rf "$bundle"
  mkdir -p "$bundle/bin" "$bundle/lib" "$bundle/data"
  grep -qx '/.device/' "$root/.git/info/exclude" 2>/dev/null ||
    echo '/.device/' >>"$root/.git/info/exclude"
  for p in "${programs[@]}"; do
    [ -x "$build/bin/$p" ] || { echo "bench-device: $build/bin/$p is not built" >&2; exit 1; }
    cp "$build/bin/$p" "$bundle/bin/"
  done
  # Every library the programs load, except the C library and the GL vendor-neutral loaders
  # (the device machine's driver provides libEGL / libGL / libOpenGL through glvnd).
  local skip='^(libc|libm|libdl|libpthread|librt|ld-linux|libGL|libEGL|libGLX|libOpenGL|libGLdispatch|libgbm|libdrm|libvulkan)\.'
  for p in "${programs[@]}"; do
    ldd "$build/bin/$p" | awk '/=> \//{print $1" "$3}'
  done | sort -u | while read -r name path; do
    if ! [[ "$name" =~ $skip ]]; then
      cp -L "$path" "$bundle/lib/$name"
    fi
  done
  # The programs link OSMesa (the default headless backend here), which pulls in LLVM, z3 and
  # ICU (about 190 MiB). The device renders through EGL: a stub of the same soname stands in,
  # whose calls fail cleanly (a context is never created through it).
  rm -f "$bundle"/lib/libOSMesa.so.* "$bundle"/lib/libLLVM* "$bundle"/lib/libz3.so.* \
    "$bundle"/lib/libxml2.so.* "$bundle"/lib/libicu*
  printf '%s\n' 'void* OSMesaCreateContextAttribs(const int* a, void* s) { (void)a; (void)s; return 0; }' \
    'void OSMesaDestroyContext(void* c) { (void)c; }' \
    'void* OSMesaGetCurrentContext(void) { return 0; }' \
    'void* OSMesaGetProcAddress(const char* n) { (void)n; return 0; }' \
    'unsigned char OSMesaMakeCurrent(void* c, void* b, int t, int w, int h) { (void)c; (void)b; (void)t; (void)w; (void)h; return 0; }' \
    >"$bundle/osmesa_stub.c"
  gcc -shared -fPIC -O2 -Wl,-soname,libOSMesa.so.8 -o "$bundle/lib/libOSMesa.so.8" \
    "$bundle/osmesa_stub.c"
  rm -f "$bundle/osmesa_stub.c"
  IFS=, read -r -a names <<<"$bundled_data"
  for n in "${names[@]}"; do
    cp "$data_src"/"$n"_[0-9]*x[0-9]*x[0-9]*_*.raw* "$bundle/data/"
  done
  cp "$data_src/datasets.json" "$data_src/MANIFEST.md" "$bundle/data/"
  strip --strip-unneeded "$bundle"/lib/*.so* "$bundle"/bin/* 2>/dev/null || true
  # Compressed: the libraries are about 70 MiB as they are.
  tar -C "$bundle" -cf - lib | xz -T2 -6 >"$bundle/lib.tar.xz"
  rm -rf "$bundle/lib"
  du -sh "$bundle" "$bundle"/*
  local size
  size=$(du -sb "$bundle" | cut -f1)
  if [ "$size" -gt $((56 * 1024 * 1024)) ]; then
    echo "bench-device: .device is $((size / 1048576)) MiB: too large to carry with the tree (64 MiB)" >&2
    exit 1
  fi
}

run() {
  local quick=0
  [ "${1:-}" = "--quick" ] && quick=1
  local out="${OUT:-${ACCELVOLUME_DEVICE_OUT:-/tmp/accelvolume-device}}"
  mkdir -p "$out"
  [ -d "$bundle/bin" ] || { echo "bench-device: no .device bundle (run 'prepare' first and carry .device)" >&2; exit 1; }
  local libs=/tmp/accelvolume-device
  mkdir -p "$libs"
  xz -dc "$bundle/lib.tar.xz" | tar -C "$libs" -xf -
  export LD_LIBRARY_PATH="$libs/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
  export ACCELVOLUME_DATA_DIR="$bundle/data" ACCELVOLUME_GL=egl
  local egl_vendor=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
  [ -f "$egl_vendor" ] && export __EGL_VENDOR_LIBRARY_FILENAMES="$egl_vendor"
  local bin="$bundle/bin" log="$out/log.txt" failed=0
  : >"$log"
  {
    echo "== machine"; nvidia-smi -L 2>/dev/null || echo "no nvidia-smi"; nproc; date -u
    echo "== probe"
    "$bin/accelvolume" render --mapper slice --size 256 256 --frames 1 \
      --stats "$out/probe.json" --out "$out/probe.png" && cat "$out/probe.json"
  } >>"$log" 2>&1 || { echo "bench-device: the probe failed (see $log)" >&2; failed=1; }
  local sizes=256,512,1024 frames=10 sets="$datasets" tfs=tf1,tf2 crop_sets=cthead,cta_avm
  if [ "$quick" = 1 ]; then sizes=256; frames=2; sets=engine; tfs=tf1; crop_sets=cthead; fi
  # No no-op column on the GPU: GALLIUM_NOOP is Mesa's, the NVIDIA driver would draw for real.
  echo "== composite" >>"$log"
  timeout 200 "$bin/accelvolume_benchmark_composite" --gl egl --data "$bundle/data" \
    --datasets "$sets" --tfs "$tfs" --sizes "$sizes" --frames "$frames" --large-frames "$frames" \
    --noop-frames 0 --json "$out/composite.json" >>"$log" 2>&1 || { echo "composite failed" >>"$log"; failed=1; }
  echo "== cropping" >>"$log"
  timeout 60 "$bin/accelvolume_benchmark_cropping" --gl egl --data "$bundle/data" \
    --datasets "$crop_sets" --frames "$frames" --json "$out/cropping.json" >>"$log" 2>&1 ||
    { echo "cropping failed" >>"$log"; failed=1; }
  echo "== image tests" >>"$log"
  local t
  for t in "${image_tests[@]}"; do
    [ "$quick" = 1 ] && [ "$t" != TestAccelVolumeVsGPURayCast ] && continue
    if timeout 60 "$bin/vtkRenderingAccelVolumeCxxTests" "$t" -T "$out" >>"$log" 2>&1; then
      echo "PASS $t" | tee -a "$out/tests.txt"
    else
      echo "FAIL $t" | tee -a "$out/tests.txt"; failed=1
    fi
  done
  tail -n 40 "$log"
  return "$failed"
}

case "${1:-}" in
  prepare) prepare ;;
  run) shift; run "$@" ;;
  *) sed -n '2,19p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; exit 2 ;;
esac
