// vtkAccelVolumeWorkers: a kept TBB task arena of the mapper's thread count.
#include "vtkAccelVolumeWorkers.h"

#include "vtkAccelVolumeMapperSupport.h"
#include "vtkSMPTools.h"

#include <cstring>

#if ACCELVOLUME_HAVE_TBB
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#endif

struct vtkAccelVolumeWorkers::Arena
{
  explicit Arena(int threads)
    : Threads(threads)
#if ACCELVOLUME_HAVE_TBB
    , Workers(threads)
#endif
  {
  }
  int Threads;
#if ACCELVOLUME_HAVE_TBB
  tbb::task_arena Workers;
#endif
};

accelvolume::ParallelFor vtkAccelVolumeWorkers::For(int threads)
{
  if (threads <= 0)
  {
    return vtkAccelVolumeSMPParallelFor();
  }
#if ACCELVOLUME_HAVE_TBB
  // One thread is the caller alone (FixedThreadsParallelFor starts none). TBB only where
  // vtkSMPTools runs on TBB itself: a process that chose another backend (the sanitizer builds
  // choose STDThread, whose hand-offs ThreadSanitizer can follow) gets plain threads too.
  if (threads == 1 || std::strcmp(vtkSMPTools::GetBackend(), "TBB") != 0)
  {
    return accelvolume::FixedThreadsParallelFor(threads);
  }
  if (!this->Kept || this->Kept->Threads != threads)
  {
    this->Kept = std::make_shared<Arena>(threads);
  }
  std::shared_ptr<Arena> arena = this->Kept;
  return [arena](std::size_t count, const std::function<void(std::size_t, std::size_t)>& body)
  {
    if (count == 0)
    {
      return;
    }
    // One item per range, as vtkAccelVolumeSMPParallelFor: the items are heavy (bands, tiles).
    arena->Workers.execute(
      [&]()
      {
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 1),
          [&](const tbb::blocked_range<std::size_t>& range) { body(range.begin(), range.end()); });
      });
  };
#else
  return accelvolume::FixedThreadsParallelFor(threads);
#endif
}
