#include "vtkAccelVolumeMapper.h"

#include "vtkAlgorithm.h"
#include "vtkInformation.h"

vtkAccelVolumeMapper::vtkAccelVolumeMapper() = default;

vtkAccelVolumeMapper::~vtkAccelVolumeMapper() = default;

void vtkAccelVolumeMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "EarlyRayTermination: " << this->EarlyRayTermination << "\n";
  os << indent << "EarlyRayTerminationThreshold: " << this->EarlyRayTerminationThreshold << "\n";
  os << indent << "LastRenderTime: " << this->LastRenderTime << "\n";
}

double* vtkAccelVolumeMapper::GetBounds()
{
  if (this->GetNumberOfInputConnections(0) == 0 && this->GetMTime() > this->MissingInputReportTime)
  {
    this->MissingInputReportTime.Modified();
    vtkErrorMacro("No input: connect a vtkImageData to the mapper");
  }
  return this->Superclass::GetBounds();
}

int vtkAccelVolumeMapper::FillInputPortInformation(int port, vtkInformation* info)
{
  this->Superclass::FillInputPortInformation(port, info);
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  return 1;
}
