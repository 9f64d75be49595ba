// ReferenceRenderer: CPU oracle for MIP / MinIP / raysum / average, finely integrated per pixel.
#ifndef accelvolume_ReferenceRenderer_h
#define accelvolume_ReferenceRenderer_h

#include "common/Blend.h"
#include "common/Affine.h"
#include "common/Camera.h"
#include "common/Geometry.h"

#include <vector>

namespace accelvolume
{


// Voxel values already normalized to [0, 1] over the data range.
struct ScalarVolume
{
  int dims[3] = { 0, 0, 0 };
  std::vector<float> values;                // x fastest: values[i + dims[0] * (j + dims[1] * k)]
  Affine indexToWorld = Affine::Identity(); // voxel (i, j, k) centre -> world

  float Value(int i, int j, int k) const;
  // Clamp-to-edge like GL_CLAMP_TO_EDGE with texcoord (p + 0.5) / n: each coordinate is clamped
  // into [0, n - 1] before interpolating.
  float SampleTrilinear(const Vec3& indexPoint) const;
  // Like GL_NEAREST: voxel floor(p + 0.5), clamped into [0, n - 1].
  float SampleNearest(const Vec3& indexPoint) const;
};

// A VTK piecewise function sampled at N points evenly over normalized [0, 1], interpolated
// linearly like a GL 1D texture with a linear filter and texcoord (s * (N - 1) + 0.5) / N.
struct OpacityTable
{
  std::vector<float> values;
  // s is clamped into [0, 1]; an empty table means opacity 1 everywhere.
  float Lookup(float normalizedScalar) const;
};


struct ReferenceOptions
{
  Blend blend = Blend::Maximum;
  double stepWorld = 0.05;         // fine integration step in world units
  double additiveUnitDistance = 1; // raysum = (1 / unit) * integral of opacity(s) * s dl
  // Normalized scalar range counted by Average (VTK's AverageIPScalarRange).
  double averageRangeMin = 0, averageRangeMax = 1;
  bool nearest = false;
  int threads = 0; // 0 = hardware concurrency; results never depend on it
};

struct ReferencePixel
{
  float value = 0;
  bool hit = false;
};

// Renders width * height pixels, returned at index i + j * width (j from the bottom).
// regions: boxes in INDEX coordinates (e.g. {0,0,0}-{nx-1,ny-1,nz-1}, or cropping boxes); clip:
// half-spaces in index coordinates. Per ray and region, the part of the ray with t >= 0 (and
// t <= raysEnd) inside box ∩ clip is split into equal steps of at most stepWorld, sampled at both
// ends and every step between.
// Maximum / Minimum: extremum of the sampled s over all regions; hit if any interval is non-empty.
// Additive: trapezoid integral of opacity(s) * s over world length / additiveUnitDistance, summed
// over regions; hit if any interval is non-empty.
// Average: trapezoid integral of opacity(s) * s * [s in range] over that of [s in range]; hit
// only when the denominator is positive.
// Pixels without a hit have value 0.
// raysEnd: optional per-pixel maximum world distance along the ray (opaque geometry), indexed like
// the result; nullptr means infinite. Throws std::invalid_argument when its size is wrong.
std::vector<ReferencePixel> RenderReference(const ScalarVolume& volume,
  const std::vector<Box>& regions, const std::vector<HalfSpace>& clip, const OpacityTable& opacity,
  const Camera& camera, int width, int height, const ReferenceOptions& options,
  const std::vector<double>* raysEnd = nullptr);

} // namespace accelvolume

#endif
