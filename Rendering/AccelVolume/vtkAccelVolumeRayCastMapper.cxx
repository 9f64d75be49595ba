// CPU ray casting volume mapper with octree / distance-map and semi-transparent cell leaping.
#include "vtkAccelVolumeRayCastMapper.h"

#include "vtkAccelVolumeImageDisplay.h"
#include "vtkAccelVolumeMapperSupport.h"
#include "vtkAccelVolumeRenderProgress.h"
#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkRenderer.h"
#include "vtkSMPTools.h"
#include "vtkTimerLog.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include "raycast/RayCastEngine.h"

#include <algorithm>
#include <cmath>
#include <new>
#include <string>
#include <thread>
#include <vector>

namespace
{
accelvolume::Blend ToBlend(int blendMode)
{
  switch (blendMode)
  {
    case vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND:
      return accelvolume::Blend::Maximum;
    case vtkVolumeMapper::MINIMUM_INTENSITY_BLEND:
      return accelvolume::Blend::Minimum;
    case vtkVolumeMapper::ADDITIVE_BLEND:
      return accelvolume::Blend::Additive;
    case vtkVolumeMapper::AVERAGE_INTENSITY_BLEND:
      return accelvolume::Blend::Average;
    default:
      return accelvolume::Blend::Composite;
  }
}

accelvolume::Affine ToAffine(vtkMatrix4x4* m)
{
  accelvolume::Affine a;
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      a.m[r][c] = m->GetElement(r, c);
    }
  }
  return a;
}
}

// Per-mapper state kept out of the public header.
class vtkAccelVolumeRayCastMapper::vtkInternals
{
public:
  accelvolume::RayCaster Caster;
  vtkAccelVolumeImageDisplay Display;
  std::vector<float> Image;
  std::vector<float> Depth;
  std::vector<float> RayDepth;
  vtkAccelVolumeCPUInputs Inputs; // tables and the versions the caster's caches were built from
  bool ReportedError = false;
};

vtkStandardNewMacro(vtkAccelVolumeRayCastMapper);

vtkAccelVolumeRayCastMapper::vtkAccelVolumeRayCastMapper()
  : Internals(new vtkInternals)
{
}

vtkAccelVolumeRayCastMapper::~vtkAccelVolumeRayCastMapper() = default;

void vtkAccelVolumeRayCastMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "LeapMode: " << this->LeapMode << "\n";
  os << indent << "CellLeaping: " << this->CellLeaping << "\n";
  os << indent << "OctreeLeafSize: " << this->OctreeLeafSize << "\n";
  os << indent << "SampleDistance: " << this->SampleDistance << "\n";
  os << indent << "InteractiveSampleDistance: " << this->InteractiveSampleDistance << "\n";
  os << indent << "ImageSampleDistance: " << this->ImageSampleDistance << "\n";
  os << indent << "MinimumImageSampleDistance: " << this->MinimumImageSampleDistance << "\n";
  os << indent << "MaximumImageSampleDistance: " << this->MaximumImageSampleDistance << "\n";
  os << indent << "AutoAdjustSampleDistances: " << this->AutoAdjustSampleDistances << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
  os << indent << "AdditiveUnitDistance: " << this->AdditiveUnitDistance << "\n";
  os << indent << "LastNumberOfRays: " << this->LastNumberOfRays << "\n";
  os << indent << "LastNumberOfSamples: " << this->LastNumberOfSamples << "\n";
  os << indent << "LastNumberOfOctreeLeaps: " << this->LastNumberOfOctreeLeaps << "\n";
  os << indent << "LastNumberOfDistanceMapLeaps: " << this->LastNumberOfDistanceMapLeaps << "\n";
  os << indent << "AccelerationBytes: " << this->AccelerationBytes << "\n";
}

void vtkAccelVolumeRayCastMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Internals->Display.ReleaseGraphicsResources(window);
}

void vtkAccelVolumeRayCastMapper::Render(vtkRenderer* renderer, vtkVolume* volume)
{
  vtkNew<vtkTimerLog> timer;
  timer->StartTimer();
  // StartEvent now; ProgressEvent from the caster's rebuilds and tiles (main thread only);
  // ProgressEvent 1 and EndEvent on every return.
  vtkAccelVolumeRenderProgress progress(this);
  vtkInternals& internals = *this->Internals;
  vtkImageData* input = nullptr;
  vtkDataArray* scalars = nullptr;
  vtkVolumeProperty* property = nullptr;
  vtkOpenGLRenderWindow* window =
    vtkAccelVolumeBeginCPURender(this, renderer, volume, input, scalars, property);
  if (!window)
  {
    return;
  }
  std::string error;
  if (this->BlendMode == vtkVolumeMapper::ISOSURFACE_BLEND ||
    this->BlendMode == vtkVolumeMapper::SLICE_BLEND)
  {
    vtkErrorMacro("Blend mode " << this->BlendMode
                                << " is not supported by the ray cast mapper (use composite, "
                                   "maximum, minimum, additive or average intensity)");
    return;
  }
  if (property->GetTransferFunctionMode() == vtkVolumeProperty::TF_2D &&
    this->BlendMode == COMPOSITE_BLEND && !internals.ReportedError)
  {
    internals.ReportedError = true;
    vtkWarningMacro("2D transfer functions are not supported by the ray cast mapper; the 1D "
                    "scalar opacity and colour are used");
  }

  double range[2];
  vtkAccelVolumeScalarRange(scalars, range);

  // The caster rebuilds its octree / classification only when the versions change.
  internals.Inputs.UpdateVolume(input, scalars);
  // NaN / infinite float values as the slice mapper's texture holds them (a finite copy).
  accelvolume::VolumeView view;
  vtkAccelVolumeView(input, internals.Inputs.GetScalars(), view); // type checked with the input
  const int* dims = view.dims;
  vtkNew<vtkMatrix4x4> indexToWorld;
  vtkAccelVolumeIndexToWorld(volume, input, indexToWorld);
  vtkNew<vtkMatrix4x4> worldToIndex;
  vtkMatrix4x4::Invert(indexToWorld, worldToIndex);
  const double voxelSpacing = vtkAccelVolumeSmallestSpacing(indexToWorld, dims);
  const bool composite = this->BlendMode == COMPOSITE_BLEND;
  accelvolume::RayCastTransfer transfer;
  double high = 0;
  internals.Inputs.UpdateTransfer(property, range, composite, voxelSpacing, transfer, high);

  int width = 0;
  int height = 0;
  int lowerLeft[2] = { 0, 0 };
  renderer->GetTiledSizeAndOrigin(&width, &height, lowerLeft, lowerLeft + 1);
  if (width < 1 || height < 1)
  {
    return;
  }

  // Interactive frames trade samples for time like vtkFixedPointVolumeRayCastMapper.
  const double allotted = volume->GetAllocatedRenderTime();
  const bool interactive = this->AutoAdjustSampleDistances && allotted > 0 && allotted < 1.0;
  double sampleDistance = interactive ? this->InteractiveSampleDistance : this->SampleDistance;
  double imageSampleDistance = this->ImageSampleDistance;
  if (interactive)
  {
    const double previous = std::max(this->LastImageSampleDistance, 1.0);
    const double ratio =
      this->LastRenderTime > 0 ? std::sqrt(this->LastRenderTime / allotted) : 1.0;
    imageSampleDistance = std::min(std::max(previous * ratio, this->MinimumImageSampleDistance),
      std::max(this->MinimumImageSampleDistance, this->MaximumImageSampleDistance));
  }
  this->LastSampleDistance = sampleDistance;
  this->LastImageSampleDistance = imageSampleDistance;
  const int imageWidth = std::max(1, static_cast<int>(std::ceil(width / imageSampleDistance)));
  const int imageHeight = std::max(1, static_cast<int>(std::ceil(height / imageSampleDistance)));

  vtkCamera* camera = renderer->GetActiveCamera();
  const double aspect = static_cast<double>(width) / height;
  vtkNew<vtkMatrix4x4> clipToWorld;
  clipToWorld->DeepCopy(camera->GetCompositeProjectionTransformMatrix(aspect, -1, 1));
  clipToWorld->Invert();
  accelvolume::RayCastView rays;
  rays.width = imageWidth;
  rays.height = imageHeight;
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      rays.clipToWorld[r][c] = clipToWorld->GetElement(r, c);
    }
  }
  rays.worldToIndex = ToAffine(worldToIndex);
  // Opaque geometry drawn before the volume stops the rays.
  if (renderer->VisibleActorCount() > 0)
  {
    internals.Depth.resize(static_cast<std::size_t>(width) * height);
    if (vtkAccelVolumeImageDisplay::ReadDepth(
          window, lowerLeft, width, height, internals.Depth.data()))
    {
      internals.RayDepth.resize(static_cast<std::size_t>(imageWidth) * imageHeight);
      for (int j = 0; j < imageHeight; ++j)
      {
        const int y = std::min(height - 1, static_cast<int>((j + 0.5) * height / imageHeight));
        for (int i = 0; i < imageWidth; ++i)
        {
          const int x = std::min(width - 1, static_cast<int>((i + 0.5) * width / imageWidth));
          internals.RayDepth[static_cast<std::size_t>(j) * imageWidth + i] =
            internals.Depth[static_cast<std::size_t>(y) * width + x];
        }
      }
      rays.depth = &internals.RayDepth;
    }
  }

  accelvolume::RayCastSettings settings;
  settings.blend = ToBlend(this->BlendMode);
  settings.sampleDistance = sampleDistance;
  settings.nearest = property->GetInterpolationType() == VTK_NEAREST_INTERPOLATION;
  settings.leap = this->LeapMode == LEAP_OCTREE
    ? accelvolume::LeapMode::Octree
    : (this->LeapMode == LEAP_DISTANCE_MAP ? accelvolume::LeapMode::DistanceMap
                                           : accelvolume::LeapMode::None);
  settings.cellLeap = this->CellLeaping != 0;
  settings.earlyTermination = this->EarlyRayTermination != 0;
  settings.terminationThreshold = this->EarlyRayTerminationThreshold;
  settings.additiveUnitDistance =
    this->AdditiveUnitDistance > 0 ? this->AdditiveUnitDistance : voxelSpacing;
  settings.averageRange[0] = this->AverageIPScalarRange[0];
  settings.averageRange[1] = this->AverageIPScalarRange[1];
  settings.octreeLeafSize = this->OctreeLeafSize;
  settings.regions = vtkAccelVolumeRegions(this, input, vtkAccelVolumeIndexBox(dims));
  settings.clip = vtkAccelVolumeClipHalfSpaces(this->ClippingPlanes, indexToWorld);

  accelvolume::RayCastLighting lighting;
  const bool shade = composite && property->GetShade(0) != 0;
  if (shade || !transfer.gradientOpacity.empty())
  {
    // Gradient opacity needs the normal matrix too (gradients in world units).
    vtkAccelVolumeCPULighting(renderer, property, indexToWorld, camera, shade, lighting);
  }

  accelvolume::ParallelFor parallel =
    [](std::size_t count, const std::function<void(std::size_t, std::size_t)>& body)
  { vtkSMPTools::For(0, count, 1, [&](std::size_t begin, std::size_t end) { body(begin, end); }); };
  accelvolume::RayCastCounters counters;
  bool ok = false;
  vtkNew<vtkTimerLog> castTimer;
  castTimer->StartTimer();
  auto cast = [&]()
  {
    // The caster reports up to 0.95 (from this thread only); showing the image is the rest.
    internals.Caster.SetProgressFunction(progress.Range(0.0, 0.95));
    try
    {
      ok = internals.Caster.Render(view, range[0], high, internals.Inputs.VolumeVersion, transfer,
        internals.Inputs.TransferVersion, lighting, rays, settings, parallel, internals.Image, counters,
        error);
    }
    catch (const std::bad_alloc&)
    {
      // The acceleration structures need up to 2 bytes per cell (+6 per voxel for shading).
      ok = false;
      error = "out of memory for the acceleration structures or the image (try LEAP_OCTREE, "
              "shading off or a smaller volume)";
    }
    internals.Caster.SetProgressFunction(nullptr); // it refers to this render's progress
  };
  // More threads than cores only adds contention (and TBB refuses them with a warning).
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  if (this->NumberOfThreads > 0)
  {
    vtkSMPTools::LocalScope(vtkSMPTools::Config{ std::min(this->NumberOfThreads, cores) }, cast);
  }
  else
  {
    cast();
  }
  castTimer->StopTimer();
  if (!ok)
  {
    vtkErrorMacro("Ray casting failed: " << error);
    return;
  }
  this->LastPrepareTime = internals.Caster.GetLastPrepareSeconds();
  this->LastCastTime = castTimer->GetElapsedTime() - this->LastPrepareTime;
  this->LastNumberOfRays = static_cast<vtkTypeInt64>(counters.rays);
  this->LastNumberOfSamples = static_cast<vtkTypeInt64>(counters.samples);
  this->LastSamplesLeapedByOctree = static_cast<vtkTypeInt64>(counters.leapedOctree);
  this->LastSamplesLeapedByDistanceMap = static_cast<vtkTypeInt64>(counters.leapedDistance);
  this->LastSamplesLeapedByCellTable = static_cast<vtkTypeInt64>(counters.leapedCell);
  this->LastSamplesInTransparentCells = static_cast<vtkTypeInt64>(counters.leapedEmptyCell);
  this->LastNumberOfTerminatedRays = static_cast<vtkTypeInt64>(counters.terminatedRays);
  this->LastNumberOfOctreeLeaps = static_cast<vtkTypeInt64>(counters.octreeLeaps);
  this->LastNumberOfDistanceMapLeaps = static_cast<vtkTypeInt64>(counters.distanceLeaps);
  this->AccelerationBytes = static_cast<vtkTypeInt64>(internals.Caster.GetAccelerationBytes());

  int castRectangle[4];
  internals.Caster.GetLastCastRectangle(castRectangle);
  if (!internals.Display.Draw(window, lowerLeft, width, height, imageWidth, imageHeight,
        internals.Image.data(), castRectangle))
  {
    vtkErrorMacro("Cannot show the ray cast image (OpenGL texture or shader failed)");
  }
  timer->StopTimer();
  this->LastRenderTime = timer->GetElapsedTime();
}
