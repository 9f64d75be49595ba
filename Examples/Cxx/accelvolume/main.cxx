// accelvolume: renders a volume file or phantom with AccelVolume's or VTK's volume mappers,
// headless, and reports timings. See `accelvolume render --help` (and `octree --help`).
#include "OctreeCommand.h"
#include "Options.h"
#include "Phantoms.h"
#include "Render.h"
#include "Stats.h"
#include "TransferFunctions.h"
#include "VolumeIO.h"

#include <vtkAccelVolumeHeadlessRenderWindow.h>

#include <dlfcn.h>

#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <new>

#ifndef ACCELVOLUME_VERSION
#define ACCELVOLUME_VERSION "unknown"
#endif

namespace
{
using namespace accelvolume::cli;

// Whether an X display can be opened. VTK's X window aborts the process when it cannot, so the
// CLI asks first; libX11 is loaded at run time (VTK's X build already depends on it).
bool CanOpenXDisplay(const char* name)
{
  void* library = dlopen("libX11.so.6", RTLD_LAZY | RTLD_LOCAL);
  if (!library)
  {
    return false;
  }
  using OpenDisplay = void* (*)(const char*);
  using CloseDisplay = int (*)(void*);
  auto open = reinterpret_cast<OpenDisplay>(dlsym(library, "XOpenDisplay"));
  auto close = reinterpret_cast<CloseDisplay>(dlsym(library, "XCloseDisplay"));
  void* display = open && close ? open(name) : nullptr;
  if (display)
  {
    close(display);
  }
  dlclose(library);
  return display != nullptr;
}

// Returns a note for the summary when the automatic choice had to change ("" otherwise).
std::string ChooseBackend(const Options& options)
{
  using Window = vtkAccelVolumeHeadlessRenderWindow;
  const char* display = std::getenv("DISPLAY");
  const bool haveDisplay = display && *display;
  int backend = options.glBackend;
  bool explicitChoice = backend >= 0;
  if (!explicitChoice)
  {
    // The module's factory follows ACCELVOLUME_GL, else X when DISPLAY is set, else headless.
    const char* variable = std::getenv("ACCELVOLUME_GL");
    const int fromEnvironment = Window::ParseBackendName(variable ? variable : "");
    explicitChoice = fromEnvironment > 0;
    backend = fromEnvironment > 0 ? fromEnvironment
      : haveDisplay               ? static_cast<int>(Window::BACKEND_X)
                                  : static_cast<int>(Window::BACKEND_AUTOMATIC);
  }
  if (backend == Window::BACKEND_X && !(haveDisplay && CanOpenXDisplay(display)))
  {
    if (explicitChoice)
    {
      throw CliError(ExitRuntime,
        haveDisplay ? "cannot open X display '" + std::string(display) + "' for --gl x"
                    : std::string("--gl x needs an X display, but DISPLAY is not set"));
    }
    Window::InstallAsDefaultRenderWindow(Window::BACKEND_AUTOMATIC);
    return "X display '" + std::string(display) + "' unavailable, rendered headless";
  }
  if (backend != Window::BACKEND_X && backend != Window::BACKEND_AUTOMATIC &&
    !Window::IsBackendAvailable(backend))
  {
    throw CliError(ExitRuntime,
      std::string("the ") + Window::GetBackendName(backend) +
        " OpenGL backend is not available on this machine");
  }
  if (options.glBackend >= 0)
  {
    setenv("ACCELVOLUME_GL", Window::GetBackendName(options.glBackend), 1);
    Window::InstallAsDefaultRenderWindow(options.glBackend);
  }
  return "";
}

void CheckOutputPath(const std::string& path, const char* flag)
{
  if (path.empty() || path == "-")
  {
    return;
  }
  namespace fs = std::filesystem;
  const fs::path parent = fs::path(path).parent_path();
  std::error_code code;
  if (!parent.empty() && !fs::is_directory(parent, code))
  {
    throw CliError(ExitRuntime,
      std::string("cannot write ") + flag + " '" + path + "': directory '" + parent.string() +
        "' does not exist");
  }
  if (fs::is_directory(path, code))
  {
    throw CliError(
      ExitRuntime, std::string("cannot write ") + flag + " '" + path + "': it is a directory");
  }
}

void CheckPhantom(const Options& options)
{
  if (!options.volume.inputPath.empty())
  {
    return;
  }
  bool known = false;
  std::string names;
  for (const std::string& name : accelvolume::PhantomNames())
  {
    known = known || name == options.volume.phantom;
    names += (names.empty() ? "" : "|") + name;
  }
  if (!known)
  {
    throw CliError(ExitUsage,
      "invalid value '" + options.volume.phantom + "' for --phantom (expected " + names + ")");
  }
  for (const int size : options.volume.phantomDims)
  {
    if (size < 1 || size > 4096)
    {
      throw CliError(ExitUsage, "--phantom-dims values must be between 1 and 4096");
    }
  }
}

int Run(int argc, char* argv[])
{
  if (argc > 1 && std::string(argv[1]) == "octree")
  {
    return RunOctreeCommand(std::vector<std::string>(argv, argv + argc));
  }
  const Options options = ParseOptions(std::vector<std::string>(argv, argv + argc));
  switch (options.action)
  {
    case Options::Action::MainHelp:
      std::cout << MainHelp();
      return 0;
    case Options::Action::RenderHelp:
      std::cout << RenderHelp();
      return 0;
    case Options::Action::Version:
      std::cout << "accelvolume " << ACCELVOLUME_VERSION << "\n";
      return 0;
    case Options::Action::Render:
      break;
  }
  CheckPhantom(options);
  CheckOutputPath(options.outPath, "--out");
  CheckOutputPath(options.statsPath, "--stats");
  // Read before the volume so that a bad --tf file fails in milliseconds, not after a large load.
  const TransferFunctionSpec transferFunction = LoadTransferFunction(options);

  VTKMessages messages;
  const std::string backendNote = ChooseBackend(options);

  std::string error;
  vtkSmartPointer<vtkImageData> image = LoadVolume(options.volume, error);
  messages.Install(); // loading swaps VTK's output window and logger levels while it runs
  if (!image)
  {
    throw CliError(ExitRuntime, error);
  }
  CheckCrop(options, image);

  const RenderResult result = RunRender(options, transferFunction, image, messages);

  if (!options.statsPath.empty())
  {
    if (options.statsPath == "-")
    {
      WriteStats(std::cout, options, image, result, messages.GetNumberOfWarnings());
      std::cout.flush();
    }
    else
    {
      std::ofstream stream(options.statsPath, std::ios::binary | std::ios::trunc);
      if (stream)
      {
        WriteStats(stream, options, image, result, messages.GetNumberOfWarnings());
      }
      if (!stream)
      {
        throw CliError(ExitRuntime, "cannot write --stats '" + options.statsPath + "'");
      }
    }
  }
  if (!options.quiet)
  {
    // With --stats - the JSON owns stdout, so the summary goes to stderr.
    std::ostream& out = options.statsPath == "-" ? std::cerr : std::cout;
    out << Summary(options, image, result) << "\n";
    if (!backendNote.empty())
    {
      out << "(" << backendNote << ")\n";
    }
    if (messages.GetNumberOfWarnings() > 0)
    {
      out << "(" << messages.GetNumberOfWarnings()
          << " VTK warning(s) suppressed; first: " << messages.GetFirstWarning() << ")\n";
    }
  }
  return 0;
}

} // namespace

int main(int argc, char* argv[])
{
  try
  {
    return Run(argc, argv);
  }
  catch (const CliError& failure)
  {
    std::cerr << "accelvolume: error: " << failure.what() << std::endl;
    return failure.Code;
  }
  catch (const std::bad_alloc&)
  {
    std::cerr << "accelvolume: error: out of memory" << std::endl;
    return ExitRuntime;
  }
  catch (const std::exception& failure)
  {
    std::cerr << "accelvolume: error: " << failure.what() << std::endl;
    return ExitRuntime;
  }
}
