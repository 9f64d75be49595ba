// Help: the text of accelvolume --help and accelvolume render --help.
#include "Options.h"

#include "Phantoms.h"

namespace accelvolume::cli
{

std::string MainHelp()
{
  return "usage: accelvolume render [flags]      render a volume (see accelvolume render --help)\n"
         "       accelvolume octree [flags]      time min-max octree builds (octree --help)\n"
         "       accelvolume --help | --version\n"
         "\n"
         "Renders a volume file or a built-in phantom with AccelVolume's slice mapper, its CPU\n"
         "ray caster (--mapper raycast: octree / distance-map and cell leaping) or one of VTK's\n"
         "volume mappers, headless by default, and writes a PNG and/or JSON timings.\n"
         "Exit codes: 0 success, 1 runtime failure, 2 usage error.\n";
}

std::string RenderHelp()
{
  std::string phantoms;
  for (const std::string& name : accelvolume::PhantomNames())
  {
    phantoms += (phantoms.empty() ? "" : "|") + name;
  }
  return "usage: accelvolume render [flags]\n"
         "\n"
         "Input (a phantom unless --input is given):\n"
         "  --phantom NAME             " +
    phantoms +
    " (default vessels)\n"
    "  --phantom-dims X Y Z       phantom size in voxels (default 128 128 128)\n"
    "  --time T                   phantom animation time, period 1 (default 0)\n"
    "  --input FILE               .mhd/.mha, .vti, .nrrd/.nhdr, .raw or .raw.gz\n"
    "  --dims X Y Z               raw input dimensions (NAME_XxYxZ_type.raw[.gz] names\n"
    "                             and a datasets.json beside the file supply them too)\n"
    "  --type T                   raw scalar type: uint8|int8|uint16|int16|int32|float32|float64\n"
    "  --spacing SX SY SZ         voxel spacing (overrides the file's)\n"
    "\n"
    "Rendering:\n"
    "  --mapper M                 slice (AccelVolume, default) | raycast (AccelVolume's CPU\n"
    "                             ray caster) | vtk-gpu (vtkGPUVolumeRayCastMapper) |\n"
    "                             vtk-fixed (vtkFixedPointVolumeRayCastMapper); all use the\n"
    "                             same camera, transfer functions and world sample distance\n"
    "  --blend B                  mip (default) | minip | additive | average | composite\n"
    "  --window LO HI             data values mapped to black..white, opacity 0..1\n"
    "                             (default: the full scalar range; minip: opacity 1)\n"
    "  --tf tf1|tf2|FILE.json     transfer function for every blend mode, replacing the default\n"
    "                             ramp; presets are laid out over --window LO HI or the data\n"
    "                             range [lo, hi]: tf1 semi-transparent (opacity 0 below\n"
    "                             lo+10%, rising to 0.35 at hi; dark red -> orange -> white),\n"
    "                             tf2 opaque surfaces (opacity steps 0 -> 1 between lo+30% and\n"
    "                             lo+32%; bone colour). A FILE (data units) is a JSON object:\n"
    "                             \"scalarOpacity\": [[x, a], ...], \"color\": [[x, r, g, b], "
    "...]\n"
    "                             (both required; x increasing, a/r/g/b in 0..1), optional\n"
    "                             \"gradientOpacity\": [[g, a], ...], \"shade\": true|false,\n"
    "                             \"ambient\", \"diffuse\", \"specular\" (0..1),\n"
    "                             \"specularPower\" (0..128), \"name\", \"description\"\n"
    "  --shade on|off             gradient shading with one headlight (default off, or the\n"
    "                             file's \"shade\"); lighting ambient 0.2 diffuse 0.7\n"
    "                             specular 0.3 power 10 unless the file gives them (the slice\n"
    "                             mapper may not shade yet; raycast, vtk-gpu and vtk-fixed do)\n"
    "  --gradient-opacity G0 A0 G1 A1\n"
    "                             opacity multiplier ramping A0..A1 over gradient magnitudes\n"
    "                             G0..G1 (gradient-magnitude units; overrides the file's)\n"
    "  --raysum-unit D            world length counted as one raysum unit (slice and raycast\n"
    "                             mappers, additive; default: largest world extent / 4)\n"
    "  --sample-distance D        world distance between samples/slices\n"
    "                             (default: the smallest voxel spacing)\n"
    "  --slices N                 slice count through the volume depth instead (slice mapper;\n"
    "                             other mappers sample at the volume diagonal / N)\n"
    "  --crop X0 X1 Y0 Y1 Z0 Z1   keep this index-space sub-volume (cropping, SubVolume)\n"
    "  --boundary-rerender on|off re-render the cut faces (slice mapper; default on)\n"
    "  --slab-samples N           MIP/MinIP slice depths sampled per proxy fragment (slice\n"
    "                             mapper; 1 = classic slicing, the default)\n"
    "  --ert on|off               composite early ray termination (slice and raycast mappers;\n"
    "                             default on)\n"
    "  --ert-interval N           slices between termination passes (default 16)\n"
    "  --ess none|fragment|octree|both\n"
    "                             composite empty-space skipping (slice mapper; default both)\n"
    "  --jitter on|off            composite per-pixel sample jitter (slice mapper; default off)\n"
    "  --gradients texture|on-the-fly\n"
    "                             shading gradients precomputed or by central differences\n"
    "                             (slice mapper; default texture)\n"
    "\n"
    "CPU mappers (raycast, vtk-fixed; usage errors with slice and vtk-gpu):\n"
    "  --threads N                threads, 0..1024 (default 0: the mapper's default); the\n"
    "                             raycast image does not depend on it\n"
    "  --image-sample-distance D  pixels per ray along each image axis, 1..32 (default 1)\n"
    "  --leap none|octree|distance\n"
    "                             raycast only: empty-space leaping over a min-max octree\n"
    "                             (every blend but average) or a per-cell distance map\n"
    "                             (composite, additive); default distance\n"
    "  --cell-leap on|off         raycast only: semi-transparent cell leaping through the\n"
    "                             Marching Cubes table (composite, additive; default off).\n"
    "                             Every leap is exact: the image stays the same\n"
    "\n"
    "View and output:\n"
    "  --size W H                 image size, 1..16384 (default 512 512)\n"
    "  --azimuth A --elevation E --roll R --zoom Z\n"
    "                             camera moves in degrees/factor after the front view\n"
    "                             (looking along +z at the volume centre, view-up +y)\n"
    "  --parallel | --perspective projection (default perspective)\n"
    "  --background R G B         background colour in 0..1 (default 0 0 0)\n"
    "  --frames N                 timed frames after one warm-up frame, each turned 2 degrees\n"
    "                             further in azimuth (default 1)\n"
    "  --out FILE.png             write the last frame\n"
    "  --stats FILE.json          write timings and settings as JSON ('-' = stdout); raycast\n"
    "                             adds \"raycast\": rays, samples, samples leaped per\n"
    "                             mechanism, terminated rays, cast_ms and prepare_ms\n"
    "  --gl osmesa|egl|x          OpenGL backend (default: $ACCELVOLUME_GL, else X when\n"
    "                             DISPLAY is set, else EGL, then OSMesa)\n"
    "  --quiet                    no summary\n"
    "  --help                     this text\n";
}

} // namespace accelvolume::cli
