// vtkAccelVolumeWorkers: the ParallelFor a CPU mapper hands its engine for a frame, with exactly
// the mapper's NumberOfThreads when it sets one. vtkSMPTools::LocalScope cannot be used for
// that: on consecutive scopes of the same thread count, Debian VTK 9.1's TBB backend leaves its
// task arena terminated and runs on every core (VTK's Initialize compares with the stale arena's
// concurrency and skips it). The workers are a TBB task arena kept between frames (no threads
// started per frame) where vtkSMPTools runs on TBB; otherwise (another backend chosen, or no
// TBB) std::threads per loop (FixedThreadsParallelFor).
#ifndef vtkAccelVolumeWorkers_h
#define vtkAccelVolumeWorkers_h

#include "common/ParallelFor.h"

#include <memory>

class vtkAccelVolumeWorkers
{
public:
  // threads > 0: exactly that many workers (the calling thread one of them); 0: vtkSMPTools'
  // own (vtkAccelVolumeSMPParallelFor). The ParallelFor stays valid after this object is gone.
  accelvolume::ParallelFor For(int threads);

private:
  struct Arena;
  std::shared_ptr<Arena> Kept; // the last thread count's arena
};

#endif
