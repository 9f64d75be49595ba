// Progress: progress ranges and reporting parallel loops.
#include "common/Progress.h"

#include <algorithm>
#include <atomic>
#include <thread>

namespace accelvolume
{

ProgressFunction ProgressRange(const ProgressFunction& report, double begin, double end)
{
  if (!report)
  {
    return ProgressFunction();
  }
  return [report, begin, end](double fraction)
  {
    const double clamped = std::min(std::max(fraction, 0.0), 1.0);
    report(begin + (end - begin) * clamped);
  };
}

ParallelFor ReportingParallelFor(
  const ParallelFor& parallel, const ProgressFunction& report, std::size_t steps)
{
  if (!report)
  {
    return parallel;
  }
  steps = std::max<std::size_t>(steps, 1);
  return [parallel, report, steps](
           std::size_t count, const std::function<void(std::size_t, std::size_t)>& body)
  {
    const std::thread::id caller = std::this_thread::get_id();
    std::atomic<std::size_t> done{ 0 };
    std::size_t reportedStep = 0; // read and written by the calling thread only
    parallel(count,
      [&](std::size_t begin, std::size_t end)
      {
        const bool calling = std::this_thread::get_id() == caller;
        for (std::size_t item = begin; item < end; ++item)
        {
          body(item, item + 1);
          const std::size_t finished = done.fetch_add(1, std::memory_order_relaxed) + 1;
          if (calling)
          {
            const std::size_t step = finished * steps / count;
            if (step > reportedStep && finished < count)
            {
              reportedStep = step;
              report(static_cast<double>(finished) / static_cast<double>(count));
            }
          }
        }
      });
    report(1.0);
  };
}

}
