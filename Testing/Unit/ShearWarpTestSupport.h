// Helpers shared by the shear-warp unit tests: parallel-for implementations, random rotations
// and views, VTK-like parallel cameras, banded compositing and small matrix utilities (plain
// C++, no VTK).
#ifndef accelvolume_test_ShearWarpTestSupport_h
#define accelvolume_test_ShearWarpTestSupport_h

#include "RandomGeometry.h" // Uniform

#include "skipping/MinMaxOctree.h" // ParallelFor
#include "shearwarp/ShearWarpCompositor.h"
#include "shearwarp/ShearWarpFactorization.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <functional>
#include <random>
#include <string>
#include <thread>
#include <vector>

namespace accelvolume_test
{
using Matrix3 = std::array<std::array<double, 3>, 3>;
using Matrix4 = std::array<std::array<double, 4>, 4>;

// Everything in one call on the calling thread.
inline void SerialParallelFor(
  std::size_t count, const std::function<void(std::size_t, std::size_t)>& body)
{
  if (count > 0)
  {
    body(0, count);
  }
}

// Splits [0, count) into uneven chunks (1, 2, 3, ... items, cycling) handed out to `threads`
// std::threads in the order they ask: no two runs need to see the same chunk-to-thread mapping.
inline accelvolume::ParallelFor UnevenThreadedFor(int threads)
{
  return [threads](std::size_t count, const std::function<void(std::size_t, std::size_t)>& body)
  {
    std::vector<std::pair<std::size_t, std::size_t>> chunks;
    for (std::size_t begin = 0, size = 1; begin < count; begin += size, size = size % 5 + 1)
    {
      chunks.emplace_back(begin, std::min(count, begin + size));
    }
    std::atomic<std::size_t> next{ 0 };
    auto work = [&]()
    {
      for (std::size_t c = next.fetch_add(1); c < chunks.size(); c = next.fetch_add(1))
      {
        body(chunks[c].first, chunks[c].second);
      }
    };
    std::vector<std::thread> workers;
    for (int t = 1; t < threads; ++t)
    {
      workers.emplace_back(work);
    }
    work();
    for (std::thread& w : workers)
    {
      w.join();
    }
  };
}

// Uniformly random rotation (from a random unit quaternion), rows are the new basis.
inline Matrix3 RandomRotation(std::mt19937& random)
{
  std::normal_distribution<double> normal;
  double q[4];
  double length = 0;
  do
  {
    length = 0;
    for (double& value : q)
    {
      value = normal(random);
      length += value * value;
    }
  } while (length < 1e-6);
  length = std::sqrt(length);
  for (double& value : q)
  {
    value /= length;
  }
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  return Matrix3{ { { 1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y) },
    { 2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x) },
    { 2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y) } } };
}

// A VTK-like camera's world -> view matrix: view x = right, y = up, the camera looks down -z.
// `direction` is the direction of projection (from the camera towards the focal point).
inline Matrix4 LookAlong(
  const double direction[3], const double up[3], const double focal[3], double distance)
{
  auto cross = [](const double* a, const double* b, double* out)
  {
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
  };
  auto normalize = [](double* v)
  {
    const double l = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int a = 0; a < 3; ++a)
    {
      v[a] /= l;
    }
  };
  double d[3] = { direction[0], direction[1], direction[2] };
  normalize(d);
  double right[3], trueUp[3];
  cross(d, up, right);
  normalize(right);
  cross(right, d, trueUp);
  double position[3];
  for (int a = 0; a < 3; ++a)
  {
    position[a] = focal[a] - distance * d[a];
  }
  Matrix4 m{};
  const double* rows[3] = { right, trueUp, d };
  for (int r = 0; r < 3; ++r)
  {
    const double sign = r == 2 ? -1.0 : 1.0; // view z points back towards the camera
    for (int c = 0; c < 3; ++c)
    {
      m[r][c] = sign * rows[r][c];
    }
    m[r][3] = -(m[r][0] * position[0] + m[r][1] * position[1] + m[r][2] * position[2]);
  }
  m[3][3] = 1;
  return m;
}

inline Matrix4 Multiply(const Matrix4& a, const Matrix4& b)
{
  Matrix4 m{};
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c)
      for (int k = 0; k < 4; ++k)
        m[r][c] += a[r][k] * b[k][c];
  return m;
}

// Gauss-Jordan with partial pivoting.
inline Matrix4 Invert(const Matrix4& m)
{
  Matrix4 a = m;
  Matrix4 inv{};
  for (int i = 0; i < 4; ++i)
    inv[i][i] = 1;
  for (int c = 0; c < 4; ++c)
  {
    int pivot = c;
    for (int r = c + 1; r < 4; ++r)
      if (std::abs(a[r][c]) > std::abs(a[pivot][c]))
        pivot = r;
    std::swap(a[c], a[pivot]);
    std::swap(inv[c], inv[pivot]);
    const double d = a[c][c];
    for (int k = 0; k < 4; ++k)
    {
      a[c][k] /= d;
      inv[c][k] /= d;
    }
    for (int r = 0; r < 4; ++r)
    {
      if (r == c)
        continue;
      const double f = a[r][c];
      for (int k = 0; k < 4; ++k)
      {
        a[r][k] -= f * a[c][k];
        inv[r][k] -= f * inv[c][k];
      }
    }
  }
  return inv;
}

// Object (volume index) coordinates of slice coordinates (i, j, k) for principal axis `axis`.
inline void SliceToObject(int axis, int i, int j, int k, int p[3])
{
  p[axis] = k;
  p[(axis + 1) % 3] = i;
  p[(axis + 2) % 3] = j;
}

// A random parallel view of a dims volume: rotation, anisotropic spacing, zoom, translation.
inline accelvolume::ShearWarpFactorization RandomFactorization(
  std::mt19937& random, const int dims[3])
{
  const Matrix3 rotation = RandomRotation(random);
  const double zoom = Uniform(random, 0.5, 2.0);
  double m[3][4];
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      m[r][c] = zoom * rotation[r][c] * (c == 0 ? 1.0 : c == 1 ? 1.7 : 0.6);
    }
    m[r][3] = Uniform(random, -20, 20);
  }
  accelvolume::ShearWarpFactorization f;
  std::string error;
  EXPECT_TRUE(accelvolume::FactorizeShearWarp(m, dims, f, error)) << error;
  return f;
}

// The whole intermediate image in random bands [v0, v1), one workspace reused by all of them:
// composite(v0, v1, first value of scanline v0, workspace, work per scanline).
template <typename Composite>
std::vector<float> InRandomBands(std::mt19937& random, const accelvolume::ShearWarpFactorization& f,
  std::size_t rowValues, float empty, Composite composite)
{
  const int height = f.intermediateSize[1];
  std::vector<float> values(rowValues * height, empty);
  accelvolume::ScanlineWorkspace workspace;
  for (int v0 = 0; v0 < height;)
  {
    const int v1 = std::min(height, v0 + 1 + static_cast<int>(random() % 9));
    std::vector<double> work(static_cast<std::size_t>(v1 - v0), -1.0);
    composite(v0, v1, values.data() + rowValues * v0, workspace, work.data());
    for (double w : work)
    {
      EXPECT_GE(w, 0.0); // a cost for every scanline of the band
    }
    v0 = v1;
  }
  return values;
}

inline bool BitIdentical(const std::vector<float>& a, const std::vector<float>& b)
{
  return a.size() == b.size() &&
    std::equal(a.begin(), a.end(), b.begin(),
      [](float x, float y) { return x == y || (std::isnan(x) && std::isnan(y)); });
}
}

#endif
