// IndexRay: a pixel ray in volume index space clipped to a region, and the step-count rule that
// places samples; the ray caster and the CPU oracles share both, so they sample identically.
#ifndef accelvolume_IndexRay_h
#define accelvolume_IndexRay_h

#include "common/Affine.h"
#include "common/Camera.h"
#include "common/Geometry.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

namespace accelvolume
{
namespace detail
{

// Absorbs rounding in length / step so an exact multiple does not gain an extra tiny step; shared
// so every oracle places its samples identically.
inline constexpr double StepCountSlack = 1e-9;

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

} // namespace detail
} // namespace accelvolume

#endif
