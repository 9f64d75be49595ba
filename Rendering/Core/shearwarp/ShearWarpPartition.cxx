// Sheared-space partition of the intermediate scanlines into balanced bands.
#include "shearwarp/ShearWarpPartition.h"

#include <algorithm>
#include <cmath>

namespace accelvolume
{

std::vector<int> EqualBands(int count, int parts)
{
  parts = std::max(parts, 1);
  count = std::max(count, 0);
  std::vector<int> bounds(static_cast<std::size_t>(parts) + 1);
  for (int b = 0; b <= parts; ++b)
  {
    bounds[b] = static_cast<int>(static_cast<long long>(count) * b / parts);
  }
  return bounds;
}

std::vector<int> BalanceBands(const std::vector<double>& cost, int parts)
{
  parts = std::max(parts, 1);
  const int count = static_cast<int>(cost.size());
  std::vector<double> prefix(cost.size() + 1, 0.0);
  for (int v = 0; v < count; ++v)
  {
    const double c = cost[v] > 0 ? cost[v] : 0.0; // NaN and negatives count as zero
    prefix[v + 1] = prefix[v] + c;
  }
  const double total = prefix.back();
  if (!(total > 0) || !std::isfinite(total))
  {
    return EqualBands(count, parts);
  }
  std::vector<int> bounds(static_cast<std::size_t>(parts) + 1, count);
  bounds[0] = 0;
  for (int b = 1; b < parts; ++b)
  {
    const double target = total * b / parts;
    // First scanline boundary whose running cost reaches the target, or the one just before it
    // when that is closer.
    int at = static_cast<int>(std::lower_bound(prefix.begin(), prefix.end(), target) - prefix.begin());
    if (at > 0 && target - prefix[at - 1] < prefix[std::min(at, count)] - target)
    {
      --at;
    }
    bounds[b] = std::min(std::max(at, bounds[b - 1]), count);
  }
  return bounds;
}

std::vector<double> ResampleCosts(const std::vector<double>& cost, int count)
{
  std::vector<double> resampled(static_cast<std::size_t>(std::max(count, 0)), 0.0);
  const int old = static_cast<int>(cost.size());
  if (old == 0 || count <= 0)
  {
    return resampled;
  }
  // Spread each old scanline's cost over the new scanlines it overlaps, by overlap length.
  const double ratio = static_cast<double>(count) / old;
  for (int v = 0; v < old; ++v)
  {
    const double c = cost[v] > 0 ? cost[v] : 0.0;
    const double begin = v * ratio;
    const double end = (v + 1) * ratio;
    for (int w = static_cast<int>(begin); w < count && w < end; ++w)
    {
      const double overlap = std::min(end, w + 1.0) - std::max(begin, static_cast<double>(w));
      if (overlap > 0)
      {
        resampled[w] += c * overlap / ratio;
      }
    }
  }
  return resampled;
}

double Imbalance(const std::vector<double>& bandCost)
{
  if (bandCost.empty())
  {
    return 1.0;
  }
  double sum = 0;
  double largest = 0;
  for (double c : bandCost)
  {
    sum += c;
    largest = std::max(largest, c);
  }
  const double mean = sum / static_cast<double>(bandCost.size());
  return mean > 0 ? largest / mean : 1.0;
}

}
