// Bricking: splitting a volume into 3D-texture bricks that share one voxel with each neighbour,
// and ordering them for compositing.
#ifndef accelvolume_Bricking_h
#define accelvolume_Bricking_h

#include "common/Geometry.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace accelvolume
{
// One brick. Index coordinates put voxel (i, j, k) at (i, j, k). The brick owns the samples in
// [ownLower, ownUpper) on every axis (the volume's first brick on an axis owns everything below,
// its last everything above), so every sample point belongs to exactly one brick. Its texture
// holds the points textureOrigin .. textureOrigin + textureSize - 1: the owned cells' corner
// points plus one more point on every side that has a neighbour, so trilinear samples and
// one-voxel central differences anywhere in the owned range read the same texels as they would
// in the whole volume (no seams).
struct Brick
{
  std::array<int, 3> gridIndex{ { 0, 0, 0 } };
  std::array<int, 3> pointLower{ { 0, 0, 0 } }; // first / last point of the owned cells
  std::array<int, 3> pointUpper{ { 0, 0, 0 } };
  std::array<int, 3> textureOrigin{ { 0, 0, 0 } };
  std::array<int, 3> textureSize{ { 1, 1, 1 } };
  std::array<bool, 3> firstOnAxis{ { true, true, true } };
  std::array<bool, 3> lastOnAxis{ { true, true, true } };

  std::uint64_t TexelCount() const
  {
    return static_cast<std::uint64_t>(textureSize[0]) * textureSize[1] * textureSize[2];
  }
};

struct BrickLayout
{
  std::array<int, 3> gridSize{ { 1, 1, 1 } };
  std::array<int, 3> cellsPerBrick{ { 0, 0, 0 } };
  std::vector<Brick> bricks; // x fastest, then y, then z
  std::uint64_t largestBrickBytes = 0;
  std::uint64_t totalBytes = 0; // every brick's texture, overlaps counted twice

  bool Single() const { return bricks.size() == 1; }
};

struct BrickRequest
{
  std::array<int, 3> dimensions{ { 1, 1, 1 } };
  int maximumTextureSize = 2048; // texels per axis (GL_MAX_3D_TEXTURE_SIZE or smaller)
  std::uint64_t bytesPerVoxel = 1;
  // 0: no budget. Otherwise the bytes the bricks may keep on the GPU at once: a volume larger
  // than that is cut into bricks of at most budget / BudgetShare bytes, so most of the budget
  // holds bricks that stay resident while the rest stream through it.
  std::uint64_t budgetBytes = 0;
};

// Bricks per budget share: smaller bricks keep more of the budget resident (all but one brick's
// worth) at the price of more draws and coarser uploads.
constexpr int BudgetShare = 8;
// Bricks are not cut thinner than this many cells per axis (unless the volume is thinner).
constexpr int MinimumBrickCells = 16;

// The volume as one brick when it fits both limits; otherwise the fewest, evenly sized bricks
// that do. False with `error` set when no brick size fits (the budget is smaller than a brick
// of MinimumBrickCells^3 cells, or the texture limit is below 4).
bool ComputeBrickLayout(const BrickRequest& request, BrickLayout& layout, std::string& error);

// The box of index space a brick owns, with the volume's own box at its outer faces (a flat axis
// spans +-0.5 there, as vtkAccelVolumeIndexBox gives).
Box BrickOwnedBox(const Brick& brick, const Box& volumeBox);

// Brick indices in front-to-back order for rays from `eye` (index space; perspective) or along
// `direction` (parallel projection, pointing away from the viewer). Bricks at equal L1 grid
// distance from the eye's brick never occlude each other along any ray, since a ray moves
// monotonically on every axis; ties keep index order so the result is deterministic.
std::vector<int> BrickVisibilityOrder(
  const BrickLayout& layout, bool perspective, const Vec3& eye, const Vec3& direction);
}

#endif
