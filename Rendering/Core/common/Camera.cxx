#include "common/Camera.h"

#include <cmath>

namespace accelvolume
{
namespace
{
constexpr double Pi = 3.14159265358979323846;
}

Ray PixelRay(const Camera& camera, int width, int height, int i, int j)
{
  const Vec3 forward = Normalize(camera.focalPoint - camera.position);
  const Vec3 right = Normalize(Cross(forward, camera.viewUp));
  const Vec3 up = Cross(right, forward);
  const double aspect = static_cast<double>(width) / height;
  const double ndcX = 2 * (i + 0.5) / width - 1;
  const double ndcY = 2 * (j + 0.5) / height - 1;
  if (camera.parallel)
  {
    const Vec3 origin = camera.position + (ndcX * aspect * camera.parallelScale) * right +
      (ndcY * camera.parallelScale) * up;
    return { origin, forward };
  }
  const double tangent = std::tan(0.5 * camera.viewAngleDegrees * Pi / 180);
  return { camera.position,
    Normalize(forward + (ndcX * aspect * tangent) * right + (ndcY * tangent) * up) };
}

} // namespace accelvolume
