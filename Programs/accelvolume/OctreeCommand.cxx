// OctreeCommand: builds vtkAccelVolumeMinMaxOctree K times and reports build, read-floor and
// re-classification timings (Lim and Shin 2009: the octree is rebuilt whenever a 4D volume changes).
#include "OctreeCommand.h"

#include "Options.h"
#include "reference/Phantoms.h"
#include "Render.h"
#include "VolumeIO.h"

#include <vtkAccelVolumeHeadlessRenderWindow.h>
#include <vtkAccelVolumeMinMaxOctree.h>

#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPiecewiseFunction.h>
#include <vtkPointData.h>
#include <vtkSMPTools.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

namespace accelvolume::cli
{
namespace
{

long ParseLong(const std::string& flag, const std::string& text)
{
  char* end = nullptr;
  errno = 0;
  const long value = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE)
  {
    throw CliError(ExitUsage, flag + " expects an integer, got '" + text + "'");
  }
  return value;
}

// Splits the octree flags from the input flags; the latter go through render's parser so the
// two commands accept (and reject) volume inputs identically.
OctreeOptions ParseOctreeOptions(const std::vector<std::string>& arguments, bool& help)
{
  // Input flags and their value counts.
  static const std::map<std::string, int> inputFlags = { { "--phantom", 1 },
    { "--phantom-dims", 3 }, { "--time", 1 }, { "--input", 1 }, { "--dims", 3 }, { "--type", 1 },
    { "--spacing", 3 } };
  OctreeOptions options;
  std::vector<std::string> forwarded = { "accelvolume", "render" };
  help = false;
  auto value = [&](std::size_t& i, const std::string& flag) -> std::string
  {
    if (i + 1 >= arguments.size() ||
      (flag != "--stats" && arguments[i + 1].size() > 2 &&
        arguments[i + 1].compare(0, 2, "--") == 0))
    {
      throw CliError(ExitUsage, flag + " expects 1 value");
    }
    return arguments[++i];
  };
  for (std::size_t i = 2; i < arguments.size(); ++i)
  {
    const std::string& flag = arguments[i];
    const auto input = inputFlags.find(flag);
    if (input != inputFlags.end())
    {
      forwarded.push_back(flag);
      for (int n = 0; n < input->second && i + 1 < arguments.size(); ++n)
      {
        forwarded.push_back(arguments[++i]);
      }
    }
    else if (flag == "--help" || flag == "-h")
    {
      help = true;
      return options;
    }
    else if (flag == "--leaf")
    {
      const long leaf = ParseLong(flag, value(i, flag));
      if (leaf < 2 || leaf > 64 || (leaf & (leaf - 1)) != 0)
      {
        throw CliError(
          ExitUsage, "--leaf must be a power of two between 2 and 64, got " + std::to_string(leaf));
      }
      options.leaf = static_cast<int>(leaf);
    }
    else if (flag == "--builder")
    {
      const std::string name = value(i, flag);
      const std::map<std::string, int> builders = {
        { "reference", vtkAccelVolumeMinMaxOctree::BUILDER_REFERENCE },
        { "cpu", vtkAccelVolumeMinMaxOctree::BUILDER_CPU },
        { "gpu", vtkAccelVolumeMinMaxOctree::BUILDER_GPU }
      };
      const auto found = builders.find(name);
      if (found == builders.end())
      {
        throw CliError(
          ExitUsage, "invalid value '" + name + "' for --builder (expected reference|cpu|gpu)");
      }
      options.builder = found->second;
    }
    else if (flag == "--threads" || flag == "--repeat")
    {
      const long number = ParseLong(flag, value(i, flag));
      const long low = flag == "--threads" ? 0 : 1;
      const long high = flag == "--threads" ? 1024 : 10000;
      if (number < low || number > high)
      {
        throw CliError(ExitUsage,
          flag + " must be between " + std::to_string(low) + " and " + std::to_string(high));
      }
      (flag == "--threads" ? options.threads : options.repeat) = static_cast<int>(number);
    }
    else if (flag == "--tf-low")
    {
      const std::string text = value(i, flag);
      char* end = nullptr;
      options.tfLow = std::strtod(text.c_str(), &end);
      if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(options.tfLow))
      {
        throw CliError(ExitUsage, "--tf-low expects a number, got '" + text + "'");
      }
      options.haveTfLow = true;
    }
    else if (flag == "--gl")
    {
      const std::string name = value(i, flag);
      options.glBackend = vtkAccelVolumeHeadlessRenderWindow::ParseBackendName(name.c_str());
      if (options.glBackend != vtkAccelVolumeHeadlessRenderWindow::BACKEND_EGL &&
        options.glBackend != vtkAccelVolumeHeadlessRenderWindow::BACKEND_OSMESA)
      {
        throw CliError(ExitUsage, "invalid value '" + name + "' for --gl (expected osmesa|egl)");
      }
    }
    else if (flag == "--stats")
    {
      options.statsPath = value(i, flag);
    }
    else if (flag == "--quiet")
    {
      options.quiet = true;
    }
    else if (flag == "--progress")
    {
      const std::string mode = value(i, flag);
      if (!ParseProgressMode(mode, options.progress))
      {
        throw CliError(
          ExitUsage, "invalid value '" + mode + "' for --progress (expected auto|off|on)");
      }
    }
    else
    {
      throw CliError(ExitUsage,
        flag.compare(0, 1, "-") == 0 ? "unknown flag '" + flag + "' (see accelvolume octree --help)"
                                     : "unexpected argument '" + flag + "'");
    }
  }
  options.volume = ParseOptions(forwarded).volume;
  if (options.volume.inputPath.empty())
  {
    // render checks the phantom name before loading (a usage error, not a load failure).
    const std::vector<std::string> names = accelvolume::PhantomNames();
    if (std::find(names.begin(), names.end(), options.volume.phantom) == names.end())
    {
      throw CliError(ExitUsage, "invalid value '" + options.volume.phantom + "' for --phantom");
    }
    for (const int size : options.volume.phantomDims)
    {
      if (size < 1 || size > 4096)
      {
        throw CliError(ExitUsage, "--phantom-dims values must be between 1 and 4096");
      }
    }
  }
  if (!options.statsPath.empty() && options.statsPath != "-")
  {
    const auto parent = std::filesystem::path(options.statsPath).parent_path();
    std::error_code code;
    if (!parent.empty() && !std::filesystem::is_directory(parent, code))
    {
      throw CliError(ExitRuntime,
        "cannot write --stats '" + options.statsPath + "': directory '" + parent.string() +
          "' does not exist");
    }
  }
  return options;
}

double MillisecondsSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
    .count();
}

// The floor a build must approach: one thread streaming every byte once (summed as 64-bit
// words so the loop is bandwidth-bound, not ALU-bound). The sum is published so it is not elided.
volatile std::uint64_t ReadFloorSink = 0;
double ReadFloorOnceMs(const void* data, std::size_t bytes)
{
  const auto start = std::chrono::steady_clock::now();
  const auto* bytePointer = static_cast<const unsigned char*>(data);
  const std::size_t words = bytes / 8;
  std::uint64_t sum = 0;
  for (std::size_t i = 0; i < words; ++i)
  {
    std::uint64_t word;
    std::memcpy(&word, bytePointer + 8 * i, 8);
    sum += word;
  }
  for (std::size_t i = 8 * words; i < bytes; ++i)
  {
    sum += bytePointer[i];
  }
  ReadFloorSink = ReadFloorSink + sum;
  return MillisecondsSince(start);
}

// Opacity 0 up to `low`, then a linear ramp to 1 at the scalar maximum.
void SetRamp(vtkPiecewiseFunction* opacity, double low, const double range[2])
{
  opacity->RemoveAllPoints();
  if (low >= range[1])
  {
    opacity->AddPoint(range[0], 0.0);
    opacity->AddPoint(range[1], 0.0);
    return;
  }
  opacity->AddPoint(std::min(low, range[0]), 0.0);
  opacity->AddPoint(low, 0.0);
  opacity->AddPoint(range[1], 1.0);
}

} // namespace

int RunOctreeCommand(const std::vector<std::string>& arguments)
{
  bool help = false;
  const OctreeOptions options = ParseOctreeOptions(arguments, help);
  if (help)
  {
    std::cout << OctreeHelp();
    return 0;
  }

  VTKMessages messages;
  std::string error;
  vtkSmartPointer<vtkImageData> image = LoadVolume(options.volume, error);
  messages.Install(); // loading swaps VTK's output window and logger levels while it runs
  if (!image)
  {
    throw CliError(ExitRuntime, error);
  }
  vtkDataArray* scalars = image->GetPointData()->GetScalars();

  OctreeResult result;
  scalars->GetRange(result.range, 0);
  result.bytes = static_cast<std::size_t>(scalars->GetNumberOfValues()) *
    static_cast<std::size_t>(scalars->GetDataTypeSize());
  result.tfLow =
    options.haveTfLow ? options.tfLow : result.range[0] + 0.1 * (result.range[1] - result.range[0]);
  // The second function for the re-classification timing: halfway between tfLow and the max.
  result.tfLowAlternate = result.tfLow + 0.5 * (result.range[1] - result.tfLow);

  vtkNew<vtkAccelVolumeMinMaxOctree> octree;
  octree->SetInputData(image);
  octree->SetLeafSize(options.leaf);
  octree->SetBuilder(options.builder);
  octree->SetNumberOfThreads(options.threads);
  switch (options.builder)
  {
    case vtkAccelVolumeMinMaxOctree::BUILDER_REFERENCE:
      result.threads = 1;
      break;
    case vtkAccelVolumeMinMaxOctree::BUILDER_CPU:
      if (options.threads > 0)
      {
        vtkSMPTools::Initialize(options.threads);
      }
      result.threads = vtkSMPTools::GetEstimatedNumberOfThreads();
      break;
    default:
      result.threads = 0;
  }

  vtkSmartPointer<vtkAccelVolumeHeadlessRenderWindow> window;
  if (options.builder == vtkAccelVolumeMinMaxOctree::BUILDER_GPU)
  {
    if (options.glBackend != vtkAccelVolumeHeadlessRenderWindow::BACKEND_AUTOMATIC &&
      !vtkAccelVolumeHeadlessRenderWindow::IsBackendAvailable(options.glBackend))
    {
      throw CliError(ExitRuntime,
        std::string("the ") +
          vtkAccelVolumeHeadlessRenderWindow::GetBackendName(options.glBackend) +
          " OpenGL backend is not available on this machine");
    }
    window = vtkSmartPointer<vtkAccelVolumeHeadlessRenderWindow>::New();
    window->SetBackend(options.glBackend);
    window->SetMultiSamples(0);
    window->SetSize(16, 16);
    window->Initialize();
    messages.ThrowIfError("cannot create an OpenGL context");
    const char* renderer = window->GetOpenGLRendererString();
    result.glRenderer = renderer && *renderer ? renderer : "unknown";
    int major = 0, minor = 0;
    window->GetOpenGLVersion(major, minor);
    if (major * 10 + minor < 43)
    {
      // The same message start the ctest gpu test keys its skip on.
      throw CliError(ExitRuntime,
        "--builder gpu needs OpenGL 4.3 compute shaders; the " +
          std::string(
            vtkAccelVolumeHeadlessRenderWindow::GetBackendName(window->GetActiveBackend())) +
          " context offers " + std::to_string(major) + "." + std::to_string(minor) + " (" +
          result.glRenderer + ")");
    }
    octree->SetRenderWindow(window);
  }

  // The bar (stderr; see --progress): one task per build, filled by the octree's ProgressEvent.
  ProgressBar bar("octree", options.progress);
  vtkNew<vtkCallbackCommand> onProgress;
  if (bar.IsShown())
  {
    onProgress->SetClientData(&bar);
    onProgress->SetCallback([](vtkObject*, unsigned long, void* client, void* data)
      { static_cast<ProgressBar*>(client)->Update(*static_cast<double*>(data)); });
    octree->AddObserver(vtkCommand::ProgressEvent, onProgress);
  }
  for (int k = 0; k < options.repeat; ++k)
  {
    // The octree rebuilds only when the scalars changed: mark them as a new time step would.
    scalars->Modified();
    image->Modified();
    bar.BeginTask(k, options.repeat, "build");
    const auto start = std::chrono::steady_clock::now();
    const bool built = octree->Update();
    result.buildMs.push_back(MillisecondsSince(start));
    messages.ThrowIfError("octree build failed");
    if (!built)
    {
      throw CliError(ExitRuntime, "octree build failed");
    }
  }
  bar.Finish();
  octree->RemoveObserver(onProgress);
  result.nodes = octree->GetNumberOfNodes();
  result.depth = octree->GetDepth();
  octree->GetLeafGridSize(result.leafGrid);

  const void* data = scalars->GetVoidPointer(0);
  for (int k = 0; k < options.repeat; ++k)
  {
    result.readFloorMs.push_back(ReadFloorOnceMs(data, result.bytes));
  }

  // One function object re-filled every call: its modification time always moves, so every
  // Classify() really re-classifies (two fixed objects could look unchanged to the octree).
  vtkNew<vtkPiecewiseFunction> opacity;
  SetRamp(opacity, result.tfLow, result.range);
  if (!octree->Classify(opacity, result.range))
  {
    messages.ThrowIfError("classification failed");
    throw CliError(ExitRuntime, "classification failed");
  }
  for (int k = 0; k < options.repeat; ++k)
  {
    SetRamp(opacity, k % 2 == 0 ? result.tfLowAlternate : result.tfLow, result.range);
    const auto start = std::chrono::steady_clock::now();
    const bool classified = octree->Classify(opacity, result.range);
    result.classifyMs.push_back(MillisecondsSince(start));
    if (!classified)
    {
      messages.ThrowIfError("classification failed");
      throw CliError(ExitRuntime, "classification failed");
    }
  }
  if (options.repeat % 2 == 1)
  {
    SetRamp(opacity, result.tfLow, result.range); // report the fraction for --tf-low
    octree->Classify(opacity, result.range);
  }
  result.transparentLeafFraction = octree->GetTransparentLeafFraction();
  messages.ThrowIfError("classification failed");
  if (window)
  {
    window->MakeCurrent();
    octree->ReleaseGraphicsResources();
  }

  if (!options.statsPath.empty())
  {
    if (options.statsPath == "-")
    {
      WriteOctreeStats(std::cout, options, image, result);
      std::cout.flush();
    }
    else
    {
      std::ofstream stream(options.statsPath, std::ios::binary | std::ios::trunc);
      if (stream)
      {
        WriteOctreeStats(stream, options, image, result);
      }
      if (!stream)
      {
        throw CliError(ExitRuntime, "cannot write --stats '" + options.statsPath + "'");
      }
    }
  }
  if (!options.quiet)
  {
    std::ostream& out = options.statsPath == "-" ? std::cerr : std::cout;
    out << OctreeSummary(options, image, result) << "\n";
  }
  return 0;
}

std::string OctreeHelp()
{
  return "usage: accelvolume octree [flags]\n"
         "\n"
         "Builds the min-max octree (Lim and Shin 2009: Morton-order min/max blocks for empty-space\n"
         "skipping) of a volume --repeat times, each time as if the data had changed, and\n"
         "reports the build time against a one-thread streaming read of the volume (the floor)\n"
         "and the re-classification time after a transfer-function change.\n"
         "\n"
         "Input: --phantom, --phantom-dims, --time, --input, --dims, --type, --spacing as in\n"
         "  accelvolume render --help (default: phantom vessels 128x128x128).\n"
         "\n"
         "Octree:\n"
         "  --leaf L                   leaf block edge in voxels, a power of two 2..64 (default "
         "8)\n"
         "  --builder B                reference (plain loops) | cpu (Morton order, vtkSMPTools;\n"
         "                             default) | gpu (OpenGL 4.3 compute shaders)\n"
         "  --threads N                cpu builder threads (0 = vtkSMPTools' default)\n"
         "  --repeat K                 builds, read-floor passes and classifications (default 5)\n"
         "  --tf-low V                 opacity 0 up to V, ramping to 1 at the maximum\n"
         "                             (default: 10% into the scalar range)\n"
         "  --gl osmesa|egl            headless OpenGL backend of the gpu builder\n"
         "                             (default: $ACCELVOLUME_GL, else EGL, then OSMesa)\n"
         "\n"
         "Output:\n"
         "  --stats FILE.json          write the results as JSON ('-' = stdout)\n"
         "  --progress auto|on|off     progress bar of the builds on stderr (default auto: only\n"
         "                             when stderr is a terminal)\n"
         "  --quiet                    no summary line\n"
         "  --help                     this text\n";
}

} // namespace accelvolume::cli
