// Camera and pixel rays with VTK's conventions, shared by the ray caster and the CPU oracles.
#ifndef accelvolume_Camera_h
#define accelvolume_Camera_h

#include "common/Geometry.h"

namespace accelvolume
{

// VTK camera semantics; viewAngleDegrees is the vertical view angle.
struct Camera
{
  Vec3 position, focalPoint, viewUp{ 0, 1, 0 };
  double viewAngleDegrees = 30;
  double parallelScale = 1;
  bool parallel = false;
};

struct Ray
{
  Vec3 origin;
  Vec3 direction; // world, unit length
};

// VTK pixel convention: pixel (i, j), j counted from the bottom, centre at NDC
// ((2 (i + 0.5) / w) - 1, (2 (j + 0.5) / h) - 1); aspect w / h. Perspective rays start at the
// camera position; parallel rays start on the plane through the camera position perpendicular to
// the view direction, with half-height parallelScale, and all travel along the view direction.
Ray PixelRay(const Camera& camera, int width, int height, int i, int j);

} // namespace accelvolume

#endif
