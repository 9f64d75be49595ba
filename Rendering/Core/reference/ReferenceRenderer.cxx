// ReferenceRenderer: CPU oracle for the projection blends, integrated finely along pixel rays.
#include "reference/ReferenceRenderer.h"

#include "reference/ReferenceCommon.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace accelvolume
{

namespace
{
using detail::StepCountSlack;

double ClampIndex(double coordinate, int count)
{
  return std::clamp(coordinate, 0.0, static_cast<double>(count - 1));
}

// Integrals accumulated over all regions of one ray.
struct RayAccumulator
{
  bool hit = false;
  float maximum = -std::numeric_limits<float>::infinity();
  float minimum = std::numeric_limits<float>::infinity();
  double weighted = 0; // integral of opacity(s) * s (times the indicator for Average)
  double length = 0;   // integral of the Average indicator
};
} // namespace

float ScalarVolume::Value(int i, int j, int k) const
{
  return values[static_cast<std::size_t>(i) +
    static_cast<std::size_t>(dims[0]) *
      (static_cast<std::size_t>(j) + static_cast<std::size_t>(dims[1]) * k)];
}

float ScalarVolume::SampleTrilinear(const Vec3& indexPoint) const
{
  const double p[3] = { ClampIndex(indexPoint.x, dims[0]), ClampIndex(indexPoint.y, dims[1]),
    ClampIndex(indexPoint.z, dims[2]) };
  int lower[3], upper[3];
  double fraction[3];
  for (int axis = 0; axis < 3; ++axis)
  {
    lower[axis] = std::min(static_cast<int>(p[axis]), dims[axis] - 1);
    upper[axis] = std::min(lower[axis] + 1, dims[axis] - 1);
    fraction[axis] = p[axis] - lower[axis];
  }
  auto lerp = [](double a, double b, double t) { return a + (b - a) * t; };
  const double x00 =
    lerp(Value(lower[0], lower[1], lower[2]), Value(upper[0], lower[1], lower[2]), fraction[0]);
  const double x10 =
    lerp(Value(lower[0], upper[1], lower[2]), Value(upper[0], upper[1], lower[2]), fraction[0]);
  const double x01 =
    lerp(Value(lower[0], lower[1], upper[2]), Value(upper[0], lower[1], upper[2]), fraction[0]);
  const double x11 =
    lerp(Value(lower[0], upper[1], upper[2]), Value(upper[0], upper[1], upper[2]), fraction[0]);
  return static_cast<float>(
    lerp(lerp(x00, x10, fraction[1]), lerp(x01, x11, fraction[1]), fraction[2]));
}

float ScalarVolume::SampleNearest(const Vec3& indexPoint) const
{
  auto nearest = [](double coordinate, int count)
  { return static_cast<int>(std::floor(ClampIndex(coordinate, count) + 0.5)); };
  return Value(std::min(nearest(indexPoint.x, dims[0]), dims[0] - 1),
    std::min(nearest(indexPoint.y, dims[1]), dims[1] - 1),
    std::min(nearest(indexPoint.z, dims[2]), dims[2] - 1));
}

float OpacityTable::Lookup(float normalizedScalar) const
{
  if (values.empty())
  {
    return 1;
  }
  const double position =
    std::clamp(static_cast<double>(normalizedScalar), 0.0, 1.0) * (values.size() - 1);
  const std::size_t lower = std::min(static_cast<std::size_t>(position), values.size() - 1);
  const std::size_t upper = std::min(lower + 1, values.size() - 1);
  const double fraction = position - lower;
  return static_cast<float>(values[lower] + (values[upper] - values[lower]) * fraction);
}

namespace
{
// Integrates one region interval [t0, t1] of the index-space ray into the accumulator; t is world
// length because the world direction has unit length.
void IntegrateInterval(const ScalarVolume& volume, const OpacityTable& opacity,
  const ReferenceOptions& options, const Vec3& origin, const Vec3& direction, double t0, double t1,
  RayAccumulator& accumulator)
{
  const double length = t1 - t0;
  const long long steps = length > 0
    ? std::max(1LL, static_cast<long long>(std::ceil(length / options.stepWorld - StepCountSlack)))
    : 0;
  const double step = steps > 0 ? length / steps : 0;
  accumulator.hit = true;
  for (long long n = 0; n <= steps; ++n)
  {
    const Vec3 point = origin + (t0 + n * step) * direction;
    const float s = options.nearest ? volume.SampleNearest(point) : volume.SampleTrilinear(point);
    // Trapezoid rule: the two end samples weigh half a step.
    const double weight = (n == 0 || n == steps) ? 0.5 * step : step;
    switch (options.blend)
    {
      case Blend::Maximum:
        accumulator.maximum = std::max(accumulator.maximum, s);
        break;
      case Blend::Minimum:
        accumulator.minimum = std::min(accumulator.minimum, s);
        break;
      case Blend::Additive:
        accumulator.weighted += weight * opacity.Lookup(s) * s;
        break;
      case Blend::Average:
        if (s >= options.averageRangeMin && s <= options.averageRangeMax)
        {
          accumulator.weighted += weight * opacity.Lookup(s) * s;
          accumulator.length += weight;
        }
        break;
      case Blend::Composite: // refused by RenderReference
      case Blend::Slice:
      case Blend::Isosurface:
        break;
    }
  }
}

ReferencePixel Finish(const RayAccumulator& accumulator, const ReferenceOptions& options)
{
  ReferencePixel pixel;
  switch (options.blend)
  {
    case Blend::Maximum:
      pixel.hit = accumulator.hit;
      pixel.value = accumulator.hit ? accumulator.maximum : 0.0f;
      break;
    case Blend::Minimum:
      pixel.hit = accumulator.hit;
      pixel.value = accumulator.hit ? accumulator.minimum : 0.0f;
      break;
    case Blend::Additive:
      pixel.hit = accumulator.hit;
      pixel.value = static_cast<float>(accumulator.weighted / options.additiveUnitDistance);
      break;
    case Blend::Average:
      pixel.hit = accumulator.length > 0;
      pixel.value =
        pixel.hit ? static_cast<float>(accumulator.weighted / accumulator.length) : 0.0f;
      break;
    case Blend::Composite: // refused by RenderReference
    case Blend::Slice:
    case Blend::Isosurface:
      break;
  }
  return pixel;
}
} // namespace

std::vector<ReferencePixel> RenderReference(const ScalarVolume& volume,
  const std::vector<Box>& regions, const std::vector<HalfSpace>& clip, const OpacityTable& opacity,
  const Camera& camera, int width, int height, const ReferenceOptions& options,
  const std::vector<double>* raysEnd)
{
  if (width <= 0 || height <= 0)
  {
    return {};
  }
  const std::size_t pixelCount = static_cast<std::size_t>(width) * height;
  constexpr const char* caller = "accelvolume::RenderReference";
  detail::CheckRaysEndAndStep(caller, pixelCount, raysEnd, options.stepWorld);
  detail::CheckVolume(caller, volume);
  if (options.blend == Blend::Composite || options.blend == Blend::Slice ||
    options.blend == Blend::Isosurface)
  {
    throw std::invalid_argument(std::string(caller) +
      ": composite is RenderReferenceComposite's blend, slice and isosurface the ray caster's");
  }
  const Affine worldToIndex = volume.indexToWorld.Inverse();
  std::vector<ReferencePixel> pixels(pixelCount);

  auto renderRow = [&](int j)
  {
    for (int i = 0; i < width; ++i)
    {
      const detail::IndexRay ray =
        detail::PixelIndexRay(worldToIndex, camera, width, height, i, j, raysEnd);
      RayAccumulator accumulator;
      for (const Box& region : regions)
      {
        double t0 = 0, t1 = 0;
        if (detail::ClipRayToRegion(ray, region, clip, t0, t1))
        {
          IntegrateInterval(
            volume, opacity, options, ray.origin, ray.direction, t0, t1, accumulator);
        }
      }
      pixels[static_cast<std::size_t>(j) * width + i] = Finish(accumulator, options);
    }
  };

  detail::ForEachRowInParallel(height, options.threads, renderRow);
  return pixels;
}

} // namespace accelvolume
