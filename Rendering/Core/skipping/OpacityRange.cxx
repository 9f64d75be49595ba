// OpacityRange: the emptiness rule of MinMaxOctree::Classify as a reusable object (prefix count
// over the opacity table, then O(1) per value range).
#include "skipping/OpacityRange.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace accelvolume
{

namespace
{
constexpr double Infinity = std::numeric_limits<double>::infinity();
// TransparentBelow nudges its answer by single ulps onto the exact table position; a handful of
// steps suffices (the first guess is within a few ulps), the cap only guards the loop.
constexpr int MaximumNudges = 64;

// The rule on table positions a <= b: 1 when some entry in [floor(a), ceil(b)], after clamping
// both to [0, last], is opaque (prefix: the opaque-entry prefix count). zero must be 0.0 but
// should not be a compile-time constant: against a literal 0 GCC compiles the clamp to a branch,
// which mispredicts on noisy data (many cells touch the lowest value); against a variable it
// emits maxsd.
inline std::uint8_t RuleOnPositions(
  double a, double b, double zero, double last, const std::size_t* prefix)
{
  // Clamp before converting, so infinite bounds stay well defined (written so that a NaN
  // position, from a NaN bound the caller masks out, becomes 0 rather than undefined).
  a = a > zero ? a : zero;
  a = a < last ? a : last;
  b = b > zero ? b : zero;
  b = b < last ? b : last;
  // Non-negative now, so truncation is floor; avoids libm floor/ceil calls (this runs per
  // node or cell on every transfer-function edit). Through a signed type: double to unsigned
  // conversion is branchy on x86-64.
  const std::int64_t first = static_cast<std::int64_t>(a);
  std::int64_t lastIndex = static_cast<std::int64_t>(b);
  lastIndex += static_cast<double>(lastIndex) < b ? 1 : 0;
  return prefix[lastIndex + 1] != prefix[first] ? 1 : 0;
}
}

OpacityRange::OpacityRange(
  const std::vector<float>& opacity, double rangeMin, double rangeMax, float threshold)
  : RangeMin(rangeMin)
  , RangeMax(rangeMax)
  , Count(opacity.size())
{
  this->Prefix.assign(this->Count + 1, 0);
  for (std::size_t m = 0; m < this->Count; ++m)
  {
    // NaN entries compare false: transparent.
    this->Prefix[m + 1] = this->Prefix[m] + (opacity[m] > threshold ? 1 : 0);
  }
  const double last = this->Count > 0 ? static_cast<double>(this->Count - 1) : 0.0;
  const double range = rangeMax - rangeMin;
  // A non-finite range (NaN or overflowing bounds) has no usable map: every value sees the
  // whole table, which is conservative.
  this->Unmapped = !std::isfinite(range);
  // Table positions per scalar unit. One multiply per bound (not a divide): faster, and exact
  // when values land on table entries with N - 1 == rangeMax - rangeMin (e.g. 8-bit tables).
  // The arithmetic must stay as it is: TransparentBelow and the tests rely on it.
  this->Scale = (range != 0.0 && !this->Unmapped) ? last / range : 0.0;
  // A denormal range can overflow the scale; positions would turn NaN (0 * inf).
  this->Unmapped = this->Unmapped || !std::isfinite(this->Scale);
}

inline bool OpacityRange::PositionsMayBeOpaque(double a, double b) const
{
  const double last = static_cast<double>(this->Count - 1);
  return RuleOnPositions(a, b, last * 0.0, last, this->Prefix.data()) != 0;
}

bool OpacityRange::MayBeOpaque(double minimum, double maximum) const
{
  // Empty and all-NaN ranges (min > max); the negated test also catches NaN bounds.
  if (!(minimum <= maximum) || this->Count == 0)
  {
    return false;
  }
  if (this->Count == 1 || this->Unmapped)
  {
    // One entry is a constant opacity; the whole table applies.
    return this->Prefix[this->Count] > 0;
  }
  if (this->RangeMax == this->RangeMin)
  {
    // A step at rangeMin: below -> entry 0, above -> entry N-1, on it -> either (whole table).
    std::size_t first = 0;
    std::size_t lastIndex = this->Count - 1;
    if (maximum < this->RangeMin)
    {
      lastIndex = 0;
    }
    else if (minimum > this->RangeMin)
    {
      first = this->Count - 1;
    }
    return this->Prefix[lastIndex + 1] - this->Prefix[first] > 0;
  }
  // Positions of the bounds; a decreasing map (negative scale) swaps them.
  double a = (minimum - this->RangeMin) * this->Scale;
  double b = (maximum - this->RangeMin) * this->Scale;
  if (a > b)
  {
    std::swap(a, b);
  }
  return this->PositionsMayBeOpaque(a, b);
}

void OpacityRange::MayBeOpaque(
  const double* minimum, const double* maximum, std::size_t count, std::uint8_t* result) const
{
  const bool general = this->Count >= 2 && !this->Unmapped && this->RangeMax != this->RangeMin;
  if (!general)
  {
    for (std::size_t i = 0; i < count; ++i)
    {
      result[i] = this->MayBeOpaque(minimum[i], maximum[i]) ? 1 : 0;
    }
    return;
  }
  // Branch-free per range (the scalar call's branches mispredict on noisy data): the map's
  // direction is fixed, so the lower position comes from the same bound every time (for
  // minimum <= maximum the scalar call's swap picks the same one, rounding being monotone);
  // empty and NaN ranges are computed harmlessly and masked.
  // Members are copied to locals: the byte stores to result could alias them otherwise.
  const double* low = this->Scale > 0 ? minimum : maximum;
  const double* high = this->Scale > 0 ? maximum : minimum;
  const double rangeMin = this->RangeMin;
  const double scale = this->Scale;
  const double last = static_cast<double>(this->Count - 1);
  const double zero = last * 0.0; // see RuleOnPositions
  const std::size_t* prefix = this->Prefix.data();
  for (std::size_t i = 0; i < count; ++i)
  {
    const std::uint8_t valid = minimum[i] <= maximum[i] ? 1 : 0;
    const std::uint8_t opaque = RuleOnPositions(
      (low[i] - rangeMin) * scale, (high[i] - rangeMin) * scale, zero, last, prefix);
    result[i] = valid & opaque;
  }
}

double OpacityRange::TransparentBelow() const
{
  if (this->Count == 0 || this->Prefix[this->Count] == 0)
  {
    return Infinity; // nothing is opaque
  }
  // First opaque entry: Prefix is non-decreasing, Prefix[firstOpaque + 1] is the first nonzero.
  const std::size_t firstOpaque = static_cast<std::size_t>(
    std::upper_bound(this->Prefix.begin(), this->Prefix.end(), std::size_t(0)) -
    this->Prefix.begin() - 1);
  if (firstOpaque == 0 || this->Count == 1 || this->Unmapped)
  {
    // Entry 0 opaque (the lowest values get it), a constant opaque table, or no usable map.
    return -Infinity;
  }
  if (this->RangeMax == this->RangeMin)
  {
    // Step: values below rangeMin get entry 0, which is transparent here.
    return this->RangeMin;
  }
  if (this->RangeMin > this->RangeMax)
  {
    return -Infinity; // decreasing maps are not supported (documented)
  }
  // Entries 0 .. firstOpaque-1 are transparent, so values whose table position is at most
  // P = firstOpaque - 1 interpolate between transparent entries only. Return the largest value
  // whose position, computed with MayBeOpaque's arithmetic, is <= P: values below it then map
  // to positions <= P too (rounding is monotone), so MayBeOpaque agrees that they are
  // transparent, not only exact arithmetic.
  const double position = static_cast<double>(firstOpaque - 1);
  const auto mapsBelow = [this, position](double value)
  { return (value - this->RangeMin) * this->Scale <= position; };
  double t = this->RangeMin + position / this->Scale;
  for (int n = 0; n < MaximumNudges && !mapsBelow(t); ++n)
  {
    t = std::nextafter(t, -Infinity);
  }
  if (!mapsBelow(t))
  {
    return this->RangeMin; // unreachable in practice; position 0 is always safe
  }
  for (int n = 0; n < MaximumNudges && mapsBelow(std::nextafter(t, Infinity)); ++n)
  {
    t = std::nextafter(t, Infinity);
  }
  return t;
}

}
