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

#include <CLI/CLI.hpp>

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

// --builder gpu: a headless OpenGL 4.3 context for the compute-shader builder (its renderer string
// goes into result).
vtkSmartPointer<vtkAccelVolumeHeadlessRenderWindow> CreateGpuBuilderWindow(
  const OctreeOptions& options, VTKMessages& messages, OctreeResult& result)
{
  if (options.glBackend != vtkAccelVolumeHeadlessRenderWindow::BACKEND_AUTOMATIC &&
    !vtkAccelVolumeHeadlessRenderWindow::IsBackendAvailable(options.glBackend))
  {
    throw CliError(ExitRuntime,
      std::string("the ") + vtkAccelVolumeHeadlessRenderWindow::GetBackendName(options.glBackend) +
        " OpenGL backend is not available on this machine");
  }
  auto window = vtkSmartPointer<vtkAccelVolumeHeadlessRenderWindow>::New();
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
  return window;
}

} // namespace

void AddOctreeFlags(CLI::App& command, OctreeOptions& options)
{
  command.option_defaults()->group("Octree");
  AddFlag(command, "--leaf", 1, "L", "leaf block edge in voxels, a power of two 2..64 (default 8)",
    [&](const FlagValues& values)
    {
      const int leaf = ParseInteger("--leaf", values[0]);
      if (leaf < 2 || leaf > 64 || (leaf & (leaf - 1)) != 0)
      {
        throw CliError(
          ExitUsage, "--leaf must be a power of two between 2 and 64, got " + std::to_string(leaf));
      }
      options.leaf = static_cast<int>(leaf);
    });
  AddFlag(command, "--builder", 1, "B",
    "reference (plain loops) | cpu (Morton order, vtkSMPTools;\n"
    "default) | gpu (OpenGL 4.3 compute shaders)",
    [&](const FlagValues& values)
    {
      const std::map<std::string, int> builders = {
        { "reference", vtkAccelVolumeMinMaxOctree::BUILDER_REFERENCE },
        { "cpu", vtkAccelVolumeMinMaxOctree::BUILDER_CPU },
        { "gpu", vtkAccelVolumeMinMaxOctree::BUILDER_GPU }
      };
      const auto found = builders.find(values[0]);
      if (found == builders.end())
      {
        throw CliError(ExitUsage,
          "invalid value '" + values[0] + "' for --builder (expected reference|cpu|gpu)");
      }
      options.builder = found->second;
    });
  AddBoundedInteger(command, "--threads", "N", "cpu builder threads (0 = vtkSMPTools' default)",
    0, 1024, [&](int value) { options.threads = value; });
  AddBoundedInteger(command, "--repeat", "N",
    "builds, read-floor passes and classifications (default 5)", 1, 10000,
    [&](int value) { options.repeat = value; });
  AddFlag(command, "--tf-low", 1, "V",
    "opacity 0 up to V, ramping to 1 at the maximum\n"
    "(default: 10% into the scalar range)",
    [&](const FlagValues& values)
    {
      const std::string& text = values[0];
      char* end = nullptr;
      options.tfLow = std::strtod(text.c_str(), &end);
      if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(options.tfLow))
      {
        throw CliError(ExitUsage, "--tf-low expects a number, got '" + text + "'");
      }
      options.haveTfLow = true;
    });
  AddFlag(command, "--gl", 1, "osmesa|egl",
    "headless OpenGL backend of the gpu builder\n"
    "(default: $ACCELVOLUME_GL, else EGL, then OSMesa)",
    [&](const FlagValues& values)
    {
      options.glBackend = vtkAccelVolumeHeadlessRenderWindow::ParseBackendName(values[0].c_str());
      if (options.glBackend != vtkAccelVolumeHeadlessRenderWindow::BACKEND_EGL &&
        options.glBackend != vtkAccelVolumeHeadlessRenderWindow::BACKEND_OSMESA)
      {
        throw CliError(
          ExitUsage, "invalid value '" + values[0] + "' for --gl (expected osmesa|egl)");
      }
    });
  command.option_defaults()->group("Output");
  AddFlag(
    command, "--stats", 1, "FILE.json", "write the results as JSON ('-' = stdout)",
    [&](const FlagValues& values) { options.statsPath = values[0]; }, true);
  AddProgressFlag(command, options.progress,
    "progress bar of the builds on stderr (default auto: only\n"
    "when stderr is a terminal)");
  AddSwitch(command, "--quiet", "no summary line", [&]() { options.quiet = true; });
}

void CheckOctree(const OctreeOptions& options)
{
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
}

int RunOctreeCommand(const OctreeOptions& options)
{
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
    window = CreateGpuBuilderWindow(options, messages, result);
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

} // namespace accelvolume::cli
