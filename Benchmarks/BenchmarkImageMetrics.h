// Image comparison helpers of the cropping benchmark: projected crop-box footprint, the band
// along its outline, and error statistics of an 8-bit RGB image against a reference image.
#ifndef accelvolume_benchmark_BenchmarkImageMetrics_h
#define accelvolume_benchmark_BenchmarkImageMetrics_h

#include <cstdint>
#include <vector>

namespace accelvolume::benchmark
{

struct Point2
{
  double x = 0;
  double y = 0;
};

// Convex hull (counter-clockwise, no repeated first point) of a point set; Andrew's monotone chain.
std::vector<Point2> ConvexHull(std::vector<Point2> points);

// One byte per pixel (row 0 at the bottom, like OpenGL / VTK display coordinates): 1 where the
// pixel centre (i + 0.5, j + 0.5) lies inside the polygon.
std::vector<std::uint8_t> PolygonMask(const std::vector<Point2>& polygon, int width, int height);

// 1 where the pixel centre lies within `radius` pixels of the polygon outline (either side).
std::vector<std::uint8_t> OutlineBandMask(
  const std::vector<Point2>& polygon, int width, int height, double radius);

// 1 where any channel of the RGB image is above `threshold` (0..255).
std::vector<std::uint8_t> NonBackgroundMask(
  const std::vector<std::uint8_t>& rgb, int width, int height, int threshold = 0);

// Elementwise OR / AND of two masks of the same size.
std::vector<std::uint8_t> MaskOr(
  const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b);
std::vector<std::uint8_t> MaskAnd(
  const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b);

// Accumulated error of grey levels (mean of R, G, B; 0..255) over the pixels of a mask.
struct ErrorStats
{
  double SumSquared = 0; // sum of squared differences (grey levels^2)
  double Max = 0;        // largest absolute difference (grey levels)
  long long Pixels = 0;  // pixels in the mask
  long long Above = 0;   // pixels whose absolute difference exceeds the threshold

  double Rms() const;
  double AboveFraction() const;
  void Add(const ErrorStats& other); // pool (e.g. over several views)
};

ErrorStats CompareImages(const std::vector<std::uint8_t>& reference,
  const std::vector<std::uint8_t>& image, const std::vector<std::uint8_t>& mask,
  double aboveThreshold);

// CompareImages over the pixels non-black in either image (the black background would dilute the
// RMS by the empty share of the window).
ErrorStats CompareVisible(const std::vector<std::uint8_t>& reference,
  const std::vector<std::uint8_t>& image, int width, int height, double aboveThreshold = 2.0);

// Pixels whose RGB bytes differ at all, and the largest byte difference (255 when the sizes
// differ).
struct ByteDifferences
{
  long long Pixels = 0;
  int Max = 0;
};
ByteDifferences CompareBytes(
  const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b);

// |image - reference| of the grey levels scaled by `gain`, clamped, as RGB (for inspection).
std::vector<std::uint8_t> DifferenceImage(
  const std::vector<std::uint8_t>& reference, const std::vector<std::uint8_t>& image, double gain);

} // namespace accelvolume::benchmark

#endif
