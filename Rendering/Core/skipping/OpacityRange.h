// OpacityRange: "can any value in [min, max] get a non-zero opacity?" for an opacity table,
// in O(1) after an O(N) prefix count. Shared by the min-max octree's classification and the
// ray caster's per-cell classification so both judge emptiness by one rule.
#ifndef accelvolume_OpacityRange_h
#define accelvolume_OpacityRange_h

#include <cstddef>
#include <cstdint>
#include <vector>

namespace accelvolume
{

class OpacityRange
{
public:
  // opacity: N entries sampled evenly over [rangeMin, rangeMax] of the raw scalar values and
  // linearly interpolated in between (outside values clamp to the ends). Same conventions as
  // MinMaxOctree::Classify (rangeMin > rangeMax maps decreasingly, rangeMin == rangeMax is a
  // step, N == 1 constant, empty table: everything transparent).
  OpacityRange(
    const std::vector<float>& opacity, double rangeMin, double rangeMax, float threshold = 0.0f);

  // True when some value in [minimum, maximum] may get opacity > threshold (exact for
  // threshold 0 and non-negative opacities, conservative otherwise). minimum > maximum
  // (an empty or all-NaN range) is transparent.
  bool MayBeOpaque(double minimum, double maximum) const;

  // MayBeOpaque for count ranges at once (result[i] = 1 or 0), identical to the one-range
  // call; runs the loop-invariant branches once (per-cell classification calls it per row).
  void MayBeOpaque(
    const double* minimum, const double* maximum, std::size_t count, std::uint8_t* result) const;

  // The largest value t such that every value < t has opacity <= threshold (values decreasing
  // maps are not supported: returns -inf then). -inf when entry 0 is already opaque, +inf when
  // nothing is opaque.
  // For an increasing map with first opaque entry i > 0, t is the value at table position i - 1
  // (rangeMin + (i - 1) (rangeMax - rangeMin) / (N - 1)), rounded so that MayBeOpaque(-inf, t)
  // is false and MayBeOpaque(-inf, nextafter(t, +inf)) true: values <= t are transparent also
  // under MayBeOpaque's floating-point arithmetic. A step (rangeMin == rangeMax) answers
  // rangeMin (values below get the transparent entry 0); N == 1 answers -inf or +inf; a
  // non-finite range with any opaque entry answers -inf.
  double TransparentBelow() const;

private:
  std::vector<std::size_t> Prefix; // Prefix[i]: entries > threshold among the first i
  double RangeMin = 0, RangeMax = 0;
  std::size_t Count = 0;
  // Table positions per scalar unit, (N - 1) / (rangeMax - rangeMin); 0 for a step or N <= 1.
  double Scale = 0;
  // The range or the scale is not finite (NaN or overflowing bounds, a denormal range): every
  // value sees the whole table.
  bool Unmapped = false;

  // MayBeOpaque's general case (N >= 2, finite nonzero range): the rule on table positions
  // a <= b before clamping.
  bool PositionsMayBeOpaque(double a, double b) const;
};

}

#endif
