// vtkAccelVolumeRenderProgress: Start / Progress / End events of one render, main thread only.
#include "vtkAccelVolumeRenderProgress.h"

#include "vtkAlgorithm.h"
#include "vtkCommand.h"
#include "vtkObject.h"

#include <algorithm>

namespace
{
// Smaller steps tell an observer nothing; dropping them bounds the events of a render.
constexpr double MinimumStep = 0.001;

void Fire(vtkObject* object, double fraction)
{
  if (auto* algorithm = vtkAlgorithm::SafeDownCast(object))
  {
    algorithm->UpdateProgress(fraction);
  }
  else
  {
    object->InvokeEvent(vtkCommand::ProgressEvent, &fraction);
  }
}
}

vtkAccelVolumeRenderProgress::vtkAccelVolumeRenderProgress(vtkObject* object)
  : Object(object)
  , Thread(std::this_thread::get_id())
{
  this->Observed = object->HasObserver(vtkCommand::ProgressEvent) != 0;
  object->InvokeEvent(vtkCommand::StartEvent, nullptr);
  Fire(object, 0.0);
}

vtkAccelVolumeRenderProgress::~vtkAccelVolumeRenderProgress()
{
  if (this->Last < 1.0)
  {
    this->Last = 1.0;
    Fire(this->Object, 1.0);
  }
  this->Object->InvokeEvent(vtkCommand::EndEvent, nullptr);
}

void vtkAccelVolumeRenderProgress::Report(double fraction)
{
  if (std::this_thread::get_id() != this->Thread)
  {
    return;
  }
  fraction = std::min(std::max(fraction, this->Last), 1.0);
  const bool finished = fraction >= 1.0 && this->Last < 1.0;
  if (!finished && fraction - this->Last < MinimumStep)
  {
    return;
  }
  this->Last = fraction;
  Fire(this->Object, fraction);
}

accelvolume::ProgressFunction vtkAccelVolumeRenderProgress::Range(double begin, double end)
{
  if (!this->Observed)
  {
    return accelvolume::ProgressFunction();
  }
  return accelvolume::ProgressRange(
    [this](double fraction) { this->Report(fraction); }, begin, end);
}
