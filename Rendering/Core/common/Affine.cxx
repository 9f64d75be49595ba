#include "common/Affine.h"

#include <cmath>
#include <stdexcept>

namespace accelvolume
{

Vec3 Affine::Apply(const Vec3& p) const
{
  return { m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z + m[0][3],
    m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z + m[1][3],
    m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z + m[2][3] };
}

Vec3 Affine::ApplyLinear(const Vec3& v) const
{
  return { m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
    m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z, m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z };
}

Affine Affine::Inverse() const
{
  // Adjugate over determinant for the linear part; the translation follows as -A^-1 t.
  const double a = m[0][0], b = m[0][1], c = m[0][2];
  const double d = m[1][0], e = m[1][1], f = m[1][2];
  const double g = m[2][0], h = m[2][1], k = m[2][2];
  const double determinant = a * (e * k - f * h) - b * (d * k - f * g) + c * (d * h - e * g);
  if (!(std::abs(determinant) > 0) || !std::isfinite(determinant))
  {
    throw std::domain_error("accelvolume::Affine::Inverse: singular matrix");
  }
  const double s = 1.0 / determinant;
  Affine inverse{};
  inverse.m[0][0] = (e * k - f * h) * s;
  inverse.m[0][1] = (c * h - b * k) * s;
  inverse.m[0][2] = (b * f - c * e) * s;
  inverse.m[1][0] = (f * g - d * k) * s;
  inverse.m[1][1] = (a * k - c * g) * s;
  inverse.m[1][2] = (c * d - a * f) * s;
  inverse.m[2][0] = (d * h - e * g) * s;
  inverse.m[2][1] = (b * g - a * h) * s;
  inverse.m[2][2] = (a * e - b * d) * s;
  const Vec3 translation = inverse.ApplyLinear({ m[0][3], m[1][3], m[2][3] });
  inverse.m[0][3] = -translation.x;
  inverse.m[1][3] = -translation.y;
  inverse.m[2][3] = -translation.z;
  return inverse;
}

Affine Affine::Identity()
{
  return { { { 1, 0, 0, 0 }, { 0, 1, 0, 0 }, { 0, 0, 1, 0 } } };
}

} // namespace accelvolume
