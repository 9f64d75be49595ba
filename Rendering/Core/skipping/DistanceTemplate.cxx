// DistanceTemplate: the per-axis step-count tables of the distance template (Lim and Shin 2008), and the
// conservative lookup that replaces a ray-box exit computation per leap.
//
// Never overestimating takes two guards on top of the paper's integer lookup:
// - rounding: the distance to the exit face is lowered by a margin relative to the magnitudes
//   involved (SafetyRelative * (1 + |position| + |face|)), far above the few ulps by which
//   position + j * step (evaluated directly, not accumulated) can differ from exact arithmetic;
// - callers whose |step| exceeds the template's maximum step on an axis get an exact division
//   for that axis instead of a wrong table entry.
// The integer lookup floor(m) loses less than one cell of distance per axis: at most
// floor(1 / |step|) + 1 samples against the exact floor(m / |step|) when |step| is the maximum,
// one sample for steps longer than a cell, more for finer sampling (the price of a table indexed
// by whole cells).
#include "skipping/DistanceTemplate.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace accelvolume
{

namespace
{
// Step counts saturate here (axes with maximum step 0, or tiny steps): far beyond any ray.
constexpr std::int64_t StepCap = std::int64_t(1) << 30;
constexpr double SafetyRelative = 1e-9;

double Component(const Vec3& v, int axis)
{
  return axis == 0 ? v.x : (axis == 1 ? v.y : v.z);
}

// floor(distance / step) for distance >= 0 and step > 0, never above the true quotient (the
// division's rounding is corrected by multiplying back), saturated at StepCap.
std::int64_t StepsWithin(double distance, double step)
{
  const double quotient = std::floor(distance / step);
  if (!(quotient < static_cast<double>(StepCap))) // also catches NaN and inf
  {
    return StepCap;
  }
  std::int64_t q = std::max<std::int64_t>(0, static_cast<std::int64_t>(quotient));
  while (q > 0 && static_cast<double>(q) * step > distance)
  {
    --q;
  }
  while (q + 1 < StepCap && static_cast<double>(q + 1) * step <= distance)
  {
    ++q;
  }
  return q;
}
}

void DistanceTemplate::Build(const double maximumStep[3], int maximumDistance)
{
  this->MaximumDistance = std::max(maximumDistance, 1);
  for (int a = 0; a < 3; ++a)
  {
    const double step = maximumStep[a];
    std::vector<std::int64_t>& steps = this->Steps[a];
    steps.resize(static_cast<std::size_t>(this->MaximumDistance) + 1);
    for (int m = 0; m <= this->MaximumDistance; ++m)
    {
      // A zero maximum step never leaves along this axis. Negative or NaN maxima are invalid:
      // their entries are never used, as no |step| passes StepsInside's bound check.
      steps[m] = step > 0 ? StepsWithin(static_cast<double>(m), step) : StepCap;
    }
  }
  this->MaximumStep[0] = maximumStep[0];
  this->MaximumStep[1] = maximumStep[1];
  this->MaximumStep[2] = maximumStep[2];
}

std::int64_t DistanceTemplate::StepsInside(
  const Box& box, const Vec3& position, const Vec3& step) const
{
  const bool built = this->MaximumDistance > 0;
  std::int64_t result = -1; // no limit yet
  for (int a = 0; a < 3; ++a)
  {
    const double p = Component(position, a);
    const double lower = Component(box.lower, a);
    const double upper = Component(box.upper, a);
    // Outside the box (or NaN): not even the current sample is inside, nor any later one on
    // this axis for sure; answering 0 is always safe.
    if (!(p >= lower && p <= upper))
    {
      return 0;
    }
    const double s = Component(step, a);
    if (s == 0)
    {
      continue; // the ray never leaves through this axis
    }
    if (!std::isfinite(s))
    {
      return 0; // NaN or infinite steps leave at once
    }
    const double face = s > 0 ? upper : lower;
    const double distance =
      (s > 0 ? upper - p : p - lower) - SafetyRelative * (1.0 + std::fabs(p) + std::fabs(face));
    if (!(distance >= 0))
    {
      return 0;
    }
    const double size = std::fabs(s);
    std::int64_t axisSteps;
    if (built && size <= this->MaximumStep[a])
    {
      // distance is finite here (it passed >= 0 from finite values), so the clamp is exact.
      const double whole = std::min(std::floor(distance), double(this->MaximumDistance));
      axisSteps = this->Steps[a][static_cast<std::size_t>(whole)];
    }
    else
    {
      axisSteps = StepsWithin(distance, size); // outside the template's contract: exact
    }
    result = result < 0 ? axisSteps : std::min(result, axisSteps);
  }
  if (result < 0)
  {
    // No axis moves: saturate at the template's largest entry.
    result = 0;
    for (int a = 0; a < 3 && built; ++a)
    {
      result = std::max(result, this->Steps[a][static_cast<std::size_t>(this->MaximumDistance)]);
    }
    result = built ? result : StepCap;
  }
  return result;
}

}
