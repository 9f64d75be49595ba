// Shear-warp volume mapper: run-length encoded volume, skip links, balanced scanline bands on
// threads and MPI ranks.
#include "vtkAccelVolumeShearWarpMapper.h"

#include "vtkAccelVolumeDepthCopy.h"
#include "vtkAccelVolumeDepthPeeling.h"
#include "vtkAccelVolumeImageDisplay.h"
#include "vtkAccelVolumeInputAdapter.h"
#include "vtkAccelVolumeMPIExchange.h"
#include "vtkAccelVolumeMapperSupport.h"
#include "vtkAccelVolumeRenderProgress.h"
#include "vtkAccelVolumeWorkers.h"
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
#include "vtkTimerLog.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"
#include "vtk_glew.h"

#include "shearwarp/ShearWarpEngine.h"
#include "shearwarp/ShearWarpPartition.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <new>
#include <string>
#include <thread>
#include <utility>
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
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// Why vtkAccelVolumeBeginCPURender refused (it reported the error on this rank; this text goes to
// the other ranks).
std::string WhyNotRenderable(vtkVolumeMapper* mapper, vtkAccelVolumeInputAdapter& adapter,
  vtkRenderer* renderer, vtkVolume* volume)
{
  if (!vtkOpenGLRenderWindow::SafeDownCast(renderer->GetRenderWindow()))
  {
    return "no OpenGL render window";
  }
  vtkImageData* input = nullptr;
  vtkDataArray* scalars = nullptr;
  std::string error;
  if (!adapter.Fetch(mapper, input, scalars, error))
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

// Everything one frame needs, gathered from the mapper, the renderer and the volume before the
// engine runs.
struct ShearWarpFrameInputs
{
  accelvolume::ShearWarpSettings settings;
  accelvolume::VolumeView view;
  double range[2] = { 0, 0 };
  double high = 0;
  accelvolume::RayCastTransfer transfer;
  accelvolume::ShearWarpView frame;
  accelvolume::RayCastLighting lighting;
  int width = 0;
  int height = 0;
  int lowerLeft[2] = { 0, 0 };
  int threads = 1;
  accelvolume::ParallelFor parallel; // exactly `threads` workers when the mapper sets a count
};

// What one frame produced, on this rank.
struct ShearWarpFrameResult
{
  accelvolume::ShearWarpStats stats;
  int rectangle[4] = { 0, -1, 0, -1 };
  bool ok = false;
  bool empty = false; // another rank had nothing to draw: every rank skips the frame
  double gatherSeconds = 0;
  std::string error;
};

// The view-dependent part of the frame: the image size and the voxel-to-image map.
void SetUpShearWarpView(vtkCamera* camera, vtkMatrix4x4* indexToWorld, int width, int height,
  accelvolume::ShearWarpView& frame)
{
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
  accelvolume::ParallelVoxelToImage(
    indexToWorldRows, worldToView, camera->GetParallelScale(), width, height, frame.voxelToImage);
  // VTK's window centre shifts the parallel view in NDC.
  double centre[2];
  camera->GetWindowCenter(centre);
  frame.voxelToImage[0][3] += centre[0] * width / 2.0;
  frame.voxelToImage[1][3] += centre[1] * height / 2.0;
}
}

class vtkAccelVolumeShearWarpMapper::vtkInternals
{
public:
  accelvolume::ShearWarpRenderer Renderer;
  vtkAccelVolumeImageDisplay Display;
  std::vector<float> Image;
  std::vector<double> BandTimes;
  vtkAccelVolumeCPUInputs Inputs;     // tables and the versions the encodings were built from
  vtkAccelVolumeMPIExchange Exchange; // bounded exchanges with the other ranks
  vtkAccelVolumeWorkers Workers;      // the mapper's thread count, kept between frames
  bool WarnedUnsupported = false;

  // Checks the mapper's settings and gathers the frame's inputs; FrameReady, or the code and
  // reason the frame status exchange passes to the other ranks.
  int PrepareFrame(vtkAccelVolumeShearWarpMapper* self, vtkRenderer* renderer, vtkVolume* volume,
    vtkImageData* input, vtkDataArray* scalars, vtkVolumeProperty* property,
    ShearWarpFrameInputs& in, std::string& why);
  // Renders the frame on this rank alone, or with every rank of the controller.
  void RenderFrame(const ShearWarpFrameInputs& in, int ranks, int rank,
    vtkAccelVolumeRenderProgress& progress, ShearWarpFrameResult& out);
  void RenderFrameOnRanks(const ShearWarpFrameInputs& in, int ranks, int rank,
    vtkAccelVolumeRenderProgress& progress, ShearWarpFrameResult& out);
  // Gathers the bands on rank 0 and shares every rank's timings; false when a rank failed.
  bool GatherBands(const std::vector<int>& rankBounds, const std::vector<double>& bandSeconds,
    bool composited, int ranks, int threads, ShearWarpFrameResult& out);
  void RecordCounters(vtkAccelVolumeShearWarpMapper* self, const ShearWarpFrameResult& out);
  // With one worker compositing a plain frame of one rank that the GPU warps, each band is
  // drawn as soon as it is composited (the GL driver draws it while the next band composites);
  // otherwise Show draws the whole image.
  void DrawBandsWhileCompositing(vtkOpenGLRenderWindow* window, const ShearWarpFrameInputs& in,
    bool enable, float colourScale, float colourBias);
  // The engine's intermediate image and warp with its display pixels, as the display takes them.
  vtkAccelVolumeImageDisplay::Warp IntermediateWarp(
    const accelvolume::ShearWarpDisplayPixels& pixels);
  // Draws the frame: the intermediate image warped by the GPU, or (WarpOnGPU off, or past the
  // texture size limit) the image warped here.
  bool Show(vtkOpenGLRenderWindow* window, const int lowerLeft[2], const ShearWarpFrameInputs& in,
    ShearWarpFrameResult& out, float colourScale, float colourBias, int selectionMode,
    const float selectionColour[3], bool peeling);
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
  os << indent << "WarpOnGPU: " << this->WarpOnGPU << "\n";
  os << indent << "BackgroundEncoding: " << this->BackgroundEncoding << "\n";
  os << indent << "Controller: " << this->Controller << "\n";
  os << indent << "CommunicationTimeout: " << this->CommunicationTimeout << "\n";
  os << indent << "LastImbalance: " << this->LastImbalance << "\n";
  os << indent << "LastNumberOfWorkers: " << this->LastNumberOfWorkers << "\n";
  os << indent << "LastNumberOfImageParts: " << this->LastNumberOfImageParts << "\n";
  os << indent << "LastImagePartsTime: " << this->LastImagePartsTime << "\n";
  os << indent << "EncodedBytes: " << this->EncodedBytes << "\n";
}

void vtkAccelVolumeShearWarpMapper::SetCommunicationAbortFunction(
  void (*function)(const char* message))
{
  vtkAccelVolumeMPIExchange::SetAbortFunction(function);
}

void vtkAccelVolumeShearWarpMapper::FinishBackgroundEncoding()
{
  this->Internals->Renderer.FinishBackgroundEncodings();
}

double vtkAccelVolumeShearWarpMapper::GetLastBandTime(int band) const
{
  const auto& times = this->Internals->BandTimes;
  return band >= 0 && band < static_cast<int>(times.size()) ? times[band] : 0.0;
}

int vtkAccelVolumeShearWarpMapper::GetLastNumberOfScanlines() const
{
  return static_cast<int>(this->Internals->Renderer.GetScanlineSeconds().size());
}

double vtkAccelVolumeShearWarpMapper::GetLastScanlineTime(int scanline) const
{
  const std::vector<double>& times = this->Internals->Renderer.GetScanlineSeconds();
  return scanline >= 0 && scanline < static_cast<int>(times.size()) ? times[scanline] : 0.0;
}

void vtkAccelVolumeShearWarpMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  const vtkAccelVolumeWindowContext current(window);
  this->Internals->Display.ReleaseGraphicsResources(window);
}

int vtkAccelVolumeShearWarpMapper::vtkInternals::PrepareFrame(vtkAccelVolumeShearWarpMapper* self,
  vtkRenderer* renderer, vtkVolume* volume, vtkImageData* input, vtkDataArray* scalars,
  vtkVolumeProperty* property, ShearWarpFrameInputs& in, std::string& why)
{
  accelvolume::ShearWarpSettings& settings = in.settings;
  switch (self->BlendMode)
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
      vtkErrorWithObjectMacro(self,
        "Blend mode " << self->BlendMode
                      << " is not supported by the shear-warp mapper (use composite, "
                         "maximum or minimum intensity)");
      why = "blend mode " + std::to_string(self->BlendMode) + " not supported";
      return FrameFailed;
  }
  vtkCamera* camera = renderer->GetActiveCamera();
  if (!camera->GetParallelProjection())
  {
    vtkErrorWithObjectMacro(self,
      "The shear-warp mapper needs a parallel projection "
      "(vtkCamera::ParallelProjectionOn)");
    why = "perspective camera (shear-warp needs a parallel projection)";
    return FrameFailed;
  }
  if (!this->WarnedUnsupported &&
    (self->Cropping || (self->ClippingPlanes && self->ClippingPlanes->GetNumberOfItems() > 0) ||
      property->GetTransferFunctionMode() == vtkVolumeProperty::TF_2D))
  {
    this->WarnedUnsupported = true;
    vtkWarningWithObjectMacro(self,
      "The shear-warp mapper ignores cropping, clipping planes and 2D transfer "
      "functions; the whole volume is rendered with the 1D transfer function");
  }

  vtkAccelVolumeScalarRange(scalars, in.range);

  this->Inputs.UpdateVolume(input, scalars); // encodings are rebuilt only on change
  // NaN / infinite float values as the slice mapper's texture holds them (a finite copy).
  vtkAccelVolumeView(input, this->Inputs.GetScalars(), in.view); // type checked with the input
  const int* dims = in.view.dims;
  vtkNew<vtkMatrix4x4> indexToWorld;
  vtkAccelVolumeIndexToWorld(volume, input, indexToWorld);
  const double voxelSpacing = vtkAccelVolumeSmallestSpacing(indexToWorld, dims);

  const bool composite = self->BlendMode == COMPOSITE_BLEND;
  this->Inputs.UpdateTransfer(property, in.range, composite, input, in.transfer, in.high);

  renderer->GetTiledSizeAndOrigin(&in.width, &in.height, in.lowerLeft, in.lowerLeft + 1);
  if (in.width < 1 || in.height < 1)
  {
    return FrameEmpty;
  }
  SetUpShearWarpView(camera, indexToWorld, in.width, in.height, in.frame);

  if (composite && property->GetShade(0) != 0)
  {
    vtkAccelVolumeCPULighting(renderer, property, indexToWorld, dims, camera, true, in.lighting);
  }

  // The cores this process may use (an MPI launcher may bind each rank to one): more threads
  // than that only contend, and TBB warns about them.
  const int cores = UsableCores();
  in.threads = self->NumberOfThreads > 0 ? std::min(self->NumberOfThreads, cores) : cores;
  in.parallel = this->Workers.For(self->NumberOfThreads > 0 ? in.threads : 0);
  settings.runLengthEncoding = self->RunLengthEncoding != 0;
  settings.earlyTermination = self->EarlyRayTermination != 0;
  settings.terminationThreshold = self->EarlyRayTerminationThreshold;
  settings.shading = self->ShadingMode == SHADING_PHONG
    ? accelvolume::ShearWarpShading::Phong
    : accelvolume::ShearWarpShading::LookupTable;
  settings.bands = in.threads;
  settings.balance = self->LoadBalancing != 0;
  settings.warp = self->WarpOnGPU == 0;
  settings.displayPixels = !settings.warp; // converted by the band workers (one rank)
  settings.backgroundEncodings = self->BackgroundEncoding != 0;
  return FrameReady;
}

void vtkAccelVolumeShearWarpMapper::vtkInternals::RenderFrame(const ShearWarpFrameInputs& in,
  int ranks, int rank, vtkAccelVolumeRenderProgress& progress, ShearWarpFrameResult& out)
{
  try
  {
    if (ranks == 1)
    {
      // The engine reports up to 0.95; showing the image is the rest.
      this->Renderer.SetProgressFunction(progress.Range(0.0, 0.95));
      out.ok = this->Renderer.Render(in.view, in.range[0], in.high, this->Inputs.VolumeVersion,
        in.transfer, this->Inputs.TransferVersion, in.lighting, in.frame, in.settings,
        in.parallel, this->Image, out.rectangle, out.stats, out.error);
      return;
    }
    this->RenderFrameOnRanks(in, ranks, rank, progress, out);
  }
  catch (const std::bad_alloc&)
  {
    out.ok = false;
    out.error = "out of memory for the run-length encoded volume or the images";
  }
}

void vtkAccelVolumeShearWarpMapper::vtkInternals::RenderFrameOnRanks(const ShearWarpFrameInputs& in,
  int ranks, int rank, vtkAccelVolumeRenderProgress& progress, ShearWarpFrameResult& out)
{
  // SPMD: every rank factorizes and encodes alike, composites its own band of scanlines
  // (split among its threads), and rank 0 gathers the bands and warps. The encoding reports
  // up to 0.6, then each phase once. Every exchange with another rank is bounded in time
  // (CommunicationTimeout; vtkAccelVolumeMPIExchange).
  accelvolume::ShearWarpRenderer& engine = this->Renderer;
  const accelvolume::ParallelFor& parallel = in.parallel;
  const int threads = in.threads;
  engine.SetProgressFunction(progress.Range(0.0, 0.6));
  try
  {
    out.ok = engine.BeginFrame(in.view, in.range[0], in.high, this->Inputs.VolumeVersion,
      in.transfer, this->Inputs.TransferVersion, in.lighting, in.frame, in.settings, parallel,
      out.stats, out.error);
  }
  catch (const std::bad_alloc&)
  {
    out.ok = false;
    out.error = "out of memory for the run-length encoded volume or the images";
  }
  // A rank that cannot render must not leave the others waiting for its band: every rank
  // learns the lowest rank that failed, and why.
  const vtkAccelVolumeMPIExchange::Failure failure =
    this->Exchange.AgreeOnFailure(out.ok ? FrameReady : FrameFailed, out.error, "frame status");
  if (failure.Rank >= 0)
  {
    out.empty = out.ok && failure.Code == FrameEmpty; // this rank's own failure is still reported
    out.ok = false;
    if (failure.Rank != rank)
    {
      out.error =
        "rank " + std::to_string(failure.Rank) + " cannot render the frame: " + failure.Message;
    }
    return;
  }
  progress.Report(0.6);
  const double compositeStart = Now();
  const std::vector<int> rankBounds = engine.Bands(ranks * threads, in.settings.balance);
  // Rank r owns the consecutive thread bands [r * threads, (r + 1) * threads).
  const int first = rank * threads;
  std::vector<double> bandSeconds(static_cast<std::size_t>(ranks * threads), 0.0);
  std::vector<std::thread::id> bandWorker(static_cast<std::size_t>(threads));
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
          bandWorker[t] = std::this_thread::get_id();
        }
      });
  }
  catch (const std::bad_alloc&)
  {
    composited = false;
  }
  out.stats.compositeSeconds = Now() - compositeStart;
  out.stats.workers = accelvolume::DistinctWorkers(std::move(bandWorker));
  progress.Report(0.75);
  if (!this->GatherBands(rankBounds, bandSeconds, composited, ranks, threads, out))
  {
    return;
  }
  progress.Report(0.9);
  engine.GetCounters(out.stats);
  if (rank == 0 && in.settings.warp)
  {
    const double warpStart = Now();
    engine.Warp(parallel, this->Image, out.rectangle);
    out.stats.warpSeconds = Now() - warpStart;
  }
  else if (rank == 0)
  {
    accelvolume::WarpedRectangle(engine.GetFactorization(), in.width, in.height, out.rectangle);
  }
  progress.Report(0.95);
}

bool vtkAccelVolumeShearWarpMapper::vtkInternals::Show(vtkOpenGLRenderWindow* window,
  const int lowerLeft[2], const ShearWarpFrameInputs& in, ShearWarpFrameResult& out,
  float colourScale, float colourBias, int selectionMode, const float selectionColour[3],
  bool peeling)
{
  if (!in.settings.warp)
  {
    const vtkAccelVolumeImageDisplay::Warp intermediate =
      this->IntermediateWarp(this->Renderer.GetDisplayPixels());
    if (this->Display.DrawWarped(window, lowerLeft, in.width, in.height, in.width, in.height,
          intermediate, out.rectangle, colourScale, colourBias, selectionMode, selectionColour,
          peeling))
    {
      return true;
    }
    const double warpStart = Now();
    this->Renderer.Warp(in.parallel, this->Image, out.rectangle);
    out.stats.warpSeconds = Now() - warpStart;
  }
  return this->Display.Draw(window, lowerLeft, in.width, in.height, in.width, in.height,
    this->Image.data(), out.rectangle, colourScale, colourBias, selectionMode, selectionColour,
    peeling);
}

vtkAccelVolumeImageDisplay::Warp vtkAccelVolumeShearWarpMapper::vtkInternals::IntermediateWarp(
  const accelvolume::ShearWarpDisplayPixels& pixels)
{
  const accelvolume::ShearWarpFactorization& f = this->Renderer.GetFactorization();
  return { this->Renderer.GetIntermediateImage(), { f.intermediateSize[0], f.intermediateSize[1] },
    f.warp, f.inverseWarp, pixels.rgba, pixels.rowFirst, pixels.rowLast };
}

void vtkAccelVolumeShearWarpMapper::vtkInternals::DrawBandsWhileCompositing(
  vtkOpenGLRenderWindow* window, const ShearWarpFrameInputs& in, bool enable, float colourScale,
  float colourBias)
{
  this->Display.BeginWarpedFrame();
  if (!enable)
  {
    this->Renderer.SetRowsReadyFunction(nullptr);
    return;
  }
  this->Renderer.SetRowsReadyFunction(
    [this, window, &in, colourScale, colourBias](
      const accelvolume::ShearWarpDisplayPixels& pixels, int rowsReady)
    {
      const vtkAccelVolumeImageDisplay::Warp intermediate = this->IntermediateWarp(pixels);
      this->Display.DrawWarpedRows(
        window, in.lowerLeft, in.width, in.height, intermediate, rowsReady, colourScale, colourBias);
    });
}

bool vtkAccelVolumeShearWarpMapper::vtkInternals::GatherBands(const std::vector<int>& rankBounds,
  const std::vector<double>& bandSeconds, bool composited, int ranks, int threads,
  ShearWarpFrameResult& out)
{
  accelvolume::ShearWarpRenderer& engine = this->Renderer;
  const double gatherStart = Now();
  const accelvolume::ShearWarpFactorization& f = engine.GetFactorization();
  const vtkIdType rowValues = 4 * static_cast<vtkIdType>(f.intermediateSize[0]);
  std::vector<vtkIdType> rankOffsets(static_cast<std::size_t>(ranks + 1));
  for (int r = 0; r <= ranks; ++r)
  {
    rankOffsets[r] = rowValues * rankBounds[r * threads];
  }
  this->Exchange.GatherToRoot(engine.GetIntermediateImage(), rankOffsets.data(), "band rows");
  // Everyone balances the next frame with every rank's scanline times (summed in rank order
  // on rank 0, so every rank holds the same costs and bands), and rank 0 reports every
  // band's time; the last value counts the ranks that failed to composite.
  const std::vector<double>& local = engine.GetScanlineSeconds();
  std::vector<double> mine(local);
  mine.insert(mine.end(), bandSeconds.begin(), bandSeconds.end());
  mine.push_back(composited ? 0.0 : 1.0);
  std::vector<double> summed(mine.size(), 0.0);
  this->Exchange.Sum(mine.data(), summed.data(), static_cast<vtkIdType>(mine.size()), "timings");
  if (summed.back() > 0)
  {
    out.ok = false;
    out.error = composited ? "another rank ran out of memory while compositing"
                           : "out of memory while compositing";
    return false;
  }
  const auto bandsBegin = summed.begin() + static_cast<std::ptrdiff_t>(local.size());
  engine.SetScanlineCosts(std::vector<double>(summed.begin(), bandsBegin));
  const std::vector<double> allBands(bandsBegin, summed.end() - 1);
  out.stats.bandSeconds = allBands;
  out.stats.bandBounds = rankBounds;
  out.stats.imbalance = accelvolume::Imbalance(allBands);
  out.gatherSeconds = Now() - gatherStart;
  return true;
}

void vtkAccelVolumeShearWarpMapper::vtkInternals::RecordCounters(
  vtkAccelVolumeShearWarpMapper* self, const ShearWarpFrameResult& out)
{
  const accelvolume::ShearWarpStats& stats = out.stats;
  self->LastEncodeTime = stats.encodeSeconds;
  self->LastTableTime = stats.tableSeconds;
  self->LastCompositeTime = stats.compositeSeconds;
  self->LastGatherTime = out.gatherSeconds;
  self->LastWarpTime = stats.warpSeconds;
  self->LastImagePartsTime = stats.rowsShownSeconds;
  self->LastImbalance = stats.imbalance;
  self->LastNumberOfBands = static_cast<int>(stats.bandSeconds.size());
  self->LastNumberOfWorkers = stats.workers;
  this->BandTimes = stats.bandSeconds;
  self->LastNumberOfVoxels = static_cast<vtkTypeInt64>(stats.voxels);
  self->LastNumberOfSamples = static_cast<vtkTypeInt64>(stats.samples);
  self->LastNumberOfSkippedPixels = static_cast<vtkTypeInt64>(stats.terminatedPixelVisits);
  self->LastPrincipalAxis = stats.principalAxis;
  self->LastNumberOfStoredVoxels = static_cast<vtkTypeInt64>(stats.storedVoxels);
  self->EncodedBytes = static_cast<vtkTypeInt64>(this->Renderer.GetEncodedBytes());
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
  vtkOpenGLRenderWindow* window = vtkAccelVolumeBeginCPURender(
    this, *this->InputAdapter, renderer, volume, input, scalars, property);
  if (!window)
  {
    leaveEarly(
      FrameFailed, ranks > 1 ? WhyNotRenderable(this, *this->InputAdapter, renderer, volume) : "");
    return;
  }
  if (this->HasHiddenPoints(input))
  {
    this->WarnNotApplicable("blanking (hidden points of the ghost array)",
      "the CPU mappers draw hidden points; vtkAccelVolumeSliceMapper hides them");
  }
  ShearWarpFrameInputs in;
  std::string why;
  const int status =
    internals.PrepareFrame(this, renderer, volume, input, scalars, property, in, why);
  if (status != FrameReady)
  {
    leaveEarly(status, why);
    return;
  }

  float colourScale = 1.0f;
  float colourBias = 0.0f;
  this->GetFinalColorScaleAndBias(colourScale, colourBias);
  float selectionColour[3];
  const int selectionMode = vtkAccelVolumeSelectionMode(renderer, selectionColour);
  // Depth peeling: shown once, in the first volumetric stage (every rank still composites in
  // every stage, so the ranks' exchanges stay in step).
  const vtkAccelVolumePeelStage peel = vtkAccelVolumeGetPeelStage(window, volume, this);
  const bool peeling = peel == vtkAccelVolumePeelStage::OutsideRange;
  internals.DrawBandsWhileCompositing(window, in,
    ranks == 1 && in.settings.bands == 1 && !in.settings.warp && selectionMode == 0 &&
      peel == vtkAccelVolumePeelStage::None,
    colourScale, colourBias);

  // The frame's GL commands so far (clears, opaque geometry) go to the driver now, to be
  // executed while the CPU composites, not after.
  glFlush();
  ShearWarpFrameResult out;
  internals.RenderFrame(in, ranks, rank, progress, out);
  internals.Renderer.SetProgressFunction(nullptr); // it refers to this render's progress
  internals.Renderer.SetRowsReadyFunction(nullptr); // and this one to its inputs
  if (!out.ok)
  {
    if (!out.empty)
    {
      vtkErrorMacro("Shear-warp rendering failed: " << out.error);
    }
    return;
  }
  const int origin[2] = { 0, 0 }; // the pass's targets are viewport-sized
  this->LastNumberOfImageParts = 0;
  if (rank == 0 && peel != vtkAccelVolumePeelStage::Later)
  {
    if (!internals.Show(window, peeling ? origin : in.lowerLeft, in, out, colourScale, colourBias,
          selectionMode, selectionColour, peeling))
    {
      vtkErrorMacro("Cannot show the shear-warp image (OpenGL texture or shader failed)");
    }
    this->LastNumberOfImageParts = internals.Display.GetLastNumberOfParts();
  }
  // After showing: a CPU warp the GPU could not take counts too.
  internals.RecordCounters(this, out);
  this->LastRenderTime = Now() - start;
}
