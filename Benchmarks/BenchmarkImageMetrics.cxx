#include "BenchmarkImageMetrics.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace accelvolume::benchmark
{
namespace
{
double Cross(const Point2& o, const Point2& a, const Point2& b)
{
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

double SegmentDistance(const Point2& p, const Point2& a, const Point2& b)
{
  const double dx = b.x - a.x;
  const double dy = b.y - a.y;
  const double length2 = dx * dx + dy * dy;
  double t = length2 > 0 ? ((p.x - a.x) * dx + (p.y - a.y) * dy) / length2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  const double ex = a.x + t * dx - p.x;
  const double ey = a.y + t * dy - p.y;
  return std::sqrt(ex * ex + ey * ey);
}

double Grey(const std::vector<std::uint8_t>& rgb, size_t pixel)
{
  return (rgb[3 * pixel] + rgb[3 * pixel + 1] + rgb[3 * pixel + 2]) / 3.0;
}
}

std::vector<Point2> ConvexHull(std::vector<Point2> points)
{
  std::sort(points.begin(), points.end(),
    [](const Point2& a, const Point2& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  if (points.size() < 3)
  {
    return points;
  }
  std::vector<Point2> hull(2 * points.size());
  size_t k = 0;
  for (size_t i = 0; i < points.size(); ++i)
  {
    while (k >= 2 && Cross(hull[k - 2], hull[k - 1], points[i]) <= 0)
    {
      --k;
    }
    hull[k++] = points[i];
  }
  for (size_t i = points.size() - 1, lower = k + 1; i > 0; --i)
  {
    while (k >= lower && Cross(hull[k - 2], hull[k - 1], points[i - 1]) <= 0)
    {
      --k;
    }
    hull[k++] = points[i - 1];
  }
  hull.resize(k - 1);
  return hull;
}

std::vector<std::uint8_t> PolygonMask(const std::vector<Point2>& polygon, int width, int height)
{
  std::vector<std::uint8_t> mask(static_cast<size_t>(width) * height, 0);
  const size_t n = polygon.size();
  if (n < 3)
  {
    return mask;
  }
  for (int j = 0; j < height; ++j)
  {
    for (int i = 0; i < width; ++i)
    {
      const Point2 p{ i + 0.5, j + 0.5 };
      bool inside = true;
      for (size_t e = 0; e < n && inside; ++e)
      {
        inside = Cross(polygon[e], polygon[(e + 1) % n], p) >= 0; // counter-clockwise hull
      }
      mask[static_cast<size_t>(j) * width + i] = inside ? 1 : 0;
    }
  }
  return mask;
}

std::vector<std::uint8_t> OutlineBandMask(
  const std::vector<Point2>& polygon, int width, int height, double radius)
{
  std::vector<std::uint8_t> mask(static_cast<size_t>(width) * height, 0);
  const size_t n = polygon.size();
  for (int j = 0; j < height; ++j)
  {
    for (int i = 0; i < width; ++i)
    {
      const Point2 p{ i + 0.5, j + 0.5 };
      for (size_t e = 0; e < n; ++e)
      {
        if (SegmentDistance(p, polygon[e], polygon[(e + 1) % n]) <= radius)
        {
          mask[static_cast<size_t>(j) * width + i] = 1;
          break;
        }
      }
    }
  }
  return mask;
}

std::vector<std::uint8_t> NonBackgroundMask(
  const std::vector<std::uint8_t>& rgb, int width, int height, int threshold)
{
  std::vector<std::uint8_t> mask(static_cast<size_t>(width) * height, 0);
  for (size_t p = 0; p < mask.size(); ++p)
  {
    mask[p] =
      (rgb[3 * p] > threshold || rgb[3 * p + 1] > threshold || rgb[3 * p + 2] > threshold) ? 1 : 0;
  }
  return mask;
}

std::vector<std::uint8_t> MaskOr(
  const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b)
{
  std::vector<std::uint8_t> result(a.size());
  for (size_t p = 0; p < a.size(); ++p)
  {
    result[p] = (a[p] || b[p]) ? 1 : 0;
  }
  return result;
}

std::vector<std::uint8_t> MaskAnd(
  const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b)
{
  std::vector<std::uint8_t> result(a.size());
  for (size_t p = 0; p < a.size(); ++p)
  {
    result[p] = (a[p] && b[p]) ? 1 : 0;
  }
  return result;
}

double ErrorStats::Rms() const
{
  return this->Pixels > 0 ? std::sqrt(this->SumSquared / static_cast<double>(this->Pixels)) : 0.0;
}

double ErrorStats::AboveFraction() const
{
  return this->Pixels > 0 ? static_cast<double>(this->Above) / static_cast<double>(this->Pixels)
                          : 0.0;
}

void ErrorStats::Add(const ErrorStats& other)
{
  this->SumSquared += other.SumSquared;
  this->Max = std::max(this->Max, other.Max);
  this->Pixels += other.Pixels;
  this->Above += other.Above;
}

ErrorStats CompareImages(const std::vector<std::uint8_t>& reference,
  const std::vector<std::uint8_t>& image, const std::vector<std::uint8_t>& mask,
  double aboveThreshold)
{
  ErrorStats stats;
  for (size_t p = 0; p < mask.size(); ++p)
  {
    if (!mask[p])
    {
      continue;
    }
    const double difference = std::abs(Grey(image, p) - Grey(reference, p));
    stats.SumSquared += difference * difference;
    stats.Max = std::max(stats.Max, difference);
    ++stats.Pixels;
    if (difference > aboveThreshold)
    {
      ++stats.Above;
    }
  }
  return stats;
}

std::vector<std::uint8_t> DifferenceImage(
  const std::vector<std::uint8_t>& reference, const std::vector<std::uint8_t>& image, double gain)
{
  std::vector<std::uint8_t> result(reference.size());
  for (size_t p = 0; p < reference.size() / 3; ++p)
  {
    const double signedDifference = Grey(image, p) - Grey(reference, p);
    const auto value =
      static_cast<std::uint8_t>(std::clamp(std::abs(signedDifference) * gain, 0.0, 255.0));
    // Red: darker than the reference (missed samples), green: brighter.
    result[3 * p] = signedDifference < 0 ? value : 0;
    result[3 * p + 1] = signedDifference > 0 ? value : 0;
    result[3 * p + 2] = 0;
  }
  return result;
}

ErrorStats CompareVisible(const std::vector<std::uint8_t>& reference,
  const std::vector<std::uint8_t>& image, int width, int height, double aboveThreshold)
{
  return CompareImages(reference, image,
    MaskOr(NonBackgroundMask(reference, width, height), NonBackgroundMask(image, width, height)),
    aboveThreshold);
}

ByteDifferences CompareBytes(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b)
{
  ByteDifferences result;
  result.Max = a.size() == b.size() ? 0 : 255;
  for (std::size_t p = 0; p + 2 < a.size() && p + 2 < b.size(); p += 3)
  {
    int differs = 0;
    for (std::size_t channel = p; channel < p + 3; ++channel)
    {
      differs = std::max(differs, std::abs(int(a[channel]) - int(b[channel])));
    }
    result.Pixels += differs > 0;
    result.Max = std::max(result.Max, differs);
  }
  return result;
}

} // namespace accelvolume::benchmark
