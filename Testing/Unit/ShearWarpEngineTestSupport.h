// Scenes, cameras and renders shared by the shear-warp engine tests: a procedural volume, a
// VTK-like parallel camera with matching shear-warp and ray-cast views, and image comparison.
#ifndef accelvolume_test_ShearWarpEngineTestSupport_h
#define accelvolume_test_ShearWarpEngineTestSupport_h

#include "ShearWarpTestSupport.h"

#include "raycast/RayCastEngine.h"
#include "shearwarp/ShearWarpEngine.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace accelvolume_test
{
using namespace accelvolume;

// A procedural volume (see Content) as uint8 and uint16 (x 200), range [0, 255] / [0, 51000].
struct Scene
{
  int dims[3];
  std::vector<std::uint8_t> u8;
  std::vector<std::uint16_t> u16;
  VolumeView view;
  double range[2] = { 0, 255 };
};

enum class Content
{
  SphereAndBar, // a soft sphere (linear falloff to 0 at its surface) and a sharp-edged bar
  Inverted,     // 255 - the above: bright background, dark sphere and bar (for MinIP)
  Blobs,        // two soft ellipsoids off the centre: smooth, asymmetric in every axis
  Edges         // single bright voxels on the volume's corners and edges, empty elsewhere:
                // slices whose only voxel is on their first or last scanline, empty slices
};

inline Scene MakeScene(const int dims[3], bool sixteenBit, Content content = Content::SphereAndBar)
{
  Scene scene;
  std::copy(dims, dims + 3, scene.dims);
  const double c[3] = { dims[0] * 0.5, dims[1] * 0.47, dims[2] * 0.5 };
  const double r[3] = { dims[0] * 0.375, dims[1] * 0.34, dims[2] * 0.375 };
  // Blobs: centre and radius as fractions of the dimensions.
  const double blobs[2][4] = { { 0.62, 0.4, 0.58, 0.3 }, { 0.3, 0.65, 0.35, 0.2 } };
  for (int z = 0; z < dims[2]; ++z)
    for (int y = 0; y < dims[1]; ++y)
      for (int x = 0; x < dims[0]; ++x)
      {
        double v = 0;
        if (content == Content::Edges)
        {
          // On two or three of the volume's faces at once, and every seventh slice of z empty.
          const int faces = (x == 0 || x == dims[0] - 1) + (y == 0 || y == dims[1] - 1) +
            (z == 0 || z == dims[2] - 1);
          v = faces >= 2 && (x + 2 * y + 3 * z) % 5 < 2 && z % 7 != 3 ? 240 : 0;
        }
        else if (content == Content::Blobs)
        {
          for (const auto& b : blobs)
          {
            const double dx = (x - b[0] * dims[0]) / (b[3] * dims[0]);
            const double dy = (y - b[1] * dims[1]) / (b[3] * dims[1]);
            const double dz = (z - b[2] * dims[2]) / (b[3] * dims[2]);
            const double d = std::sqrt(dx * dx + dy * dy + dz * dz);
            v = std::max(v, d < 1 ? 255 * (1 - d) : 0.0);
          }
        }
        else
        {
          const double dx = (x - c[0]) / r[0], dy = (y - c[1]) / r[1], dz = (z - c[2]) / r[2];
          const double d = std::sqrt(dx * dx + dy * dy + dz * dz);
          v = d < 1 ? std::floor(255 * (1 - d)) : 0;
          if (std::abs(x - dims[0] * 0.69) < dims[0] / 20.0 &&
            std::abs(y - dims[1] * 0.31) < dims[1] / 16.0)
          {
            v = 250;
          }
          if (content == Content::Inverted)
          {
            v = 255 - v;
          }
        }
        scene.u8.push_back(static_cast<std::uint8_t>(v));
        scene.u16.push_back(static_cast<std::uint16_t>(std::lround(v * 200)));
      }
  scene.view.type = sixteenBit ? ScalarType::UInt16 : ScalarType::UInt8;
  scene.view.data = sixteenBit ? static_cast<const void*>(scene.u16.data())
                               : static_cast<const void*>(scene.u8.data());
  std::copy(dims, dims + 3, scene.view.dims);
  scene.range[1] = sixteenBit ? 51000 : 255;
  return scene;
}

// Colour ramp, opacity zero below 20% of the range then rising to 0.3 (or, for `low`, zero
// above 80% and rising towards the bottom: what MinIP of the inverted scene shows).
inline RayCastTransfer MakeTransfer(float opacityScale = 0.3f, bool low = false)
{
  RayCastTransfer tf;
  const int n = 256;
  tf.rgba.resize(4 * n);
  for (int i = 0; i < n; ++i)
  {
    const float t = i / (n - 1.0f);
    tf.rgba[4 * i] = t;
    tf.rgba[4 * i + 1] = 0.5f + 0.5f * t;
    tf.rgba[4 * i + 2] = 1 - t;
    tf.rgba[4 * i + 3] =
      low ? (t > 0.8f ? 0 : (0.8f - t) * opacityScale) : (t < 0.2f ? 0 : (t - 0.2f) * opacityScale);
  }
  return tf;
}

// A VTK-like parallel camera orbiting the volume centre (azimuth about y from +z, elevation
// towards +y), with matching shear-warp and ray-cast views and lighting (headlight).
struct ViewSetup
{
  ShearWarpView sw;
  RayCastView rc;
  RayCastLighting lighting;
};

inline ViewSetup MakeCamera(const Scene& scene, double azimuth, double elevation,
  const double spacing[3], int width, int height, double parallelScale, bool shade)
{
  const double a = azimuth * 3.14159265358979323846 / 180;
  const double e = elevation * 3.14159265358979323846 / 180;
  const double projection[3] = { -std::sin(a) * std::cos(e), -std::sin(e),
    -std::cos(a) * std::cos(e) };
  const double up[3] = { 0, 1, 0 };
  double centre[3];
  for (int q = 0; q < 3; ++q)
  {
    centre[q] = (scene.dims[q] - 1) * spacing[q] / 2;
  }
  const Matrix4 worldToView = LookAlong(projection, up, centre, 200);
  ViewSetup camera;
  double indexToWorld[3][4] = {};
  double w2v[4][4];
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c)
      w2v[r][c] = worldToView[r][c];
  for (int q = 0; q < 3; ++q)
  {
    indexToWorld[q][q] = spacing[q];
    camera.sw.indexToWorld[q][q] = spacing[q];
  }
  camera.sw.width = width;
  camera.sw.height = height;
  ParallelVoxelToImage(indexToWorld, w2v, parallelScale, width, height, camera.sw.voxelToImage);

  // Orthographic projection with near 1, far 400 (the volume is ~200 away), as NDC -> world.
  Matrix4 ortho{};
  const double aspect = static_cast<double>(width) / height;
  const double n = 1, f = 400;
  ortho[0][0] = 1 / (parallelScale * aspect);
  ortho[1][1] = 1 / parallelScale;
  ortho[2][2] = -2 / (f - n);
  ortho[2][3] = -(f + n) / (f - n);
  ortho[3][3] = 1;
  const Matrix4 clipToWorld = Invert(Multiply(ortho, worldToView));
  camera.rc.width = width;
  camera.rc.height = height;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c)
      camera.rc.clipToWorld[r][c] = clipToWorld[r][c];
  camera.rc.worldToIndex = Affine::Identity();
  for (int q = 0; q < 3; ++q)
  {
    camera.rc.worldToIndex.m[q][q] = 1 / spacing[q];
  }

  RayCastLighting& l = camera.lighting;
  l.shade = shade;
  l.model.lights.emplace_back(); // white, shining along -z
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
    {
      l.indexToEye[r][c] = worldToView[r][c] * spacing[c];
      l.normalMatrix[r][c] = worldToView[r][c] / spacing[c]; // inverse transpose of R S
    }
  return camera;
}

inline constexpr double Isotropic[3] = { 1, 1, 1 };

struct Frame
{
  std::vector<float> rgba;
  int rectangle[4] = { 0, -1, 0, -1 };
  ShearWarpStats stats;
};

inline Frame RenderFrame(ShearWarpRenderer& renderer, const Scene& scene, const RayCastTransfer& tf,
  const ViewSetup& camera, const ShearWarpSettings& settings,
  const ParallelFor& parallel = SerialParallelFor, std::uint64_t transferVersion = 1,
  std::uint64_t volumeVersion = 1)
{
  Frame frame;
  std::string error;
  EXPECT_TRUE(renderer.Render(scene.view, scene.range[0], scene.range[1], volumeVersion, tf,
    transferVersion, camera.lighting, camera.sw, settings, parallel, frame.rgba, frame.rectangle,
    frame.stats, error))
    << error;
  return frame;
}

inline std::vector<float> RayCast(
  const Scene& scene, const RayCastTransfer& tf, const ViewSetup& camera, Blend blend)
{
  RayCastSettings settings;
  settings.blend = blend;
  settings.sampleDistance = 1.0;
  settings.regions.push_back(
    Box{ Vec3{ 0, 0, 0 }, Vec3{ scene.dims[0] - 1.0, scene.dims[1] - 1.0, scene.dims[2] - 1.0 } });
  RayCaster caster;
  std::vector<float> rgba;
  RayCastCounters counters;
  std::string error;
  EXPECT_TRUE(caster.Render(scene.view, scene.range[0], scene.range[1], 1, tf, 1, camera.lighting,
    camera.rc, settings, SerialParallelFor, rgba, counters, error))
    << error;
  return rgba;
}

inline void ExpectTransparentOutside(const Frame& frame, int width, int height)
{
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
    {
      if (x >= frame.rectangle[0] && x <= frame.rectangle[1] && y >= frame.rectangle[2] &&
        y <= frame.rectangle[3])
      {
        continue;
      }
      for (int c = 0; c < 4; ++c)
      {
        ASSERT_EQ(frame.rgba[4 * (static_cast<std::size_t>(y) * width + x) + c], 0.0f)
          << "pixel " << x << " " << y << " outside the rectangle";
      }
    }
}

inline const char* BlendName(Blend blend)
{
  return blend == Blend::Composite ? "composite"
    : blend == Blend::Maximum      ? "MIP"
                                            : "MinIP";
}

struct Comparison
{
  double meanDifference = 0; // per channel, over every pixel
  double centroidDistance = 0;
  double alpha[2] = { 0, 0 }; // total alpha, shear-warp and ray caster
};

inline Comparison Compare(
  const std::vector<float>& sw, const std::vector<float>& rc, int width, int height)
{
  Comparison result;
  double sum = 0;
  double cx[2] = { 0, 0 }, cy[2] = { 0, 0 };
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
    {
      const std::size_t p = 4 * (static_cast<std::size_t>(y) * width + x);
      for (int c = 0; c < 4; ++c)
      {
        sum += std::abs(sw[p + c] - rc[p + c]);
      }
      const float a[2] = { sw[p + 3], rc[p + 3] };
      for (int q = 0; q < 2; ++q)
      {
        cx[q] += (x + 0.5) * a[q];
        cy[q] += (y + 0.5) * a[q];
        result.alpha[q] += a[q];
      }
    }
  result.meanDifference = sum / (4.0 * width * height);
  const double dx = cx[0] / result.alpha[0] - cx[1] / result.alpha[1];
  const double dy = cy[0] / result.alpha[0] - cy[1] / result.alpha[1];
  result.centroidDistance = std::sqrt(dx * dx + dy * dy);
  return result;
}

}

#endif
