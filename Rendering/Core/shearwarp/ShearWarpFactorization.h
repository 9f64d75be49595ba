// ShearWarpFactorization: Lacroute's factorization of a parallel view into a shear of the volume
// slices (so every ray runs parallel to a volume axis) and a 2D affine warp (plain C++, no VTK).
//
// Object space is voxel index space (voxel centres at integers, x fastest). The principal axis k
// is the one most parallel to the rays; i = (k + 1) % 3 and j = (k + 2) % 3 span the slices.
// Voxel (i, j, k) lands on the intermediate image at
//   (u, v) = (i + shear[0] k + translate[0], j + shear[1] k + translate[1]),
// so all voxels one ray passes through share (u, v), and the intermediate image maps to the
// final image by the affine `warp`: image = warp * (u, v, 1). Slices are composited front to
// back (`sliceStep` = +1 when slice 0 is nearest to the viewer).
#ifndef accelvolume_ShearWarpFactorization_h
#define accelvolume_ShearWarpFactorization_h

#include <string>

namespace accelvolume
{

struct ShearWarpFactorization
{
  int axes[3] = { 0, 1, 2 };      // object axes playing i, j, k (k: principal viewing axis)
  int sliceDims[3] = { 0, 0, 0 }; // ni, nj, nk
  double shear[2] = { 0, 0 };     // intermediate offset of slice k per unit k
  double translate[2] = { 0, 0 }; // makes every offset >= 0
  int intermediateSize[2] = { 0, 0 };
  double warp[2][3] = {};         // intermediate (u, v) -> image (x, y)
  double inverseWarp[2][3] = {};  // image (x, y) -> intermediate (u, v)
  int firstSlice = 0;             // nearest slice to the viewer
  int sliceStep = 1;              // +1 or -1, front to back
  double rayStep[3] = { 0, 0, 0 }; // object-space (x, y, z) step of a ray from one slice to the next

  // Intermediate offset of slice k (its voxel (0, 0) lands at (offset[0], offset[1])).
  void SliceOffset(int k, double offset[2]) const
  {
    offset[0] = this->shear[0] * k + this->translate[0];
    offset[1] = this->shear[1] * k + this->translate[1];
  }
};

// voxelToImage: row-major 3x4 affine, voxel index -> continuous image coordinates (x, y: pixel
// (a, b) covers [a, a + 1) x [b, b + 1), rows from the bottom; z: depth growing away from the
// viewer). Parallel projections only. False with error when the map is singular or dims < 1.
bool FactorizeShearWarp(const double voxelToImage[3][4], const int dims[3],
  ShearWarpFactorization& factorization, std::string& error);

}

#endif
