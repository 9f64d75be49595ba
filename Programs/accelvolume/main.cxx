// accelvolume: renders a volume file or phantom with AccelVolume's or VTK's volume mappers,
// headless, and reports timings. See `accelvolume render --help` (and `octree --help`).
#include "OctreeCommand.h"
#include "Options.h"
#include "reference/Phantoms.h"
#include "Render.h"
#include "Stats.h"
#include "TransferFunctions.h"
#include "VolumeIO.h"

#include <vtkAccelVolumeHeadlessRenderWindow.h>
#include <vtkAccelVolumeMPIExchange.h>
#include <vtkMPI.h> // MPI_Abort
#include <vtkMPIController.h>
#include <vtkMultiProcessController.h>

#include <dlfcn.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <new>
#include <sstream>
#include <string>
#include <vector>

#ifndef ACCELVOLUME_VERSION
#define ACCELVOLUME_VERSION "unknown"
#endif

namespace
{
using namespace accelvolume::cli;

// --mpi: ranks other than 0 print nothing, not even errors (rank 0 reports the agreed failure).
bool SilentRank = false;

// The launcher's rank before MPI is initialized (Open MPI, MPICH, PMIx); 0 when not launched so.
int LauncherRank()
{
  for (const char* name : { "OMPI_COMM_WORLD_RANK", "PMIX_RANK", "PMI_RANK" })
  {
    const char* value = std::getenv(name);
    if (value && *value)
    {
      return std::atoi(value);
    }
  }
  return 0;
}

// --mpi: a wait for another rank ran out (--mpi-timeout; called on the exchange's watchdog thread
// while this rank is blocked in MPI): one error line, then MPI_Abort ends every rank.
void AbortJob(const char* message)
{
  std::fprintf(stderr, "accelvolume: error: %s\n", message);
  std::fflush(stderr);
  MPI_Abort(MPI_COMM_WORLD, ExitRuntime);
}

// --mpi, rank 0: Open MPI's mpiexec ends every rank with SIGTERM when one dies or aborts (its own
// message names that rank); rank 0 says what it was waiting for. Async-signal-safe calls only.
extern "C" void OnTerminate(int)
{
  const auto put = [](const char* text)
  {
    const ssize_t written = write(STDERR_FILENO, text, std::strlen(text));
    static_cast<void>(written);
  };
  const char* pending = vtkAccelVolumeMPIExchange::GetPendingWait();
  put("accelvolume: error: rank 0 was ended by SIGTERM");
  if (*pending)
  {
    put(" while waiting for ");
    put(pending);
  }
  put(" (the MPI launcher ends every rank when one dies or aborts; its message names that "
      "rank)\n");
  _exit(ExitRuntime);
}

// --mpi: MPI initialized for the whole render (vtkMPIController as VTK's global controller) and
// finalized when the render is over, on success and on agreed failures alike. Every wait for
// another rank is bounded by timeout (the exchange's watchdog; AbortJob when one runs out).
class MPISession
{
public:
  MPISession(int* argc, char*** argv, double timeout)
  {
    this->Controller = vtkMPIController::New();
    this->Controller->Initialize(argc, argv);
    vtkMultiProcessController::SetGlobalController(this->Controller);
    this->Exchange.SetController(this->Controller);
    this->Exchange.SetTimeout(timeout);
    vtkAccelVolumeMPIExchange::SetAbortFunction(&AbortJob);
    if (this->Rank() == 0 && this->Controller->GetNumberOfProcesses() > 1)
    {
      std::signal(SIGTERM, &OnTerminate);
    }
  }
  ~MPISession()
  {
    {
      // MPI_Finalize waits for every rank.
      const double seconds = 2 * this->Exchange.GetTimeout();
      std::ostringstream message;
      message << "rank " << this->Rank() << " waited " << seconds
              << " s in MPI_Finalize (the MPI communication timeout): another rank hung or died";
      vtkAccelVolumeMPIExchange::Guard guard(
        this->Exchange, seconds, message.str(), "the other ranks in MPI_Finalize");
      this->Controller->Finalize();
    }
    std::signal(SIGTERM, SIG_DFL);
    vtkAccelVolumeMPIExchange::SetAbortFunction(nullptr);
    vtkMultiProcessController::SetGlobalController(nullptr);
    this->Controller->Delete();
  }
  MPISession(const MPISession&) = delete;
  MPISession& operator=(const MPISession&) = delete;
  vtkAccelVolumeMPIExchange* Get() { return &this->Exchange; }
  int Rank() const { return this->Controller->GetLocalProcessId(); }

private:
  vtkMPIController* Controller = nullptr;
  vtkAccelVolumeMPIExchange Exchange;
};

// Runs step on every rank; when it fails on any rank, every rank throws (rank 0 reports the
// lowest failed rank's error, "rank N: ..." when that is another rank), so no rank goes on to
// wait for a failed one.
template <typename Step>
void Agreed(vtkAccelVolumeMPIExchange* mpi, const char* what, Step&& step)
{
  if (!mpi)
  {
    step();
    return;
  }
  int code = 0;
  std::string message;
  try
  {
    step();
  }
  catch (const CliError& failure)
  {
    code = failure.Code;
    message = failure.what();
  }
  catch (const std::bad_alloc&)
  {
    code = ExitRuntime;
    message = "out of memory";
  }
  catch (const std::exception& failure)
  {
    code = ExitRuntime;
    message = failure.what();
  }
  ThrowIfAnyRankFailed(mpi, code, message, what);
}

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
  const std::vector<std::string> arguments(argv, argv + argc);
  for (std::size_t i = 2; i < arguments.size() && arguments[1] != "octree"; ++i)
  {
    // Under mpirun, a usage error found before MPI starts is printed by rank 0 only.
    SilentRank = SilentRank || (arguments[i] == "--mpi" && LauncherRank() > 0);
  }
  Options options;
  OctreeOptions octree;
  switch (ParseCommandLine(arguments, options, octree))
  {
    case Options::Action::MainHelp:
      std::cout << MainHelp();
      return 0;
    case Options::Action::RenderHelp:
      std::cout << RenderHelp();
      return 0;
    case Options::Action::OctreeHelp:
      std::cout << OctreeHelp();
      return 0;
    case Options::Action::Version:
      std::cout << "accelvolume " << ACCELVOLUME_VERSION << "\n";
      return 0;
    case Options::Action::Octree:
      return RunOctreeCommand(octree);
    case Options::Action::Render:
      break;
  }
  // --mpi: every rank builds the same scene and renders the same frames; rank 0 alone writes
  // the PNG, the stats and the summary.
  std::unique_ptr<MPISession> mpi;
  if (options.mpi)
  {
    mpi = std::make_unique<MPISession>(&argc, &argv, options.mpiTimeout);
    SilentRank = mpi->Rank() != 0;
    if (SilentRank)
    {
      options.outPath.clear();
      options.statsPath.clear();
      options.quiet = true;
      options.progress = ProgressMode::Off; // one bar: rank 0's
    }
  }
  vtkAccelVolumeMPIExchange* exchange = mpi ? mpi->Get() : nullptr;

  TransferFunctionSpec transferFunction;
  VTKMessages messages;
  std::string backendNote;
  vtkSmartPointer<vtkImageData> image;
  Agreed(exchange, "input status",
    [&]()
    {
      CheckPhantom(options);
      CheckOutputPath(options.outPath, "--out");
      CheckOutputPath(options.statsPath, "--stats");
      // Read before the volume so that a bad --tf file fails in milliseconds, not after a large
      // load.
      transferFunction = LoadTransferFunction(options);
      backendNote = ChooseBackend(options);
      std::string error;
      image = LoadVolume(options.volume, error);
      messages.Install(); // loading swaps VTK's output window and logger levels while it runs
      if (!image)
      {
        throw CliError(ExitRuntime, error);
      }
      CheckCrop(options, image);
    });

  const RenderResult result = RunRender(options, transferFunction, image, messages, exchange);

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
    if (!SilentRank)
    {
      std::cerr << "accelvolume: error: " << failure.what() << std::endl;
    }
    // A failure all ranks agreed on is the job's through rank 0's status: the others end
    // cleanly, or the launcher could abort the job on their status before rank 0 has printed
    // the error line (it prints after MPI is finalised).
    return SilentRank && failure.Agreed ? 0 : failure.Code;
  }
  catch (const std::bad_alloc&)
  {
    if (!SilentRank)
    {
      std::cerr << "accelvolume: error: out of memory" << std::endl;
    }
    return ExitRuntime;
  }
  catch (const std::exception& failure)
  {
    if (!SilentRank)
    {
      std::cerr << "accelvolume: error: " << failure.what() << std::endl;
    }
    return ExitRuntime;
  }
}
