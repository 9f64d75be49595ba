// ReferenceCommon: internal helpers shared by the CPU reference oracles (not installed API).
#ifndef accelvolume_ReferenceCommon_h
#define accelvolume_ReferenceCommon_h

#include "accelvolume/ReferenceRenderer.h"

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

// Absorbs rounding in length / step so an exact multiple does not gain an extra tiny step; shared
// so every oracle places its samples identically.
inline constexpr double StepCountSlack = 1e-9;

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

// A pixel ray in volume index space, with the world-length limit raysEnd puts on it.
struct IndexRay
{
  Vec3 origin;
  Vec3 direction;
  double end;
};

// The world direction has unit length, so t along the index-space ray is still world length and
// raysEnd applies to it unchanged.
inline IndexRay PixelIndexRay(const Affine& worldToIndex, const Camera& camera, int width,
  int height, int i, int j, const std::vector<double>* raysEnd)
{
  const std::size_t index = static_cast<std::size_t>(j) * width + i;
  const Ray ray = PixelRay(camera, width, height, i, j);
  return { worldToIndex.Apply(ray.origin), worldToIndex.ApplyLinear(ray.direction),
    raysEnd ? (*raysEnd)[index] : std::numeric_limits<double>::infinity() };
}

// Clips the ray's pass through one region to [0, end]; false when it misses the region, the
// clipped interval is inverted, or it is unbounded (nothing finite to integrate).
inline bool ClipRayToRegion(const IndexRay& ray, const Box& region,
  const std::vector<HalfSpace>& clip, double& t0, double& t1)
{
  t0 = 0;
  t1 = 0;
  if (!IntersectRayRegion(ray.origin, ray.direction, region, clip, t0, t1))
  {
    return false;
  }
  t0 = std::max(t0, 0.0);
  t1 = std::min(t1, ray.end);
  return t0 <= t1 && std::isfinite(t1);
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
