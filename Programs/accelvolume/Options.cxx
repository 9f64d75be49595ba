// Options: parsing and help text of the accelvolume command line.
#include "Options.h"

#include <vtkAccelVolumeHeadlessRenderWindow.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <map>
#include <sstream>

namespace accelvolume::cli
{
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

int ParseInteger(const std::string& flag, const std::string& text)
{
  char* end = nullptr;
  errno = 0;
  const long value = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE || value > 1 << 30 ||
    value < -(1 << 30))
  {
    throw Usage(flag + " expects an integer, got '" + text + "'");
  }
  return static_cast<int>(value);
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

class ArgumentReader
{
public:
  ArgumentReader(const std::vector<std::string>& arguments, std::size_t start)
    : Arguments(arguments)
    , Position(start)
  {
  }
  bool Done() const { return this->Position >= this->Arguments.size(); }
  std::string Next() { return this->Arguments[this->Position++]; }
  // The values of flag; a missing value (end of line or another flag) is a usage error.
  std::vector<std::string> Values(const std::string& flag, int count)
  {
    std::vector<std::string> values;
    for (int i = 0; i < count; ++i)
    {
      const bool missing = this->Done() ||
        (this->Arguments[this->Position].compare(0, 2, "--") == 0 &&
          this->Arguments[this->Position].size() > 2);
      if (missing)
      {
        throw Usage(
          flag + " expects " + std::to_string(count) + " value" + (count == 1 ? "" : "s"));
      }
      values.push_back(this->Next());
    }
    return values;
  }
  std::string Value(const std::string& flag) { return this->Values(flag, 1)[0]; }
  std::vector<double> Numbers(const std::string& flag, int count)
  {
    std::vector<double> numbers;
    for (const std::string& text : this->Values(flag, count))
    {
      numbers.push_back(ParseNumber(flag, text));
    }
    return numbers;
  }
  std::vector<int> Integers(const std::string& flag, int count)
  {
    std::vector<int> numbers;
    for (const std::string& text : this->Values(flag, count))
    {
      numbers.push_back(ParseInteger(flag, text));
    }
    return numbers;
  }

private:
  const std::vector<std::string>& Arguments;
  std::size_t Position;
};

void ParseRenderFlags(ArgumentReader& reader, Options& options)
{
  using Handler = std::function<void(const std::string&)>;
  VolumeRequest& volume = options.volume;
  const std::map<std::string, Handler> handlers = {
    { "--phantom", [&](const std::string& f) { volume.phantom = reader.Value(f); } },
    { "--phantom-dims",
      [&](const std::string& f)
      {
        const std::vector<int> dims = reader.Integers(f, 3);
        std::copy(dims.begin(), dims.end(), volume.phantomDims);
      } },
    { "--time", [&](const std::string& f) { volume.phantomTime = reader.Numbers(f, 1)[0]; } },
    { "--input", [&](const std::string& f) { volume.inputPath = reader.Value(f); } },
    { "--dims",
      [&](const std::string& f)
      {
        const std::vector<int> dims = reader.Integers(f, 3);
        if (*std::min_element(dims.begin(), dims.end()) < 1)
        {
          throw Usage("--dims values must be at least 1, got " + std::to_string(dims[0]) + " " +
            std::to_string(dims[1]) + " " + std::to_string(dims[2]));
        }
        std::copy(dims.begin(), dims.end(), volume.dims);
        volume.haveDims = true;
      } },
    { "--type",
      [&](const std::string& f)
      {
        const std::string name = reader.Value(f);
        volume.kind = ParseScalarKind(name);
        if (volume.kind == ScalarKind::Unknown)
        {
          throw Usage("invalid value '" + name +
            "' for --type (expected uint8|int8|uint16|int16|int32|float32|float64)");
        }
      } },
    { "--spacing",
      [&](const std::string& f)
      {
        const std::vector<double> spacing = reader.Numbers(f, 3);
        for (int axis = 0; axis < 3; ++axis)
        {
          if (spacing[axis] <= 0)
          {
            throw Usage("--spacing values must be positive");
          }
          volume.spacing[axis] = spacing[axis];
        }
        volume.haveSpacing = true;
      } },
    { "--mapper",
      [&](const std::string& f)
      {
        options.mapper = ParseChoice<MapperKind>(f, reader.Value(f),
          { { "slice", MapperKind::Slice }, { "raycast", MapperKind::RayCast },
            { "vtk-gpu", MapperKind::VTKGPU }, { "vtk-fixed", MapperKind::VTKFixed },
            { "shearwarp", MapperKind::ShearWarp }, { "smart", MapperKind::Smart } });
      } },
    { "--blend",
      [&](const std::string& f)
      {
        options.blend = ParseChoice<BlendKind>(f, reader.Value(f),
          { { "mip", BlendKind::MIP }, { "minip", BlendKind::MinIP },
            { "additive", BlendKind::Additive }, { "average", BlendKind::Average },
            { "composite", BlendKind::Composite } });
      } },
    { "--window",
      [&](const std::string& f)
      {
        const std::vector<double> window = reader.Numbers(f, 2);
        if (!(window[0] < window[1]))
        {
          throw Usage("--window needs LO < HI, got " + FormatNumber(window[0]) + " " +
            FormatNumber(window[1]));
        }
        options.window[0] = window[0];
        options.window[1] = window[1];
        options.haveWindow = true;
      } },
    { "--tf", [&](const std::string& f) { options.transferFunction = reader.Value(f); } },
    { "--shade",
      [&](const std::string& f)
      {
        options.shade = ParseChoice<bool>(f, reader.Value(f), { { "on", true }, { "off", false } });
        options.haveShade = true;
      } },
    { "--gradient-opacity",
      [&](const std::string& f)
      {
        const std::vector<double> ramp = reader.Numbers(f, 4);
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
      } },
    { "--raysum-unit",
      [&](const std::string& f)
      {
        options.raysumUnit = reader.Numbers(f, 1)[0];
        if (options.raysumUnit <= 0)
        {
          throw Usage("--raysum-unit must be positive");
        }
        options.haveRaysumUnit = true;
      } },
    { "--size",
      [&](const std::string& f)
      {
        const std::vector<int> size = reader.Integers(f, 2);
        for (int axis = 0; axis < 2; ++axis)
        {
          if (size[axis] <= 0 || size[axis] > 16384)
          {
            throw Usage("--size values must be between 1 and 16384, got " +
              std::to_string(size[0]) + " " + std::to_string(size[1]));
          }
          options.size[axis] = size[axis];
        }
      } },
    { "--azimuth", [&](const std::string& f) { options.azimuth = reader.Numbers(f, 1)[0]; } },
    { "--elevation", [&](const std::string& f) { options.elevation = reader.Numbers(f, 1)[0]; } },
    { "--roll", [&](const std::string& f) { options.roll = reader.Numbers(f, 1)[0]; } },
    { "--zoom",
      [&](const std::string& f)
      {
        options.zoom = reader.Numbers(f, 1)[0];
        if (options.zoom <= 0)
        {
          throw Usage("--zoom must be positive");
        }
      } },
    { "--parallel",
      [&](const std::string&)
      {
        options.parallel = true;
        options.havePerspective = false;
      } },
    { "--perspective",
      [&](const std::string&)
      {
        options.parallel = false;
        options.havePerspective = true;
      } },
    { "--crop",
      [&](const std::string& f)
      {
        const std::vector<double> crop = reader.Numbers(f, 6);
        std::copy(crop.begin(), crop.end(), options.crop);
        options.haveCrop = true;
      } },
    { "--boundary-rerender",
      [&](const std::string& f)
      {
        options.boundaryRerender =
          ParseChoice<bool>(f, reader.Value(f), { { "on", true }, { "off", false } });
      } },
    { "--ert",
      [&](const std::string& f)
      {
        options.earlyRayTermination =
          ParseChoice<bool>(f, reader.Value(f), { { "on", true }, { "off", false } });
      } },
    { "--ert-interval",
      [&](const std::string& f)
      {
        options.ertInterval = reader.Integers(f, 1)[0];
        if (options.ertInterval < 1 || options.ertInterval > 4096)
        {
          throw Usage("--ert-interval must be between 1 and 4096");
        }
      } },
    { "--jitter",
      [&](const std::string& f) {
        options.jitter =
          ParseChoice<bool>(f, reader.Value(f), { { "on", true }, { "off", false } });
      } },
    { "--gradients",
      [&](const std::string& f)
      {
        options.precomputeGradients =
          ParseChoice<bool>(f, reader.Value(f), { { "texture", true }, { "on-the-fly", false } });
      } },
    { "--ess",
      [&](const std::string& f)
      {
        options.emptySpaceSkipping = ParseChoice<int>(
          f, reader.Value(f), { { "none", 0 }, { "fragment", 1 }, { "octree", 2 }, { "both", 3 } });
      } },
    { "--slab-samples",
      [&](const std::string& f)
      {
        options.slabSamples = reader.Integers(f, 1)[0];
        if (options.slabSamples < 1 || options.slabSamples > 64)
        {
          throw Usage("--slab-samples must be between 1 and 64");
        }
      } },
    { "--gpu-budget",
      [&](const std::string& f)
      {
        options.gpuBudgetMiB = reader.Numbers(f, 1)[0];
        if (!(options.gpuBudgetMiB >= 0 && options.gpuBudgetMiB <= 16.0 * 1024 * 1024))
        {
          throw Usage("--gpu-budget must be between 0 (no budget) and 16777216 MiB");
        }
      } },
    { "--max-brick",
      [&](const std::string& f)
      {
        options.maxBrick = reader.Integers(f, 1)[0];
        if (options.maxBrick != 0 && (options.maxBrick < 4 || options.maxBrick > 65536))
        {
          throw Usage("--max-brick must be 0 (the GL limit) or between 4 and 65536 texels");
        }
      } },
    { "--sample-distance",
      [&](const std::string& f)
      {
        options.sampleDistance = reader.Numbers(f, 1)[0];
        if (options.sampleDistance <= 0)
        {
          throw Usage("--sample-distance must be positive");
        }
        options.haveSampleDistance = true;
      } },
    { "--slices",
      [&](const std::string& f)
      {
        options.slices = reader.Integers(f, 1)[0];
        if (options.slices < 2 || options.slices > 65536)
        {
          throw Usage("--slices must be between 2 and 65536");
        }
      } },
    { "--leap",
      [&](const std::string& f)
      {
        options.leap = ParseChoice<LeapKind>(f, reader.Value(f),
          { { "none", LeapKind::None }, { "octree", LeapKind::Octree },
            { "distance", LeapKind::DistanceMap } });
        options.haveLeap = true;
      } },
    { "--cell-leap",
      [&](const std::string& f)
      {
        options.cellLeap =
          ParseChoice<bool>(f, reader.Value(f), { { "on", true }, { "off", false } });
        options.haveCellLeap = true;
      } },
    { "--threads",
      [&](const std::string& f)
      {
        options.threads = reader.Integers(f, 1)[0];
        if (options.threads < 0 || options.threads > 1024)
        {
          throw Usage("--threads must be between 0 and 1024 (0 = the mapper's default)");
        }
        options.haveThreads = true;
      } },
    { "--image-sample-distance",
      [&](const std::string& f)
      {
        options.imageSampleDistance = reader.Numbers(f, 1)[0];
        if (options.imageSampleDistance < 1 || options.imageSampleDistance > 32)
        {
          throw Usage("--image-sample-distance must be between 1 and 32");
        }
        options.haveImageSampleDistance = true;
      } },
    { "--balance",
      [&](const std::string& f)
      {
        options.balance =
          ParseChoice<bool>(f, reader.Value(f), { { "on", true }, { "off", false } });
        options.haveBalance = true;
      } },
    { "--rle",
      [&](const std::string& f)
      {
        options.runLengthEncoding =
          ParseChoice<bool>(f, reader.Value(f), { { "on", true }, { "off", false } });
        options.haveRunLengthEncoding = true;
      } },
    { "--shading",
      [&](const std::string& f)
      {
        options.phongShading =
          ParseChoice<bool>(f, reader.Value(f), { { "table", false }, { "phong", true } });
        options.haveShading = true;
      } },
    { "--mpi", [&](const std::string&) { options.mpi = true; } },
    { "--mpi-timeout",
      [&](const std::string& f)
      {
        options.mpiTimeout = reader.Numbers(f, 1)[0];
        if (!(options.mpiTimeout >= 0 && options.mpiTimeout <= 86400))
        {
          throw Usage("--mpi-timeout must be between 0 and 86400 seconds (0 = wait forever)");
        }
        options.haveMpiTimeout = true;
      } },
    { "--frames",
      [&](const std::string& f)
      {
        options.frames = reader.Integers(f, 1)[0];
        if (options.frames < 1 || options.frames > 100000)
        {
          throw Usage("--frames must be between 1 and 100000");
        }
      } },
    { "--out", [&](const std::string& f) { options.outPath = reader.Value(f); } },
    { "--stats",
      [&](const std::string& f)
      {
        // "-" is a value here, so it is read without the flag check of Value().
        if (reader.Done())
        {
          throw Usage(f + " expects 1 value");
        }
        options.statsPath = reader.Next();
      } },
    { "--gl",
      [&](const std::string& f)
      {
        options.gl = reader.Value(f);
        options.glBackend =
          vtkAccelVolumeHeadlessRenderWindow::ParseBackendName(options.gl.c_str());
        if (options.glBackend < 0)
        {
          throw Usage("invalid value '" + options.gl + "' for --gl (expected osmesa|egl|x)");
        }
      } },
    { "--background",
      [&](const std::string& f)
      {
        const std::vector<double> colour = reader.Numbers(f, 3);
        for (int i = 0; i < 3; ++i)
        {
          if (colour[i] < 0 || colour[i] > 1)
          {
            throw Usage("--background values must lie in [0, 1]");
          }
          options.background[i] = colour[i];
        }
      } },
    { "--quiet", [&](const std::string&) { options.quiet = true; } },
    { "--progress",
      [&](const std::string& f)
      {
        const std::string mode = reader.Value(f);
        if (!ParseProgressMode(mode, options.progress))
        {
          throw Usage("invalid value '" + mode + "' for --progress (expected auto|off|on)");
        }
      } },
  };
  while (!reader.Done())
  {
    const std::string flag = reader.Next();
    if (flag == "--help" || flag == "-h")
    {
      options.action = Options::Action::RenderHelp;
      return;
    }
    const auto handler = handlers.find(flag);
    if (handler == handlers.end())
    {
      throw Usage(flag.compare(0, 1, "-") == 0
          ? "unknown flag '" + flag + "' (see accelvolume render --help)"
          : "unexpected argument '" + flag + "'");
    }
    handler->second(flag);
  }
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
  // Mapper-specific flags that would silently do nothing elsewhere are usage errors.
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
  onlyFor(options.haveRunLengthEncoding, "--rle", shearWarp || smart,
    "--mapper shearwarp and smart");
  onlyFor(options.haveShading, "--shading", shearWarp || smart, "--mapper shearwarp and smart");
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
  if (options.volume.inputPath.empty() &&
    (options.volume.haveDims || options.volume.kind != ScalarKind::Unknown))
  {
    throw Usage("--dims and --type need --input (a raw file)");
  }
}

} // namespace

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

Options ParseOptions(const std::vector<std::string>& arguments)
{
  Options options;
  if (arguments.size() < 2)
  {
    throw Usage("no command given (try accelvolume --help)");
  }
  const std::string command = arguments[1];
  if (command == "--help" || command == "-h" || command == "help")
  {
    options.action = Options::Action::MainHelp;
    return options;
  }
  if (command == "--version")
  {
    options.action = Options::Action::Version;
    return options;
  }
  if (command != "render")
  {
    throw Usage((command.compare(0, 1, "-") == 0 ? "unknown flag '" : "unknown command '") +
      command + "' (expected 'render' or 'octree'; try accelvolume --help)");
  }
  ArgumentReader reader(arguments, 2);
  ParseRenderFlags(reader, options);
  return options;
}

} // namespace accelvolume::cli
