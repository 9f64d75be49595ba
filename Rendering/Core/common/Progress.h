// Progress: how far a long Core operation has got, reported to its caller (plain C++, no VTK).
//
// Core operations report progress only from the thread that called them, never from another
// worker of a ParallelFor, so a VTK face can invoke its observers (GUI progress bars) directly.
// A parallel loop reports without splitting its range or adding barriers: every finished item
// is counted, and whenever the calling thread (which works in the loop too, as vtkSMPTools'
// backends have it) finishes one it reports the fraction done, if that passed the next step.
// Images and structures stay bit-identical: Core results never depend on how a ParallelFor
// hands out its items.
#ifndef accelvolume_Progress_h
#define accelvolume_Progress_h

#include "common/ParallelFor.h"

#include <cstddef>
#include <functional>

namespace accelvolume
{

// Receives the fraction of an operation done, in [0, 1] and non-decreasing over the operation.
using ProgressFunction = std::function<void(double fraction)>;

// Reports a reporting loop makes at most (besides the final 1): enough for a smooth bar, few
// enough for observers to cost nothing.
constexpr std::size_t ProgressSteps = 16;

// Maps an operation's [0, 1] onto [begin, end] of a larger one. Empty when report is empty.
ProgressFunction ProgressRange(const ProgressFunction& report, double begin, double end);

// A ParallelFor for loops of heavy items (image tiles, volume slices): runs `parallel`, hands
// the body one item at a time, and reports the fraction of items done each time it passes
// another 1/steps, from the thread that called it (while the others keep working), and 1 when
// the loop is over. Without report it is `parallel` itself.
ParallelFor ReportingParallelFor(
  const ParallelFor& parallel, const ProgressFunction& report, std::size_t steps = ProgressSteps);

}

#endif
