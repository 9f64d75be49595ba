// ReferenceCommon: internal helpers shared by the CPU reference oracles (not installed API).
#ifndef accelvolume_ReferenceCommon_h
#define accelvolume_ReferenceCommon_h

#include "common/IndexRay.h"
#include "reference/ReferenceRenderer.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace accelvolume
{
namespace detail
{


// Checks common to every oracle, in the order the oracles have always reported them; `caller`
// prefixes the message so each oracle's exceptions keep their own name.
inline void CheckRaysEndAndStep(
  const char* caller, std::size_t pixelCount, const std::vector<double>* raysEnd, double stepWorld)
{
  if (raysEnd && raysEnd->size() != pixelCount)
  {
    throw std::invalid_argument(std::string(caller) + ": raysEnd size != width * height");
  }
  if (!(stepWorld > 0))
  {
    throw std::invalid_argument(std::string(caller) + ": stepWorld must be positive");
  }
}

// Kept apart from CheckRaysEndAndStep because the composite oracle checks its own options between
// the two, and which error wins when several arguments are bad must not change.
inline void CheckVolume(const char* caller, const ScalarVolume& volume)
{
  if (volume.dims[0] <= 0 || volume.dims[1] <= 0 || volume.dims[2] <= 0 ||
    volume.values.size() !=
      static_cast<std::size_t>(volume.dims[0]) * volume.dims[1] * volume.dims[2])
  {
    throw std::invalid_argument(std::string(caller) + ": values do not match dims");
  }
}


// Calls body(j) once for every row in [0, height) on up to `threads` threads (0 = hardware
// concurrency), the calling thread included.
template <typename RowBody>
void ForEachRowInParallel(int height, int threads, RowBody&& body)
{
  const unsigned hardware = std::max(1u, std::thread::hardware_concurrency());
  const int threadCount = std::min(height, threads > 0 ? threads : static_cast<int>(hardware));
  // Rows are handed out dynamically; each pixel is computed alone, so results ignore scheduling.
  std::atomic<int> nextRow{ 0 };
  auto work = [&]()
  {
    for (int j = nextRow++; j < height; j = nextRow++)
    {
      body(j);
    }
  };
  std::vector<std::thread> workers;
  for (int t = 1; t < threadCount; ++t)
  {
    workers.emplace_back(work);
  }
  work();
  for (std::thread& worker : workers)
  {
    worker.join();
  }
}

} // namespace detail
} // namespace accelvolume

#endif
