// MinMaxOctree: min-max octree over a scalar volume in Morton (Z) order, its builders,
// transfer-function classification and the empty-space queries renderers use.
//
// Layout (shared by the CPU builders, the GPU compute builder and the queries):
// - The volume (nx, ny, nz voxels, x fastest) is cut into leaf blocks of L^3 voxels, L a power
//   of two in [2, 64]. Leaf (i, j, k) covers voxels [i*L, (i+1)*L] x [j*L, (j+1)*L] x
//   [k*L, (k+1)*L] clamped to [0, n-1]: one voxel of overlap, so that every trilinear sample
//   taken inside the leaf's box [i*L, (i+1)*L] (index space) only reads voxels the leaf covers.
// - Level 0 holds the leaves, level l the nodes of 2^l x 2^l x 2^l leaves, up to the root at
//   level Depth, where 2^Depth >= the largest leaf-grid size (bx, by, bz) = ceil((n-1)/L)
//   (at least 1). A node at level l with coordinates (i, j, k) is stored at index
//   Morton(i, j, k) within its level, so the 8 children of a parent p are 8p .. 8p+7.
// - Level l stores Morton(max coordinate present) + 1 nodes (not the whole 8^(Depth-l) cube):
//   a parent's child range never passes the end of its child level. Nodes outside the volume
//   (padding) are empty: minimum = +inf, maximum = -inf.
// - Node min/max are floats of the raw scalar values; for types a float cannot hold exactly
//   (int32, double) the minimum is rounded down and the maximum up, so skipping stays
//   conservative. NaN voxels are ignored.
#ifndef accelvolume_MinMaxOctree_h
#define accelvolume_MinMaxOctree_h

#include "common/Geometry.h"
#include "common/ParallelFor.h"
#include "common/VolumeView.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace accelvolume
{
// Interleaves the low 21 bits of x, y, z (x in bit 0).
std::uint64_t MortonEncode(std::uint32_t x, std::uint32_t y, std::uint32_t z);
void MortonDecode(std::uint64_t code, std::uint32_t& x, std::uint32_t& y, std::uint32_t& z);

struct OctreeLevel
{
  int gridSize[3] = { 0, 0, 0 }; // nodes present per axis at this level
  std::vector<float> minimum;    // by Morton index; +inf for padding
  std::vector<float> maximum;    // by Morton index; -inf for padding
};

class MinMaxOctree
{
public:
  // Layout for dims and leaf size; false with error for dims < 1 or a bad leaf size, or for
  // volumes so large that a level would need more than 2^31 nodes (or a leaf-grid coordinate
  // more than 21 bits). Allocates every level with all nodes empty (+inf, -inf).
  bool Configure(const int dims[3], int leafSize, std::string& error);

  // Builders: all fill every level and give identical results. They fail (with error) when not
  // configured, without data or when the volume's dims differ from the configured ones. A node
  // whose voxels are all NaN ends up empty (+inf, -inf) like padding. Building clears any
  // classification.
  // Plain loops over every node, each reading its voxel range (the test oracle and baseline).
  bool BuildReference(const VolumeView& volume, std::string& error);
  // Parallel: one pass over the voxels fills the leaves (work items are leaf slabs), then one
  // work item per parent per level. Identical output for any ParallelFor / thread count.
  bool BuildParallel(const VolumeView& volume, const ParallelFor& parallel, std::string& error);
  // Fills levels 1..Depth from level 0 (used after a GPU leaf pass read back, and by the above).
  void BuildUpperLevels(const ParallelFor& parallel);

  int GetLeafSize() const { return this->LeafSize; }
  int GetDepth() const { return static_cast<int>(this->Levels.size()) - 1; }
  const int* GetDimensions() const { return this->Dimensions; }
  const OctreeLevel& GetLevel(int level) const { return this->Levels[level]; }
  OctreeLevel& GetLevel(int level) { return this->Levels[level]; }
  // Total array length over all levels (padding nodes included).
  std::size_t GetNumberOfNodes() const;
  // Index-space box a node's samples may come from: [i*L*2^l, (i+1)*L*2^l] clamped to the volume.
  // Padding nodes get an empty box (Box::IsEmpty).
  Box NodeBox(int level, std::uint64_t index) const;
  // True for nodes outside the volume and for indices past the level's end.
  bool IsPadding(int level, std::uint64_t index) const;

  // --- Classification (transfer-function dependent, kept apart from the build) ---
  // opacity: table of N >= 2 opacities sampled evenly over [rangeMin, rangeMax] of the raw
  // scalar values and linearly interpolated in between (values outside clamp to the ends).
  // A node is transparent when no value in [min, max] can get opacity > threshold.
  // O(nodes + N) with a prefix count over the table.
  // Rule: [min, max] maps to table positions [pmin, pmax] (clamped to [0, N-1]); the node is
  // non-transparent iff some entry with index in [floor(pmin), ceil(pmax)] is > threshold. This
  // is exact for threshold 0 and non-negative opacities and conservative otherwise. Each node is
  // judged on its own range, so a transparent parent always has transparent children. Padding
  // and empty nodes (min > max) are transparent. rangeMin > rangeMax maps values decreasingly.
  // rangeMin == rangeMax is a step: values below map to entry 0, above to entry N-1, and the
  // value itself to the whole table (conservative whichever side a renderer picks). N == 1 is a
  // constant opacity; an empty table makes everything transparent.
  void Classify(
    const std::vector<float>& opacity, double rangeMin, double rangeMax, float threshold = 0.0f);
  bool IsClassified() const { return !this->Transparent.empty(); }
  // transparent flags per level, by Morton index (padding counts as transparent)
  const std::vector<std::uint8_t>& GetTransparentFlags(int level) const
  {
    return this->Transparent[level];
  }
  bool IsTransparent(int level, std::uint64_t index) const;
  // Keeps a node transparent only where `other` (classified, the same layout: another
  // component of the same volume) is transparent too, so that several components' opacities
  // classify one octree. Does nothing unless both are classified with equal depths.
  void IntersectTransparency(const MinMaxOctree& other);

  // --- Queries (need Classify; unclassified, everything counts as non-transparent) ---
  // The largest transparent node whose box contains the index-space point; false if the
  // leaf containing it is not transparent (or the point is outside the volume box).
  // A point on a face shared by two leaves belongs to the leaf on its higher side (leaf
  // floor(p / L) per axis), except on the volume's far faces, which belong to the last leaf.
  // The answer is an ancestor-or-self of that leaf.
  bool LargestEmptyNodeAt(const Vec3& point, int& level, std::uint64_t& index) const;
  // Along origin + t * direction (index space), t in [t0, t1]: the smallest t >= t0 at which
  // the ray enters a non-transparent leaf box, or t1 if it never does before t1.
  // [t0, t1] is first clipped to the volume box. An exact octree walk (largest empty node, jump
  // to its exit face, step across it), so the answer never lies past the true entry; at points
  // on shared faces the leaf the ray moves into is the one tested (a ray lying exactly in a
  // shared face, direction component 0, uses the higher leaf: safe for rendering, as samples on
  // a shared face read only voxels both leaves cover).
  double NextNonEmpty(const Vec3& origin, const Vec3& direction, double t0, double t1) const;
  // Boxes (index space, with overlap) of the non-transparent leaves, merged where a whole
  // subtree is non-transparent (its node box replaces its leaves). A subtree reaching past the
  // volume merges when all its non-padding leaves are non-transparent: its clamped box is
  // exactly their union. Boxes come in Morton (depth-first) order.
  std::vector<Box> NonEmptyBoxes() const;

private:
  // Shared argument checks of the builders.
  bool CheckVolume(const VolumeView& volume, std::string& error) const;
  // Leaf-grid coordinate containing p along an axis: the leaf the ray (direction d along the
  // axis) moves into when p lies on a shared face, clamped to the grid.
  int LocateLeaf(double p, double d, int axis) const;
  // Highest transparent ancestor-or-self (level, index) of leaf coordinates c; false if none.
  bool LargestEmptyNodeOfLeaf(const int c[3], int& level, std::uint64_t& index) const;

  int Dimensions[3] = { 0, 0, 0 };
  int LeafSize = 8;
  std::vector<OctreeLevel> Levels;
  std::vector<std::vector<std::uint8_t>> Transparent;
};

// Runs body(0, count) on the calling thread.
void SerialFor(std::size_t count, const std::function<void(std::size_t, std::size_t)>& body);
}

#endif
