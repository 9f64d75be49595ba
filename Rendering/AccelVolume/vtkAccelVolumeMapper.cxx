#include "vtkAccelVolumeMapper.h"

#include "vtkAccelVolumeInputAdapter.h"
#include "vtkAlgorithm.h"
#include "vtkDataSetAttributes.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>

vtkAccelVolumeMapper::vtkAccelVolumeMapper()
  : InputAdapter(new vtkAccelVolumeInputAdapter)
{
}

vtkAccelVolumeMapper::~vtkAccelVolumeMapper() = default;

void vtkAccelVolumeMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "EarlyRayTermination: " << this->EarlyRayTermination << "\n";
  os << indent << "EarlyRayTerminationThreshold: " << this->EarlyRayTerminationThreshold << "\n";
  os << indent << "LastRenderTime: " << this->LastRenderTime << "\n";
  os << indent << "FinalColorWindow: " << this->FinalColorWindow << "\n";
  os << indent << "FinalColorLevel: " << this->FinalColorLevel << "\n";
}

int vtkAccelVolumeMapper::IsRenderSupported(vtkRenderWindow* window, vtkVolumeProperty*)
{
  return !window || vtkOpenGLRenderWindow::SafeDownCast(window) ? 1 : 0;
}

void vtkAccelVolumeMapper::GetFinalColorScaleAndBias(float& scale, float& bias) const
{
  const float window = std::abs(this->FinalColorWindow) < 1.0e-6f
    ? std::copysign(1.0e-6f, this->FinalColorWindow)
    : this->FinalColorWindow;
  scale = 1.0f / window;
  bias = 0.5f - this->FinalColorLevel / window;
}

bool vtkAccelVolumeMapper::HasHiddenPoints(vtkImageData* image)
{
  vtkUnsignedCharArray* ghosts = image ? image->GetPointGhostArray() : nullptr;
  if (!ghosts)
  {
    return false;
  }
  if (ghosts != this->HiddenPointsArray || ghosts->GetMTime() != this->HiddenPointsTime)
  {
    this->HiddenPointsArray = ghosts;
    this->HiddenPointsTime = ghosts->GetMTime();
    this->HiddenPoints = false;
    for (vtkIdType i = 0; i < ghosts->GetNumberOfTuples() && !this->HiddenPoints; ++i)
    {
      this->HiddenPoints = (ghosts->GetValue(i) & vtkDataSetAttributes::HIDDENPOINT) != 0;
    }
  }
  return this->HiddenPoints;
}

void vtkAccelVolumeMapper::WarnNotApplicable(const char* member, const char* why)
{
  if (this->WarnedNotApplicable.insert(member).second)
  {
    vtkWarningMacro(<< member << " has no effect on " << this->GetClassName() << ": " << why);
  }
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
