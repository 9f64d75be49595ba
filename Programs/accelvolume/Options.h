// Options: the accelvolume command line, parsed and checked before any VTK object exists.
#ifndef accelvolume_cli_Options_h
#define accelvolume_cli_Options_h

#include "ProgressBar.h"
#include "VolumeIO.h"

#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace CLI
{
class App;
class Option;
}

namespace accelvolume::cli
{

// Exit codes: 0 success, 1 runtime failure (input, rendering, output), 2 usage error.
constexpr int ExitRuntime = 1;
constexpr int ExitUsage = 2;

// Thrown for anything the CLI reports as "accelvolume: error: <what()>" before exiting with code.
class CliError : public std::runtime_error
{
public:
  CliError(int code, const std::string& message, bool agreed = false)
    : std::runtime_error(message)
    , Code(code)
    , Agreed(agreed)
  {
  }
  int Code;
  bool Agreed; // --mpi: every rank knows of this failure (rank 0 reports it)
};

enum class MapperKind
{
  Slice,   // vtkAccelVolumeSliceMapper
  RayCast, // vtkAccelVolumeRayCastMapper (CPU)
  VTKGPU,  // vtkGPUVolumeRayCastMapper
  VTKFixed, // vtkFixedPointVolumeRayCastMapper
  ShearWarp, // vtkAccelVolumeShearWarpMapper (CPU, parallel projection only)
  Smart      // vtkAccelVolumeSmartMapper (picks slice, raycast or shearwarp per frame)
};

// vtkAccelVolumeRayCastMapper::LEAP_* (empty-space leaping of --mapper raycast).
enum class LeapKind
{
  None,
  Octree,
  DistanceMap
};

enum class BlendKind
{
  MIP,
  MinIP,
  Additive,
  Average,
  Composite
};

const char* MapperName(MapperKind mapper);
const char* BlendName(BlendKind blend);
const char* LeapName(LeapKind leap);

struct Options
{
  enum class Action
  {
    Render,
    Octree, // `accelvolume octree`: its options are in an OctreeOptions (OctreeCommand.h)
    MainHelp,
    RenderHelp,
    OctreeHelp,
    Version
  };
  Action action = Action::Render;

  VolumeRequest volume; // --input / --phantom / --dims / --type / --spacing / --time
  MapperKind mapper = MapperKind::Slice;
  BlendKind blend = BlendKind::MIP;
  bool haveWindow = false;
  double window[2] = { 0, 1 };
  std::string transferFunction; // --tf: "" (default ramp), tf1, tf2 or a JSON file
  bool haveShade = false;       // --shade given (it overrides the JSON file's "shade")
  bool shade = false;
  bool haveGradientOpacity = false;
  double gradientOpacity[4] = { 0, 0, 0, 0 }; // G0 A0 G1 A1
  bool haveRaysumUnit = false;
  double raysumUnit = 0;
  int size[2] = { 512, 512 };
  double azimuth = 0, elevation = 0, roll = 0, zoom = 1;
  bool parallel = false;
  bool havePerspective = false; // --perspective given (and not overridden by a later --parallel)
  bool haveCrop = false;
  double crop[6] = { 0, 0, 0, 0, 0, 0 }; // index coordinates
  bool boundaryRerender = true;
  int slabSamples = 0; // 0 = the mapper's default
  double gpuBudgetMiB = 0; // --gpu-budget: slice mapper's GPU memory budget for bricks (0 = none)
  int maxBrick = 0;        // --max-brick: slice mapper's largest brick axis (0 = GL limit)
  bool earlyRayTermination = true;
  int ertInterval = 0;        // 0 = the mapper's default
  int emptySpaceSkipping = 3; // vtkAccelVolumeSliceMapper::SKIP_* (both by default)
  bool precomputeGradients = true;
  bool jitter = false;
  bool gpuSlices = true; // --gpu-slices: composite proxy slices generated in the vertex stage
  bool halfFloatTarget = false; // --half-float: 16-bit float accumulation target
  int sliceCompositing = 0;     // --compositing: vtkAccelVolumeSliceMapper::SLICE_COMPOSITING_*
  bool haveSampleDistance = false;
  double sampleDistance = 0;
  int slices = 0; // 0 = not given
  int frames = 1;
  // --mapper raycast only (the have* flags let the parser reject them for other mappers).
  bool haveLeap = false;
  LeapKind leap = LeapKind::Octree;
  bool haveCellLeap = false;
  bool cellLeap = true;
  // CPU mappers only (raycast, vtk-fixed): 0 = the mapper's default.
  int threads = 0;
  bool haveThreads = false;
  double imageSampleDistance = 1; // pixels per ray along each image axis
  bool haveImageSampleDistance = false;
  // --mapper shearwarp only.
  bool haveBalance = false;
  bool balance = true; // load-balanced scanline bands
  bool haveRunLengthEncoding = false;
  bool runLengthEncoding = true;
  bool haveShading = false;
  bool phongShading = false; // --shading phong (else the lookup table)
  bool haveWarp = false;
  bool warpOnGPU = true;     // --warp gpu (else cpu)
  bool haveBackgroundEncoding = false;
  bool backgroundEncoding = true; // --background-encoding on|off
  bool mpi = false;          // --mpi: vtkMPIController for the shear-warp mapper
  bool haveMpiTimeout = false;
  double mpiTimeout = 60; // --mpi-timeout: longest wait for another rank, seconds (0 = forever)
  std::string outPath;
  std::string statsPath; // "-" = stdout
  std::string gl;        // as given ("" = automatic)
  int glBackend = -1;    // vtkAccelVolumeHeadlessRenderWindow::Backends value once parsed
  double background[3] = { 0, 0, 0 };
  bool quiet = false;
  ProgressMode progress = ProgressMode::Automatic; // --progress: a bar on stderr
};

struct OctreeOptions; // OctreeCommand.h

// Parses argv (argv[0] is the program) with CLI11 into render (`accelvolume render`) or octree
// (`accelvolume octree`) and returns what to do. Throws CliError(ExitUsage, ...) for unknown
// flags, missing or malformed values, bad enum names, out-of-range numbers and flags that do not
// apply to the chosen mapper. Checks that need the volume (crop bounds) happen later.
Options::Action ParseCommandLine(
  const std::vector<std::string>& arguments, Options& render, OctreeOptions& octree);

// The help texts, generated by CLI11 from the registered flags.
std::string MainHelp();
std::string RenderHelp();
std::string OctreeHelp();

// Flag registration shared by `render` and `octree` (CLI11). Every flag's callback runs as soon
// as the flag and its values are read: in command-line order, once per occurrence (so a later
// occurrence overrides an earlier one). A value that looks like a long flag ("--x") counts as
// missing unless anyValue. take throws CliError(ExitUsage, ...) for a bad value.
using FlagValues = std::vector<std::string>;
CLI::Option* AddFlag(CLI::App& command, const std::string& flag, int count, const std::string& text,
  const std::string& help, std::function<void(const FlagValues&)> take, bool anyValue = false);
// --flag N with N an integer in [low, high]; the usage errors are "--flag expects an integer,
// got 'x'" and "--flag must be between low and high".
void AddBoundedInteger(CLI::App& command, const std::string& flag, const std::string& text,
  const std::string& help, int low, int high, std::function<void(int)> take);
// An integer flag value (|value| <= 2^30), else CliError(ExitUsage, "--flag expects an integer,
// got 'text'").
int ParseInteger(const std::string& flag, const std::string& text);
// A flag without a value.
CLI::Option* AddSwitch(
  CLI::App& command, const std::string& flag, const std::string& help, std::function<void()> take);
// --progress auto|on|off.
void AddProgressFlag(CLI::App& command, ProgressMode& mode, const std::string& help);
// The input flags (--phantom, --phantom-dims, --time, --input, --dims, --type, --spacing), in the
// help group "Input"; CheckInput runs after parsing.
void AddInputFlags(CLI::App& command, VolumeRequest& volume);
void CheckInput(const VolumeRequest& volume);
// Every flag of `render` (the input flags first) and, after parsing, the checks between them (a
// flag that would silently do nothing is a usage error; CheckInput last).
void AddRenderFlags(CLI::App& command, Options& options);
void CheckRender(Options& options);

} // namespace accelvolume::cli

#endif
