// Options: the flags of `accelvolume render` (CLI11), their help text and the checks between them.
#include "Options.h"

#include "reference/Phantoms.h"

#include <vtkAccelVolumeHeadlessRenderWindow.h>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <map>
#include <sstream>
#include <type_traits>

namespace accelvolume::cli
{

int ParseInteger(const std::string& flag, const std::string& text)
{
  char* end = nullptr;
  errno = 0;
  const long value = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE || value > 1 << 30 ||
    value < -(1 << 30))
  {
    throw CliError(ExitUsage, flag + " expects an integer, got '" + text + "'");
  }
  return static_cast<int>(value);
}

namespace
{

CliError Usage(const std::string& message)
{
  return CliError(ExitUsage, message);
}

double ParseNumber(const std::string& flag, const std::string& text)
{
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE || !std::isfinite(value))
  {
    throw Usage(flag + " expects a number, got '" + text + "'");
  }
  return value;
}

std::string FormatNumber(double value)
{
  std::ostringstream stream;
  stream << value;
  return stream.str();
}

template <typename Enum>
Enum ParseChoice(
  const std::string& flag, const std::string& text, const std::map<std::string, Enum>& choices)
{
  const auto found = choices.find(text);
  if (found == choices.end())
  {
    std::string names;
    for (const auto& choice : choices)
    {
      names += (names.empty() ? "" : "|") + choice.first;
    }
    throw Usage("invalid value '" + text + "' for " + flag + " (expected " + names + ")");
  }
  return found->second;
}

// --flag X (one number), --flag N (one integer), and the same with count values.
void AddNumber(CLI::App& command, const std::string& flag, const std::string& text,
  const std::string& help, std::function<void(double)> take)
{
  AddFlag(command, flag, 1, text, help,
    [flag, take](const FlagValues& values) { take(ParseNumber(flag, values[0])); });
}

void AddInteger(CLI::App& command, const std::string& flag, const std::string& text,
  const std::string& help, std::function<void(int)> take)
{
  AddFlag(command, flag, 1, text, help,
    [flag, take](const FlagValues& values) { take(ParseInteger(flag, values[0])); });
}

void AddNumbers(CLI::App& command, const std::string& flag, int count, const std::string& text,
  const std::string& help, std::function<void(const std::vector<double>&)> take)
{
  AddFlag(command, flag, count, text, help,
    [flag, take](const FlagValues& values)
    {
      std::vector<double> numbers;
      for (const std::string& value : values)
      {
        numbers.push_back(ParseNumber(flag, value));
      }
      take(numbers);
    });
}

void AddIntegers(CLI::App& command, const std::string& flag, int count, const std::string& text,
  const std::string& help, std::function<void(const std::vector<int>&)> take)
{
  AddFlag(command, flag, count, text, help,
    [flag, take](const FlagValues& values)
    {
      std::vector<int> numbers;
      for (const std::string& value : values)
      {
        numbers.push_back(ParseInteger(flag, value));
      }
      take(numbers);
    });
}

void AddText(CLI::App& command, const std::string& flag, const std::string& text,
  const std::string& help, std::string& target)
{
  AddFlag(
    command, flag, 1, text, help, [&target](const FlagValues& values) { target = values[0]; });
}

template <typename Enum>
void AddChoice(CLI::App& command, const std::string& flag, const std::string& text,
  const std::string& help, std::map<std::string, Enum> choices, std::function<void(Enum)> take)
{
  AddFlag(command, flag, 1, text, help,
    [flag, choices, take](const FlagValues& values)
    { take(ParseChoice<Enum>(flag, values[0], choices)); });
}

// --flag N (Number int) or --flag X (Number double) within [low, high]; outside it the error is
// "--flag must be between low and high" + note.
template <typename Number>
void AddBounded(CLI::App& command, const std::string& flag, const std::string& text,
  const std::string& help, Number low, Number high, const std::string& note,
  std::function<void(Number)> take)
{
  AddFlag(command, flag, 1, text, help,
    [=](const FlagValues& values)
    {
      Number value;
      if constexpr (std::is_integral<Number>::value)
      {
        value = ParseInteger(flag, values[0]);
      }
      else
      {
        value = ParseNumber(flag, values[0]);
      }
      if (!(value >= low && value <= high))
      {
        throw Usage(
          flag + " must be between " + FormatNumber(low) + " and " + FormatNumber(high) + note);
      }
      take(value);
    });
}

// --flag X with X > 0.
void AddPositive(CLI::App& command, const std::string& flag, const std::string& text,
  const std::string& help, std::function<void(double)> take)
{
  AddNumber(command, flag, text, help,
    [flag, take](double value)
    {
      if (value <= 0)
      {
        throw Usage(flag + " must be positive");
      }
      take(value);
    });
}

// --flag on|off.
void AddOnOff(CLI::App& command, const std::string& flag, const std::string& help,
  std::function<void(bool)> take)
{
  AddChoice<bool>(command, flag, "on|off", help, { { "on", true }, { "off", false } }, take);
}

// The mapper and how it blends, classifies, shades and samples.
void AddRenderingFlags(CLI::App& command, Options& options)
{
  AddChoice<MapperKind>(command, "--mapper", "M",
    "slice (AccelVolume, default) | raycast (AccelVolume's CPU\n"
    "ray caster) | shearwarp (AccelVolume's CPU shear-warp:\n"
    "parallel projection, composite/mip/minip, one sample per\n"
    "volume slice) | vtk-gpu (vtkGPUVolumeRayCastMapper) |\n"
    "vtk-fixed (vtkFixedPointVolumeRayCastMapper) | smart\n"
    "(vtkAccelVolumeSmartMapper: slice, raycast or shearwarp per\n"
    "frame, each configured by its own flags); all use the\n"
    "same camera, transfer functions and world sample distance",
    { { "slice", MapperKind::Slice }, { "raycast", MapperKind::RayCast },
      { "vtk-gpu", MapperKind::VTKGPU }, { "vtk-fixed", MapperKind::VTKFixed },
      { "shearwarp", MapperKind::ShearWarp }, { "smart", MapperKind::Smart } },
    [&](MapperKind mapper) { options.mapper = mapper; });
  AddChoice<BlendKind>(command, "--blend", "B",
    "mip (default) | minip | additive | average | composite",
    { { "mip", BlendKind::MIP }, { "minip", BlendKind::MinIP }, { "additive", BlendKind::Additive },
      { "average", BlendKind::Average }, { "composite", BlendKind::Composite } },
    [&](BlendKind blend) { options.blend = blend; });
  AddNumbers(command, "--window", 2, "LO HI",
    "data values mapped to black..white, opacity 0..1\n"
    "(default: the full scalar range; minip: opacity 1)",
    [&](const std::vector<double>& window)
    {
      if (!(window[0] < window[1]))
      {
        throw Usage(
          "--window needs LO < HI, got " + FormatNumber(window[0]) + " " + FormatNumber(window[1]));
      }
      options.window[0] = window[0];
      options.window[1] = window[1];
      options.haveWindow = true;
    });
  AddText(command, "--tf", "tf1|tf2|FILE.json",
    "transfer function for every blend mode, replacing the default\n"
    "ramp; presets are laid out over --window LO HI or the data\n"
    "range [lo, hi]: tf1 semi-transparent (opacity 0 below\n"
    "lo+10%, rising to 0.35 at hi; dark red -> orange -> white),\n"
    "tf2 opaque surfaces (opacity steps 0 -> 1 between lo+30% and\n"
    "lo+32%; bone colour). A FILE (data units) is a JSON object:\n"
    "\"scalarOpacity\": [[x, a], ...], \"color\": [[x, r, g, b], ...]\n"
    "(both required; x increasing, a/r/g/b in 0..1), optional\n"
    "\"gradientOpacity\": [[g, a], ...], \"shade\": true|false,\n"
    "\"ambient\", \"diffuse\", \"specular\" (0..1),\n"
    "\"specularPower\" (0..128), \"name\", \"description\"",
    options.transferFunction);
  AddOnOff(command, "--shade",
    "gradient shading with one headlight (default off, or the\n"
    "file's \"shade\"); lighting ambient 0.2 diffuse 0.7\n"
    "specular 0.3 power 10 unless the file gives them (the slice\n"
    "mapper may not shade yet; raycast, shearwarp, vtk-gpu and\n"
    "vtk-fixed do)",
    [&](bool shade)
    {
      options.shade = shade;
      options.haveShade = true;
    });
  AddNumbers(command, "--gradient-opacity", 4, "G0 A0 G1 A1",
    "opacity multiplier ramping A0..A1 over gradient magnitudes\n"
    "G0..G1 (gradient-magnitude units; overrides the file's)",
    [&](const std::vector<double>& ramp)
    {
      if (!(ramp[0] >= 0 && ramp[0] < ramp[2]))
      {
        throw Usage("--gradient-opacity needs 0 <= G0 < G1, got " + FormatNumber(ramp[0]) + " " +
          FormatNumber(ramp[2]));
      }
      if (ramp[1] < 0 || ramp[1] > 1 || ramp[3] < 0 || ramp[3] > 1)
      {
        throw Usage("--gradient-opacity opacities A0 A1 must lie in [0, 1]");
      }
      std::copy(ramp.begin(), ramp.end(), options.gradientOpacity);
      options.haveGradientOpacity = true;
    });
  AddPositive(command, "--raysum-unit", "D",
    "world length counted as one raysum unit (slice and raycast\n"
    "mappers, additive; default: largest world extent / 4)",
    [&](double unit)
    {
      options.raysumUnit = unit;
      options.haveRaysumUnit = true;
    });
  AddPositive(command, "--sample-distance", "D",
    "world distance between samples/slices\n"
    "(default: the smallest voxel spacing)",
    [&](double distance)
    {
      options.sampleDistance = distance;
      options.haveSampleDistance = true;
    });
  AddBounded<int>(command, "--slices", "N",
    "slice count through the volume depth instead (slice mapper;\n"
    "other mappers sample at the volume diagonal / N)",
    2, 65536, "", [&](int slices) { options.slices = slices; });
}

// Cropping and the slice mapper's acceleration switches (ERT and ESS also reach other mappers).
void AddAccelerationFlags(CLI::App& command, Options& options)
{
  AddNumbers(command, "--crop", 6, "X0 X1 Y0 Y1 Z0 Z1",
    "keep this index-space sub-volume (cropping, SubVolume)",
    [&](const std::vector<double>& crop)
    {
      std::copy(crop.begin(), crop.end(), options.crop);
      options.haveCrop = true;
    });
  AddOnOff(command, "--boundary-rerender", "re-render the cut faces (slice mapper; default on)",
    [&](bool on) { options.boundaryRerender = on; });
  AddBounded<int>(command, "--slab-samples", "N",
    "slice depths sampled per proxy fragment, one blend per slab\n"
    "(slice mapper: MIP, MinIP, composite; 1 = classic slicing,\n"
    "the default)",
    1, 64, "", [&](int samples) { options.slabSamples = samples; });
  AddNumber(command, "--gpu-budget", "MIB",
    "GPU memory the volume's bricks may hold (slice mapper;\n"
    "default 0 = no budget); beyond it bricks stream per frame",
    [&](double budget)
    {
      if (!(budget >= 0 && budget <= 16.0 * 1024 * 1024))
      {
        throw Usage("--gpu-budget must be between 0 (no budget) and 16777216 MiB");
      }
      options.gpuBudgetMiB = budget;
    });
  AddInteger(command, "--max-brick", "N",
    "largest brick texture per axis (slice mapper; default 0 =\n"
    "GL_MAX_3D_TEXTURE_SIZE)",
    [&](int brick)
    {
      if (brick != 0 && (brick < 4 || brick > 65536))
      {
        throw Usage("--max-brick must be 0 (the GL limit) or between 4 and 65536 texels");
      }
      options.maxBrick = brick;
    });
  AddOnOff(command, "--ert",
    "early ray termination (slice, raycast: composite;\n"
    "shearwarp: skip links over saturated pixels, every blend;\n"
    "default on)",
    [&](bool on) { options.earlyRayTermination = on; });
  AddBounded<int>(command, "--ert-interval", "N", "slices between termination passes (default 16)",
    1, 4096, "", [&](int interval) { options.ertInterval = interval; });
  AddChoice<int>(command, "--ess", "none|fragment|octree|both",
    "composite empty-space skipping (slice mapper; default both)",
    { { "none", 0 }, { "fragment", 1 }, { "octree", 2 }, { "both", 3 } },
    [&](int skipping) { options.emptySpaceSkipping = skipping; });
  AddOnOff(command, "--jitter", "composite per-pixel sample jitter (slice mapper; default off)",
    [&](bool on) { options.jitter = on; });
  AddOnOff(command, "--gpu-slices",
    "composite proxy slices generated on the GPU (slice mapper;\n"
    "default on; off = CPU-clipped slice polygons)",
    [&](bool on) { options.gpuSlices = on; });
  AddOnOff(command, "--half-float",
    "accumulate in a 16-bit float target (slice mapper;\n"
    "default off = 32-bit float)",
    [&](bool on) { options.halfFloatTarget = on; });
  AddChoice<int>(command, "--compositing", "auto|raster|compute",
    "how the slice mapper composites its slices: rasterised proxy\n"
    "slices blended into the target, or one compute pass per frame\n"
    "(default auto: compute where the frame and the context allow)",
    { { "auto", 0 }, { "raster", 1 }, { "compute", 2 } },
    [&](int mode) { options.sliceCompositing = mode; });
  AddChoice<bool>(command, "--gradients", "texture|on-the-fly",
    "shading gradients precomputed or by central differences\n"
    "(slice mapper; default texture)",
    { { "texture", true }, { "on-the-fly", false } },
    [&](bool precompute) { options.precomputeGradients = precompute; });
}

// The CPU mappers' flags (usage errors with the GPU mappers: CheckRender).
void AddCpuFlags(CLI::App& command, Options& options)
{
  AddBounded<int>(command, "--threads", "N",
    "threads, 0..1024 (default 0: the mapper's default); the\n"
    "raycast and shearwarp images do not depend on it",
    0, 1024, " (0 = the mapper's default)",
    [&](int threads)
    {
      options.threads = threads;
      options.haveThreads = true;
    });
  AddBounded<double>(command, "--image-sample-distance", "D",
    "pixels per ray along each image axis, 1..32 (default 1;\n"
    "raycast and vtk-fixed)",
    1, 32, "",
    [&](double distance)
    {
      options.imageSampleDistance = distance;
      options.haveImageSampleDistance = true;
    });
  AddChoice<LeapKind>(command, "--leap", "none|octree|distance",
    "raycast and smart: empty-space leaping over a min-max octree\n"
    "(every blend but average) or a per-cell distance map\n"
    "(composite, additive); default distance",
    { { "none", LeapKind::None }, { "octree", LeapKind::Octree },
      { "distance", LeapKind::DistanceMap } },
    [&](LeapKind leap)
    {
      options.leap = leap;
      options.haveLeap = true;
    });
  AddOnOff(command, "--cell-leap",
    "raycast and smart: semi-transparent cell leaping through the\n"
    "Marching Cubes table (composite, additive; default off).\n"
    "Every leap is exact: the image stays the same",
    [&](bool on)
    {
      options.cellLeap = on;
      options.haveCellLeap = true;
    });
}

// --mapper shearwarp's flags (the smart mapper takes them too, except --mpi).
void AddShearWarpFlags(CLI::App& command, Options& options)
{
  AddOnOff(command, "--balance",
    "balance the scanline bands with the previous frame's\n"
    "per-scanline times (default on); off: equal bands",
    [&](bool on)
    {
      options.balance = on;
      options.haveBalance = true;
    });
  AddOnOff(command, "--rle",
    "run-length encode the classified volume (default on); off:\n"
    "every voxel composited (with --ert off the image is the same)",
    [&](bool on)
    {
      options.runLengthEncoding = on;
      options.haveRunLengthEncoding = true;
    });
  AddChoice<bool>(command, "--shading", "table|phong",
    "composite shading by a per-frame table over quantized normals\n"
    "(default) or Phong per voxel (with --shade on)",
    { { "table", false }, { "phong", true } },
    [&](bool phong)
    {
      options.phongShading = phong;
      options.haveShading = true;
    });
  AddChoice<bool>(command, "--warp", "gpu|cpu",
    "shear-warp's warp: while drawing the intermediate image on\n"
    "the GPU (default), or on the CPU into a viewport-sized image",
    { { "gpu", true }, { "cpu", false } },
    [&](bool gpu)
    {
      options.warpOnGPU = gpu;
      options.haveWarp = true;
    });
  AddOnOff(command, "--background-encoding",
    "composite: encode the other two principal axes in a\n"
    "background thread (default on); off: when a view needs them",
    [&](bool on)
    {
      options.backgroundEncoding = on;
      options.haveBackgroundEncoding = true;
    });
  AddSwitch(command, "--mpi",
    "run under mpirun: every rank renders the same frames and\n"
    "composites its bands, rank 0 gathers them and alone writes\n"
    "--out, --stats and the summary; the image is the same as\n"
    "one process's. A rank that fails makes every rank stop;\n"
    "rank 0 names it",
    [&]() { options.mpi = true; });
  AddBounded<double>(command, "--mpi-timeout", "S",
    "--mpi: the longest a rank waits for another, in seconds\n"
    "(default 60; 0 = forever); then rank 0 names the rank it\n"
    "waited for and the job is aborted (MPI_Abort)",
    0, 86400, " seconds (0 = wait forever)",
    [&](double timeout)
    {
      options.mpiTimeout = timeout;
      options.haveMpiTimeout = true;
    });
}

// The camera and the image.
void AddViewFlags(CLI::App& command, Options& options)
{
  AddIntegers(command, "--size", 2, "W H", "image size, 1..16384 (default 512 512)",
    [&](const std::vector<int>& size)
    {
      for (int axis = 0; axis < 2; ++axis)
      {
        if (size[axis] <= 0 || size[axis] > 16384)
        {
          throw Usage("--size values must be between 1 and 16384, got " + std::to_string(size[0]) +
            " " + std::to_string(size[1]));
        }
        options.size[axis] = size[axis];
      }
    });
  AddNumber(command, "--azimuth", "A",
    "camera azimuth in degrees from the front view (looking\n"
    "along +z at the volume centre, view-up +y; default 0)",
    [&](double degrees) { options.azimuth = degrees; });
  AddNumber(command, "--elevation", "E",
    "camera elevation in degrees from the front view (default 0)",
    [&](double degrees) { options.elevation = degrees; });
  AddNumber(command, "--roll", "R", "camera roll in degrees from the front view (default 0)",
    [&](double degrees) { options.roll = degrees; });
  AddPositive(command, "--zoom", "Z", "camera zoom factor (default 1)",
    [&](double zoom) { options.zoom = zoom; });
  AddSwitch(command, "--parallel", "parallel projection (default perspective; shearwarp: parallel)",
    [&]()
    {
      options.parallel = true;
      options.havePerspective = false;
    });
  AddSwitch(command, "--perspective", "perspective projection (default; not with shearwarp)",
    [&]()
    {
      options.parallel = false;
      options.havePerspective = true;
    });
  AddNumbers(command, "--background", 3, "R G B", "background colour in 0..1 (default 0 0 0)",
    [&](const std::vector<double>& colour)
    {
      for (int i = 0; i < 3; ++i)
      {
        if (colour[i] < 0 || colour[i] > 1)
        {
          throw Usage("--background values must lie in [0, 1]");
        }
        options.background[i] = colour[i];
      }
    });
  AddBounded<int>(command, "--frames", "N",
    "timed frames after one warm-up frame, each turned 2 degrees\n"
    "further in azimuth (default 1)",
    1, 100000, "", [&](int frames) { options.frames = frames; });
}

// Where the image, the timings and the progress go, and the OpenGL backend.
void AddOutputFlags(CLI::App& command, Options& options)
{
  AddText(command, "--out", "FILE.png", "write the last frame", options.outPath);
  AddFlag(
    command, "--stats", 1, "FILE.json",
    "write timings and settings as JSON ('-' = stdout); raycast\n"
    "adds \"raycast\": rays, samples, samples leaped per\n"
    "mechanism, leaps taken, terminated rays, acceleration\n"
    "bytes, cast_ms and prepare_ms;\n"
    "shearwarp adds \"shearwarp\": encode/table/composite/\n"
    "gather/warp ms, bands and their ms, imbalance, voxels,\n"
    "samples, skipped pixels, principal axis, stored voxels,\n"
    "encoded bytes, ranks and threads; slice adds \"slice\":\n"
    "render_ms, proxy polygons, boundary faces, termination\n"
    "passes; smart adds \"smart\": the mode it chose, why, and\n"
    "render_ms, with the chosen mapper's object filled; every\n"
    "mapper reports mapper_render_ms (its own last render time)",
    [&](const FlagValues& values) { options.statsPath = values[0]; }, true);
  AddFlag(command, "--gl", 1, "osmesa|egl|x",
    "OpenGL backend (default: $ACCELVOLUME_GL, else X when\n"
    "DISPLAY is set, else EGL, then OSMesa)",
    [&](const FlagValues& values)
    {
      options.gl = values[0];
      options.glBackend = vtkAccelVolumeHeadlessRenderWindow::ParseBackendName(options.gl.c_str());
      if (options.glBackend < 0)
      {
        throw Usage("invalid value '" + options.gl + "' for --gl (expected osmesa|egl|x)");
      }
    });
  AddProgressFlag(command, options.progress,
    "progress bar on stderr, fed by the mapper's progress events\n"
    "and the frame count (default auto: only when stderr is a\n"
    "terminal; off: never)");
  AddSwitch(command, "--quiet", "no summary", [&]() { options.quiet = true; });
}

} // namespace

void AddBoundedInteger(CLI::App& command, const std::string& flag, const std::string& text,
  const std::string& help, int low, int high, std::function<void(int)> take)
{
  AddBounded<int>(command, flag, text, help, low, high, "", std::move(take));
}

void AddRenderFlags(CLI::App& command, Options& options)
{
  AddInputFlags(command, options.volume);
  command.option_defaults()->group("Rendering");
  AddRenderingFlags(command, options);
  AddAccelerationFlags(command, options);
  command.option_defaults()->group(
    "CPU mappers (raycast, shearwarp, vtk-fixed, and smart for the ones it may pick)");
  AddCpuFlags(command, options);
  command.option_defaults()->group(
    "Shear-warp (--mapper shearwarp, and smart for its shear-warp frames)");
  AddShearWarpFlags(command, options);
  command.option_defaults()->group("View and output");
  AddViewFlags(command, options);
  AddOutputFlags(command, options);
}

void CheckRender(Options& options)
{
  if (options.mapper == MapperKind::VTKFixed && options.blend == BlendKind::Average)
  {
    throw Usage("--mapper vtk-fixed does not support --blend average (VTK's fixed-point mapper "
                "has composite, MIP, MinIP and additive only)");
  }
  // The smart mapper takes the flags of the mappers it may pick (each configures that one).
  const bool smart = options.mapper == MapperKind::Smart;
  const bool rayCast = options.mapper == MapperKind::RayCast || smart;
  const bool shearWarp = options.mapper == MapperKind::ShearWarp;
  const bool cpu = rayCast || shearWarp || options.mapper == MapperKind::VTKFixed;
  const auto onlyFor = [&](bool given, const char* flag, bool valid, const char* mappers)
  {
    if (given && !valid)
    {
      throw Usage(std::string(flag) + " applies only to " + mappers + ", not --mapper " +
        MapperName(options.mapper));
    }
  };
  onlyFor(options.haveLeap, "--leap", rayCast, "--mapper raycast and smart");
  onlyFor(options.haveCellLeap, "--cell-leap", rayCast, "--mapper raycast and smart");
  onlyFor(options.haveThreads, "--threads", cpu,
    "the CPU mappers (raycast, shearwarp, vtk-fixed) and smart");
  onlyFor(options.haveImageSampleDistance, "--image-sample-distance", cpu && !shearWarp,
    "--mapper raycast, vtk-fixed and smart");
  onlyFor(options.haveBalance, "--balance", shearWarp || smart, "--mapper shearwarp and smart");
  onlyFor(
    options.haveRunLengthEncoding, "--rle", shearWarp || smart, "--mapper shearwarp and smart");
  onlyFor(options.haveShading, "--shading", shearWarp || smart, "--mapper shearwarp and smart");
  onlyFor(options.haveWarp, "--warp", shearWarp || smart, "--mapper shearwarp and smart");
  onlyFor(options.haveBackgroundEncoding, "--background-encoding", shearWarp || smart,
    "--mapper shearwarp and smart");
  onlyFor(options.mpi, "--mpi", shearWarp, "--mapper shearwarp");
  const bool slice = options.mapper == MapperKind::Slice || smart;
  onlyFor(options.gpuBudgetMiB > 0, "--gpu-budget", slice, "--mapper slice and smart");
  onlyFor(options.maxBrick > 0, "--max-brick", slice, "--mapper slice and smart");
  if (options.haveMpiTimeout && !options.mpi)
  {
    throw Usage("--mpi-timeout applies only with --mpi");
  }
  if (shearWarp)
  {
    // Shear-warp factorizes a parallel view only: it is the default for this mapper, and an
    // explicit --perspective is refused rather than silently changed.
    if (options.havePerspective)
    {
      throw Usage("--mapper shearwarp renders parallel projections only; drop --perspective "
                  "(shearwarp always uses --parallel)");
    }
    options.parallel = true;
    if (options.blend == BlendKind::Additive || options.blend == BlendKind::Average)
    {
      throw Usage(std::string("--mapper shearwarp does not support --blend ") +
        BlendName(options.blend) + " (it has composite, mip and minip)");
    }
    // Settings shear-warp has no use for would silently do nothing.
    if (options.haveCrop)
    {
      throw Usage("--mapper shearwarp does not crop; drop --crop");
    }
    if (options.haveSampleDistance || options.slices > 0)
    {
      throw Usage(std::string(options.haveSampleDistance ? "--sample-distance" : "--slices") +
        " does not apply to --mapper shearwarp (it samples once per volume slice)");
    }
    if (options.haveRaysumUnit)
    {
      throw Usage("--raysum-unit does not apply to --mapper shearwarp (no additive blend)");
    }
  }
  if (options.haveSampleDistance && options.slices > 0)
  {
    throw Usage("--sample-distance and --slices are mutually exclusive");
  }
  CheckInput(options.volume);
}

void AddProgressFlag(CLI::App& command, ProgressMode& mode, const std::string& help)
{
  AddFlag(command, "--progress", 1, "auto|on|off", help,
    [&mode](const FlagValues& values)
    {
      if (!ParseProgressMode(values[0], mode))
      {
        throw Usage("invalid value '" + values[0] + "' for --progress (expected auto|off|on)");
      }
    });
}

void AddInputFlags(CLI::App& command, VolumeRequest& volume)
{
  command.option_defaults()->group("Input (a phantom unless --input is given)");
  std::string phantoms;
  for (const std::string& name : accelvolume::PhantomNames())
  {
    phantoms += (phantoms.empty() ? "" : "|") + name;
  }
  AddText(command, "--phantom", "NAME", phantoms + " (default vessels)", volume.phantom);
  AddIntegers(command, "--phantom-dims", 3, "X Y Z", "phantom size in voxels (default 128 128 128)",
    [&](const std::vector<int>& dims) { std::copy(dims.begin(), dims.end(), volume.phantomDims); });
  AddNumber(command, "--time", "T", "phantom animation time, period 1 (default 0)",
    [&](double time) { volume.phantomTime = time; });
  AddText(
    command, "--input", "FILE", ".mhd/.mha, .vti, .nrrd/.nhdr, .raw or .raw.gz", volume.inputPath);
  AddIntegers(command, "--dims", 3, "X Y Z",
    "raw input dimensions (NAME_XxYxZ_type.raw[.gz] names\n"
    "and a datasets.json beside the file supply them too)",
    [&](const std::vector<int>& dims)
    {
      if (*std::min_element(dims.begin(), dims.end()) < 1)
      {
        throw Usage("--dims values must be at least 1, got " + std::to_string(dims[0]) + " " +
          std::to_string(dims[1]) + " " + std::to_string(dims[2]));
      }
      std::copy(dims.begin(), dims.end(), volume.dims);
      volume.haveDims = true;
    });
  AddFlag(command, "--type", 1, "T",
    "raw scalar type: uint8|int8|uint16|int16|int32|float32|float64",
    [&](const FlagValues& values)
    {
      volume.kind = ParseScalarType(values[0]);
      if (volume.kind == std::nullopt)
      {
        throw Usage("invalid value '" + values[0] +
          "' for --type (expected uint8|int8|uint16|int16|int32|float32|float64)");
      }
    });
  AddNumbers(command, "--spacing", 3, "SX SY SZ", "voxel spacing (overrides the file's)",
    [&](const std::vector<double>& spacing)
    {
      for (int axis = 0; axis < 3; ++axis)
      {
        if (spacing[axis] <= 0)
        {
          throw Usage("--spacing values must be positive");
        }
        volume.spacing[axis] = spacing[axis];
      }
      volume.haveSpacing = true;
    });
}

void CheckInput(const VolumeRequest& volume)
{
  if (volume.inputPath.empty() && (volume.haveDims || volume.kind != std::nullopt))
  {
    throw Usage("--dims and --type need --input (a raw file)");
  }
}

const char* MapperName(MapperKind mapper)
{
  switch (mapper)
  {
    case MapperKind::Slice:
      return "slice";
    case MapperKind::RayCast:
      return "raycast";
    case MapperKind::VTKGPU:
      return "vtk-gpu";
    case MapperKind::VTKFixed:
      return "vtk-fixed";
    case MapperKind::ShearWarp:
      return "shearwarp";
    case MapperKind::Smart:
      return "smart";
  }
  return "unknown";
}

const char* BlendName(BlendKind blend)
{
  switch (blend)
  {
    case BlendKind::MIP:
      return "mip";
    case BlendKind::MinIP:
      return "minip";
    case BlendKind::Additive:
      return "additive";
    case BlendKind::Average:
      return "average";
    case BlendKind::Composite:
      return "composite";
  }
  return "unknown";
}

const char* LeapName(LeapKind leap)
{
  switch (leap)
  {
    case LeapKind::None:
      return "none";
    case LeapKind::Octree:
      return "octree";
    case LeapKind::DistanceMap:
      return "distance";
  }
  return "unknown";
}

} // namespace accelvolume::cli
