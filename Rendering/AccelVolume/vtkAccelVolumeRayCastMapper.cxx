// CPU ray casting volume mapper with octree / distance-map and semi-transparent cell leaping.
#include "vtkAccelVolumeRayCastMapper.h"

#include "vtkAccelVolumeCPUMask.h"
#include "vtkAccelVolumeDepthCopy.h"
#include "vtkAccelVolumeDepthPeeling.h"
#include "vtkAccelVolumeImageDisplay.h"
#include "vtkAccelVolumeInputAdapter.h"
#include "vtkAccelVolumeMapperSupport.h"
#include "vtkAccelVolumeRenderProgress.h"
#include "vtkAccelVolumeWorkers.h"
#include "vtkActor2D.h"
#include "vtkCamera.h"
#include "vtkContourValues.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPlane.h"
#include "vtkPointData.h"
#include "vtkPropCollection.h"
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
// Whether the renderer shows a prop that may have drawn depth before the volumes: any visible
// prop but volumes and 2D overlays (whatever pass drew it, unlike GetNumberOfPropsRendered).
bool HasVisibleGeometry(vtkRenderer* renderer)
{
  vtkPropCollection* props = renderer->GetViewProps();
  vtkCollectionSimpleIterator it;
  props->InitTraversal(it);
  while (vtkProp* prop = props->GetNextProp(it))
  {
    if (prop->GetVisibility() && !vtkVolume::SafeDownCast(prop) && !vtkActor2D::SafeDownCast(prop))
    {
      return true;
    }
  }
  return false;
}

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
    case vtkVolumeMapper::SLICE_BLEND:
      return accelvolume::Blend::Slice;
    case vtkVolumeMapper::ISOSURFACE_BLEND:
      return accelvolume::Blend::Isosurface;
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

// One frame's inputs to the caster, gathered from the mapper, the renderer and the volume.
struct RayCastFrameInputs
{
  accelvolume::VolumeView View;
  double Range[2] = { 0, 0 };
  double High = 0;
  double VoxelSpacing = 0;
  double LockedSampleDistance = 0; // vtkVolumeMapper::SpacingAdjustedSampleDistance
  vtkNew<vtkMatrix4x4> IndexToWorld;
  vtkNew<vtkMatrix4x4> WorldToIndex;
  accelvolume::RayCastTransfer Transfer;
  int Width = 0;
  int Height = 0;
  int LowerLeft[2] = { 0, 0 };
  int ImageWidth = 0;
  int ImageHeight = 0;
  accelvolume::RayCastView Rays;
  accelvolume::RayCastSettings Settings;
  accelvolume::RayCastLighting Lighting;
};
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
  vtkAccelVolumeCPUMask Mask;     // the mask input or the ghost arrays, as bytes
  vtkAccelVolumeWorkers Workers;  // the mapper's thread count, kept between frames
  bool ReportedError = false;

  // Steps of Render, in order.
  // Checks the blend mode and brings the volume and its tables up to date; false (reported)
  // when the frame cannot be cast.
  bool PrepareInputs(vtkAccelVolumeRayCastMapper* self, vtkImageData* input, vtkDataArray* scalars,
    vtkVolumeProperty* property, vtkVolume* volume, RayCastFrameInputs& in);
  // The mask bytes and label tables for this frame (part of PrepareInputs).
  bool PrepareMask(vtkAccelVolumeRayCastMapper* self, vtkImageData* input,
    vtkVolumeProperty* property, int components, RayCastFrameInputs& in);
  // The rays' image size and camera; false when the viewport is empty.
  bool SetUpRays(vtkAccelVolumeRayCastMapper* self, vtkRenderer* renderer,
    vtkOpenGLRenderWindow* window, vtkVolume* volume, RayCastFrameInputs& in);
  void ReadSceneDepth(vtkOpenGLRenderWindow* window, RayCastFrameInputs& in);
  void FillSettings(vtkAccelVolumeRayCastMapper* self, vtkRenderer* renderer, vtkImageData* input,
    vtkVolumeProperty* property, RayCastFrameInputs& in);
  // Casts the rays on the mapper's threads; false with error set on failure.
  bool Cast(vtkAccelVolumeRayCastMapper* self, vtkAccelVolumeRenderProgress& progress,
    const RayCastFrameInputs& in, accelvolume::RayCastCounters& counters, std::string& error);
  void RecordCounters(vtkAccelVolumeRayCastMapper* self,
    const accelvolume::RayCastCounters& counters, double castSeconds);
};

vtkStandardNewMacro(vtkAccelVolumeRayCastMapper);

vtkAccelVolumeRayCastMapper::vtkAccelVolumeRayCastMapper()
  : Internals(new vtkInternals)
{
  this->InputAdapter->SetMaximumComponents(4);
}

vtkAccelVolumeRayCastMapper::~vtkAccelVolumeRayCastMapper()
{
  this->SetMaskInput(nullptr);
}

void vtkAccelVolumeRayCastMapper::SetMaskInput(vtkImageData* mask)
{
  if (mask == this->MaskInput)
  {
    return;
  }
  if (this->MaskInput)
  {
    this->MaskInput->UnRegister(this);
  }
  this->MaskInput = mask;
  if (mask)
  {
    mask->Register(this);
  }
  this->Modified();
}

void vtkAccelVolumeRayCastMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "LeapMode: " << this->LeapMode << "\n";
  os << indent << "CellLeaping: " << this->CellLeaping << "\n";
  os << indent << "OctreeLeafSize: " << this->OctreeLeafSize << "\n";
  os << indent << "LockSampleDistanceToInputSpacing: " << this->LockSampleDistanceToInputSpacing
     << "\n";
  os << indent << "IntermixIntersectingGeometry: " << this->IntermixIntersectingGeometry << "\n";
  os << indent << "SampleDistance: " << this->SampleDistance << "\n";
  os << indent << "InteractiveSampleDistance: " << this->InteractiveSampleDistance << "\n";
  os << indent << "ImageSampleDistance: " << this->ImageSampleDistance << "\n";
  os << indent << "MinimumImageSampleDistance: " << this->MinimumImageSampleDistance << "\n";
  os << indent << "MaximumImageSampleDistance: " << this->MaximumImageSampleDistance << "\n";
  os << indent << "AutoAdjustSampleDistances: " << this->AutoAdjustSampleDistances << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
  os << indent << "AdditiveUnitDistance: " << this->AdditiveUnitDistance << "\n";
  os << indent << "MaskInput: " << this->MaskInput << "\n";
  os << indent << "MaskType: " << this->MaskType << "\n";
  os << indent << "MaskBlendFactor: " << this->MaskBlendFactor << "\n";
  os << indent << "LastNumberOfRays: " << this->LastNumberOfRays << "\n";
  os << indent << "LastNumberOfSamples: " << this->LastNumberOfSamples << "\n";
  os << indent << "LastNumberOfOctreeLeaps: " << this->LastNumberOfOctreeLeaps << "\n";
  os << indent << "LastNumberOfDistanceMapLeaps: " << this->LastNumberOfDistanceMapLeaps << "\n";
  os << indent << "LastNumberOfCulledPixels: " << this->LastNumberOfCulledPixels << "\n";
  os << indent << "LastNumberOfPacketRays: " << this->LastNumberOfPacketRays << "\n";
  os << indent << "AccelerationBytes: " << this->AccelerationBytes << "\n";
}

void vtkAccelVolumeRayCastMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  const vtkAccelVolumeWindowContext current(window);
  this->Internals->Display.ReleaseGraphicsResources(window);
}

bool vtkAccelVolumeRayCastMapper::vtkInternals::PrepareInputs(vtkAccelVolumeRayCastMapper* self,
  vtkImageData* input, vtkDataArray* scalars, vtkVolumeProperty* property, vtkVolume* volume,
  RayCastFrameInputs& in)
{
  if (self->BlendMode == vtkVolumeMapper::SLICE_BLEND &&
    !vtkPlane::SafeDownCast(property->GetSliceFunction()))
  {
    vtkErrorWithObjectMacro(
      self, "SLICE_BLEND needs a vtkPlane as the volume property's slice function");
    return false;
  }
  const int components = scalars->GetNumberOfComponents();
  if (components > 1)
  {
    const bool independent = property->GetIndependentComponents() != 0;
    if (!independent && components != 2 && components != 4)
    {
      vtkErrorWithObjectMacro(self,
        "Dependent components must be 2 (luminance, alpha) or 4 (RGBA), not " << components);
      return false;
    }
  }
  if (property->GetTransferFunctionMode() == vtkVolumeProperty::TF_2D &&
    self->BlendMode == COMPOSITE_BLEND && !this->ReportedError)
  {
    this->ReportedError = true;
    vtkWarningWithObjectMacro(self,
      "2D transfer functions are not supported by the ray cast mapper; the 1D "
      "scalar opacity and colour are used");
  }

  vtkAccelVolumeScalarRange(scalars, in.Range);

  // The caster rebuilds its octree / classification only when the versions change.
  this->Inputs.UpdateVolume(input, scalars);
  // NaN / infinite float values as the slice mapper's texture holds them (a finite copy).
  vtkAccelVolumeView(input, this->Inputs.GetScalars(), in.View); // type checked with the input
  vtkAccelVolumeIndexToWorld(volume, input, in.IndexToWorld);
  vtkMatrix4x4::Invert(in.IndexToWorld, in.WorldToIndex);
  in.VoxelSpacing = vtkAccelVolumeSmallestSpacing(in.IndexToWorld, in.View.dims);
  double spacing[3];
  int extent[6];
  input->GetSpacing(spacing);
  input->GetExtent(extent);
  in.LockedSampleDistance = self->SpacingAdjustedSampleDistance(spacing, extent);
  const bool composite = self->BlendMode == COMPOSITE_BLEND;
  this->Inputs.UpdateTransfer(property, in.Range, composite, input, in.Transfer, in.High);
  this->Inputs.UpdateComponents(property, this->Inputs.GetScalars(), composite, in.Transfer);
  return this->PrepareMask(self, input, property, components, in);
}

bool vtkAccelVolumeRayCastMapper::vtkInternals::PrepareMask(vtkAccelVolumeRayCastMapper* self,
  vtkImageData* input, vtkVolumeProperty* property, int components, RayCastFrameInputs& in)
{
  // As vtkAccelVolumeSliceMapper: a label map colours composite one-component frames and is
  // ignored otherwise; a binary mask (and the ghost arrays' hidden points) hides samples.
  const bool labelType = self->MaskInput && self->MaskType == LabelMapMaskType;
  const bool labelMap =
    labelType && self->MaskBlendFactor > 0 && self->BlendMode == COMPOSITE_BLEND;
  if (labelMap && components > 1)
  {
    self->WarnNotApplicable("a label-map mask of multi-component scalars",
      "label maps colour one-component scalars (as vtkGPUVolumeRayCastMapper)");
  }
  bool changed = false;
  std::string error;
  if (!this->Mask.Update(input, self->MaskInput, self->MaskType == BinaryMaskType,
        labelMap && components == 1, changed, error))
  {
    vtkErrorWithObjectMacro(self, << error);
    return false;
  }
  if (changed)
  {
    ++this->Inputs.VolumeVersion; // the distance map holds the mask's empty cells
  }
  this->Mask.UpdateLabelTables(property, in.Range, in.High, vtkAccelVolumeCPUInputs::TableSize);
  in.Settings.mask = this->Mask.GetBytes();
  in.Settings.maskNeighbours = this->Mask.GetNeighbours();
  in.Settings.labelTables = this->Mask.GetLabelTables();
  in.Settings.labelBlend = self->MaskBlendFactor;
  return true;
}

bool vtkAccelVolumeRayCastMapper::vtkInternals::SetUpRays(vtkAccelVolumeRayCastMapper* self,
  vtkRenderer* renderer, vtkOpenGLRenderWindow* window, vtkVolume* volume, RayCastFrameInputs& in)
{
  renderer->GetTiledSizeAndOrigin(&in.Width, &in.Height, in.LowerLeft, in.LowerLeft + 1);
  const int width = in.Width;
  const int height = in.Height;
  if (width < 1 || height < 1)
  {
    return false;
  }

  // Interactive frames trade samples for time like vtkFixedPointVolumeRayCastMapper.
  const double allotted = volume->GetAllocatedRenderTime();
  const bool interactive = self->AutoAdjustSampleDistances && allotted > 0 && allotted < 1.0;
  double sampleDistance = interactive ? self->InteractiveSampleDistance : self->SampleDistance;
  if (self->LockSampleDistanceToInputSpacing)
  {
    sampleDistance = in.LockedSampleDistance;
  }
  double imageSampleDistance = self->ImageSampleDistance;
  if (interactive)
  {
    const double previous = std::max(self->LastImageSampleDistance, 1.0);
    const double ratio =
      self->LastRenderTime > 0 ? std::sqrt(self->LastRenderTime / allotted) : 1.0;
    imageSampleDistance = std::min(std::max(previous * ratio, self->MinimumImageSampleDistance),
      std::max(self->MinimumImageSampleDistance, self->MaximumImageSampleDistance));
  }
  self->LastSampleDistance = sampleDistance;
  self->LastImageSampleDistance = imageSampleDistance;
  in.Settings.sampleDistance = sampleDistance;
  in.ImageWidth = std::max(1, static_cast<int>(std::ceil(width / imageSampleDistance)));
  in.ImageHeight = std::max(1, static_cast<int>(std::ceil(height / imageSampleDistance)));

  vtkCamera* camera = renderer->GetActiveCamera();
  const double aspect = static_cast<double>(width) / height;
  vtkNew<vtkMatrix4x4> clipToWorld;
  clipToWorld->DeepCopy(camera->GetCompositeProjectionTransformMatrix(aspect, -1, 1));
  clipToWorld->Invert();
  accelvolume::RayCastView& rays = in.Rays;
  rays.width = in.ImageWidth;
  rays.height = in.ImageHeight;
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      rays.clipToWorld[r][c] = clipToWorld->GetElement(r, c);
    }
  }
  rays.worldToIndex = ToAffine(in.WorldToIndex);
  // Opaque geometry drawn before the volume stops the rays. With none (VisibleActorCount
  // counts the volumes too) the depth read-back would cost a full-window read every frame.
  if (self->IntermixIntersectingGeometry && HasVisibleGeometry(renderer))
  {
    this->ReadSceneDepth(window, in);
  }
  return true;
}

void vtkAccelVolumeRayCastMapper::vtkInternals::ReadSceneDepth(
  vtkOpenGLRenderWindow* window, RayCastFrameInputs& in)
{
  const int width = in.Width;
  const int height = in.Height;
  const int imageWidth = in.ImageWidth;
  const int imageHeight = in.ImageHeight;
  this->Depth.resize(static_cast<std::size_t>(width) * height);
  if (this->Display.ReadDepth(window, in.LowerLeft, width, height, this->Depth.data()))
  {
    this->RayDepth.resize(static_cast<std::size_t>(imageWidth) * imageHeight);
    for (int j = 0; j < imageHeight; ++j)
    {
      const int y = std::min(height - 1, static_cast<int>((j + 0.5) * height / imageHeight));
      for (int i = 0; i < imageWidth; ++i)
      {
        const int x = std::min(width - 1, static_cast<int>((i + 0.5) * width / imageWidth));
        this->RayDepth[static_cast<std::size_t>(j) * imageWidth + i] =
          this->Depth[static_cast<std::size_t>(y) * width + x];
      }
    }
    in.Rays.depth = &this->RayDepth;
  }
}

void vtkAccelVolumeRayCastMapper::vtkInternals::FillSettings(vtkAccelVolumeRayCastMapper* self,
  vtkRenderer* renderer, vtkImageData* input, vtkVolumeProperty* property, RayCastFrameInputs& in)
{
  accelvolume::RayCastSettings& settings = in.Settings;
  settings.blend = ToBlend(self->BlendMode);
  settings.nearest = property->GetInterpolationType() == VTK_NEAREST_INTERPOLATION;
  settings.leap = self->LeapMode == LEAP_OCTREE
    ? accelvolume::LeapMode::Octree
    : (self->LeapMode == LEAP_DISTANCE_MAP ? accelvolume::LeapMode::DistanceMap
                                           : accelvolume::LeapMode::None);
  settings.cellLeap = self->CellLeaping != 0;
  settings.earlyTermination = self->EarlyRayTermination != 0;
  settings.terminationThreshold = self->EarlyRayTerminationThreshold;
  settings.additiveUnitDistance = self->AdditiveUnitDistance > 0
    ? self->AdditiveUnitDistance
    : std::max(1.0e-6, property->GetScalarOpacityUnitDistance(0)); // VTK's unit
  settings.averageRange[0] = self->AverageIPScalarRange[0];
  settings.averageRange[1] = self->AverageIPScalarRange[1];
  settings.octreeLeafSize = self->OctreeLeafSize;
  settings.regions = vtkAccelVolumeRegions(self, input, vtkAccelVolumeIndexBox(in.View.dims));
  settings.clip = vtkAccelVolumeClipHalfSpaces(self->ClippingPlanes, in.IndexToWorld);
  if (vtkPlane* plane = vtkPlane::SafeDownCast(property->GetSliceFunction()))
  {
    settings.slicePlane = vtkAccelVolumeIndexHalfSpace(plane, in.IndexToWorld);
  }
  if (self->BlendMode == ISOSURFACE_BLEND)
  {
    vtkContourValues* values = property->GetIsoSurfaceValues();
    settings.isoValues.assign(
      values->GetValues(), values->GetValues() + values->GetNumberOfContours());
    std::sort(settings.isoValues.begin(), settings.isoValues.end());
  }
  else
  {
    settings.isoValues.clear();
  }

  const bool composite = self->BlendMode == COMPOSITE_BLEND;
  const bool shade =
    (composite || self->BlendMode == SLICE_BLEND || self->BlendMode == ISOSURFACE_BLEND) &&
    property->GetShade(0) != 0;
  bool gradientOpacity = !in.Transfer.gradientOpacity.empty();
  for (const accelvolume::RayCastComponentTable& table : in.Transfer.components.tables)
  {
    gradientOpacity = gradientOpacity || !table.gradientOpacity.empty();
  }
  if (shade || gradientOpacity)
  {
    // Gradient opacity needs the normal matrix too (gradients in world units).
    vtkAccelVolumeCPULighting(renderer, property, in.IndexToWorld, in.View.dims,
      renderer->GetActiveCamera(), shade, in.Lighting);
  }
}

bool vtkAccelVolumeRayCastMapper::vtkInternals::Cast(vtkAccelVolumeRayCastMapper* self,
  vtkAccelVolumeRenderProgress& progress, const RayCastFrameInputs& in,
  accelvolume::RayCastCounters& counters, std::string& error)
{
  // More threads than cores only adds contention. A set thread count gets exactly that many
  // workers (vtkAccelVolumeWorkers.h: vtkSMPTools::LocalScope does not hold it).
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const accelvolume::ParallelFor parallel =
    this->Workers.For(self->NumberOfThreads > 0 ? std::min(self->NumberOfThreads, cores) : 0);
  bool ok = false;
  auto cast = [&]()
  {
    // The caster reports up to 0.95 (from this thread only); showing the image is the rest.
    this->Caster.SetProgressFunction(progress.Range(0.0, 0.95));
    try
    {
      ok = this->Caster.Render(in.View, in.Range[0], in.High, this->Inputs.VolumeVersion,
        in.Transfer, this->Inputs.TransferVersion, in.Lighting, in.Rays, in.Settings, parallel,
        this->Image, counters, error);
    }
    catch (const std::bad_alloc&)
    {
      // The acceleration structures need up to 2 bytes per cell (+6 per voxel for shading).
      ok = false;
      error = "out of memory for the acceleration structures or the image (try LEAP_OCTREE, "
              "shading off or a smaller volume)";
    }
    this->Caster.SetProgressFunction(nullptr); // it refers to this render's progress
  };
  cast();
  return ok;
}

void vtkAccelVolumeRayCastMapper::vtkInternals::RecordCounters(vtkAccelVolumeRayCastMapper* self,
  const accelvolume::RayCastCounters& counters, double castSeconds)
{
  self->LastPrepareTime = this->Caster.GetLastPrepareSeconds();
  self->LastCastTime = castSeconds - self->LastPrepareTime;
  self->LastNumberOfRays = static_cast<vtkTypeInt64>(counters.rays);
  self->LastNumberOfSamples = static_cast<vtkTypeInt64>(counters.samples);
  self->LastSamplesLeapedByOctree = static_cast<vtkTypeInt64>(counters.leapedOctree);
  self->LastSamplesLeapedByDistanceMap = static_cast<vtkTypeInt64>(counters.leapedDistance);
  self->LastSamplesLeapedByCellTable = static_cast<vtkTypeInt64>(counters.leapedCell);
  self->LastSamplesInTransparentCells = static_cast<vtkTypeInt64>(counters.leapedEmptyCell);
  self->LastNumberOfTerminatedRays = static_cast<vtkTypeInt64>(counters.terminatedRays);
  self->LastNumberOfOctreeLeaps = static_cast<vtkTypeInt64>(counters.octreeLeaps);
  self->LastNumberOfDistanceMapLeaps = static_cast<vtkTypeInt64>(counters.distanceLeaps);
  self->LastNumberOfCulledPixels = static_cast<vtkTypeInt64>(counters.culledPixels);
  self->LastNumberOfPacketRays = static_cast<vtkTypeInt64>(counters.packetRays);
  self->AccelerationBytes = static_cast<vtkTypeInt64>(this->Caster.GetAccelerationBytes());
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
  vtkOpenGLRenderWindow* window = vtkAccelVolumeBeginCPURender(
    this, *this->InputAdapter, renderer, volume, input, scalars, property);
  if (!window)
  {
    return;
  }
  const vtkAccelVolumePeelStage peel = vtkAccelVolumeGetPeelStage(window, volume, this);
  if (peel == vtkAccelVolumePeelStage::Later)
  {
    return; // drawn whole in the first volumetric stage of depth peeling
  }
  RayCastFrameInputs in;
  if (!internals.PrepareInputs(this, input, scalars, property, volume, in) ||
    !internals.SetUpRays(this, renderer, window, volume, in))
  {
    return;
  }
  internals.FillSettings(this, renderer, input, property, in);

  accelvolume::RayCastCounters counters;
  std::string error;
  vtkNew<vtkTimerLog> castTimer;
  castTimer->StartTimer();
  const bool ok = internals.Cast(this, progress, in, counters, error);
  castTimer->StopTimer();
  if (!ok)
  {
    vtkErrorMacro("Ray casting failed: " << error);
    return;
  }
  internals.RecordCounters(this, counters, castTimer->GetElapsedTime());

  int castRectangle[4];
  internals.Caster.GetLastCastRectangle(castRectangle);
  float colourScale = 1.0f;
  float colourBias = 0.0f;
  this->GetFinalColorScaleAndBias(colourScale, colourBias);
  float selectionColour[3];
  const int selectionMode = vtkAccelVolumeSelectionMode(renderer, selectionColour);
  // vtkDualDepthPeelingPass's targets are viewport-sized, drawn from (0, 0).
  const bool peeling = peel == vtkAccelVolumePeelStage::OutsideRange;
  const int origin[2] = { 0, 0 };
  if (!internals.Display.Draw(window, peeling ? origin : in.LowerLeft, in.Width, in.Height,
        in.ImageWidth, in.ImageHeight, internals.Image.data(), castRectangle, colourScale,
        colourBias, selectionMode, selectionColour, peeling))
  {
    vtkErrorMacro("Cannot show the ray cast image (OpenGL texture or shader failed)");
  }
  timer->StopTimer();
  this->LastRenderTime = timer->GetElapsedTime();
}
