// Slice-based MIP / MinIP / raysum / average volume mapper with cut-face re-rendering.
#include "vtkAccelVolumeSliceMapper.h"

#include "vtkAccelVolumeSliceMapperInternals.h"

#include "vtkAccelVolumeDepthCopy.h"
#include "vtkAccelVolumeDepthPeeling.h"
#include "vtkAccelVolumeInputAdapter.h"
#include "vtkAccelVolumeMapperSupport.h"
#include "vtkAccelVolumeMinMaxOctree.h"
#include "vtkAccelVolumeMinMaxOctreeInternals.h"
#include "vtkAccelVolumeRenderProgress.h"
#include "vtkAccelVolumeSliceGeometry.h"
#include "vtkAccelVolumeSliceMask.h"
#include "vtkAccelVolumeSlicePasses.h"
#include "vtkAccelVolumeSliceResources.h"
#include "vtkCamera.h"
#include "vtkContourValues.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPlane.h"
#include "vtkPlaneCollection.h"
#include "vtkPointData.h"
#include "vtkRenderer.h"
#include "vtkTextureObject.h"
#include "vtkTimerLog.h"
#include "vtkUnsignedCharArray.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"
#include "vtk_glew.h"

#include "common/Geometry.h"
#include "skipping/MinMaxOctree.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace
{
constexpr int MaximumClipPlanes = vtkAccelVolumeSliceFrame::MaximumClipPlanes;

bool IsSupportedBlend(int blendMode)
{
  return blendMode == vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND ||
    blendMode == vtkVolumeMapper::MINIMUM_INTENSITY_BLEND ||
    blendMode == vtkVolumeMapper::ADDITIVE_BLEND ||
    blendMode == vtkVolumeMapper::AVERAGE_INTENSITY_BLEND ||
    blendMode == vtkVolumeMapper::COMPOSITE_BLEND ||
    blendMode == vtkVolumeMapper::ISOSURFACE_BLEND || blendMode == vtkVolumeMapper::SLICE_BLEND;
}

// Iso-surfaces are drawn by the composite passes (front to back, terminated), and so is a slice
// plane (one classified sample per pixel).
// Every contour value has a non-zero scalar opacity.
bool ContourValuesVisible(vtkVolumeProperty* property, vtkContourValues* values)
{
  vtkPiecewiseFunction* opacity = property->GetScalarOpacity(0);
  for (int i = 0; i < values->GetNumberOfContours(); ++i)
  {
    if (!(opacity->GetValue(values->GetValue(i)) > 0.0))
    {
      return false;
    }
  }
  return true;
}

// SLICE_BLEND: the property's slice plane (world) in index space, cut to each cropping region
// and the clip planes. Empty when the plane misses them; `error` says why there is no plane.
std::vector<accelvolume::Polygon> SlicePlanePolygons(
  vtkVolumeProperty* property, const vtkAccelVolumeSliceView& view, std::string& error)
{
  vtkPlane* plane = vtkPlane::SafeDownCast(property->GetSliceFunction());
  if (!plane)
  {
    error = property->GetSliceFunction()
      ? "SLICE_BLEND needs a vtkPlane as the property's slice function (got " +
        std::string(property->GetSliceFunction()->GetClassName()) + ")"
      : "SLICE_BLEND needs a slice function on the volume property (vtkPlane)";
    return {};
  }
  // The plane n.p + offset = 0 of the index half-space is n.p = -offset.
  const accelvolume::HalfSpace indexPlane = vtkAccelVolumeIndexHalfSpace(plane, view.IndexToWorld);
  std::vector<accelvolume::Polygon> polygons;
  for (const accelvolume::Box& region : view.Regions)
  {
    accelvolume::Polygon polygon =
      accelvolume::PlaneRegionPolygon(indexPlane.normal, -indexPlane.offset, region, view.Clip);
    if (!polygon.empty())
    {
      polygons.push_back(std::move(polygon));
    }
  }
  return polygons;
}

accelvolume::Vec3 MakeVec3(double x, double y, double z)
{
  accelvolume::Vec3 v;
  v.x = x;
  v.y = y;
  v.z = z;
  return v;
}

// Slices start at the reference depth (no per-frame offset).
constexpr double SlicePhase = 0.0;

}

vtkStandardNewMacro(vtkAccelVolumeSliceMapper);

vtkAccelVolumeSliceMapper::vtkAccelVolumeSliceMapper()
  : Internals(new vtkInternals)
{
  // BlendMode keeps vtkVolumeMapper's default, composite, like every VTK volume mapper: a
  // drop-in replacement must draw the same picture without being told the blend mode.
  this->InputAdapter->SetMaximumComponents(4);
}

vtkAccelVolumeSliceMapper::~vtkAccelVolumeSliceMapper()
{
  this->SetMaskInput(nullptr);
  if (this->DepthPassContourValues)
  {
    this->DepthPassContourValues->Delete();
  }
  this->SetTransfer2DYAxisArray(nullptr);
}

const char* vtkAccelVolumeSliceMapper::GetOpenGLRenderer()
{
  return this->Internals->Renderer.c_str();
}

void vtkAccelVolumeSliceMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  const vtkAccelVolumeWindowContext current(window);
  this->Internals->Resources.ReleaseGraphicsResources(window);
  this->Internals->Mask.ReleaseGraphicsResources(window);
  // GPU-built octree levels (OctreeBuilder GPU) live in this context too.
  this->Internals->Octree->ReleaseGraphicsResources();
  this->Internals->Octree->SetInputTexture(nullptr);
  for (auto& octree : this->Internals->ComponentOctrees)
  {
    octree->ReleaseGraphicsResources();
  }
}

bool vtkAccelVolumeSliceMapper::ValidateInput(
  vtkImageData* input, vtkDataArray* scalars, const std::string& inputError, vtkVolume* volume)
{
  std::string error = inputError;
  if (!input || !scalars || !error.empty() || !vtkAccelVolumeCheckGeometry(this, error))
  {
    vtkErrorMacro(<< error);
    return false;
  }
  vtkVolumeProperty* property = volume->GetProperty();
  const int components = scalars->GetNumberOfComponents();
  if (components > 1)
  {
    const bool independent = !property || property->GetIndependentComponents();
    if (property && property->GetTransferFunctionMode() == vtkVolumeProperty::TF_2D)
    {
      vtkErrorMacro("2D transfer functions need one-component scalars");
      return false;
    }
    if (!independent && components != 2 && components != 4)
    {
      vtkErrorMacro(
        "Dependent components must be 2 (luminance, alpha) or 4 (RGBA), not " << components);
      return false;
    }
  }
  if (!IsSupportedBlend(this->BlendMode))
  {
    vtkErrorMacro("Blend mode " << this->BlendMode
                                << " is not supported by the slice mapper (use composite, "
                                   "maximum, minimum, additive or average intensity)");
    return false;
  }
  if (!volume->GetProperty())
  {
    vtkErrorMacro("The volume has no property");
    return false;
  }
  if (this->ClippingPlanes && this->ClippingPlanes->GetNumberOfItems() > MaximumClipPlanes)
  {
    vtkErrorMacro("At most " << MaximumClipPlanes << " clipping planes are supported");
    return false;
  }
  return true;
}

bool vtkAccelVolumeSliceMapper::vtkInternals::UploadVolume(vtkAccelVolumeSliceMapper* self,
  vtkOpenGLRenderWindow* window, vtkImageData* input, vtkDataArray* scalars,
  vtkVolumeProperty* property, const double range[2])
{
  std::string error;
  if (scalars->GetNumberOfComponents() > 1)
  {
    const bool colourComponents =
      !property->GetIndependentComponents() && scalars->GetNumberOfComponents() == 4;
    if (!this->Resources.PrepareMultiComponentVolume(
          window, input, scalars, colourComponents, error))
    {
      vtkErrorWithObjectMacro(self, "Cannot upload the volume: " << error);
      return false;
    }
    this->Resources.UpdateComponentTables(window, property, scalars->GetNumberOfComponents(),
      property->GetIndependentComponents() != 0);
    this->Resources.UpdateTransferTable(window, property, range); // bound by every pass
    this->Frame.Components = scalars->GetNumberOfComponents();
    return true;
  }
  this->ComponentImages.clear();
  this->Frame.Components = 1;
  // Partitions: bricks no larger than a block plus the voxel neighbours share.
  int brickSize = self->MaximumBrickSize;
  const int* dims = input->GetDimensions();
  for (int a = 0; a < 3; ++a)
  {
    if (self->Partitions[a] > 1 && dims[a] > 1)
    {
      const int block = (dims[a] - 1 + self->Partitions[a] - 1) / self->Partitions[a];
      const int size = std::max(4, block + 1);
      brickSize = brickSize > 0 ? std::min(brickSize, size) : size;
    }
  }
  if (!this->Resources.PrepareVolume(window, input, scalars, range,
        static_cast<std::uint64_t>(self->GPUMemoryBudget), brickSize, error))
  {
    vtkErrorWithObjectMacro(self, "Cannot upload the volume: " << error);
    return false;
  }
  this->Resources.UpdateTransferTable(window, property, range);
  return true;
}

bool vtkAccelVolumeSliceMapper::vtkInternals::SetUpView(vtkAccelVolumeSliceMapper* self,
  vtkRenderer* renderer, vtkVolume* volume, vtkImageData* input, vtkAccelVolumeSliceView& view)
{
  view.Input = input;
  input->GetDimensions(view.Dimensions);

  // Index -> world: the image's index-to-physical matrix, then the prop's matrix.
  vtkAccelVolumeIndexToWorld(volume, input, view.IndexToWorld);
  renderer->GetTiledSizeAndOrigin(&view.Width, &view.Height, view.LowerLeft, view.LowerLeft + 1);
  if (view.Width < 1 || view.Height < 1)
  {
    return false;
  }
  view.Camera = renderer->GetActiveCamera();
  const double aspect = static_cast<double>(view.Width) / view.Height;
  view.View = view.Camera->GetViewTransformMatrix();
  view.Projection->DeepCopy(view.Camera->GetProjectionTransformMatrix(aspect, -1, 1));
  vtkMatrix4x4::Multiply4x4(view.View, view.IndexToWorld, view.IndexToEye);
  vtkMatrix4x4::Multiply4x4(view.Projection, view.IndexToEye, view.IndexToClip);
  vtkMatrix4x4::Invert(view.IndexToEye, view.EyeToIndex);
  vtkMatrix4x4::Invert(view.Projection, view.InverseProjection);

  view.VolumeBox = vtkAccelVolumeIndexBox(view.Dimensions);
  view.Regions = vtkAccelVolumeRegions(self, input, view.VolumeBox);
  view.Clip = vtkAccelVolumeClipHalfSpaces(self->ClippingPlanes, view.IndexToWorld);
  return true;
}

void vtkAccelVolumeSliceMapper::vtkInternals::ChooseSliceSpacing(
  vtkAccelVolumeSliceMapper* self, vtkVolume* volume, vtkAccelVolumeSliceView& view)
{
  const accelvolume::Box& volumeBox = view.VolumeBox;
  vtkMatrix4x4* indexToEye = view.IndexToEye;
  // Eye depth (distance in front of the camera plane) as a function of the index point.
  const accelvolume::Vec3 depthGradient = MakeVec3(
    -indexToEye->GetElement(2, 0), -indexToEye->GetElement(2, 1), -indexToEye->GetElement(2, 2));
  const double depthOffset = -indexToEye->GetElement(2, 3);

  // Slice spacing in world units.
  const double voxelSpacing = vtkAccelVolumeSmallestSpacing(view.IndexToWorld, view.Dimensions);
  double depthMinimum = VTK_DOUBLE_MAX;
  double depthMaximum = -VTK_DOUBLE_MAX;
  for (int corner = 0; corner < 8; ++corner)
  {
    const accelvolume::Vec3 p = MakeVec3(corner & 1 ? volumeBox.upper.x : volumeBox.lower.x,
      corner & 2 ? volumeBox.upper.y : volumeBox.lower.y,
      corner & 4 ? volumeBox.upper.z : volumeBox.lower.z);
    const double depth = accelvolume::Dot(depthGradient, p) + depthOffset;
    depthMinimum = std::min(depthMinimum, depth);
    depthMaximum = std::max(depthMaximum, depth);
  }
  const double depthExtent = std::max(depthMaximum - depthMinimum, 1.0e-9);
  // Slice depths reach the shaders relative to the volume centre's (float precision).
  const double referenceDepth = 0.5 * (depthMinimum + depthMaximum);
  double spacing = self->SampleDistance;
  if (!self->AutoAdjustSampleDistances && self->LockSampleDistanceToInputSpacing)
  {
    double inputSpacing[3];
    int extent[6];
    view.Input->GetSpacing(inputSpacing);
    view.Input->GetExtent(extent);
    spacing = self->SpacingAdjustedSampleDistance(inputSpacing, extent);
  }
  if (self->NumberOfSlices > 0)
  {
    spacing = depthExtent / self->NumberOfSlices;
  }
  else if (self->AutoAdjustSampleDistances)
  {
    spacing = voxelSpacing;
    const double allotted = volume->GetAllocatedRenderTime();
    if (allotted > 0 && allotted < 1.0 && self->LastRenderTime > allotted)
    {
      spacing *= std::min(self->InteractiveSlowdownLimit, self->LastRenderTime / allotted);
    }
  }
  if (depthExtent / spacing > self->MaximumNumberOfSlices)
  {
    spacing = depthExtent / self->MaximumNumberOfSlices;
  }
  vtkMatrix4x4* eyeToIndex = view.EyeToIndex;
  accelvolume::ViewRays& rays = view.Rays;
  rays.depthGradient = depthGradient;
  rays.depthOffset = depthOffset;
  rays.perspective = view.Camera->GetParallelProjection() == 0;
  rays.eye = MakeVec3(
    eyeToIndex->GetElement(0, 3), eyeToIndex->GetElement(1, 3), eyeToIndex->GetElement(2, 3));
  rays.direction = MakeVec3(
    -eyeToIndex->GetElement(0, 2), -eyeToIndex->GetElement(1, 2), -eyeToIndex->GetElement(2, 2));
  view.VoxelSpacing = voxelSpacing;
  view.ReferenceDepth = referenceDepth;
  view.Spacing = spacing;
}

void vtkAccelVolumeSliceMapper::vtkInternals::BuildProxyGeometry(vtkAccelVolumeSliceMapper* self,
  vtkOpenGLRenderWindow* window, vtkImageData* input, vtkDataArray* scalars,
  vtkVolumeProperty* property, const double range[2], const vtkAccelVolumeSliceView& view,
  bool& skipEmptyLeaves, vtkAccelVolumeSliceGeometryStats& geometryStats)
{
  const bool extremum =
    self->BlendMode == MAXIMUM_INTENSITY_BLEND || self->BlendMode == MINIMUM_INTENSITY_BLEND;
  const bool composite = vtkAccelVolumeCompositeLike(self->BlendMode);
  const bool transferFunction2D = self->BlendMode == COMPOSITE_BLEND &&
    property->GetTransferFunctionMode() == vtkVolumeProperty::TF_2D;
  // Composite slabs: plain samples of one cropping region (depth passes, iso-surfaces, slice
  // planes and labels sample per fragment; a depth image wants each sample's own depth).
  const bool compositeSlabs = self->BlendMode == COMPOSITE_BLEND && view.Regions.size() == 1 &&
    !self->UsesDepthPass() && !self->UsesLabelMap() && !self->RenderToImage;
  // A binary mask is tested once per fragment: plain slices.
  // Multi-component samples keep several values per sample: plain slices too.
  const int slabSamples = (extremum || compositeSlabs) && !self->MaskInput &&
      !this->UsedGhostMask && this->Frame.Components == 1
    ? self->SlabSamples
    : 1;
  // The octree is classified with the 1D scalar opacity, which says nothing about a 2D table.
  // ... nor does it know a label map's colours (a binary mask only removes samples).
  // ... nor an iso-surface's colours, which come from the iso-values rather than the voxels.
  // ... nor where a depth pass's contour lies, unless every contour value is visible (a leaf
  // whose voxels a crossing reads holds the value, so it is not transparent then).
  const bool contourCulled =
    self->UsesDepthPass() && !ContourValuesVisible(property, self->GetDepthPassContourValues());
  // Multi-component scalars: the octree of each contributing component (see LeafSources).
  self->LastOctreeBuilder = -1; // UpdateEmptyLeaves says which built the frame's octree
  const bool computeSlices = this->UseComputeSlices(self, window, view);
  skipEmptyLeaves = self->BlendMode == COMPOSITE_BLEND && !transferFunction2D && !contourCulled &&
    !self->UsesLabelMap() && (self->EmptySpaceSkipping & SKIP_OCTREE) &&
    this->UpdateEmptyLeaves(
      self, window, this->LeafSources(input, scalars, property, range), computeSlices);
  const accelvolume::BrickLayout& layout = this->Resources.GetBrickLayout();
  vtkAccelVolumeSliceGeometryInput geometry;
  geometry.Regions = &view.Regions;
  geometry.Clip = &view.Clip;
  geometry.VolumeBox = view.VolumeBox;
  geometry.Rays = view.Rays;
  geometry.ReferenceDepth = view.ReferenceDepth;
  geometry.Spacing = view.Spacing;
  geometry.Phase = SlicePhase;
  geometry.Composite = composite;
  geometry.FrontToBack = self->FrontToBack != 0;
  // A slab's samples run along the ray, across brick faces: bricks take plain slices.
  geometry.SlabSamples = layout.Single() ? slabSamples : 1;
  geometry.BoundaryFaces = self->BoundaryRerendering != 0;
  geometry.NonEmpty = skipEmptyLeaves && this->HaveNonEmptyBoxes ? &this->NonEmptyBoxes : nullptr;
  geometry.Layout = &layout;
  geometry.GenerateSlices = self->GPUSliceGeneration != 0;
  geometry.ComputeSlices = computeSlices;
  // Relative depth of the slice plane nearest the reference depth (the compute slices count
  // planes from it; slice depths are Phase + k * Spacing).
  const double nearest = std::round((view.ReferenceDepth - SlicePhase) / view.Spacing);
  this->Frame.SliceBase =
    static_cast<float>(SlicePhase + nearest * view.Spacing - view.ReferenceDepth);
  std::vector<accelvolume::Polygon> slicePlane;
  if (self->BlendMode == SLICE_BLEND)
  {
    std::string planeError;
    slicePlane = SlicePlanePolygons(property, view, planeError);
    geometry.SlicePlane = &slicePlane;
    if (!planeError.empty())
    {
      self->WarnNotApplicable("SliceFunction", planeError.c_str());
    }
  }
  vtkAccelVolumeBuildSliceGeometry(
    geometry, this->Frame, this->Vertices, this->SliceRecords, geometryStats);
  self->LastSlicesGenerated = this->Frame.GeneratedSlices;
  self->LastSliceCompositing =
    this->Frame.ComputeSlices ? SLICE_COMPOSITING_COMPUTE : SLICE_COMPOSITING_RASTER;
  this->AreaFractionPending = false;
  if (composite && (this->Frame.GeneratedSlices || this->Frame.ComputeSlices))
  {
    // Kept for GetLastProxyAreaFraction: the polygons are not clipped here to know it.
    this->AreaFractionPending = true;
    this->AreaRegions = view.Regions;
    this->AreaClip = view.Clip;
    this->AreaInput = geometry;
    this->AreaInput.Regions = &this->AreaRegions;
    this->AreaInput.Clip = &this->AreaClip;
    this->AreaInput.Layout = nullptr;
    this->AreaInput.SlicePlane = nullptr;
  }
  else if (composite)
  {
    self->LastProxyAreaFraction = geometryStats.KeptAreaFraction;
  }
  this->Frame.SlabSamples = geometry.SlabSamples;
}

bool vtkAccelVolumeSliceMapper::vtkInternals::UseComputeSlices(vtkAccelVolumeSliceMapper* self,
  vtkOpenGLRenderWindow* window, const vtkAccelVolumeSliceView& view)
{
  const int blend = self->BlendMode;
  // Masks that hide samples or recolour them (a label map with blend factor 0 changes nothing).
  const bool masked = this->UsedGhostMask ||
    (self->MaskInput && (self->MaskType == BinaryMaskType || self->UsesLabelMap()));
  if (self->SliceCompositing == SLICE_COMPOSITING_RASTER ||
    !(blend == COMPOSITE_BLEND || blend == MAXIMUM_INTENSITY_BLEND ||
      blend == MINIMUM_INTENSITY_BLEND) ||
    this->Frame.Components != 1 || masked || self->RenderToImage ||
    self->UsesDepthPass() || view.Regions.size() != 1 ||
    !this->Resources.GetBrickLayout().Single())
  {
    return false;
  }
  if (this->ComputeWindow != window)
  {
    std::string why;
    this->ComputeSupported = vtkAccelVolumeSliceCompute::IsSupported(window, why);
    this->ComputeWindow = window;
  }
  return this->ComputeSupported;
}

bool vtkAccelVolumeSliceMapper::vtkInternals::FillFrame(vtkAccelVolumeSliceMapper* self,
  vtkRenderer* renderer, vtkOpenGLRenderWindow* window, vtkImageData* input, vtkDataArray* scalars,
  vtkVolumeProperty* property, const double range[2], const vtkAccelVolumeSliceView& view,
  bool skipEmptyLeaves)
{
  const bool composite = vtkAccelVolumeCompositeLike(self->BlendMode);
  vtkAccelVolumeSliceFrame& frame = this->Frame;
  frame.BlendMode = composite ? COMPOSITE_BLEND : self->BlendMode;
  frame.IsoSurface = self->BlendMode == ISOSURFACE_BLEND;
  frame.DepthPassStage = self->UsesDepthPass() ? 2 : 0;
  // The property's iso-values (or the depth pass's contour values) normalised to the data
  // range, ascending (VTK's order).
  vtkContourValues* values = frame.IsoSurface
    ? property->GetIsoSurfaceValues()
    : (frame.DepthPassStage ? self->DepthPassContourValues : nullptr);
  frame.IsoSurfaceCount = 0;
  // Independent components: iso-surfaces of the component of the largest weight (the first of
  // equals, as VTK), normalised to its own range (VTK 9.1 takes component 0's range there);
  // dependent ones: of component 0 (VTK's). The depth pass contours component 0
  // (vtkContourFilter's default).
  frame.IsoComponent = 0;
  const int components = scalars->GetNumberOfComponents(); // Frame.Components is filled below
  for (int c = 1; c < components && frame.IsoSurface && property->GetIndependentComponents(); ++c)
  {
    if (property->GetComponentWeight(c) > property->GetComponentWeight(frame.IsoComponent))
    {
      frame.IsoComponent = c;
    }
  }
  const double* isoRange =
    components > 1 ? this->Resources.ComponentRanges[frame.IsoComponent] : range;
  if (values)
  {
    std::vector<double> iso(
      values->GetValues(), values->GetValues() + values->GetNumberOfContours());
    std::sort(iso.begin(), iso.end());
    const double width = isoRange[1] > isoRange[0] ? isoRange[1] - isoRange[0] : 1.0;
    for (double value : iso)
    {
      if (frame.IsoSurfaceCount < vtkAccelVolumeSliceFrame::MaximumIsoSurfaces)
      {
        frame.IsoSurfaceValues[frame.IsoSurfaceCount++] =
          static_cast<float>((value - isoRange[0]) / width);
      }
    }
  }
  frame.Linear = property->GetInterpolationType() != VTK_NEAREST_INTERPOLATION;
  // Image sample distance: a target that many times smaller, magnified by the resolve pass
  // (render-to-image keeps full resolution: its depth image is per window pixel).
  const double imageSampleDistance =
    self->RenderToImage ? 1.0 : std::max(1.0f, self->ImageSampleDistance);
  frame.ViewportWidth = view.Width;
  frame.ViewportHeight = view.Height;
  frame.Width = std::max(1, static_cast<int>(std::ceil(view.Width / imageSampleDistance)));
  frame.Height = std::max(1, static_cast<int>(std::ceil(view.Height / imageSampleDistance)));
  frame.LowerLeft[0] = view.LowerLeft[0];
  frame.LowerLeft[1] = view.LowerLeft[1];
  // vtkDualDepthPeelingPass's targets are viewport-sized, drawn from (0, 0).
  frame.DrawLowerLeft[0] = frame.ClearSecondTarget ? 0 : view.LowerLeft[0];
  frame.DrawLowerLeft[1] = frame.ClearSecondTarget ? 0 : view.LowerLeft[1];
  for (int c = 0; c < 3; ++c)
  {
    frame.Dimensions[c] = static_cast<float>(view.Dimensions[c]);
  }
  frame.IndexToClip = view.IndexToClip;
  frame.IndexToEye = view.IndexToEye;
  frame.EyeToIndex = view.EyeToIndex;
  frame.Projection = view.Projection;
  frame.InverseProjection = view.InverseProjection;
  frame.ReferenceDepth = view.ReferenceDepth;
  frame.ClipPlaneCount = static_cast<int>(view.Clip.size());
  float clipUniforms[MaximumClipPlanes][4] = {};
  for (size_t i = 0; i < view.Clip.size(); ++i)
  {
    clipUniforms[i][0] = static_cast<float>(view.Clip[i].normal.x);
    clipUniforms[i][1] = static_cast<float>(view.Clip[i].normal.y);
    clipUniforms[i][2] = static_cast<float>(view.Clip[i].normal.z);
    clipUniforms[i][3] = static_cast<float>(view.Clip[i].offset);
  }
  std::copy(
    &clipUniforms[0][0], &clipUniforms[0][0] + 4 * MaximumClipPlanes, &frame.ClipPlanes[0][0]);
  frame.SliceSpacing = static_cast<float>(view.Spacing);
  frame.SlicePhase = static_cast<float>(SlicePhase);
  // A slice plane is drawn as a cut face.
  frame.SlicePlane = self->BlendMode == SLICE_BLEND;
  frame.BoundaryRerendering = (self->BoundaryRerendering != 0 && !composite) || frame.SlicePlane;
  frame.OpacityUnitDistance =
    static_cast<float>(std::max(1.0e-6, property->GetScalarOpacityUnitDistance(0)));
  frame.Parallel = view.Camera->GetParallelProjection() != 0;
  frame.FrontToBack = self->FrontToBack != 0;
  frame.Jitter = self->Jittering != 0 && self->BlendMode != SLICE_BLEND;
  frame.EarlyTermination =
    composite && !frame.SlicePlane && self->EarlyRayTermination && frame.FrontToBack;
  frame.TerminationInterval = self->EarlyRayTerminationInterval;
  frame.TerminationThreshold = static_cast<float>(self->EarlyRayTerminationThreshold);
  frame.TerminationPasses = 0;
  frame.HalfFloatTarget = self->HalfFloatTarget != 0;
  frame.CountSamples = self->CountSamples && frame.ComputeSlices;
  frame.Samples = -1;
  frame.TransferFunction2D =
    composite && property->GetTransferFunctionMode() == vtkVolumeProperty::TF_2D;
  if (frame.TransferFunction2D)
  {
    std::string tableError;
    if (!this->Resources.UpdateTransferFunction2D(
          window, property->GetTransferFunction2D(0), tableError))
    {
      vtkErrorWithObjectMacro(self, "Cannot use the 2D transfer function: " << tableError);
      return false;
    }
    // The table's y axis spans VTK's gradient magnitudes: [0, a quarter of the data range].
    frame.Gradient2DMaximum =
      static_cast<float>(0.25 * (range[1] > range[0] ? range[1] - range[0] : 1.0));
  }
  frame.SkipTransparentSamples = self->BlendMode == COMPOSITE_BLEND &&
    (self->EmptySpaceSkipping & SKIP_FRAGMENT) && !self->UsesLabelMap();
  this->FillComponentsAndMasks(self, scalars, property, view);
  frame.SkipEmptyLeaves = skipEmptyLeaves;
  self->LastTransparentLeafFraction =
    frame.SkipEmptyLeaves ? self->LastTransparentLeafFraction : -1.0;
  frame.LeafSize = static_cast<float>(self->OctreeLeafSize);
  int blocks[3];
  vtkAccelVolumeSliceResources::BlockGridOf(this->LeafGrid, blocks);
  for (int c = 0; c < 3; ++c)
  {
    frame.LeafGridMaximum[c] = static_cast<float>(std::max(0, this->LeafGrid[c] - 1));
    frame.BlockGridMaximum[c] = static_cast<float>(std::max(0, blocks[c] - 1));
  }
  this->FillShadingAndGradients(self, renderer, window, input, scalars, property, range, view);
  this->FillProjectionScales(self, property, range);
  self->GetFinalColorScaleAndBias(frame.ColourScale, frame.ColourBias);
  frame.SelectionMode = vtkAccelVolumeSelectionMode(renderer, frame.SelectionColour);
  frame.RenderToImage = self->RenderToImage != 0 && frame.SelectionMode == 0;
  frame.ColourImage = this->ColourImage;
  frame.DepthImage = this->DepthImage;
  frame.Vertices = &this->Vertices;
  frame.SliceRecords = &this->SliceRecords;
  return true;
}

bool vtkAccelVolumeSliceMapper::vtkInternals::DrawPasses(
  vtkAccelVolumeSliceMapper* self, vtkOpenGLRenderWindow* window, std::string& passError)
{
  if (this->Renderer.empty())
  {
    const char* name = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    this->Renderer = name ? name : "unknown";
  }
  vtkAccelVolumeSliceFrame& frame = this->Frame;
  this->Resources.Bricks.BeginFrame();
  this->Resources.BeginFrameTimer(); // the passes' GPU time (ended in Render)
  const bool rendered = vtkAccelVolumeRenderSlicePasses(window, this->Resources, frame, passError);
  self->LastNumberOfTerminationPasses = frame.TerminationPasses;
  self->LastNumberOfSamples = static_cast<vtkIdType>(frame.Samples);
  self->LastNumberOfBricks = static_cast<int>(this->Resources.GetBrickLayout().bricks.size());
  self->LastNumberOfBricksDrawn = static_cast<int>(frame.Bricks.size());
  self->LastNumberOfBrickUploads = this->Resources.Bricks.GetFrameUploads();
  self->LastUploadedBytes = static_cast<vtkIdType>(this->Resources.Bricks.GetFrameUploadedBytes());
  self->LastResidentBytes = static_cast<vtkIdType>(this->Resources.Bricks.GetResidentBytes());
  this->Resources.ReleaseEncodedScalarsIfResident();
  return rendered;
}

void vtkAccelVolumeSliceMapper::Render(vtkRenderer* renderer, vtkVolume* volume)
{
  vtkNew<vtkTimerLog> timer;
  timer->StartTimer();
  // StartEvent now; ProgressEvent after each stage (volume upload, octree and proxy geometry,
  // slice passes, GPU finish); ProgressEvent 1 and EndEvent on every return.
  vtkAccelVolumeRenderProgress progress(this);
  vtkInternals& internals = *this->Internals;
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(renderer->GetRenderWindow());
  if (!window)
  {
    vtkErrorMacro("vtkAccelVolumeSliceMapper needs an OpenGL render window");
    return;
  }
  const vtkAccelVolumePeelStage peel = vtkAccelVolumeGetPeelStage(window, volume, this);
  if (peel == vtkAccelVolumePeelStage::Later)
  {
    return; // drawn whole in the first volumetric stage of depth peeling
  }
  internals.Frame.ClearSecondTarget = peel == vtkAccelVolumePeelStage::OutsideRange;
  vtkImageData* input = nullptr;
  vtkDataArray* scalars = nullptr;
  std::string inputError;
  this->InputAdapter->Fetch(this, input, scalars, inputError);
  if (!this->ValidateInput(input, scalars, inputError, volume))
  {
    return;
  }
  this->WarnUnappliedSettings();
  double range[2];
  vtkAccelVolumeScalarRange(scalars, range);

  vtkVolumeProperty* property = volume->GetProperty();
  if (!internals.UploadVolume(this, window, input, scalars, property, range))
  {
    return;
  }
  vtkImageData* mask = internals.EffectiveMask(this, input);
  if (mask)
  {
    std::string maskError;
    if (!internals.Mask.Update(window, mask, input->GetDimensions(),
          mask == this->MaskInput && this->MaskType == LabelMapMaskType, maskError))
    {
      vtkErrorMacro(<< maskError);
      return;
    }
    if (this->UsesLabelMap())
    {
      internals.Mask.UpdateLabelTable(window, property, range);
    }
  }
  progress.Report(0.3); // the upload is the slow part of a first frame on a large volume

  vtkAccelVolumeSliceView view;
  if (!internals.SetUpView(this, renderer, volume, input, view))
  {
    return;
  }
  internals.ChooseSliceSpacing(this, volume, view);
  bool skipEmptyLeaves = false;
  vtkAccelVolumeSliceGeometryStats geometryStats;
  internals.BuildProxyGeometry(
    this, window, input, scalars, property, range, view, skipEmptyLeaves, geometryStats);
  progress.Report(0.45); // octree classification and proxy geometry
  this->LastSliceSpacing = view.Spacing;
  this->LastNumberOfSlices = geometryStats.Slices;
  this->LastNumberOfProxyPolygons = geometryStats.ProxyPolygons;
  this->LastNumberOfBoundaryFaces = geometryStats.BoundaryFaces;

  if (!internals.FillFrame(
        this, renderer, window, input, scalars, property, range, view, skipEmptyLeaves))
  {
    return;
  }
  std::string passError;
  const bool rendered = internals.DrawPasses(this, window, passError);
  if (rendered && this->RenderToImage && this->ClampDepthToBackface)
  {
    internals.ClampDepthImageToBackface(view);
  }
  progress.Report(0.6); // passes issued; the GPU may still be working on them

  // No wait for the GPU: the frame's time is its CPU time, or the GPU time of the latest frame
  // the timer queries returned when that is longer.
  internals.Resources.EndFrameTimer();
  timer->StopTimer();
  this->LastGPUTime = internals.Resources.GetLastGPUSeconds();
  this->LastRenderTime = std::max(timer->GetElapsedTime(), this->LastGPUTime);
  if (!rendered && !internals.ReportedError)
  {
    internals.ReportedError = true;
    vtkErrorMacro("Rendering failed: " << passError);
  }
}
