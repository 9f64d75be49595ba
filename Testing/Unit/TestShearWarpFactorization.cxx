// ShearWarpFactorization: for random parallel views (VTK-like cameras over anisotropic volumes,
// views along every principal axis from both sides, and random affine maps), the shear followed
// by the warp reproduces the voxel -> image map, the principal axis and the slice order follow
// the viewing direction, every sheared slice fits the intermediate image, and bad input fails.
#include "ShearWarpTestSupport.h"

#include "shearwarp/ShearWarpEngine.h" // ParallelVoxelToImage
#include "shearwarp/ShearWarpFactorization.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>

using namespace accelvolume;
using namespace accelvolume_test;

namespace
{

struct ViewCase
{
  double voxelToImage[3][4];
  int dims[3];
};

int UniformInt(std::mt19937& random, int low, int high)
{
  return std::uniform_int_distribution<int>(low, high)(random);
}

// A VTK-like parallel camera on an anisotropic (optionally rotated) volume. axisView >= 0 looks
// along object axis axisView / 2 from its negative (even) or positive (odd) side, slightly tilted
// when `tilt`.
ViewCase CameraCase(std::mt19937& random, int axisView, bool tilt)
{
  ViewCase c;
  for (int& d : c.dims)
  {
    d = UniformInt(random, 1, 70);
  }
  const double spacing[3] = { Uniform(random, 0.2, 3.0), Uniform(random, 0.2, 3.0),
    Uniform(random, 0.2, 3.0) };
  // Volume direction matrix: identity for axis views (so the object axis is the world axis).
  Matrix3 direction = RandomRotation(random);
  if (axisView >= 0)
  {
    direction = Matrix3{ { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } } };
  }
  double indexToWorld[3][4];
  for (int r = 0; r < 3; ++r)
  {
    for (int col = 0; col < 3; ++col)
    {
      indexToWorld[r][col] = direction[r][col] * spacing[col];
    }
    indexToWorld[r][3] = Uniform(random, -50, 50);
  }
  double projection[3];
  if (axisView >= 0)
  {
    projection[0] = projection[1] = projection[2] = 0;
    projection[axisView / 2] = axisView % 2 ? -1.0 : 1.0; // odd: camera on the positive side
    if (tilt)
    {
      for (double& value : projection)
      {
        value += Uniform(random, -0.2, 0.2);
      }
    }
  }
  else
  {
    std::normal_distribution<double> normal;
    for (double& value : projection)
    {
      value = normal(random);
    }
  }
  double up[3] = { Uniform(random, -1, 1), Uniform(random, -1, 1), Uniform(random, -1, 1) };
  const double pl = std::sqrt(
    projection[0] * projection[0] + projection[1] * projection[1] + projection[2] * projection[2]);
  const double ul = std::sqrt(up[0] * up[0] + up[1] * up[1] + up[2] * up[2]);
  const double cosine =
    (projection[0] * up[0] + projection[1] * up[1] + projection[2] * up[2]) / (pl * ul);
  if (std::abs(cosine) > 0.95)
  {
    up[0] = projection[1];
    up[1] = projection[2];
    up[2] = -projection[0] + 0.5;
  }
  const double focal[3] = { Uniform(random, -30, 30), Uniform(random, -30, 30),
    Uniform(random, -30, 30) };
  const Matrix4 view = LookAlong(projection, up, focal, Uniform(random, 10, 500));
  double worldToView[4][4];
  for (int r = 0; r < 4; ++r)
  {
    for (int col = 0; col < 4; ++col)
    {
      worldToView[r][col] = view[r][col];
    }
  }
  const int width = UniformInt(random, 1, 400);
  const int height = UniformInt(random, 1, 400);
  ParallelVoxelToImage(
    indexToWorld, worldToView, Uniform(random, 1, 100), width, height, c.voxelToImage);
  return c;
}

// A random affine map with a well-conditioned linear part.
ViewCase AffineCase(std::mt19937& random)
{
  ViewCase c;
  for (int& d : c.dims)
  {
    d = UniformInt(random, 1, 50);
  }
  std::normal_distribution<double> normal;
  while (true)
  {
    for (auto& row : c.voxelToImage)
    {
      for (double& value : row)
      {
        value = normal(random) * 3.0;
      }
    }
    const double(*m)[4] = c.voxelToImage;
    const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
      m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
      m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    if (std::abs(det) > 1.0)
    {
      return c;
    }
  }
}

// The object-space direction along which image x, y stay fixed and depth grows: rows 0 and 1 of
// the linear part are orthogonal to it.
void DepthDirection(const double m[3][4], double d[3])
{
  d[0] = m[0][1] * m[1][2] - m[0][2] * m[1][1];
  d[1] = m[0][2] * m[1][0] - m[0][0] * m[1][2];
  d[2] = m[0][0] * m[1][1] - m[0][1] * m[1][0];
  if (m[2][0] * d[0] + m[2][1] * d[1] + m[2][2] * d[2] < 0)
  {
    for (int a = 0; a < 3; ++a)
    {
      d[a] = -d[a];
    }
  }
}

void Apply(const double m[3][4], const double p[3], double out[3])
{
  for (int r = 0; r < 3; ++r)
  {
    out[r] = m[r][0] * p[0] + m[r][1] * p[1] + m[r][2] * p[2] + m[r][3];
  }
}

// Scale of row r of m at p, for relative tolerances.
double Magnitude(const double m[3][4], int r, const double p[3])
{
  return 1.0 + std::abs(m[r][0] * p[0]) + std::abs(m[r][1] * p[1]) + std::abs(m[r][2] * p[2]) +
    std::abs(m[r][3]);
}

void CheckFactorization(std::mt19937& random, const ViewCase& c, const std::string& label)
{
  SCOPED_TRACE(label);
  ShearWarpFactorization f;
  std::string error;
  ASSERT_TRUE(FactorizeShearWarp(c.voxelToImage, c.dims, f, error)) << error;

  // (b) The principal axis is the axis most parallel to the rays; |shear| <= 1.
  double d[3];
  DepthDirection(c.voxelToImage, d);
  int k = 0;
  for (int a = 1; a < 3; ++a)
  {
    if (std::abs(d[a]) > std::abs(d[k]))
    {
      k = a;
    }
  }
  ASSERT_EQ(f.axes[2], k);
  ASSERT_EQ(f.axes[0], (k + 1) % 3);
  ASSERT_EQ(f.axes[1], (k + 2) % 3);
  const int i = f.axes[0], j = f.axes[1];
  EXPECT_EQ(f.sliceDims[0], c.dims[i]);
  EXPECT_EQ(f.sliceDims[1], c.dims[j]);
  EXPECT_EQ(f.sliceDims[2], c.dims[k]);
  EXPECT_LE(std::abs(f.shear[0]), 1.0 + 1e-12);
  EXPECT_LE(std::abs(f.shear[1]), 1.0 + 1e-12);
  // One slice along a ray moves (d_i / d_k, d_j / d_k) in the slice: the shear undoes it, so the
  // whole ray lands on one intermediate pixel.
  EXPECT_NEAR(f.shear[0], -d[i] / d[k], 1e-12);
  EXPECT_NEAR(f.shear[1], -d[j] / d[k], 1e-12);

  // (a) Shear then warp reproduces the view's x, y for random object points.
  for (int n = 0; n < 20; ++n)
  {
    const double p[3] = { Uniform(random, 0, c.dims[0] - 1), Uniform(random, 0, c.dims[1] - 1),
      Uniform(random, 0, c.dims[2] - 1) };
    double image[3];
    Apply(c.voxelToImage, p, image);
    const double u = p[i] + f.shear[0] * p[k] + f.translate[0];
    const double v = p[j] + f.shear[1] * p[k] + f.translate[1];
    for (int r = 0; r < 2; ++r)
    {
      const double warped = f.warp[r][0] * u + f.warp[r][1] * v + f.warp[r][2];
      ASSERT_NEAR(warped, image[r], 1e-9 * Magnitude(c.voxelToImage, r, p)) << "row " << r;
    }
    // (e) inverseWarp undoes warp.
    const double x = f.warp[0][0] * u + f.warp[0][1] * v + f.warp[0][2];
    const double y = f.warp[1][0] * u + f.warp[1][1] * v + f.warp[1][2];
    const double back[2] = { f.inverseWarp[0][0] * x + f.inverseWarp[0][1] * y +
        f.inverseWarp[0][2],
      f.inverseWarp[1][0] * x + f.inverseWarp[1][1] * y + f.inverseWarp[1][2] };
    const double scale =
      1.0 + std::abs(u) + std::abs(v) + std::abs(f.translate[0]) + std::abs(f.translate[1]);
    EXPECT_NEAR(back[0], u, 1e-9 * scale);
    EXPECT_NEAR(back[1], v, 1e-9 * scale);
  }
  // (e) as matrices: inverseWarp * warp = identity (linear part and translation).
  for (int r = 0; r < 2; ++r)
  {
    for (int col = 0; col < 3; ++col)
    {
      double value = col == 2 ? f.inverseWarp[r][2] : 0.0;
      for (int q = 0; q < 2; ++q)
      {
        value += f.inverseWarp[r][q] * f.warp[q][col];
      }
      const double expected = col == r ? 1.0 : 0.0;
      EXPECT_NEAR(value, expected,
        1e-9 *
          (1.0 + std::abs(f.warp[0][2]) + std::abs(f.warp[1][2]) + std::abs(f.inverseWarp[r][2])));
    }
  }

  // (c) Every slice lands inside the intermediate image with room for the bilinear footprint:
  // pixel u of slice k reads voxels floor(u - offset) and floor(u - offset) + 1, so voxels
  // [0, n) reach pixels [floor(offset), floor(offset) + n]; the image starts at offset 0.
  double lowest[2] = { std::numeric_limits<double>::infinity(),
    std::numeric_limits<double>::infinity() };
  double highest[2] = { -lowest[0], -lowest[1] };
  for (int slice = 0; slice < f.sliceDims[2]; ++slice)
  {
    double offset[2];
    f.SliceOffset(slice, offset);
    for (int a = 0; a < 2; ++a)
    {
      ASSERT_GE(offset[a], -1e-9) << "slice " << slice;
      ASSERT_LE(std::floor(offset[a]) + f.sliceDims[a] + 1, f.intermediateSize[a])
        << "slice " << slice << " axis " << a;
      lowest[a] = std::min(lowest[a], offset[a]);
      highest[a] = std::max(highest[a], offset[a]);
    }
  }
  for (int a = 0; a < 2; ++a)
  {
    EXPECT_LE(lowest[a], 1e-9);
    // Not wastefully large either.
    EXPECT_LE(f.intermediateSize[a], f.sliceDims[a] + std::ceil(highest[a]) + 2);
  }

  // (d) Front to back: firstSlice is nearest the viewer and rayStep walks the ray deeper.
  EXPECT_TRUE(f.sliceStep == 1 || f.sliceStep == -1);
  EXPECT_EQ(f.firstSlice, f.sliceStep == 1 ? 0 : f.sliceDims[2] - 1);
  EXPECT_EQ(f.rayStep[k], static_cast<double>(f.sliceStep));
  for (int a = 0; a < 3; ++a)
  {
    // The step follows the depth direction with a positive factor.
    EXPECT_NEAR(f.rayStep[a], d[a] / std::abs(d[k]), 1e-12);
  }
  for (int n = 0; n < 5; ++n)
  {
    double p[3] = { Uniform(random, 0, c.dims[0] - 1), Uniform(random, 0, c.dims[1] - 1),
      Uniform(random, 0, c.dims[2] - 1) };
    p[k] = f.firstSlice;
    double q[3];
    for (int a = 0; a < 3; ++a)
    {
      q[a] = p[a] + f.rayStep[a];
    }
    double near[3], far[3];
    Apply(c.voxelToImage, p, near);
    Apply(c.voxelToImage, q, far);
    EXPECT_NEAR(far[0], near[0], 1e-9 * Magnitude(c.voxelToImage, 0, p)); // same ray
    EXPECT_NEAR(far[1], near[1], 1e-9 * Magnitude(c.voxelToImage, 1, p));
    EXPECT_GT(far[2], near[2]); // the next slice is deeper
    // The same ray in the last slice (composited last) is deeper too.
    if (f.sliceDims[2] > 1)
    {
      double last[3];
      for (int a = 0; a < 3; ++a)
      {
        last[a] = p[a] + (f.sliceDims[2] - 1) * f.rayStep[a];
      }
      double lastImage[3];
      Apply(c.voxelToImage, last, lastImage);
      EXPECT_GT(lastImage[2], near[2]);
    }
  }
}

} // namespace

TEST(ShearWarpFactorization, ReproducesRandomCameraViews)
{
  std::mt19937 random(20260411);
  for (int trial = 0; trial < 400; ++trial)
  {
    const ViewCase c = CameraCase(random, -1, false);
    CheckFactorization(random, c, "camera trial " + std::to_string(trial));
  }
}

TEST(ShearWarpFactorization, ViewsAlongEveryAxisFromBothSides)
{
  std::mt19937 random(99);
  int principal[3][2] = {};
  int steps[2] = {};
  for (int trial = 0; trial < 120; ++trial)
  {
    const int axisView = trial % 6;
    const bool tilt = trial >= 6 && trial % 2 == 1;
    const ViewCase c = CameraCase(random, axisView, tilt);
    CheckFactorization(
      random, c, "axis view " + std::to_string(axisView) + " trial " + std::to_string(trial));
    ShearWarpFactorization f;
    std::string error;
    ASSERT_TRUE(FactorizeShearWarp(c.voxelToImage, c.dims, f, error));
    if (!tilt)
    {
      // Straight down an axis: no shear, that axis is principal, and looking from the positive
      // side (camera at +axis, rays going to -axis) starts at the last slice.
      EXPECT_EQ(f.axes[2], axisView / 2);
      EXPECT_NEAR(f.shear[0], 0.0, 1e-12);
      EXPECT_NEAR(f.shear[1], 0.0, 1e-12);
      if (f.sliceDims[2] > 1)
      {
        EXPECT_EQ(f.sliceStep, axisView % 2 ? -1 : 1) << axisView;
      }
    }
    ++principal[f.axes[2]][f.sliceStep > 0];
    ++steps[f.sliceStep > 0];
  }
  for (int a = 0; a < 3; ++a)
  {
    EXPECT_GT(principal[a][0], 0) << "axis " << a << " never seen from the positive side";
    EXPECT_GT(principal[a][1], 0) << "axis " << a << " never seen from the negative side";
  }
}

TEST(ShearWarpFactorization, ReproducesRandomAffineMaps)
{
  std::mt19937 random(5);
  for (int trial = 0; trial < 400; ++trial)
  {
    const ViewCase c = AffineCase(random);
    CheckFactorization(random, c, "affine trial " + std::to_string(trial));
  }
}

TEST(ShearWarpFactorization, SingularMapsAndEmptyVolumesFail)
{
  const int dims[3] = { 4, 5, 6 };
  ShearWarpFactorization f;
  std::string error;
  // A rank-2 linear part: row 2 = row 0 + row 1.
  double rank2[3][4] = { { 1, 2, 0, 3 }, { 0, 1, 1, 4 }, { 1, 3, 1, 0 } };
  EXPECT_FALSE(FactorizeShearWarp(rank2, dims, f, error));
  EXPECT_FALSE(error.empty());
  // No depth at all (what a perspective matrix's affine part may look like after dropping w).
  error.clear();
  double flat[3][4] = { { 1, 0, 0, 0 }, { 0, 1, 0, 0 }, { 0, 0, 0, 1 } };
  EXPECT_FALSE(FactorizeShearWarp(flat, dims, f, error));
  EXPECT_FALSE(error.empty());
  // A zero column: one object axis projects nowhere.
  error.clear();
  double zeroColumn[3][4] = { { 1, 0, 0, 0 }, { 0, 0, 1, 0 }, { 1, 0, 2, 0 } };
  EXPECT_FALSE(FactorizeShearWarp(zeroColumn, dims, f, error));
  EXPECT_FALSE(error.empty());
  error.clear();
  double zero[3][4] = {};
  EXPECT_FALSE(FactorizeShearWarp(zero, dims, f, error));
  EXPECT_FALSE(error.empty());
  error.clear();
  double notANumber[3][4] = { { 1, 0, 0, 0 }, { 0, 1, 0, 0 },
    { 0, 0, std::numeric_limits<double>::quiet_NaN(), 0 } };
  EXPECT_FALSE(FactorizeShearWarp(notANumber, dims, f, error));
  EXPECT_FALSE(error.empty());

  const double good[3][4] = { { 1, 0, 0, 0 }, { 0, 1, 0, 0 }, { 0, 0, 1, 0 } };
  for (int a = 0; a < 3; ++a)
  {
    for (int bad : { 0, -3 })
    {
      int empty[3] = { 4, 5, 6 };
      empty[a] = bad;
      error.clear();
      EXPECT_FALSE(FactorizeShearWarp(good, empty, f, error)) << a << " " << bad;
      EXPECT_FALSE(error.empty());
    }
  }
  error.clear();
  EXPECT_TRUE(FactorizeShearWarp(good, dims, f, error)) << error;
  const int single[3] = { 1, 1, 1 };
  EXPECT_TRUE(FactorizeShearWarp(good, single, f, error)) << error;
}
