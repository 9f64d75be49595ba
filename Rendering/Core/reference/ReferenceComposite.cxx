// ReferenceComposite: CPU oracle for front-to-back composite ray casting with opacity correction.
#include "reference/ReferenceComposite.h"

#include "reference/ReferenceCommon.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace accelvolume
{

namespace
{
using detail::StepCountSlack;

struct Rgb
{
  double r = 1, g = 1, b = 1;
};

// Same interpolation as OpacityTable::Lookup, so colour and opacity agree about which table entry a
// scalar falls on (as two GL 1D textures of the same size would).
Rgb LookupColour(const std::vector<float>& table, float normalizedScalar)
{
  const std::size_t count = table.size() / 3;
  if (count == 0)
  {
    return {};
  }
  const double position = std::clamp(static_cast<double>(normalizedScalar), 0.0, 1.0) * (count - 1);
  const std::size_t lower = std::min(static_cast<std::size_t>(position), count - 1);
  const std::size_t upper = std::min(lower + 1, count - 1);
  const double fraction = position - lower;
  auto channel = [&](std::size_t c)
  { return table[3 * lower + c] + (table[3 * upper + c] - table[3 * lower + c]) * fraction; };
  return { channel(0), channel(1), channel(2) };
}

struct Interval
{
  double t0, t1;
};

struct Accumulator
{
  double rgb[3] = { 0, 0, 0 };
  double alpha = 0;
};

// Composites one interval of the index-space ray; t is world length because the world direction
// has unit length.
void CompositeInterval(const ScalarVolume& volume, const std::vector<float>& colourTable,
  const OpacityTable& opacity, const CompositeOptions& options, const Vec3& origin,
  const Vec3& direction, const Interval& interval, Accumulator& accumulator)
{
  const double length = interval.t1 - interval.t0;
  if (!(length > 0))
  {
    return; // zero length: every corrected opacity would be 0
  }
  const long long steps =
    std::max(1LL, static_cast<long long>(std::ceil(length / options.stepWorld - StepCountSlack)));
  const double step = length / steps;
  const double exponent = step / options.opacityUnitDistance;
  for (long long n = 0; n < steps; ++n)
  {
    if (accumulator.alpha >= 1)
    {
      return; // fully opaque: (1 - A) is 0, further samples change nothing
    }
    const Vec3 point = origin + (interval.t0 + (n + 0.5) * step) * direction;
    const float s = options.nearest ? volume.SampleNearest(point) : volume.SampleTrilinear(point);
    const double tableAlpha = std::clamp(static_cast<double>(opacity.Lookup(s)), 0.0, 1.0);
    const double a = 1 - std::pow(1 - tableAlpha, exponent);
    if (a <= 0)
    {
      continue;
    }
    const Rgb c = LookupColour(colourTable, s);
    const double weight = (1 - accumulator.alpha) * a;
    accumulator.rgb[0] += weight * c.r;
    accumulator.rgb[1] += weight * c.g;
    accumulator.rgb[2] += weight * c.b;
    accumulator.alpha += weight;
  }
}
} // namespace

std::vector<CompositePixel> RenderReferenceComposite(const ScalarVolume& volume,
  const std::vector<Box>& regions, const std::vector<HalfSpace>& clip,
  const std::vector<float>& colourTable, const OpacityTable& opacity, const Camera& camera,
  int width, int height, const CompositeOptions& options, const std::vector<double>* raysEnd)
{
  if (width <= 0 || height <= 0)
  {
    return {};
  }
  const std::size_t pixelCount = static_cast<std::size_t>(width) * height;
  constexpr const char* caller = "accelvolume::RenderReferenceComposite";
  detail::CheckRaysEndAndStep(caller, pixelCount, raysEnd, options.stepWorld);
  if (!(options.opacityUnitDistance > 0))
  {
    throw std::invalid_argument(
      "accelvolume::RenderReferenceComposite: opacityUnitDistance must be positive");
  }
  if (colourTable.size() % 3 != 0)
  {
    throw std::invalid_argument(
      "accelvolume::RenderReferenceComposite: colourTable size is not a multiple of 3");
  }
  detail::CheckVolume(caller, volume);
  const Affine worldToIndex = volume.indexToWorld.Inverse();
  std::vector<CompositePixel> pixels(pixelCount);

  auto renderRow = [&](int j)
  {
    std::vector<Interval> intervals;
    for (int i = 0; i < width; ++i)
    {
      const detail::IndexRay ray =
        detail::PixelIndexRay(worldToIndex, camera, width, height, i, j, raysEnd);
      intervals.clear();
      for (const Box& region : regions)
      {
        double t0 = 0, t1 = 0;
        // Strictly positive length only: an empty interval composites nothing.
        if (detail::ClipRayToRegion(ray, region, clip, t0, t1) && t0 < t1)
        {
          intervals.push_back({ t0, t1 });
        }
      }
      // Front to back needs the regions in ray order, whatever order the caller listed them in;
      // stable so equal keys keep a fixed order and results stay deterministic.
      std::stable_sort(intervals.begin(), intervals.end(),
        [](const Interval& a, const Interval& b) { return a.t0 < b.t0; });
      Accumulator accumulator;
      for (const Interval& interval : intervals)
      {
        CompositeInterval(
          volume, colourTable, opacity, options, ray.origin, ray.direction, interval, accumulator);
      }
      CompositePixel& pixel = pixels[static_cast<std::size_t>(j) * width + i];
      for (int c = 0; c < 3; ++c)
      {
        pixel.rgba[c] = static_cast<float>(accumulator.rgb[c]);
      }
      pixel.rgba[3] = static_cast<float>(accumulator.alpha);
    }
  };

  detail::ForEachRowInParallel(height, options.threads, renderRow);
  return pixels;
}

} // namespace accelvolume
