// MinMaxOctreeQueries: transfer-function classification of octree nodes and empty-space queries.
#include "skipping/MinMaxOctree.h"
#include "skipping/OpacityRange.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace accelvolume
{

namespace
{
// Subtree states of NonEmptyBoxes.
constexpr std::uint8_t SubtreeHasTransparentLeaf = 0;
constexpr std::uint8_t SubtreeAllNonTransparent = 1;
constexpr std::uint8_t SubtreeOnlyPadding = 2;
constexpr std::uint64_t ChildrenPerNode = 8;
// Extra NextNonEmpty steps beyond the number of leaf boundary planes, which bounds the steps in
// exact arithmetic (each step crosses at least one plane); hitting the cap answers conservatively.
constexpr int ExtraWalkSteps = 16;

double Component(const Vec3& v, int axis)
{
  return axis == 0 ? v.x : (axis == 1 ? v.y : v.z);
}
}

void MinMaxOctree::Classify(
  const std::vector<float>& opacity, double rangeMin, double rangeMax, float threshold)
{
  // OpacityRange holds the rule documented in the header, shared with the ray caster's cells.
  const OpacityRange range(opacity, rangeMin, rangeMax, threshold);
  this->Transparent.resize(this->Levels.size());
  for (std::size_t level = 0; level < this->Levels.size(); ++level)
  {
    const OctreeLevel& nodes = this->Levels[level];
    std::vector<std::uint8_t>& flags = this->Transparent[level];
    flags.resize(nodes.minimum.size());
    const float* minimum = nodes.minimum.data();
    const float* maximum = nodes.maximum.data();
    for (std::size_t n = 0; n < flags.size(); ++n)
    {
      // Padding and all-NaN nodes (min > max) come out transparent.
      flags[n] = range.MayBeOpaque(minimum[n], maximum[n]) ? 0 : 1;
    }
  }
}

bool MinMaxOctree::IsTransparent(int level, std::uint64_t index) const
{
  if (!this->IsClassified() || level < 0 || level > this->GetDepth())
  {
    return false;
  }
  const std::vector<std::uint8_t>& flags = this->Transparent[level];
  return index >= flags.size() || flags[index] != 0;
}

void MinMaxOctree::IntersectTransparency(const MinMaxOctree& other)
{
  if (!this->IsClassified() || !other.IsClassified() ||
    other.Transparent.size() != this->Transparent.size())
  {
    return;
  }
  for (std::size_t level = 0; level < this->Transparent.size(); ++level)
  {
    std::vector<std::uint8_t>& flags = this->Transparent[level];
    const std::vector<std::uint8_t>& others = other.Transparent[level];
    for (std::size_t i = 0; i < flags.size() && i < others.size(); ++i)
    {
      flags[i] = static_cast<std::uint8_t>(flags[i] && others[i]);
    }
  }
}

int MinMaxOctree::LocateLeaf(double p, double d, int axis) const
{
  const int grid = this->Levels[0].gridSize[axis];
  double q = p / this->LeafSize;
  // Clamp before converting (points may lie slightly outside after rounding).
  q = std::min(std::max(q, -1.0), static_cast<double>(grid) + 1.0);
  const double cell = d < 0 ? std::ceil(q) - 1.0 : std::floor(q);
  return std::min(std::max(static_cast<int>(cell), 0), grid - 1);
}

bool MinMaxOctree::LargestEmptyNodeOfLeaf(const int c[3], int& level, std::uint64_t& index) const
{
  if (!this->IsClassified())
  {
    return false;
  }
  // Transparency is monotone (a transparent parent has transparent children), so the first
  // transparent node on the way down is the largest.
  for (int l = this->GetDepth(); l >= 0; --l)
  {
    const std::uint64_t i = MortonEncode(static_cast<std::uint32_t>(c[0] >> l),
      static_cast<std::uint32_t>(c[1] >> l), static_cast<std::uint32_t>(c[2] >> l));
    if (this->Transparent[l][i])
    {
      level = l;
      index = i;
      return true;
    }
  }
  return false;
}

bool MinMaxOctree::LargestEmptyNodeAt(const Vec3& point, int& level, std::uint64_t& index) const
{
  if (this->Levels.empty())
  {
    return false;
  }
  int c[3];
  for (int axis = 0; axis < 3; ++axis)
  {
    const double p = Component(point, axis);
    // Written so that NaN coordinates count as outside.
    if (!(p >= 0.0 && p <= this->Dimensions[axis] - 1.0))
    {
      return false;
    }
    c[axis] = this->LocateLeaf(p, 0.0, axis);
  }
  return this->LargestEmptyNodeOfLeaf(c, level, index);
}

double MinMaxOctree::NextNonEmpty(
  const Vec3& origin, const Vec3& direction, double t0, double t1) const
{
  if (this->Levels.empty() || !(t0 <= t1))
  {
    return t1;
  }
  double o[3], d[3];
  double enter = t0;
  double leave = t1;
  for (int axis = 0; axis < 3; ++axis)
  {
    o[axis] = Component(origin, axis);
    d[axis] = Component(direction, axis);
    const double far = this->Dimensions[axis] - 1.0;
    if (d[axis] == 0.0)
    {
      if (!(o[axis] >= 0.0 && o[axis] <= far))
      {
        return t1;
      }
      continue;
    }
    double ta = (0.0 - o[axis]) / d[axis];
    double tb = (far - o[axis]) / d[axis];
    if (ta > tb)
    {
      std::swap(ta, tb);
    }
    enter = std::max(enter, ta);
    leave = std::min(leave, tb);
  }
  if (!(enter <= leave))
  {
    return t1;
  }
  double t = enter;
  int c[3];
  for (int axis = 0; axis < 3; ++axis)
  {
    const double p = std::min(std::max(o[axis] + t * d[axis], 0.0), this->Dimensions[axis] - 1.0);
    c[axis] = this->LocateLeaf(d[axis] == 0.0 ? o[axis] : p, d[axis], axis);
  }

  const int* grid = this->Levels[0].gridSize;
  const int maximumSteps = grid[0] + grid[1] + grid[2] + ExtraWalkSteps;
  for (int step = 0; step < maximumSteps; ++step)
  {
    int level = 0;
    std::uint64_t index = 0;
    if (!this->LargestEmptyNodeOfLeaf(c, level, index))
    {
      return t; // c is a non-transparent leaf the ray is in at t
    }
    // The node in leaf coordinates [first, last] per axis, and the time the ray leaves it.
    int first[3], last[3];
    double exitTimes[3];
    double exitTime = std::numeric_limits<double>::infinity();
    for (int axis = 0; axis < 3; ++axis)
    {
      first[axis] = (c[axis] >> level) << level;
      last[axis] = std::min(first[axis] + (1 << level) - 1, grid[axis] - 1);
      exitTimes[axis] = std::numeric_limits<double>::infinity();
      if (d[axis] != 0.0)
      {
        const double boundary = d[axis] > 0
          ? std::min(
              static_cast<double>(last[axis] + 1) * this->LeafSize, this->Dimensions[axis] - 1.0)
          : static_cast<double>(first[axis]) * this->LeafSize;
        exitTimes[axis] = (boundary - o[axis]) / d[axis];
      }
      exitTime = std::min(exitTime, exitTimes[axis]);
    }
    if (exitTime >= leave)
    {
      return t1;
    }
    t = std::max(t, exitTime);
    for (int axis = 0; axis < 3; ++axis)
    {
      if (d[axis] == 0.0)
      {
        continue;
      }
      if (exitTimes[axis] <= exitTime)
      {
        // Crossing this face: step into the neighbour exactly rather than relocating the
        // rounded point, which could land back in the node just left.
        c[axis] = d[axis] > 0 ? last[axis] + 1 : first[axis] - 1;
        if (c[axis] < 0 || c[axis] >= grid[axis])
        {
          return t1;
        }
      }
      else
      {
        // The ray keeps within the node along this axis; coordinates only move forward.
        const int located = this->LocateLeaf(o[axis] + t * d[axis], d[axis], axis);
        c[axis] = d[axis] > 0 ? std::max(c[axis], located) : std::min(c[axis], located);
        c[axis] = std::min(std::max(c[axis], first[axis]), last[axis]);
      }
    }
  }
  return t;
}

std::vector<Box> MinMaxOctree::NonEmptyBoxes() const
{
  std::vector<Box> boxes;
  const int depth = this->GetDepth();
  if (depth < 0)
  {
    return boxes;
  }
  // Per node: does its subtree hold a transparent leaf, only non-transparent leaves, or nothing?
  std::vector<std::vector<std::uint8_t>> state(this->Levels.size());
  state[0].resize(this->Levels[0].minimum.size());
  for (std::size_t n = 0; n < state[0].size(); ++n)
  {
    state[0][n] = this->IsPadding(0, n)
      ? SubtreeOnlyPadding
      : (this->IsTransparent(0, n) ? SubtreeHasTransparentLeaf : SubtreeAllNonTransparent);
  }
  for (int level = 1; level <= depth; ++level)
  {
    const std::vector<std::uint8_t>& children = state[level - 1];
    std::vector<std::uint8_t>& parents = state[level];
    parents.resize(this->Levels[level].minimum.size());
    for (std::size_t p = 0; p < parents.size(); ++p)
    {
      std::uint8_t combined = SubtreeOnlyPadding;
      const std::size_t end = std::min<std::size_t>(ChildrenPerNode * (p + 1), children.size());
      for (std::size_t c = ChildrenPerNode * p; c < end; ++c)
      {
        combined = std::min(combined, children[c]);
      }
      parents[p] = combined;
    }
  }
  // Depth-first from the root; children pushed in reverse so boxes come out in Morton order.
  std::vector<std::pair<int, std::uint64_t>> stack{ { depth, 0 } };
  while (!stack.empty())
  {
    const std::pair<int, std::uint64_t> node = stack.back();
    stack.pop_back();
    const std::uint8_t s = state[node.first][node.second];
    if (s == SubtreeAllNonTransparent)
    {
      boxes.push_back(this->NodeBox(node.first, node.second));
    }
    else if (s == SubtreeHasTransparentLeaf && node.first > 0)
    {
      const std::size_t childCount = state[node.first - 1].size();
      for (std::uint64_t c = ChildrenPerNode; c-- > 0;)
      {
        const std::uint64_t child = ChildrenPerNode * node.second + c;
        if (child < childCount)
        {
          stack.emplace_back(node.first - 1, child);
        }
      }
    }
  }
  return boxes;
}

}
