// DistanceTemplate (after Lim and Shin 2008, "A distance template for octree traversal in CPU-based
// volume ray casting", 2008): precomputed step counts that take a ray out of an empty octree
// node without a ray-box intersection per leap.
//
// A ray takes samples p_k = p_0 + k s (index space). Inside an empty node's box, let m_a be the
// distance (in cells) from the sample to the box face the ray leaves through along axis a. The
// template holds, per axis, steps[a][m] = floor(m / |s_a|max) for integer m: the ray stays in
// the box for that many more samples along that axis. |s_a|max is the largest |s_a| over the
// rays sharing the template (a tile of pixels), so one template serves them all,
// conservatively.
#ifndef accelvolume_DistanceTemplate_h
#define accelvolume_DistanceTemplate_h

#include "common/Geometry.h" // Box, Vec3

#include <cstdint>
#include <vector>

namespace accelvolume
{

class DistanceTemplate
{
public:
  // maximumStep: the largest |s_a| per axis over the rays using the template (>= 0);
  // maximumDistance: the largest box extent in cells that will be asked about (>= 1; smaller
  // values are raised to 1). Farther exit faces are looked up at maximumDistance: still safe,
  // only shorter. A zero maximumStep[a] makes axis a's entries 2^30 (the ray never leaves
  // through it); counts are floor(m / maximumStep[a]) corrected for the division's rounding
  // (never above the true quotient), saturated at 2^30.
  void Build(const double maximumStep[3], int maximumDistance);

  // Samples after the current one (at `position`, inside `box`) that still lie in the box
  // (faces included) for a ray with per-sample step `step` (|step[a]| <= maximumStep[a]).
  // Never overestimates; saturates at the template's largest entry for axes with step 0.
  // Precisely: for every j in [1, result], position + j * step (evaluated directly in double,
  // not accumulated sample by sample) lies in the box. Axes with step 0 impose no limit; when
  // no axis moves the answer is the template's largest entry (2^30 for a zero maximum step).
  // A position outside the box or a non-finite step answers 0. An axis with |step[a]| >
  // maximumStep[a] (a caller bug), or an unbuilt template, gets the exact floor(m_a / |step[a]|)
  // instead of the table. Against the exact count, the whole-cell lookup loses at most
  // floor(1 / maximumStep[a]) + 1 samples (one for steps longer than a cell).
  std::int64_t StepsInside(const Box& box, const Vec3& position, const Vec3& step) const;

  int GetMaximumDistance() const { return this->MaximumDistance; }

private:
  int MaximumDistance = 0;
  double MaximumStep[3] = { 0, 0, 0 }; // as given to Build, to detect larger caller steps
  std::vector<std::int64_t> Steps[3];  // Steps[a][m], m in [0, MaximumDistance]
};

}

#endif
