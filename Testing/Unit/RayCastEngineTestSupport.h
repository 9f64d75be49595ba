// Helpers shared by the ray caster engine's unit tests (TestRayCastEngine.cxx,
// TestRayCastLeaping.cxx): VTK-like views, random transfer functions, phantom scenes and cameras,
// base settings and one-frame casts (plain C++, no VTK); threaded loops are
// MinMaxOctreeTestSupport's.
#ifndef accelvolume_test_RayCastEngineTestSupport_h
#define accelvolume_test_RayCastEngineTestSupport_h

#include "raycast/RayCastEngine.h"
#include "reference/Phantoms.h"

#include "MinMaxOctreeTestSupport.h"
#include "ShearWarpTestSupport.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>
#include <string>
#include <vector>

namespace accelvolume_test
{
namespace raycast_engine
{
using namespace accelvolume;

// Row-major 4x4 helpers (shared with the shear-warp tests) for VTK-like view and projection
// matrices.
using Matrix = accelvolume_test::Matrix4;
using accelvolume_test::Invert;
using accelvolume_test::Multiply;

// A camera looking at `focal` from `position` (VTK conventions), as NDC -> world.
inline RayCastView MakeView(
  const Camera& camera, int width, int height, double nearDistance, double farDistance)
{
  const Vec3 forward = Normalize(camera.focalPoint - camera.position);
  const Vec3 right = Normalize(Cross(forward, camera.viewUp));
  const Vec3 up = Cross(right, forward);
  Matrix view{};
  const Vec3 rows[3] = { right, up, -forward };
  for (int r = 0; r < 3; ++r)
  {
    view[r][0] = rows[r].x;
    view[r][1] = rows[r].y;
    view[r][2] = rows[r].z;
    view[r][3] = -Dot(rows[r], camera.position);
  }
  view[3][3] = 1;
  Matrix projection{};
  const double aspect = static_cast<double>(width) / height;
  const double n = nearDistance, f = farDistance;
  if (camera.parallel)
  {
    const double s = camera.parallelScale;
    projection[0][0] = 1.0 / (s * aspect);
    projection[1][1] = 1.0 / s;
    projection[2][2] = -2.0 / (f - n);
    projection[2][3] = -(f + n) / (f - n);
    projection[3][3] = 1;
  }
  else
  {
    const double t = 1.0 / std::tan(camera.viewAngleDegrees * 3.14159265358979 / 360.0);
    projection[0][0] = t / aspect;
    projection[1][1] = t;
    projection[2][2] = -(f + n) / (f - n);
    projection[2][3] = -2.0 * f * n / (f - n);
    projection[3][2] = -1;
  }
  const Matrix clipToWorld = Invert(Multiply(projection, view));
  RayCastView result;
  result.width = width;
  result.height = height;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c)
      result.clipToWorld[r][c] = clipToWorld[r][c];
  return result;
}

// Piecewise-linear transfer function with zero runs (so leaping has work to do).
inline std::vector<float> RandomTable(std::mt19937& random, int size, bool opaqueStart)
{
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<float> rgba(4 * size);
  const int rampStart = opaqueStart ? 0 : static_cast<int>(size * (0.2f + 0.5f * unit(random)));
  const int bandEnd =
    std::min(size, rampStart + static_cast<int>(size * (0.1f + 0.5f * unit(random))));
  const float peak = 0.05f + 0.6f * unit(random);
  for (int i = 0; i < size; ++i)
  {
    const float s = static_cast<float>(i) / (size - 1);
    rgba[4 * i] = s;
    rgba[4 * i + 1] = 1.0f - s;
    rgba[4 * i + 2] = 0.5f + 0.5f * std::sin(9.0f * s);
    float a = 0;
    if (i >= rampStart && i < bandEnd)
      a = peak * static_cast<float>(i - rampStart + 1) / (bandEnd - rampStart);
    rgba[4 * i + 3] = a;
  }
  return rgba;
}

struct Scene
{
  std::vector<std::uint8_t> u8;
  std::vector<std::uint16_t> u16;
  std::vector<std::int16_t> s16;
  std::vector<float> f32;
  VolumeView view;
  double range[2] = { 0, 1000 };
};

// The "blobs" phantom in the requested type, with range [0, 1000] scaled to the type.
inline Scene MakeScene(ScalarType type, const int dims[3], double time)
{
  PhantomVolume phantom;
  std::string error;
  EXPECT_TRUE(GeneratePhantom("blobs", dims, time, phantom, error)) << error;
  Scene scene;
  scene.view.type = type;
  std::copy(dims, dims + 3, scene.view.dims);
  switch (type)
  {
    case ScalarType::UInt8:
      for (float v : phantom.values)
        scene.u8.push_back(static_cast<std::uint8_t>(std::lround(v * 0.255)));
      scene.view.data = scene.u8.data();
      scene.range[1] = 255;
      break;
    case ScalarType::UInt16:
      for (float v : phantom.values)
        scene.u16.push_back(static_cast<std::uint16_t>(std::lround(v * 4)));
      scene.view.data = scene.u16.data();
      scene.range[1] = 4000;
      break;
    case ScalarType::Int16:
      for (float v : phantom.values)
        scene.s16.push_back(static_cast<std::int16_t>(std::lround(v * 2) - 1000));
      scene.view.data = scene.s16.data();
      scene.range[0] = -1000;
      scene.range[1] = 1000;
      break;
    default:
      scene.f32 = phantom.values;
      scene.view.data = scene.f32.data();
      break;
  }
  return scene;
}

inline Camera RandomCamera(std::mt19937& random, const int dims[3], bool parallel)
{
  std::uniform_real_distribution<double> angle(0.0, 6.283185307);
  std::uniform_real_distribution<double> elevation(-1.2, 1.2);
  const Vec3 centre{ (dims[0] - 1) / 2.0, (dims[1] - 1) / 2.0, (dims[2] - 1) / 2.0 };
  const double radius = 2.2 * std::max({ dims[0], dims[1], dims[2] });
  const double a = angle(random), e = elevation(random);
  Camera camera;
  camera.focalPoint = centre;
  camera.position = centre +
    Vec3{ radius * std::cos(e) * std::cos(a), radius * std::cos(e) * std::sin(a),
      radius * std::sin(e) };
  camera.viewUp = { 0, 0, 1 };
  camera.viewAngleDegrees = 30;
  camera.parallel = parallel;
  camera.parallelScale = 0.6 * std::max({ dims[0], dims[1], dims[2] });
  return camera;
}

inline RayCastSettings BaseSettings(const int dims[3], Blend blend)
{
  RayCastSettings settings;
  settings.blend = blend;
  settings.sampleDistance = 0.7;
  settings.octreeLeafSize = 4;
  settings.tileSize = 8;
  settings.regions.push_back({ { 0, 0, 0 }, { dims[0] - 1.0, dims[1] - 1.0, dims[2] - 1.0 } });
  return settings;
}

struct Result
{
  std::vector<float> rgba;
  RayCastCounters counters;
  std::size_t accelerationBytes = 0; // the caster's after the frame
};

// One frame of `reused`, or of a fresh caster.
inline Result Cast(const Scene& scene, const RayCastTransfer& transfer,
  const RayCastLighting& lighting, const RayCastView& view, const RayCastSettings& settings,
  const ParallelFor& parallel = SerialFor, RayCaster* reused = nullptr)
{
  RayCaster fresh;
  RayCaster& caster = reused ? *reused : fresh;
  Result result;
  std::string error;
  EXPECT_TRUE(caster.Render(scene.view, scene.range[0], scene.range[1], 1, transfer, 1, lighting,
    view, settings, parallel, result.rgba, result.counters, error))
    << error;
  result.accelerationBytes = caster.GetAccelerationBytes();
  return result;
}

using accelvolume_test::ThreadedFor;

inline bool Identical(const std::vector<float>& a, const std::vector<float>& b)
{
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin());
}

} // namespace raycast_engine
} // namespace accelvolume_test

#endif
