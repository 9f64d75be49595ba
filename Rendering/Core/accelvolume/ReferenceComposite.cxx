// ReferenceComposite: CPU oracle for front-to-back composite ray casting with opacity correction.
#include "accelvolume/ReferenceComposite.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <thread>

namespace accelvolume
{

namespace
{
// Absorbs rounding in length / step so an exact multiple does not gain an extra tiny step
// (the same slack RenderReference uses).
constexpr double StepCountSlack = 1e-9;

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
  if (raysEnd && raysEnd->size() != pixelCount)
  {
    throw std::invalid_argument(
      "accelvolume::RenderReferenceComposite: raysEnd size != width * height");
  }
  if (!(options.stepWorld > 0))
  {
    throw std::invalid_argument(
      "accelvolume::RenderReferenceComposite: stepWorld must be positive");
  }
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
  if (volume.dims[0] <= 0 || volume.dims[1] <= 0 || volume.dims[2] <= 0 ||
    volume.values.size() !=
      static_cast<std::size_t>(volume.dims[0]) * volume.dims[1] * volume.dims[2])
  {
    throw std::invalid_argument("accelvolume::RenderReferenceComposite: values do not match dims");
  }
  const Affine worldToIndex = volume.indexToWorld.Inverse();
  std::vector<CompositePixel> pixels(pixelCount);

  auto renderRow = [&](int j)
  {
    std::vector<Interval> intervals;
    for (int i = 0; i < width; ++i)
    {
      const std::size_t index = static_cast<std::size_t>(j) * width + i;
      const Ray ray = PixelRay(camera, width, height, i, j);
      const Vec3 origin = worldToIndex.Apply(ray.origin);
      const Vec3 direction = worldToIndex.ApplyLinear(ray.direction);
      const double end = raysEnd ? (*raysEnd)[index] : std::numeric_limits<double>::infinity();
      intervals.clear();
      for (const Box& region : regions)
      {
        double t0 = 0, t1 = 0;
        if (!IntersectRayRegion(origin, direction, region, clip, t0, t1))
        {
          continue;
        }
        t0 = std::max(t0, 0.0);
        t1 = std::min(t1, end);
        if (t0 < t1 && std::isfinite(t1))
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
          volume, colourTable, opacity, options, origin, direction, interval, accumulator);
      }
      CompositePixel& pixel = pixels[index];
      for (int c = 0; c < 3; ++c)
      {
        pixel.rgba[c] = static_cast<float>(accumulator.rgb[c]);
      }
      pixel.rgba[3] = static_cast<float>(accumulator.alpha);
    }
  };

  const unsigned hardware = std::max(1u, std::thread::hardware_concurrency());
  const int threadCount =
    std::min(height, options.threads > 0 ? options.threads : static_cast<int>(hardware));
  // Rows are handed out dynamically; each pixel is computed alone, so results ignore scheduling.
  std::atomic<int> nextRow{ 0 };
  auto work = [&]()
  {
    for (int j = nextRow++; j < height; j = nextRow++)
    {
      renderRow(j);
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
  return pixels;
}

} // namespace accelvolume
