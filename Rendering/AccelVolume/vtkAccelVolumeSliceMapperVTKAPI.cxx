// vtkAccelVolumeSliceMapper: the members that exist for vtkGPUVolumeRayCastMapper's API (memory
// limits, partitions, masks and blanking, render-to-image images, depth pass, reduction ratio,
// render support) and the warnings for VTK settings it does not apply.
#include "vtkAccelVolumeSliceMapper.h"

#include "vtkAccelVolumeSliceMapperInternals.h"

#include "vtkContourValues.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkMatrix4x4.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPointData.h"
#include "vtkVolumeProperty.h"

#include "common/Geometry.h"

#include <algorithm>
#include <cmath>

void vtkAccelVolumeSliceMapper::SetMaxMemoryInBytes(vtkIdType bytes)
{
  this->MaxMemoryInBytes = std::max<vtkIdType>(0, bytes);
  this->SetGPUMemoryBudget(
    static_cast<vtkIdType>(static_cast<double>(this->MaxMemoryInBytes) * this->MaxMemoryFraction));
  this->Modified();
}

void vtkAccelVolumeSliceMapper::SetMaxMemoryFraction(float fraction)
{
  this->MaxMemoryFraction = std::min(1.0f, std::max(0.1f, fraction));
  this->SetMaxMemoryInBytes(this->MaxMemoryInBytes);
}

void vtkAccelVolumeSliceMapper::SetPartitions(unsigned short x, unsigned short y, unsigned short z)
{
  const unsigned short wanted[3] = { std::max<unsigned short>(1, x), std::max<unsigned short>(1, y),
    std::max<unsigned short>(1, z) };
  if (!std::equal(wanted, wanted + 3, this->Partitions))
  {
    std::copy(wanted, wanted + 3, this->Partitions);
    this->Modified();
  }
}

void vtkAccelVolumeSliceMapper::SetMaskInput(vtkImageData* mask)
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

vtkContourValues* vtkAccelVolumeSliceMapper::GetDepthPassContourValues()
{
  if (!this->DepthPassContourValues)
  {
    this->DepthPassContourValues = vtkContourValues::New();
  }
  return this->DepthPassContourValues;
}

bool vtkAccelVolumeSliceMapper::UsesLabelMap() const
{
  return this->MaskInput && this->MaskType == LabelMapMaskType && this->MaskBlendFactor > 0 &&
    this->BlendMode == COMPOSITE_BLEND;
}

double vtkAccelVolumeSliceMapper::GetLastProxyAreaFraction()
{
  if (this->Internals->AreaFractionPending)
  {
    this->Internals->AreaFractionPending = false;
    this->LastProxyAreaFraction = vtkAccelVolumeSliceKeptAreaFraction(this->Internals->AreaInput);
  }
  return this->LastProxyAreaFraction;
}

void vtkAccelVolumeSliceMapper::GetReductionRatio(double ratio[3])
{
  ratio[0] = ratio[1] = ratio[2] = 1.0;
}

int vtkAccelVolumeSliceMapper::IsRenderSupported(
  vtkRenderWindow* window, vtkVolumeProperty* property)
{
  if (window && !vtkOpenGLRenderWindow::SafeDownCast(window))
  {
    return 0;
  }
  (void)property; // every property the mapper accepts renders with OpenGL 3.2
  return 1;
}

bool vtkAccelVolumeSliceMapper::UsesDepthPass() const
{
  return this->UseDepthPass && this->BlendMode == COMPOSITE_BLEND && this->DepthPassContourValues &&
    this->DepthPassContourValues->GetNumberOfContours() > 0;
}

void vtkAccelVolumeSliceMapper::WarnUnappliedSettings()
{
  if (this->UseDepthPass && this->BlendMode == COMPOSITE_BLEND && !this->UsesDepthPass())
  {
    this->WarnNotApplicable(
      "UseDepthPass without contour values", "the volume is drawn without a depth pass");
  }
  if (!this->ReportProgress)
  {
    this->WarnNotApplicable("ReportProgress", "progress events are always sent");
  }
  if (this->ColorRangeType != SCALAR || this->ScalarOpacityRangeType != SCALAR ||
    this->GradientOpacityRangeType != SCALAR)
  {
    this->WarnNotApplicable("NATIVE transfer-function ranges", "the tables span the data range");
  }
  if (this->Transfer2DYAxisArray && *this->Transfer2DYAxisArray)
  {
    this->WarnNotApplicable(
      "Transfer2DYAxisArray", "the 2D transfer function's y axis is the gradient magnitude");
  }
}

void vtkAccelVolumeSliceMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SampleDistance: " << this->SampleDistance << "\n";
  os << indent << "AutoAdjustSampleDistances: " << this->AutoAdjustSampleDistances << "\n";
  os << indent << "NumberOfSlices: " << this->NumberOfSlices << "\n";
  os << indent << "MaximumNumberOfSlices: " << this->MaximumNumberOfSlices << "\n";
  os << indent << "BoundaryRerendering: " << this->BoundaryRerendering << "\n";
  os << indent << "SlabSamples: " << this->SlabSamples << "\n";
  os << indent << "GPUSliceGeneration: " << this->GPUSliceGeneration << "\n";
  os << indent << "HalfFloatTarget: " << this->HalfFloatTarget << "\n";
  os << indent << "SliceCompositing: " << this->SliceCompositing << "\n";
  os << indent << "LastSliceCompositing: " << this->LastSliceCompositing << "\n";
  os << indent << "CountSamples: " << this->CountSamples << "\n";
  os << indent << "LastNumberOfSamples: " << this->LastNumberOfSamples << "\n";
  os << indent << "EmptySpaceSkipping: " << this->EmptySpaceSkipping << "\n";
  os << indent << "FrontToBack: " << this->FrontToBack << "\n";
  os << indent << "PrecomputeGradients: " << this->PrecomputeGradients << "\n";
  os << indent << "Jittering: " << this->Jittering << "\n";
  os << indent << "OctreeLeafSize: " << this->OctreeLeafSize << "\n";
  os << indent << "OctreeBuilder: " << this->OctreeBuilder << "\n";
  os << indent << "LastOctreeBuilder: " << this->LastOctreeBuilder << "\n";
  os << indent << "EarlyRayTerminationInterval: " << this->EarlyRayTerminationInterval << "\n";
  os << indent << "LastNumberOfTerminationPasses: " << this->LastNumberOfTerminationPasses << "\n";
  os << indent << "AdditiveUnitDistance: " << this->AdditiveUnitDistance << "\n";
  os << indent << "LastSliceSpacing: " << this->LastSliceSpacing << "\n";
  os << indent << "LastNumberOfSlices: " << this->LastNumberOfSlices << "\n";
  os << indent << "LastNumberOfProxyPolygons: " << this->LastNumberOfProxyPolygons << "\n";
  os << indent << "LastNumberOfBoundaryFaces: " << this->LastNumberOfBoundaryFaces << "\n";
  os << indent << "GPUMemoryBudget: " << this->GPUMemoryBudget << "\n";
  os << indent << "MaximumBrickSize: " << this->MaximumBrickSize << "\n";
  os << indent << "LastNumberOfBricks: " << this->LastNumberOfBricks << "\n";
  os << indent << "LastNumberOfBricksDrawn: " << this->LastNumberOfBricksDrawn << "\n";
  os << indent << "LastNumberOfBrickUploads: " << this->LastNumberOfBrickUploads << "\n";
  os << indent << "LastUploadedBytes: " << this->LastUploadedBytes << "\n";
  os << indent << "LastResidentBytes: " << this->LastResidentBytes << "\n";
  os << indent << "LockSampleDistanceToInputSpacing: " << this->LockSampleDistanceToInputSpacing
     << "\n";
  os << indent << "ImageSampleDistance: " << this->ImageSampleDistance << "\n";
  os << indent << "MinimumImageSampleDistance: " << this->MinimumImageSampleDistance << "\n";
  os << indent << "MaximumImageSampleDistance: " << this->MaximumImageSampleDistance << "\n";
  os << indent << "MaxMemoryInBytes: " << this->MaxMemoryInBytes << "\n";
  os << indent << "MaxMemoryFraction: " << this->MaxMemoryFraction << "\n";
  os << indent << "Partitions: " << this->Partitions[0] << " " << this->Partitions[1] << " "
     << this->Partitions[2] << "\n";
  os << indent << "MaskInput: " << this->MaskInput << "\n";
  os << indent << "MaskType: " << this->MaskType << "\n";
  os << indent << "MaskBlendFactor: " << this->MaskBlendFactor << "\n";
  os << indent << "RenderToImage: " << this->RenderToImage << "\n";
  os << indent << "UseDepthPass: " << this->UseDepthPass << "\n";
}

vtkImageData* vtkAccelVolumeSliceMapper::vtkInternals::EffectiveMask(
  vtkAccelVolumeSliceMapper* self, vtkImageData* input)
{
  vtkImageData* user = self->MaskInput;
  const bool userBinary = user && self->MaskType == BinaryMaskType;
  this->UsedGhostMask = false;
  if (user && !userBinary)
  {
    return user; // a label map keeps its own meaning; hidden points are then drawn
  }
  if (vtkAccelVolumeHiddenPointsMask(input, user, this->GhostMask, this->GhostMaskTime))
  {
    this->UsedGhostMask = true;
    return this->GhostMask;
  }
  return user;
}

void vtkAccelVolumeSliceMapper::GetDepthImage(vtkImageData* image)
{
  if (!image)
  {
    return;
  }
  vtkImageData* depth = this->Internals->DepthImage;
  if (depth->GetNumberOfPoints() == 0)
  {
    image->Initialize();
    return;
  }
  // VTK's DepthImageScalarType: float window depth, or scaled to the integer type's range.
  if (this->DepthImageScalarType != VTK_UNSIGNED_CHAR &&
    this->DepthImageScalarType != VTK_UNSIGNED_SHORT)
  {
    image->DeepCopy(depth);
    return;
  }
  image->SetDimensions(depth->GetDimensions());
  image->AllocateScalars(this->DepthImageScalarType, 1);
  const auto* in = static_cast<const float*>(depth->GetScalarPointer());
  const double scale = this->DepthImageScalarType == VTK_UNSIGNED_CHAR ? 255.0 : 65535.0;
  vtkDataArray* out = image->GetPointData()->GetScalars();
  for (vtkIdType i = 0; i < depth->GetNumberOfPoints(); ++i)
  {
    out->SetComponent(i, 0, std::floor(std::min(1.0f, std::max(0.0f, in[i])) * scale + 0.5));
  }
}

void vtkAccelVolumeSliceMapper::GetColorImage(vtkImageData* image)
{
  if (!image)
  {
    return;
  }
  if (this->Internals->ColourImage->GetNumberOfPoints() == 0)
  {
    image->Initialize();
    return;
  }
  image->DeepCopy(this->Internals->ColourImage);
}

void vtkAccelVolumeSliceMapper::vtkInternals::ClampDepthImageToBackface(
  const vtkAccelVolumeSliceView& view)
{
  vtkImageData* depth = this->DepthImage;
  if (depth->GetNumberOfPoints() == 0)
  {
    return;
  }
  int dims[3];
  depth->GetDimensions(dims);
  auto* values = static_cast<float*>(depth->GetScalarPointer());
  vtkNew<vtkMatrix4x4> clipToIndex;
  vtkMatrix4x4::Invert(view.IndexToClip, clipToIndex);
  const auto unproject = [&](double x, double y, double z)
  {
    double point[4] = { x, y, z, 1.0 };
    clipToIndex->MultiplyPoint(point, point);
    return accelvolume::Vec3{ point[0] / point[3], point[1] / point[3], point[2] / point[3] };
  };
  for (int j = 0; j < dims[1]; ++j)
  {
    for (int i = 0; i < dims[0]; ++i)
    {
      float& value = values[static_cast<size_t>(j) * dims[0] + i];
      if (value < 1.0f)
      {
        continue;
      }
      const double x = 2.0 * (i + 0.5) / dims[0] - 1.0;
      const double y = 2.0 * (j + 0.5) / dims[1] - 1.0;
      const accelvolume::Vec3 nearPoint = unproject(x, y, -1.0);
      const accelvolume::Vec3 direction = unproject(x, y, 1.0) - nearPoint;
      double enter = 0.0;
      double leave = 0.0;
      if (!accelvolume::IntersectRayRegion(
            nearPoint, direction, view.VolumeBox, view.Clip, enter, leave) ||
        leave < 0.0 || enter > 1.0)
      {
        continue;
      }
      const accelvolume::Vec3 entry = nearPoint + std::max(enter, 0.0) * direction;
      double clip[4] = { entry.x, entry.y, entry.z, 1.0 };
      view.IndexToClip->MultiplyPoint(clip, clip);
      value = static_cast<float>(std::min(1.0, std::max(0.0, 0.5 * clip[2] / clip[3] + 0.5)));
    }
  }
}
