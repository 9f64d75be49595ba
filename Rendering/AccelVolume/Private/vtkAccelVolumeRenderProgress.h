// vtkAccelVolumeRenderProgress: the StartEvent, ProgressEvent..., EndEvent sequence of one
// mapper Render (or one octree build), as VTK filters report progress. Not installed.
//
// Construction fires StartEvent and ProgressEvent 0; Report fires ProgressEvent with values kept
// in [0, 1] and non-decreasing (steps under 0.001 are dropped, so a render fires a bounded
// number of events); destruction fires ProgressEvent 1 (unless already sent) and EndEvent, so
// every return path of a Render closes the sequence, errors included. On a vtkAlgorithm the
// values go through UpdateProgress (ProgressShift / ProgressScale, vtkProgressObserver).
//
// Events are fired only on the thread that constructed the object: a report from any other
// thread is dropped, because observers (GUI progress bars) may only run on the main thread.
//
// Besides these, VTK's pipeline fires StartEvent, ProgressEvent 0 and 1 and EndEvent of its own
// when it re-executes a modified mapper (vtkVolume and vtkAbstractVolumeMapper::GetBounds call
// the mapper's Update(), a pass that does nothing): observers see that short sequence before
// the render's, and only after the mapper was modified.
#ifndef vtkAccelVolumeRenderProgress_h
#define vtkAccelVolumeRenderProgress_h

#include "common/Progress.h" // ProgressFunction

#include <thread>

class vtkObject;

class vtkAccelVolumeRenderProgress
{
public:
  explicit vtkAccelVolumeRenderProgress(vtkObject* object);
  ~vtkAccelVolumeRenderProgress();
  vtkAccelVolumeRenderProgress(const vtkAccelVolumeRenderProgress&) = delete;
  vtkAccelVolumeRenderProgress& operator=(const vtkAccelVolumeRenderProgress&) = delete;

  // Whether anyone observes the object's ProgressEvent (checked once, at construction): only
  // then do the engines count finished tiles and slices to report.
  bool IsObserved() const { return this->Observed; }

  // Fires ProgressEvent with `fraction` (clamped to [0, 1] and to the last value sent).
  void Report(double fraction);

  // A Core progress function reporting [begin, end] of this sequence; empty when nobody
  // observes, so the engines' loops run exactly as without progress.
  accelvolume::ProgressFunction Range(double begin, double end);

private:
  vtkObject* Object;
  std::thread::id Thread;
  bool Observed = false;
  double Last = 0;
};

#endif
