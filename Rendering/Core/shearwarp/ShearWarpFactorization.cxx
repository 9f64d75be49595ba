// Lacroute's shear-warp factorization of a parallel view.
#include "shearwarp/ShearWarpFactorization.h"

#include "common/Affine.h"

#include <cmath>
#include <stdexcept>

namespace accelvolume
{
bool FactorizeShearWarp(const double voxelToImage[3][4], const int dims[3],
  ShearWarpFactorization& f, std::string& error)
{
  f = ShearWarpFactorization();
  if (dims[0] < 1 || dims[1] < 1 || dims[2] < 1)
  {
    error = "shear-warp: the volume has no voxels";
    return false;
  }
  Affine map;
  double linear[3][3];
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      map.m[r][c] = voxelToImage[r][c];
      if (c < 3)
      {
        linear[r][c] = voxelToImage[r][c];
      }
    }
  }
  Affine inverse;
  try
  {
    inverse = map.Inverse();
  }
  catch (const std::domain_error&)
  {
    error = "shear-warp: the voxel-to-image map is singular";
    return false;
  }
  // The object-space direction the image's depth axis comes from: the rays.
  const double ray[3] = { inverse.m[0][2], inverse.m[1][2], inverse.m[2][2] };
  int k = 0;
  for (int a = 1; a < 3; ++a)
  {
    if (std::abs(ray[a]) > std::abs(ray[k]))
    {
      k = a;
    }
  }
  const int i = (k + 1) % 3;
  const int j = (k + 2) % 3;
  f.axes[0] = i;
  f.axes[1] = j;
  f.axes[2] = k;
  f.sliceDims[0] = dims[i];
  f.sliceDims[1] = dims[j];
  f.sliceDims[2] = dims[k];
  // One slice along the ray moves (ray_i / ray_k, ray_j / ray_k) in the slice; the shear undoes it.
  f.shear[0] = -ray[i] / ray[k];
  f.shear[1] = -ray[j] / ray[k];
  const int lastSlice = dims[k] - 1;
  for (int a = 0; a < 2; ++a)
  {
    f.translate[a] = f.shear[a] < 0 ? -f.shear[a] * lastSlice : 0.0;
    // + 1: a pixel at the far edge still meets the last voxel through the bilinear footprint.
    f.intermediateSize[a] =
      f.sliceDims[a] + static_cast<int>(std::ceil(std::abs(f.shear[a]) * lastSlice)) + 1;
  }

  // Front to back: does a step to slice k + 1 along the ray go deeper into the image?
  double step[3] = { 0, 0, 0 };
  step[k] = 1.0;
  step[i] = -f.shear[0];
  step[j] = -f.shear[1];
  const double depth = linear[2][0] * step[0] + linear[2][1] * step[1] + linear[2][2] * step[2];
  f.sliceStep = depth >= 0 ? 1 : -1;
  f.firstSlice = depth >= 0 ? 0 : lastSlice;
  for (int a = 0; a < 3; ++a)
  {
    f.rayStep[a] = step[a] * f.sliceStep;
  }

  // Slice 0 has no shear offset beyond the translation: its voxel (u - t_i, v - t_j) is on the
  // ray of intermediate pixel (u, v), and the parallel projection maps the whole ray to one pixel.
  for (int r = 0; r < 2; ++r)
  {
    f.warp[r][0] = linear[r][i];
    f.warp[r][1] = linear[r][j];
    f.warp[r][2] =
      voxelToImage[r][3] - linear[r][i] * f.translate[0] - linear[r][j] * f.translate[1];
  }
  const double det = f.warp[0][0] * f.warp[1][1] - f.warp[0][1] * f.warp[1][0];
  if (!(std::abs(det) > 1e-300) || !std::isfinite(det))
  {
    error = "shear-warp: the warp is singular (the view is not a parallel projection)";
    return false;
  }
  const double s = 1.0 / det;
  f.inverseWarp[0][0] = f.warp[1][1] * s;
  f.inverseWarp[0][1] = -f.warp[0][1] * s;
  f.inverseWarp[1][0] = -f.warp[1][0] * s;
  f.inverseWarp[1][1] = f.warp[0][0] * s;
  f.inverseWarp[0][2] = -(f.inverseWarp[0][0] * f.warp[0][2] + f.inverseWarp[0][1] * f.warp[1][2]);
  f.inverseWarp[1][2] = -(f.inverseWarp[1][0] * f.warp[0][2] + f.inverseWarp[1][1] * f.warp[1][2]);
  return true;
}

}
