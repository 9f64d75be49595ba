// The brute-force reference renderer of VolPackRendererCheck.
#include "VolPackReference.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace accelvolume
{
namespace bench
{
void Normalize(double v[3])
{
  const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  for (int a = 0; a < 3; ++a)
  {
    v[a] /= n;
  }
}

namespace
{
bool Invert3(const double m[3][3], double inv[3][3])
{
  const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
    m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
    m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  if (std::abs(det) < 1e-12)
  {
    return false;
  }
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      const int r1 = (c + 1) % 3, r2 = (c + 2) % 3, c1 = (r + 1) % 3, c2 = (r + 2) % 3;
      inv[r][c] = (m[r1][c1] * m[r2][c2] - m[r1][c2] * m[r2][c1]) / det;
    }
  }
  return true;
}

double Lookup(const std::vector<float>& table, double s)
{
  const double x = std::min(255.0, std::max(0.0, s));
  const int i = std::min(254, static_cast<int>(x));
  const double t = x - i;
  return (1 - t) * table[i] + t * table[i + 1];
}

// Colour channel c (0..2) of the scene's table at scalar s: grey, or colour's r, g, b.
double TableColour(const VolPackScene& scene, int c, double s)
{
  if (scene.colour.empty())
  {
    return Lookup(scene.grey, s);
  }
  const double x = std::min(255.0, std::max(0.0, s));
  const int i = std::min(254, static_cast<int>(x));
  const double t = x - i;
  return (1 - t) * scene.colour[3 * i + c] + t * scene.colour[3 * (i + 1) + c];
}

// Per voxel, for the shaded reference: opacity (per voxel of ray length) and the shaded colour
// c * (ambient + diffuse max(N.L, 0)) + specular max(N.H, 0)^power of each channel, N the
// central-difference gradient taken to image space (inverse transpose) and turned to face the
// viewer (image -z); zero on the volume's border (ambient only), as vpVolumeNormals.
void ShadeVoxels(const VolPackScene& scene, const double inv[3][3], std::vector<float>& alpha,
  std::vector<float>& rgb)
{
  const int* d = scene.dims;
  const std::size_t count = static_cast<std::size_t>(d[0]) * d[1] * d[2];
  alpha.resize(count);
  rgb.resize(3 * count);
  double l[3] = { scene.lightDirection[0], scene.lightDirection[1], scene.lightDirection[2] };
  Normalize(l);
  double h[3] = { l[0], l[1], l[2] - 1.0 }; // L + V, V = (0, 0, -1) towards the viewer
  Normalize(h);
  const std::size_t sy = d[0], sz = static_cast<std::size_t>(d[0]) * d[1];
  std::size_t n = 0;
  for (int z = 0; z < d[2]; ++z)
  {
    for (int y = 0; y < d[1]; ++y)
    {
      for (int x = 0; x < d[0]; ++x, ++n)
      {
        const double s = scene.scalars[n];
        alpha[n] = static_cast<float>(Lookup(scene.opacity, s));
        double diffuse = 0, specular = 0;
        const bool border =
          x == 0 || y == 0 || z == 0 || x == d[0] - 1 || y == d[1] - 1 || z == d[2] - 1;
        if (!border)
        {
          const double g[3] = { double(scene.scalars[n + 1]) - scene.scalars[n - 1],
            double(scene.scalars[n + sy]) - scene.scalars[n - sy],
            double(scene.scalars[n + sz]) - scene.scalars[n - sz] };
          double nrm[3];
          for (int r = 0; r < 3; ++r)
          {
            nrm[r] = inv[0][r] * g[0] + inv[1][r] * g[1] + inv[2][r] * g[2];
          }
          const double length = std::sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
          if (length > 1e-12)
          {
            const double facing = nrm[2] > 0 ? -1.0 : 1.0; // N.V >= 0 with V = (0, 0, -1)
            for (double& c : nrm)
            {
              c *= facing / length;
            }
            diffuse = std::max(0.0, nrm[0] * l[0] + nrm[1] * l[1] + nrm[2] * l[2]);
            specular = std::pow(std::max(0.0, nrm[0] * h[0] + nrm[1] * h[1] + nrm[2] * h[2]),
              static_cast<double>(scene.specularPower));
          }
        }
        for (int c = 0; c < 3; ++c)
        {
          rgb[3 * n + c] = static_cast<float>(TableColour(scene, c, s) *
              (scene.ambient + scene.diffuse * diffuse) +
            scene.specular * specular);
        }
      }
    }
  }
}

}

std::vector<float> Reference(const VolPackScene& scene)
{
  const int* d = scene.dims;
  double linear[3][3], inv[3][3];
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      linear[r][c] = scene.voxelToImage[r][c];
    }
  }
  std::vector<float> rgba(static_cast<std::size_t>(scene.width) * scene.height * 4, 0.0f);
  if (!Invert3(linear, inv))
  {
    return rgba;
  }
  // Ray direction in voxel space (depth growing = away from the viewer) and its principal axis.
  const double ray[3] = { inv[0][2], inv[1][2], inv[2][2] };
  int k = 0;
  for (int a = 1; a < 3; ++a)
  {
    k = std::abs(ray[a]) > std::abs(ray[k]) ? a : k;
  }
  const double stepLength =
    std::sqrt(ray[0] * ray[0] + ray[1] * ray[1] + ray[2] * ray[2]) / std::abs(ray[k]);
  std::vector<float> voxelAlpha, voxelRgb;
  if (scene.shade)
  {
    ShadeVoxels(scene, inv, voxelAlpha, voxelRgb);
  }
  auto voxel = [&](int x, int y, int z)
  {
    return static_cast<double>(
      scene.scalars[x + static_cast<std::size_t>(d[0]) * (y + static_cast<std::size_t>(d[1]) * z)]);
  };
  for (int b = 0; b < scene.height; ++b)
  {
    for (int a = 0; a < scene.width; ++a)
    {
      // Voxel-space point of the pixel centre at depth 0; the ray is base + depth * ray.
      const double image[3] = { a + 0.5 - scene.voxelToImage[0][3],
        b + 0.5 - scene.voxelToImage[1][3], -scene.voxelToImage[2][3] };
      double base[3];
      for (int r = 0; r < 3; ++r)
      {
        base[r] = inv[r][0] * image[0] + inv[r][1] * image[1] + inv[r][2] * image[2];
      }
      double colour[3] = { 0, 0, 0 }, alpha = 0;
      for (int n = 0; n < d[k] && alpha < scene.maxRayOpacity; ++n)
      {
        // Front to back: slices in order of increasing depth.
        const int slice = ray[k] > 0 ? n : d[k] - 1 - n;
        const double depth = (slice - base[k]) / ray[k];
        double p[3];
        bool inside = true;
        for (int c = 0; c < 3; ++c)
        {
          p[c] = c == k ? slice : base[c] + depth * ray[c];
          inside = inside && p[c] >= 0 && p[c] <= d[c] - 1;
        }
        if (!inside)
        {
          continue;
        }
        int i0[3];
        double t[3];
        for (int c = 0; c < 3; ++c)
        {
          i0[c] = std::min(d[c] - 2, static_cast<int>(p[c]));
          i0[c] = std::max(0, i0[c]);
          t[c] = d[c] > 1 ? p[c] - i0[c] : 0.0;
        }
        double s = 0, weighted[3] = { 0, 0, 0 }, plain[3] = { 0, 0, 0 }, weights = 0;
        for (int corner = 0; corner < 8; ++corner)
        {
          double w = 1;
          int q[3];
          for (int c = 0; c < 3; ++c)
          {
            const int bit = (corner >> c) & 1;
            w *= bit ? t[c] : 1 - t[c];
            q[c] = std::min(d[c] - 1, i0[c] + bit);
          }
          s += w * voxel(q[0], q[1], q[2]);
          if (scene.shade)
          {
            const std::size_t v =
              q[0] + static_cast<std::size_t>(d[0]) * (q[1] + static_cast<std::size_t>(d[1]) * q[2]);
            for (int c = 0; c < 3; ++c)
            {
              weighted[c] += w * voxelAlpha[v] * voxelRgb[3 * v + c];
              plain[c] += w * voxelRgb[3 * v + c];
            }
            weights += w * voxelAlpha[v];
          }
        }
        const double opacity = 1 - std::pow(1 - Lookup(scene.opacity, s), stepLength);
        for (int c = 0; c < 3; ++c)
        {
          // Shaded: the opacity-weighted mean of the voxels' colours (VolPack resamples
          // opacity * colour of classified voxels); unshaded: the table at the sample's scalar.
          const double sampleColour = !scene.shade ? TableColour(scene, c, s)
            : weights > 1e-12                      ? weighted[c] / weights
                                                   : plain[c];
          colour[c] += (1 - alpha) * opacity * sampleColour;
        }
        alpha += (1 - alpha) * opacity;
      }
      float* px = &rgba[4 * (a + static_cast<std::size_t>(scene.width) * b)];
      for (int c = 0; c < 3; ++c)
      {
        px[c] = static_cast<float>(colour[c]);
      }
      px[3] = static_cast<float>(alpha);
    }
  }
  return rgba;
}
}
}
