// Shear-warp volume mapper: run-length encoded volume, skip links, balanced scanline bands on
// threads and MPI ranks.
#include "vtkAccelVolumeShearWarpMapper.h"

#include "vtkAccelVolumeImageDisplay.h"
#include "vtkAccelVolumeMPIExchange.h"
#include "vtkAccelVolumeMapperSupport.h"
#include "vtkAccelVolumeRenderProgress.h"
#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkMatrix4x4.h"
#include "vtkMultiProcessController.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPlaneCollection.h"
#include "vtkPointData.h"
#include "vtkRenderer.h"
#include "vtkSMPTools.h"
#include "vtkTimerLog.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include "shearwarp/ShearWarpEngine.h"
#include "shearwarp/ShearWarpPartition.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <new>
#include <string>
#include <thread>
#include <vector>

#if defined(__linux__)
#include <sched.h>
#endif

namespace
{
// Cores in this process's affinity mask (vtkSMPTools' estimate follows its own settings).
int UsableCores()
{
#if defined(__linux__)
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof(set), &set) == 0)
  {
    return std::max(1, CPU_COUNT(&set));
  }
#endif
  return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

double Now()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
    .count();
}

// Why vtkAccelVolumeBeginCPURender refused (it reported the error on this rank; this text goes to
// the other ranks).
std::string WhyNotRenderable(vtkVolumeMapper* mapper, vtkRenderer* renderer, vtkVolume* volume)
{
  if (!vtkOpenGLRenderWindow::SafeDownCast(renderer->GetRenderWindow()))
  {
    return "no OpenGL render window";
  }
  vtkImageData* input = nullptr;
  vtkDataArray* scalars = nullptr;
  std::string error;
  if (!vtkAccelVolumeFetchInput(mapper, input, scalars, error))
  {
    return error;
  }
  return volume->GetProperty() ? "its input cannot be rendered" : "the volume has no property";
}

// Status codes of the frame-status exchange: a rank with nothing to draw makes every rank skip
// the frame silently; any failure makes every rank fail it.
constexpr int FrameReady = 0;
constexpr int FrameFailed = 1;
constexpr int FrameEmpty = -1;
}

class vtkAccelVolumeShearWarpMapper::vtkInternals
{
public:
  accelvolume::ShearWarpRenderer Renderer;
  vtkAccelVolumeImageDisplay Display;
  std::vector<float> Image;
  std::vector<double> BandTimes;
  vtkAccelVolumeCPUInputs Inputs; // tables and the versions the encodings were built from
  vtkAccelVolumeMPIExchange Exchange; // bounded exchanges with the other ranks
  bool WarnedUnsupported = false;
};

vtkStandardNewMacro(vtkAccelVolumeShearWarpMapper);
vtkCxxSetObjectMacro(vtkAccelVolumeShearWarpMapper, Controller, vtkMultiProcessController);

vtkAccelVolumeShearWarpMapper::vtkAccelVolumeShearWarpMapper()
  : Internals(new vtkInternals)
{
}

vtkAccelVolumeShearWarpMapper::~vtkAccelVolumeShearWarpMapper()
{
  this->SetController(nullptr);
}

void vtkAccelVolumeShearWarpMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "RunLengthEncoding: " << this->RunLengthEncoding << "\n";
  os << indent << "ShadingMode: " << this->ShadingMode << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
  os << indent << "LoadBalancing: " << this->LoadBalancing << "\n";
  os << indent << "Controller: " << this->Controller << "\n";
  os << indent << "CommunicationTimeout: " << this->CommunicationTimeout << "\n";
  os << indent << "LastImbalance: " << this->LastImbalance << "\n";
  os << indent << "EncodedBytes: " << this->EncodedBytes << "\n";
}

void vtkAccelVolumeShearWarpMapper::SetCommunicationAbortFunction(
  void (*function)(const char* message))
{
  vtkAccelVolumeMPIExchange::SetAbortFunction(function);
}

double vtkAccelVolumeShearWarpMapper::GetLastBandTime(int band) const
{
  const auto& times = this->Internals->BandTimes;
  return band >= 0 && band < static_cast<int>(times.size()) ? times[band] : 0.0;
}

void vtkAccelVolumeShearWarpMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Internals->Display.ReleaseGraphicsResources(window);
}

void vtkAccelVolumeShearWarpMapper::Render(vtkRenderer* renderer, vtkVolume* volume)
{
  const double start = Now();
  // StartEvent now; ProgressEvent from the encoding's slices and the frame's phases (main
  // thread only); ProgressEvent 1 and EndEvent on every return.
  vtkAccelVolumeRenderProgress progress(this);
  vtkInternals& internals = *this->Internals;
  vtkMultiProcessController* controller = this->Controller;
  const int ranks = controller ? std::max(1, controller->GetNumberOfProcesses()) : 1;
  const int rank = controller ? controller->GetLocalProcessId() : 0;
  vtkAccelVolumeMPIExchange& exchange = internals.Exchange;
  exchange.SetController(controller);
  exchange.SetTimeout(this->CommunicationTimeout);
  // With several ranks a return before the frame's status exchange still takes part in it, or
  // the other ranks would wait for this one.
  const auto leaveEarly = [&](int code, const std::string& why)
  {
    if (ranks > 1)
    {
      exchange.AgreeOnFailure(code, why, "frame status");
    }
  };
  vtkImageData* input = nullptr;
  vtkDataArray* scalars = nullptr;
  vtkVolumeProperty* property = nullptr;
  vtkOpenGLRenderWindow* window =
    vtkAccelVolumeBeginCPURender(this, renderer, volume, input, scalars, property);
  if (!window)
  {
    leaveEarly(FrameFailed, ranks > 1 ? WhyNotRenderable(this, renderer, volume) : "");
    return;
  }
  std::string error;
  accelvolume::ShearWarpSettings settings;
  switch (this->BlendMode)
  {
    case COMPOSITE_BLEND:
      settings.blend = accelvolume::Blend::Composite;
      break;
    case MAXIMUM_INTENSITY_BLEND:
      settings.blend = accelvolume::Blend::Maximum;
      break;
    case MINIMUM_INTENSITY_BLEND:
      settings.blend = accelvolume::Blend::Minimum;
      break;
    default:
      vtkErrorMacro("Blend mode " << this->BlendMode
                                  << " is not supported by the shear-warp mapper (use composite, "
                                     "maximum or minimum intensity)");
      leaveEarly(FrameFailed, "blend mode " + std::to_string(this->BlendMode) + " not supported");
      return;
  }
  vtkCamera* camera = renderer->GetActiveCamera();
  if (!camera->GetParallelProjection())
  {
    vtkErrorMacro("The shear-warp mapper needs a parallel projection "
                  "(vtkCamera::ParallelProjectionOn)");
    leaveEarly(FrameFailed, "perspective camera (shear-warp needs a parallel projection)");
    return;
  }
  if (!internals.WarnedUnsupported &&
    (this->Cropping || (this->ClippingPlanes && this->ClippingPlanes->GetNumberOfItems() > 0) ||
      property->GetTransferFunctionMode() == vtkVolumeProperty::TF_2D))
  {
    internals.WarnedUnsupported = true;
    vtkWarningMacro("The shear-warp mapper ignores cropping, clipping planes and 2D transfer "
                    "functions; the whole volume is rendered with the 1D transfer function");
  }

  double range[2];
  vtkAccelVolumeScalarRange(scalars, range);

  internals.Inputs.UpdateVolume(input, scalars); // encodings are rebuilt only on change
  // NaN / infinite float values as the slice mapper's texture holds them (a finite copy).
  accelvolume::VolumeView view;
  vtkAccelVolumeView(input, internals.Inputs.GetScalars(), view); // type checked with the input
  const int* dims = view.dims;
  vtkNew<vtkMatrix4x4> indexToWorld;
  vtkAccelVolumeIndexToWorld(volume, input, indexToWorld);
  const double voxelSpacing = vtkAccelVolumeSmallestSpacing(indexToWorld, dims);

  accelvolume::RayCastTransfer transfer;
  double high = 0;
  const bool composite = this->BlendMode == COMPOSITE_BLEND;
  internals.Inputs.UpdateTransfer(property, range, composite, voxelSpacing, transfer, high);

  int width = 0;
  int height = 0;
  int lowerLeft[2] = { 0, 0 };
  renderer->GetTiledSizeAndOrigin(&width, &height, lowerLeft, lowerLeft + 1);
  if (width < 1 || height < 1)
  {
    leaveEarly(FrameEmpty, "");
    return;
  }
  accelvolume::ShearWarpView frame;
  frame.width = width;
  frame.height = height;
  double indexToWorldRows[3][4];
  double worldToView[4][4];
  vtkMatrix4x4* viewMatrix = camera->GetViewTransformMatrix();
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      worldToView[r][c] = viewMatrix->GetElement(r, c);
      if (r < 3)
      {
        indexToWorldRows[r][c] = indexToWorld->GetElement(r, c);
      }
      if (r < 3 && c < 3)
      {
        frame.indexToWorld[r][c] = indexToWorld->GetElement(r, c);
      }
    }
  }
  accelvolume::ParallelVoxelToImage(indexToWorldRows, worldToView, camera->GetParallelScale(),
    width, height, frame.voxelToImage);
  // VTK's window centre shifts the parallel view in NDC.
  double centre[2];
  camera->GetWindowCenter(centre);
  frame.voxelToImage[0][3] += centre[0] * width / 2.0;
  frame.voxelToImage[1][3] += centre[1] * height / 2.0;

  accelvolume::RayCastLighting lighting;
  if (composite && property->GetShade(0) != 0)
  {
    vtkAccelVolumeCPULighting(renderer, property, indexToWorld, camera, true, lighting);
  }

  // The cores this process may use (an MPI launcher may bind each rank to one): more threads
  // than that only contend, and TBB warns about them.
  const int cores = UsableCores();
  const int threads = this->NumberOfThreads > 0 ? std::min(this->NumberOfThreads, cores) : cores;
  settings.runLengthEncoding = this->RunLengthEncoding != 0;
  settings.earlyTermination = this->EarlyRayTermination != 0;
  settings.terminationThreshold = this->EarlyRayTerminationThreshold;
  settings.shading = this->ShadingMode == SHADING_PHONG ? accelvolume::ShearWarpShading::Phong
                                                        : accelvolume::ShearWarpShading::LookupTable;
  settings.bands = threads;
  settings.balance = this->LoadBalancing != 0;

  accelvolume::ParallelFor parallel =
    [](std::size_t count, const std::function<void(std::size_t, std::size_t)>& body)
  { vtkSMPTools::For(0, count, 1, [&](std::size_t begin, std::size_t end) { body(begin, end); }); };
  accelvolume::ShearWarpStats stats;
  accelvolume::ShearWarpRenderer& engine = internals.Renderer;
  int rectangle[4] = { 0, -1, 0, -1 };
  bool ok = false;
  bool empty = false; // another rank had nothing to draw: every rank skips the frame
  double gatherSeconds = 0;
  auto renderFrame = [&]()
  {
    try
    {
      if (ranks == 1)
      {
        // The engine reports up to 0.95; showing the image is the rest.
        engine.SetProgressFunction(progress.Range(0.0, 0.95));
        ok = engine.Render(view, range[0], high, internals.Inputs.VolumeVersion, transfer,
          internals.Inputs.TransferVersion, lighting, frame, settings, parallel, internals.Image,
          rectangle, stats, error);
        return;
      }
      // SPMD: every rank factorizes and encodes alike, composites its own band of scanlines
      // (split among its threads), and rank 0 gathers the bands and warps. The encoding reports
      // up to 0.6, then each phase once. Every exchange with another rank is bounded in time
      // (CommunicationTimeout; vtkAccelVolumeMPIExchange).
      engine.SetProgressFunction(progress.Range(0.0, 0.6));
      try
      {
        ok = engine.BeginFrame(view, range[0], high, internals.Inputs.VolumeVersion, transfer,
          internals.Inputs.TransferVersion, lighting, frame, settings, parallel, stats, error);
      }
      catch (const std::bad_alloc&)
      {
        ok = false;
        error = "out of memory for the run-length encoded volume or the images";
      }
      // A rank that cannot render must not leave the others waiting for its band: every rank
      // learns the lowest rank that failed, and why.
      const vtkAccelVolumeMPIExchange::Failure failure =
        exchange.AgreeOnFailure(ok ? FrameReady : FrameFailed, error, "frame status");
      if (failure.Rank >= 0)
      {
        empty = ok && failure.Code == FrameEmpty; // this rank's own failure is still reported
        ok = false;
        if (failure.Rank != rank)
        {
          error =
            "rank " + std::to_string(failure.Rank) + " cannot render the frame: " + failure.Message;
        }
        return;
      }
      progress.Report(0.6);
      const double compositeStart = Now();
      const std::vector<int> rankBounds = engine.Bands(ranks * threads, settings.balance);
      // Rank r owns the consecutive thread bands [r * threads, (r + 1) * threads).
      const int first = rank * threads;
      std::vector<double> bandSeconds(static_cast<std::size_t>(ranks * threads), 0.0);
      // A rank that runs out of memory here still takes part in the exchanges below (its rows
      // are then meaningless) and fails the frame on every rank through the summed flag.
      bool composited = true;
      try
      {
        parallel(static_cast<std::size_t>(threads),
          [&](std::size_t begin, std::size_t end)
          {
            for (std::size_t t = begin; t < end; ++t)
            {
              const double bandStart = Now();
              engine.CompositeRows(rankBounds[first + t], rankBounds[first + t + 1]);
              bandSeconds[first + t] = Now() - bandStart;
            }
          });
      }
      catch (const std::bad_alloc&)
      {
        composited = false;
      }
      stats.compositeSeconds = Now() - compositeStart;
      progress.Report(0.75);
      const double gatherStart = Now();
      const accelvolume::ShearWarpFactorization& f = engine.GetFactorization();
      const vtkIdType rowValues = 4 * static_cast<vtkIdType>(f.intermediateSize[0]);
      std::vector<vtkIdType> rankOffsets(static_cast<std::size_t>(ranks + 1));
      for (int r = 0; r <= ranks; ++r)
      {
        rankOffsets[r] = rowValues * rankBounds[r * threads];
      }
      exchange.GatherToRoot(engine.GetIntermediateImage(), rankOffsets.data(), "band rows");
      // Everyone balances the next frame with every rank's scanline times (summed in rank order
      // on rank 0, so every rank holds the same costs and bands), and rank 0 reports every
      // band's time; the last value counts the ranks that failed to composite.
      const std::vector<double>& local = engine.GetScanlineSeconds();
      std::vector<double> mine(local);
      mine.insert(mine.end(), bandSeconds.begin(), bandSeconds.end());
      mine.push_back(composited ? 0.0 : 1.0);
      std::vector<double> summed(mine.size(), 0.0);
      exchange.Sum(mine.data(), summed.data(), static_cast<vtkIdType>(mine.size()), "timings");
      if (summed.back() > 0)
      {
        ok = false;
        error = composited ? "another rank ran out of memory while compositing"
                           : "out of memory while compositing";
        return;
      }
      const auto bandsBegin = summed.begin() + static_cast<std::ptrdiff_t>(local.size());
      engine.SetScanlineCosts(std::vector<double>(summed.begin(), bandsBegin));
      const std::vector<double> allBands(bandsBegin, summed.end() - 1);
      stats.bandSeconds = allBands;
      stats.bandBounds = rankBounds;
      stats.imbalance = accelvolume::Imbalance(allBands);
      gatherSeconds = Now() - gatherStart;
      progress.Report(0.9);
      engine.GetCounters(stats);
      if (rank == 0)
      {
        const double warpStart = Now();
        engine.Warp(parallel, internals.Image, rectangle);
        stats.warpSeconds = Now() - warpStart;
      }
      progress.Report(0.95);
    }
    catch (const std::bad_alloc&)
    {
      ok = false;
      error = "out of memory for the run-length encoded volume or the images";
    }
  };
  if (this->NumberOfThreads > 0)
  {
    vtkSMPTools::LocalScope(vtkSMPTools::Config{ threads }, renderFrame);
  }
  else
  {
    renderFrame();
  }
  engine.SetProgressFunction(nullptr); // it refers to this render's progress
  if (!ok)
  {
    if (!empty)
    {
      vtkErrorMacro("Shear-warp rendering failed: " << error);
    }
    return;
  }
  this->LastEncodeTime = stats.encodeSeconds;
  this->LastTableTime = stats.tableSeconds;
  this->LastCompositeTime = stats.compositeSeconds;
  this->LastGatherTime = gatherSeconds;
  this->LastWarpTime = stats.warpSeconds;
  this->LastImbalance = stats.imbalance;
  this->LastNumberOfBands = static_cast<int>(stats.bandSeconds.size());
  internals.BandTimes = stats.bandSeconds;
  this->LastNumberOfVoxels = static_cast<vtkTypeInt64>(stats.voxels);
  this->LastNumberOfSamples = static_cast<vtkTypeInt64>(stats.samples);
  this->LastNumberOfSkippedPixels = static_cast<vtkTypeInt64>(stats.skippedOpaque);
  this->LastPrincipalAxis = stats.principalAxis;
  this->LastNumberOfStoredVoxels = static_cast<vtkTypeInt64>(stats.storedVoxels);
  this->EncodedBytes = static_cast<vtkTypeInt64>(engine.GetEncodedBytes());

  if (rank == 0 &&
    !internals.Display.Draw(
      window, lowerLeft, width, height, width, height, internals.Image.data(), rectangle))
  {
    vtkErrorMacro("Cannot show the shear-warp image (OpenGL texture or shader failed)");
  }
  this->LastRenderTime = Now() - start;
}
