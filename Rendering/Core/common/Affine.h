// Affine: a row-major 3x4 affine map (index <-> world), shared by every mapper's Core.
#ifndef accelvolume_Affine_h
#define accelvolume_Affine_h

#include "common/Geometry.h"

namespace accelvolume
{

// Row-major 3x4 affine map: p' = M[:, 0..2] * p + M[:, 3].
struct Affine
{
  double m[3][4];
  Vec3 Apply(const Vec3& p) const;
  Vec3 ApplyLinear(const Vec3& v) const; // without the translation, for directions
  Affine Inverse() const;                // throws std::domain_error when singular
  static Affine Identity();
};

} // namespace accelvolume

#endif
