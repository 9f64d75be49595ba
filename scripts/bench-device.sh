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
#                                           matrix and the MIP / MinIP ones (ours vs
#                                           vtkGPUVolumeRayCastMapper; engine, cthead, bonsai,
#                                           aneurism; tf1 / tf2 (MinIP: ramp); 256-1024^2), the
#                                           cropped-MIP and octree benchmarks and the GPU image
#                                           tests; JSON, two probe PNGs and a log under $OUT (or
#                                           $ACCELVOLUME_DEVICE_OUT)
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
octree_sets="engine,aneurism,cta_avm,vessels"
bundled_data="$datasets,cta_avm"
programs=(accelvolume accelvolume_benchmark_composite accelvolume_benchmark_cropping
  accelvolume_benchmark_octree vtkRenderingAccelVolumeCxxTests)
# GPU image tests: the slice mapper against its CPU reference and VTK's GPU mapper.
image_tests=(TestAccelVolumeSliceMapperReference TestAccelVolumeVsGPURayCast
  TestAccelVolumeVsGPURayCastFeatures TestAccelVolumeEarlyRayTermination
  TestAccelVolumeEmptySpaceSkipping TestAccelVolumeSlabSamples TestAccelVolumeCompositeSlabs
  TestAccelVolumeComputeSlices
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
  local bin="$bundle/bin" log="$out/log.txt" failed=0 t0=$SECONDS
  : >"$log"
  stage() { echo "== $1 ($((SECONDS - t0)) s)" >>"$log"; }
  {
    echo "== machine"; nvidia-smi -L 2>/dev/null || echo "no nvidia-smi"; nproc; date -u
    local missing
    missing=$(ldd "$bin/accelvolume" | grep "not found" || true)
    [ -n "$missing" ] && echo "missing libraries: $missing"
  } >>"$log" 2>&1
  # The probe: one frame each way, compute and rasterised slices, their images and stats.
  stage probe
  local engine="$bundle/data/engine_256x256x128_uint8.raw.gz" c
  for c in compute raster; do
    "$bin/accelvolume" render --input "$engine" --blend composite --tf tf1 --shade on \
      --size 512 512 --azimuth 30 --elevation 20 --compositing "$c" --frames 5 \
      --stats "$out/probe_$c.json" --out "$out/probe_$c.png" >>"$log" 2>&1 ||
      { echo "bench-device: the $c probe failed (see $log)" >&2; failed=1; }
    cat "$out/probe_$c.json" >>"$log" 2>/dev/null; rm -f "$out/probe_$c.json"
  done
  local sizes=256,512,1024 frames=10 sets="$datasets" tfs=tf1,tf2 crop_sets=cthead,cta_avm
  if [ "$quick" = 1 ]; then sizes=256; frames=2; sets=engine; tfs=tf1; crop_sets=cthead; fi
  # No no-op column on the GPU: GALLIUM_NOOP is Mesa's, the NVIDIA driver would draw for real.
  local blend
  for blend in composite mip minip; do
    stage "$blend"
    local blend_tfs="$tfs"
    [ "$blend" = minip ] && blend_tfs=ramp
    timeout 150 "$bin/accelvolume_benchmark_composite" --gl egl --data "$bundle/data" \
      --blend "$blend" --datasets "$sets" --tfs "$blend_tfs" --sizes "$sizes" --frames "$frames" \
      --large-frames "$frames" --noop-frames 0 --json "$out/$blend.json" >>"$log" 2>&1 ||
      { echo "$blend failed" >>"$log"; failed=1; }
  done
  # The smart mapper's choice: our three mappers on the same parallel views (all threads).
  stage mappers
  local ds tf m file threads
  threads=$(nproc)
  for ds in engine cthead bonsai_hazeremoved; do
    [ "$quick" = 1 ] && [ "$ds" != engine ] && continue
    file=$(ls "$bundle/data/${ds}"_[0-9]*x[0-9]*x[0-9]*_*.raw* | head -n 1)
    for tf in tf1 tf2; do
      for m in slice raycast shearwarp; do
        local extra=(--threads "$threads")
        [ "$m" = slice ] && extra=()
        if timeout 60 "$bin/accelvolume" render --mapper "$m" --input "$file" --blend composite \
          --tf "$tf" --shade on --size 512 512 --parallel --frames "$frames" "${extra[@]}" \
          --stats "$out/mapper.json" --out "$out/mapper.png" >/dev/null 2>>"$log"; then
          echo "MAPPER $ds $tf $m $(tr -d '\n ' <"$out/mapper.json" |
            sed -n 's/.*"ms_per_frame":{"median":\([0-9.]*\).*/\1/p')" >>"$log"
        else
          echo "MAPPER $ds $tf $m failed" >>"$log"
        fi
      done
    done
  done
  rm -f "$out/mapper.json" "$out/mapper.png"
  stage cropping
  timeout 60 "$bin/accelvolume_benchmark_cropping" --gl egl --data "$bundle/data" \
    --datasets "$crop_sets" --frames "$frames" --json "$out/cropping.json" >>"$log" 2>&1 ||
    { echo "cropping failed" >>"$log"; failed=1; }
  if [ "$quick" = 0 ]; then
    stage octree
    timeout 60 "$bin/accelvolume_benchmark_octree" --gl egl --data "$bundle/data" \
      --datasets "$octree_sets" --json "$out/octree.json" >>"$log" 2>&1 ||
      { echo "octree failed" >>"$log"; failed=1; }
  fi
  stage "image tests"
  local t
  for t in "${image_tests[@]}"; do
    [ "$quick" = 1 ] && [ "$t" != TestAccelVolumeComputeSlices ] && continue
    if timeout 60 "$bin/vtkRenderingAccelVolumeCxxTests" "$t" -T "$out" >>"$log" 2>&1; then
      echo "PASS $t" | tee -a "$log"
    else
      echo "FAIL $t" | tee -a "$log"; failed=1
    fi
  done
  rm -f "$out"/*.png.diff* "$out"/Test*.png 2>/dev/null || true
  stage done
  tail -n 40 "$log"
  return "$failed"
}

case "${1:-}" in
  prepare) prepare ;;
  run) shift; run "$@" ;;
  *) sed -n '2,21p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; exit 2 ;;
esac
