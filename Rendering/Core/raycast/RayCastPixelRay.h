// RayCastPixelRay: a pixel's ray for the CPU ray caster's kernel (internal to RayCastKernel):
// its index-space line, the direction to the viewer and, where every light is fixed along it,
// each light's direction and half vector.
#ifndef accelvolume_RayCastPixelRay_h
#define accelvolume_RayCastPixelRay_h

#include "raycast/RayCastKernel.h"

#include "common/IndexRay.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

namespace accelvolume
{
namespace detail
{

// Lights a ray carries fixed directions for (more: the general lighting path).
constexpr std::size_t MaximumRayLights = 8;

// A pixel's ray: world near-plane point and unit direction, index-space origin / direction,
// and the world length before opaque geometry.
struct PixelRay
{
  IndexRay index;
  float toViewer[3]; // eye space, unit length (shading only)
  // When every light is fixed along the ray (directional, or at the eye on a ray through the
  // eye: VTK's headlight in perspective) and there are at most MaximumRayLights: each light's
  // unit direction towards it and half vector.
  bool fixedLights = false;
  float toLight[MaximumRayLights][3];
  float half[MaximumRayLights][3];
};

inline void Unproject(const double m[4][4], double x, double y, double z, double out[3])
{
  double h[4];
  for (int r = 0; r < 4; ++r)
  {
    h[r] = m[r][0] * x + m[r][1] * y + m[r][2] * z + m[r][3];
  }
  const double inverse = 1.0 / h[3];
  for (int r = 0; r < 3; ++r)
  {
    out[r] = h[r] * inverse;
  }
}

// PixelRay's fixed lights, when every light is fixed along this ray.
inline bool PassesThroughEye(const RayCastLighting& l, const IndexRay& ray)
{
  // Eye-space origin and direction of the ray: collinear when the ray passes through the eye.
  const Vec3& o = ray.origin;
  const Vec3& d = ray.direction;
  double eo[3], ed[3];
  for (int r = 0; r < 3; ++r)
  {
    eo[r] = l.indexToEye[r][0] * o.x + l.indexToEye[r][1] * o.y + l.indexToEye[r][2] * o.z +
      l.indexToEyeOffset[r];
    ed[r] = l.indexToEye[r][0] * d.x + l.indexToEye[r][1] * d.y + l.indexToEye[r][2] * d.z;
  }
  const Vec3 eyeOrigin{ eo[0], eo[1], eo[2] }, eyeDirection{ ed[0], ed[1], ed[2] };
  // On its line and starting ahead of it (the near plane lies in front of the eye).
  return Length(Cross(eyeOrigin, eyeDirection)) <=
    1.0e-7 * Length(eyeOrigin) * Length(eyeDirection) &&
    Dot(eyeOrigin, eyeDirection) > 0;
}

// VTK's headlight: at the eye, unattenuated, no cone.
inline bool IsEyeLight(const SceneLight& light)
{
  return light.positional && light.position[0] == 0 && light.position[1] == 0 &&
    light.position[2] == 0 && light.attenuation[0] == 1 && light.attenuation[1] == 0 &&
    light.attenuation[2] == 0 && light.cosCone < -1.0f;
}

// PixelRay's fixed lights, when every light is fixed along this ray (throughEye: the ray
// passes through the eye). A light at the eye is fixed along any ray: on rays through the eye
// it lies ahead of every sample; on other rays (parallel projection) its direction is taken
// once, from the point where the ray enters the volume (entryEye, eye space), as
// vtkGPUVolumeRayCastMapper does; without entryEye such rays light per sample.
inline void FixLights(
  const RayCastLighting& l, bool throughEye, PixelRay& ray, const double* entryEye = nullptr)
{
  const std::vector<SceneLight>& lights = l.model.lights;
  ray.fixedLights = lights.size() <= MaximumRayLights;
  std::size_t index = 0;
  for (const SceneLight& light : lights)
  {
    if (!ray.fixedLights)
    {
      break;
    }
    float* toLight = ray.toLight[index];
    if (!light.positional)
    {
      for (int c = 0; c < 3; ++c)
      {
        toLight[c] = -light.axis[c];
      }
    }
    else if (throughEye && IsEyeLight(light))
    {
      // Every sample of the ray lies ahead on the line from the eye: towards the light is
      // towards the viewer, unattenuated.
      std::copy(ray.toViewer, ray.toViewer + 3, toLight);
    }
    else if (entryEye != nullptr && IsEyeLight(light))
    {
      const double length = std::sqrt(
        entryEye[0] * entryEye[0] + entryEye[1] * entryEye[1] + entryEye[2] * entryEye[2]);
      for (int c = 0; c < 3; ++c)
      {
        toLight[c] = static_cast<float>(length > 0 ? -entryEye[c] / length : 0.0);
      }
    }
    else
    {
      ray.fixedLights = false;
      break;
    }
    float h[3] = { toLight[0] + ray.toViewer[0], toLight[1] + ray.toViewer[1],
      toLight[2] + ray.toViewer[2] };
    const float length = std::sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
    const float inverse = length > 0 ? 1.0f / length : 0.0f;
    for (int c = 0; c < 3; ++c)
    {
      ray.half[index][c] = h[c] * inverse;
    }
    ++index;
  }
}

// A pixel's ray in index space (its lighting: LightPixelRay, once the ray is known to meet the
// volume), set in place: a PixelRay is a few hundred bytes (its lights), and copying one per
// pixel cost more than a percent of an opaque frame.
// x and y: the pixel centre's normalised device coordinates (PixelCentre), which a caller
// casting rows of pixels computes once per column and row.
inline void SetPixelRay(const KernelFrame& frame, int i, int j, double x, double y, PixelRay& ray)
{
  const RayCastView& view = *frame.view;
  double nearPoint[3], farPoint[3];
  Unproject(view.clipToWorld, x, y, -1.0, nearPoint);
  Unproject(view.clipToWorld, x, y, 1.0, farPoint);
  const Vec3 origin{ nearPoint[0], nearPoint[1], nearPoint[2] };
  const Vec3 direction = Normalize(
    Vec3{ farPoint[0] - nearPoint[0], farPoint[1] - nearPoint[1], farPoint[2] - nearPoint[2] });
  double end = std::numeric_limits<double>::infinity();
  if (view.depth)
  {
    const float depth = (*view.depth)[static_cast<std::size_t>(j) * view.width + i];
    if (depth < 1.0f)
    {
      double hit[3];
      Unproject(view.clipToWorld, x, y, 2.0 * depth - 1.0, hit);
      end = Dot(Vec3{ hit[0], hit[1], hit[2] } - origin, direction);
    }
  }
  ray.index = { view.worldToIndex.Apply(origin), view.worldToIndex.ApplyLinear(direction), end };
  ray.fixedLights = false;
}

// Pixel i's centre of a row (or column) of `size` pixels in normalised device coordinates.
inline double PixelCentre(int i, int size)
{
  return 2.0 * (i + 0.5) / size - 1.0;
}

inline PixelRay MakePixelRay(const KernelFrame& frame, int i, int j)
{
  PixelRay ray;
  SetPixelRay(
    frame, i, j, PixelCentre(i, frame.view->width), PixelCentre(j, frame.view->height), ray);
  return ray;
}

// The ray's direction to the viewer and its fixed lights (FixLights; entryEye: see there).
// Only shading needs them.
inline void LightPixelRay(
  const RayCastLighting& l, bool throughEye, PixelRay& ray, const double* entryEye = nullptr)
{
  const Vec3& d = ray.index.direction;
  double eye[3];
  for (int r = 0; r < 3; ++r)
  {
    eye[r] = l.indexToEye[r][0] * d.x + l.indexToEye[r][1] * d.y + l.indexToEye[r][2] * d.z;
  }
  const double length = std::sqrt(eye[0] * eye[0] + eye[1] * eye[1] + eye[2] * eye[2]);
  const double inverse = length > 0 ? 1.0 / length : 0.0;
  for (int r = 0; r < 3; ++r)
  {
    ray.toViewer[r] = static_cast<float>(-eye[r] * inverse);
  }
  FixLights(l, throughEye, ray, entryEye);
}

// Whether the frame's rays light a light at the eye from their entry points (FixLights): shaded,
// rays not through the eye (frame.raysThroughEye set first), at least one such light and few
// enough lights to fix.
inline bool EyeLightsAtEntry(const KernelFrame& frame)
{
  const RayCastLighting& lighting = *frame.lighting;
  const std::vector<SceneLight>& lights = lighting.model.lights;
  return lighting.shade && !frame.raysThroughEye && lights.size() <= MaximumRayLights &&
    std::any_of(lights.begin(), lights.end(), IsEyeLight);
}

// LightPixelRay for a ray that enters the volume at index-space point `entry`.
inline void LightPixelRayAtEntry(const RayCastLighting& l, const double entry[3], PixelRay& ray)
{
  double eye[3];
  for (int r = 0; r < 3; ++r)
  {
    eye[r] = l.indexToEye[r][0] * entry[0] + l.indexToEye[r][1] * entry[1] +
      l.indexToEye[r][2] * entry[2] + l.indexToEyeOffset[r];
  }
  LightPixelRay(l, false, ray, eye);
}

// Whether every ray of the frame passes through the eye (only asked with shading and a
// positional light): a projection's rays share one centre, so three corner rays decide.
inline bool RaysPassThroughEye(const KernelFrame& frame)
{
  const RayCastLighting& lighting = *frame.lighting;
  if (!lighting.shade || !lighting.model.anyPositional)
  {
    return false;
  }
  const int w = frame.view->width, h = frame.view->height;
  const int corners[3][2] = { { 0, 0 }, { w - 1, 0 }, { 0, h - 1 } };
  for (const auto& c : corners)
  {
    if (!PassesThroughEye(lighting, MakePixelRay(frame, c[0], c[1]).index))
    {
      return false;
    }
  }
  return true;
}

} // namespace detail
} // namespace accelvolume

#endif
