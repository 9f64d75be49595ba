// ParallelFor: how Core runs loops in parallel without depending on VTK (the VTK layer passes
// vtkSMPTools::For). Core results never depend on the ranges a ParallelFor hands out.
#ifndef accelvolume_ParallelFor_h
#define accelvolume_ParallelFor_h

#include <cstddef>
#include <functional>

namespace accelvolume
{

// Runs body(begin, end) over sub-ranges covering [0, count) (possibly concurrently).
// The VTK face passes vtkSMPTools::For; the default runs serially.
using ParallelFor =
  std::function<void(std::size_t count, const std::function<void(std::size_t, std::size_t)>& body)>;

// Exactly `threads` workers (the caller and threads - 1 others) taking chunks of [0, count)
// as they finish (dynamic balance). For a user's thread count: vtkSMPTools::LocalScope does not
// limit Debian VTK 9.1's TBB backend. An exception from body is rethrown on the caller.
ParallelFor FixedThreadsParallelFor(int threads);

} // namespace accelvolume

#endif
