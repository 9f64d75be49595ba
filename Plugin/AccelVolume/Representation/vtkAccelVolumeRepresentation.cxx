// ParaView's image volume representation with AccelVolume's smart mapper as the volume mapper.
#include "vtkAccelVolumeRepresentation.h"

#include "vtkAccelVolumeMapper.h"
#include "vtkAccelVolumeRayCastMapper.h"
#include "vtkAccelVolumeShearWarpMapper.h"
#include "vtkAccelVolumeSliceMapper.h"
#include "vtkAccelVolumeSmartMapper.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"

#include <algorithm>
#include <cmath>

vtkStandardNewMacro(vtkAccelVolumeRepresentation);

vtkAccelVolumeRepresentation::vtkAccelVolumeRepresentation()
{
  // The superclass made a vtkMultiBlockVolumeMapper; every later use (input, scalar array,
  // blend mode, cropping, Actor->SetMapper in UpdateMapperParameters) goes through this
  // pointer, so replacing it is all it takes to render with our mapper.
  this->VolumeMapper = this->Mapper.GetPointer();
}

vtkAccelVolumeRepresentation::~vtkAccelVolumeRepresentation() = default;

vtkAccelVolumeSmartMapper* vtkAccelVolumeRepresentation::GetAccelVolumeMapper()
{
  return this->Mapper;
}

static_assert(vtkAccelVolumeRepresentation::MAPPER_SMART == vtkAccelVolumeSmartMapper::DEFAULT_RENDER &&
    vtkAccelVolumeRepresentation::MAPPER_SLICE == vtkAccelVolumeSmartMapper::SLICE_RENDER &&
    vtkAccelVolumeRepresentation::MAPPER_RAYCAST == vtkAccelVolumeSmartMapper::RAYCAST_RENDER &&
    vtkAccelVolumeRepresentation::MAPPER_SHEARWARP == vtkAccelVolumeSmartMapper::SHEARWARP_RENDER,
  "MapperType values are the smart mapper's render modes");

void vtkAccelVolumeRepresentation::SetMapperType(int type)
{
  if (type != MAPPER_SLICE && type != MAPPER_RAYCAST && type != MAPPER_SHEARWARP)
  {
    type = MAPPER_SMART;
  }
  if (type != this->MapperType)
  {
    this->MapperType = type;
    this->Modified();
  }
}

void vtkAccelVolumeRepresentation::SetEarlyRayTermination(bool enable)
{
  if (enable != this->EarlyRayTermination)
  {
    this->EarlyRayTermination = enable;
    this->Modified();
  }
}

void vtkAccelVolumeRepresentation::SetEmptySpaceSkipping(int mode)
{
  mode = std::min(std::max(mode, static_cast<int>(vtkAccelVolumeSliceMapper::SKIP_NONE)),
    static_cast<int>(vtkAccelVolumeSliceMapper::SKIP_BOTH));
  if (mode != this->EmptySpaceSkipping)
  {
    this->EmptySpaceSkipping = mode;
    this->Modified();
  }
}

void vtkAccelVolumeRepresentation::SetBoundaryRerendering(bool enable)
{
  if (enable != this->BoundaryRerendering)
  {
    this->BoundaryRerendering = enable;
    this->Modified();
  }
}

void vtkAccelVolumeRepresentation::SetNumberOfThreads(int threads)
{
  threads = std::min(std::max(threads, 0), 1024);
  if (threads != this->NumberOfThreads)
  {
    this->NumberOfThreads = threads;
    this->Modified();
  }
}

void vtkAccelVolumeRepresentation::SetSampleDistance(double distance)
{
  distance = std::max(distance, 0.0);
  if (distance != this->SampleDistance)
  {
    this->SampleDistance = distance;
    this->Modified();
  }
}

void vtkAccelVolumeRepresentation::UpdateMapperParameters()
{
  this->Superclass::UpdateMapperParameters();

  this->Mapper->SetRequestedRenderMode(this->MapperType);
  // A vtkAccelVolumeMapper setting: the smart mapper forwards it to the mapper it picks.
  this->Mapper->SetEarlyRayTermination(this->EarlyRayTermination);

  // The automatic sample distance is the smallest voxel spacing. Only ranks holding data
  // have the cache; the others render the outline only.
  double distance = this->SampleDistance;
  if (distance <= 0.0)
  {
    if (auto* image = vtkImageData::SafeDownCast(this->Cache))
    {
      const double* spacing = image->GetSpacing();
      distance = std::min({ std::abs(spacing[0]), std::abs(spacing[1]), std::abs(spacing[2]) });
    }
  }

  vtkAccelVolumeSliceMapper* slice = this->Mapper->GetSliceMapper();
  slice->SetEmptySpaceSkipping(this->EmptySpaceSkipping);
  slice->SetBoundaryRerendering(this->BoundaryRerendering);
  // Automatic: the slice mapper's own adjustment (smallest spacing, coarser while interacting).
  slice->SetAutoAdjustSampleDistances(this->SampleDistance <= 0.0);
  if (this->SampleDistance > 0.0)
  {
    slice->SetSampleDistance(this->SampleDistance);
  }

  vtkAccelVolumeRayCastMapper* rayCast = this->Mapper->GetRayCastMapper();
  rayCast->SetNumberOfThreads(this->NumberOfThreads);
  if (distance > 0.0)
  {
    // Still frames use SampleDistance; interactive ones twice it, as the mapper's defaults.
    rayCast->SetSampleDistance(distance);
    rayCast->SetInteractiveSampleDistance(2.0 * distance);
  }

  vtkAccelVolumeShearWarpMapper* shearWarp = this->Mapper->GetShearWarpMapper();
  shearWarp->SetNumberOfThreads(this->NumberOfThreads);
}

int vtkAccelVolumeRepresentation::GetLastRenderMode()
{
  return this->Mapper->GetLastRenderMode();
}

const char* vtkAccelVolumeRepresentation::GetLastChoiceReason()
{
  return this->Mapper->GetLastChoiceReason();
}

double vtkAccelVolumeRepresentation::GetLastRenderTime()
{
  // The chosen mapper's own time, whichever it was (vtkAccelVolumeMapper::GetLastRenderTime).
  vtkAccelVolumeMapper* last = nullptr;
  switch (this->Mapper->GetLastRenderMode())
  {
    case MAPPER_SLICE:
      last = this->Mapper->GetSliceMapper();
      break;
    case MAPPER_RAYCAST:
      last = this->Mapper->GetRayCastMapper();
      break;
    case MAPPER_SHEARWARP:
      last = this->Mapper->GetShearWarpMapper();
      break;
    default:
      break;
  }
  return last ? last->GetLastRenderTime() : 0.0;
}

double vtkAccelVolumeRepresentation::GetLastRenderWork()
{
  switch (this->Mapper->GetLastRenderMode())
  {
    case MAPPER_SLICE:
      return this->Mapper->GetSliceMapper()->GetLastNumberOfSlices();
    case MAPPER_RAYCAST:
      return static_cast<double>(this->Mapper->GetRayCastMapper()->GetLastNumberOfSamples());
    case MAPPER_SHEARWARP:
      return static_cast<double>(this->Mapper->GetShearWarpMapper()->GetLastNumberOfSamples());
    default:
      return 0.0;
  }
}

void vtkAccelVolumeRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent
     << "MapperType: " << vtkAccelVolumeSmartMapper::GetRenderModeAsString(this->MapperType)
     << "\n";
  os << indent << "EarlyRayTermination: " << this->EarlyRayTermination << "\n";
  os << indent << "EmptySpaceSkipping: " << this->EmptySpaceSkipping << "\n";
  os << indent << "BoundaryRerendering: " << this->BoundaryRerendering << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
  os << indent << "SampleDistance: " << this->SampleDistance << "\n";
  os << indent << "Mapper:\n";
  this->Mapper->PrintSelf(os, indent.GetNextIndent());
}
