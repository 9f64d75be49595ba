// The shear-warp mapper on MPI ranks (run with mpiexec -n 2): every rank builds the same scene
// and renders the same frames with a vtkMPIController given to the mapper; each rank composites
// its scanline bands with its threads and rank 0 gathers them, warps and shows the image. Rank 0
// compares every frame with a single-process render of the same scene in this program (a second
// mapper without a controller): the windows must be byte-identical. Composite (table-shaded),
// MIP and MinIP, 1 and 2 threads per rank, balanced bands over a turning camera (the turn
// changes the principal axis). Also checks the counters: the mapper reports threads x ranks
// bands, and the ranks' composited samples add up to the single process's. Failures: when one
// rank cannot render a frame (its blend mode is unsupported there only), every rank fails that
// frame at once, the others' error names that rank and its reason, and the next frame renders
// normally again (the ranks stay in step). Hung and dead ranks:
// Testing/CLI/CliMpiFaultTests.cmake.
#include "AccelVolumeTestUtilities.h"
#include "vtkAccelVolumeShearWarpMapper.h"

#include "vtkCommunicator.h"
#include "vtkMPIController.h"
#include "vtkMultiProcessController.h"

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <string>
#include <thread>

#if defined(__linux__)
#include <sched.h>
#endif

namespace
{
using namespace accelvolume_test;
constexpr int Size = 160;
constexpr int Frames = 4;
constexpr double AzimuthStep = 30.0;

struct View
{
  vtkNew<vtkAccelVolumeShearWarpMapper> Mapper;
  vtkNew<vtkVolume> Volume;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkRenderWindow> Window;
  vtkNew<ErrorRecorder> Errors;

  View(vtkImageData* image, int blend, int threads, vtkMultiProcessController* controller)
  {
    this->Mapper->SetInputData(image);
    this->Mapper->SetBlendMode(blend);
    this->Mapper->SetNumberOfThreads(threads);
    this->Mapper->SetController(controller);
    this->Mapper->AddObserver(vtkCommand::ErrorEvent, this->Errors);
    this->Volume->SetMapper(this->Mapper);
    if (blend == vtkVolumeMapper::MINIMUM_INTENSITY_BLEND)
    {
      SetMinimumProperty(this->Volume->GetProperty());
    }
    else
    {
      SetRampProperty(this->Volume->GetProperty(), 40.0, 900.0, true);
    }
    this->Volume->GetProperty()->SetShade(blend == vtkVolumeMapper::COMPOSITE_BLEND);
    this->Renderer->SetBackground(0.1, 0.1, 0.2);
    this->Renderer->AddVolume(this->Volume);
    SetupObliqueView(this->Window, this->Renderer, Size, 20, 25, false);
  }
  void Turn()
  {
    this->Renderer->GetActiveCamera()->Azimuth(AzimuthStep);
    this->Renderer->ResetCameraClippingRange();
  }
};

// Runs one scene on every rank; true on rank 0 when every check passed (other ranks: true).
bool CheckScene(vtkMultiProcessController* controller, const char* name, const char* phantom,
  int blend, int threads)
{
  const int rank = controller->GetLocalProcessId();
  const int ranks = controller->GetNumberOfProcesses();
  auto image = MakePhantom(phantom, 64, 56, 48, 1.0, 1.0, 1.25);
  View distributed(image, blend, threads, controller);
  bool ok = true;
  for (int frame = 0; frame < Frames; ++frame)
  {
    if (frame > 0)
    {
      distributed.Turn();
    }
    distributed.Window->Render();
    // The ranks' counters, summed on every rank (collective: every rank takes part).
    const vtkTypeInt64 localSamples = distributed.Mapper->GetLastNumberOfSamples();
    vtkTypeInt64 samples = 0;
    controller->AllReduce(&localSamples, &samples, 1, vtkCommunicator::SUM_OP);
    if (rank != 0)
    {
      continue;
    }
    const std::vector<float> ours = ReadPixels(distributed.Window);
    // The same frame in this process alone.
    View single(image, blend, threads, nullptr);
    for (int turn = 0; turn < frame; ++turn)
    {
      single.Turn();
    }
    single.Window->Render();
    const std::vector<float> expected = ReadPixels(single.Window);
    // As the mapper: the cores in this rank's affinity mask (mpirun may bind it to one).
    int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
#if defined(__linux__)
    cpu_set_t set;
    CPU_ZERO(&set);
    if (sched_getaffinity(0, sizeof(set), &set) == 0)
    {
      cores = std::max(1, CPU_COUNT(&set));
    }
#endif
    const int expectedBands = ranks * std::min(threads, cores);
    const bool same = ours == expected;
    const bool bandsOk = distributed.Mapper->GetLastNumberOfBands() == expectedBands &&
      single.Mapper->GetLastNumberOfBands() == std::min(threads, cores);
    const bool samplesOk = samples == single.Mapper->GetLastNumberOfSamples();
    std::cout << name << ", " << threads << " thread(s) x " << ranks << " ranks, frame " << frame
              << ": axis " << distributed.Mapper->GetLastPrincipalAxis() << ", "
              << distributed.Mapper->GetLastNumberOfBands() << " bands (expected "
              << expectedBands << "), imbalance " << distributed.Mapper->GetLastImbalance()
              << ", gather " << 1000 * distributed.Mapper->GetLastGatherTime() << " ms, samples "
              << samples << " (one process " << single.Mapper->GetLastNumberOfSamples() << ")"
              << (same ? "" : "  IMAGE DIFFERS FROM ONE PROCESS") << (bandsOk ? "" : "  BANDS")
              << (samplesOk ? "" : "  SAMPLES") << "\n";
    if (single.Errors->Count)
    {
      std::cout << "  one-process errors: " << single.Errors->Messages;
    }
    ok = ok && same && bandsOk && samplesOk && single.Errors->Count == 0;
    if (!same)
    {
      DumpImage(std::string("shearwarp_mpi_") + name, ours, Size, Size);
      DumpImage(std::string("shearwarp_single_") + name, expected, Size, Size);
    }
  }
  if (distributed.Errors->Count)
  {
    std::cout << "rank " << rank << " errors: " << distributed.Errors->Messages;
    ok = false;
  }
  return ok;
}

// Rank `failing` alone has an unsupported blend mode for one frame; true on every rank when the
// frame failed everywhere with the right errors and the next frame worked (rank 0 also compares
// it with one process's image).
bool CheckFailureAgreement(vtkMultiProcessController* controller, int failing)
{
  const int rank = controller->GetLocalProcessId();
  auto image = MakePhantom("blobs", 40, 36, 32, 1.0, 1.0, 1.0);
  View distributed(image, vtkVolumeMapper::COMPOSITE_BLEND, 1, controller);
  bool ok = distributed.Mapper->GetCommunicationTimeout() == 60.0;
  // A hang here would be a failure of the protocol: it ends the job well inside ctest's timeout.
  distributed.Mapper->SetCommunicationTimeout(20);
  if (rank == failing)
  {
    distributed.Mapper->SetBlendModeToAdditive();
  }
  distributed.Window->Render();
  const std::string expected = rank == failing
    ? std::string("is not supported by the shear-warp mapper")
    : "Shear-warp rendering failed: rank " + std::to_string(failing) +
      " cannot render the frame: blend mode " + std::to_string(vtkVolumeMapper::ADDITIVE_BLEND) +
      " not supported";
  const bool failedHere = distributed.Errors->Count == 1 &&
    distributed.Errors->Messages.find(expected) != std::string::npos;
  std::cout << "rank " << rank << ", rank " << failing << " failing: " << distributed.Errors->Count
            << " error(s): " << distributed.Errors->Messages
            << (failedHere ? "" : "  EXPECTED ONE ERROR WITH '" + expected + "'\n");
  distributed.Mapper->SetBlendModeToComposite();
  distributed.Window->Render();
  const bool recovered = distributed.Errors->Count == 1;
  ok = ok && failedHere && recovered;
  if (!recovered)
  {
    std::cout << "rank " << rank << ": the frame after the failure failed too\n";
  }
  if (rank == 0)
  {
    View single(image, vtkVolumeMapper::COMPOSITE_BLEND, 1, nullptr);
    single.Window->Render();
    const bool same = ReadPixels(distributed.Window) == ReadPixels(single.Window);
    std::cout << "frame after the failure" << (same ? " equals" : " DIFFERS FROM")
              << " one process's image\n";
    ok = ok && same && single.Errors->Count == 0;
  }
  return ok;
}
}

int TestAccelVolumeShearWarpMPI(int argc, char* argv[])
{
  vtkNew<vtkMPIController> controller;
  controller->Initialize(&argc, &argv);
  vtkMultiProcessController::SetGlobalController(controller);
  const int ranks = controller->GetNumberOfProcesses();
  bool ok = true;
  if (ranks < 2)
  {
    std::cout << "needs at least 2 MPI ranks (run under mpiexec -n 2), got " << ranks << "\n";
    ok = false;
  }
  else
  {
    for (int threads : { 1, 2 })
    {
      ok = CheckScene(controller, "composite shaded", "blobs", vtkVolumeMapper::COMPOSITE_BLEND,
             threads) &&
        ok;
      ok = CheckScene(controller, "MIP", "vessels", vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND,
             threads) &&
        ok;
    }
    ok = CheckScene(controller, "MinIP", "vessels", vtkVolumeMapper::MINIMUM_INTENSITY_BLEND, 2) &&
      ok;
    ok = CheckFailureAgreement(controller, ranks - 1) && ok;
    ok = CheckFailureAgreement(controller, 0) && ok;
  }
  // Every rank returns rank 0's verdict (and a failure on any rank).
  int local = ok ? 0 : 1;
  int failed = 0;
  if (ranks > 1)
  {
    controller->AllReduce(&local, &failed, 1, vtkCommunicator::MAX_OP);
  }
  else
  {
    failed = local;
  }
  vtkMultiProcessController::SetGlobalController(nullptr);
  controller->Finalize();
  return failed ? EXIT_FAILURE : EXIT_SUCCESS;
}
