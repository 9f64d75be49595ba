// MinMaxOctree: Morton codes, octree layout and the reference and parallel min-max builders.
#include "skipping/MinMaxOctree.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>

namespace accelvolume
{

namespace
{
// Morton codes hold 21 bits per axis in 63 bits.
constexpr std::uint64_t MortonAxisMask = 0x1fffff;
// A level may not hold more nodes than this (its Morton array would not fit a 32-bit index,
// which the GPU builder and texture layouts rely on).
constexpr std::uint64_t MaximumNodesPerLevel = std::uint64_t(1) << 31;
constexpr int MinimumLeafSize = 2;
constexpr int MaximumLeafSize = 64;
// Voxels per inner block of the row accumulation: a compile-time trip count lets the compiler
// vectorize the min/max loop even under -O2's cheap vectorizer cost model.
constexpr int AccumulateBlock = 64;
constexpr float PositiveInfinity = std::numeric_limits<float>::infinity();

// Spreads the low 21 bits of v so that bit b lands on bit 3b.
std::uint64_t SpreadBits(std::uint32_t v)
{
  std::uint64_t x = v & MortonAxisMask;
  x = (x | (x << 32)) & 0x1f00000000ffffULL;
  x = (x | (x << 16)) & 0x1f0000ff0000ffULL;
  x = (x | (x << 8)) & 0x100f00f00f00f00fULL;
  x = (x | (x << 4)) & 0x10c30c30c30c30c3ULL;
  x = (x | (x << 2)) & 0x1249249249249249ULL;
  return x;
}

// Inverse of SpreadBits: gathers every third bit starting at bit 0.
std::uint32_t CompactBits(std::uint64_t code)
{
  std::uint64_t x = code & 0x1249249249249249ULL;
  x = (x | (x >> 2)) & 0x10c30c30c30c30c3ULL;
  x = (x | (x >> 4)) & 0x100f00f00f00f00fULL;
  x = (x | (x >> 8)) & 0x1f0000ff0000ffULL;
  x = (x | (x >> 16)) & 0x1f00000000ffffULL;
  x = (x | (x >> 32)) & MortonAxisMask;
  return static_cast<std::uint32_t>(x);
}

// Largest float <= value (so a node minimum never exceeds a voxel it covers).
float RoundDown(double value)
{
  if (std::isinf(value))
  {
    return static_cast<float>(value);
  }
  if (value > std::numeric_limits<float>::max())
  {
    return std::numeric_limits<float>::max();
  }
  if (value < -std::numeric_limits<float>::max())
  {
    return -PositiveInfinity;
  }
  float result = static_cast<float>(value);
  if (static_cast<double>(result) > value)
  {
    result = std::nextafter(result, -PositiveInfinity);
  }
  return result;
}

// Smallest float >= value.
float RoundUp(double value)
{
  return -RoundDown(-value);
}

// Inclusive voxel range [first, last] of node coordinate c along an axis of n voxels, for nodes
// spanning `span` voxels; first > last for padding nodes.
void VoxelRange(std::uint32_t c, std::int64_t span, int n, std::int64_t& first, std::int64_t& last)
{
  first = static_cast<std::int64_t>(c) * span;
  last = std::min<std::int64_t>(first + span, n - 1);
}

template <typename T>
void ReferenceLevel(const T* data, const int dims[3], int leafSize, int level, OctreeLevel& out)
{
  const std::int64_t span = static_cast<std::int64_t>(leafSize) << level;
  const std::size_t nx = static_cast<std::size_t>(dims[0]);
  const std::size_t nxy = nx * static_cast<std::size_t>(dims[1]);
  for (std::size_t index = 0; index < out.minimum.size(); ++index)
  {
    std::uint32_t c[3];
    MortonDecode(index, c[0], c[1], c[2]);
    out.minimum[index] = PositiveInfinity;
    out.maximum[index] = -PositiveInfinity;
    if (static_cast<int>(c[0]) >= out.gridSize[0] || static_cast<int>(c[1]) >= out.gridSize[1] ||
      static_cast<int>(c[2]) >= out.gridSize[2])
    {
      continue; // padding
    }
    std::int64_t first[3], last[3];
    for (int axis = 0; axis < 3; ++axis)
    {
      VoxelRange(c[axis], span, dims[axis], first[axis], last[axis]);
    }
    // Doubles hold every supported scalar exactly, so rounding happens once, at the end.
    double low = std::numeric_limits<double>::infinity();
    double high = -std::numeric_limits<double>::infinity();
    for (std::int64_t z = first[2]; z <= last[2]; ++z)
    {
      for (std::int64_t y = first[1]; y <= last[1]; ++y)
      {
        const T* row = data + static_cast<std::size_t>(z) * nxy + static_cast<std::size_t>(y) * nx;
        for (std::int64_t x = first[0]; x <= last[0]; ++x)
        {
          const double v = static_cast<double>(row[x]);
          if (std::isnan(v))
          {
            continue;
          }
          low = std::min(low, v);
          high = std::max(high, v);
        }
      }
    }
    out.minimum[index] = RoundDown(low);
    out.maximum[index] = RoundUp(high);
  }
}

// Initial accumulator values: any voxel replaces them (floats start at +-inf so that a leaf of
// only NaNs ends up empty, +inf / -inf, like the reference builder).
template <typename T>
T LowestStart()
{
  return std::is_floating_point<T>::value ? std::numeric_limits<T>::infinity()
                                          : std::numeric_limits<T>::max();
}

template <typename T>
T HighestStart()
{
  return std::is_floating_point<T>::value ? -std::numeric_limits<T>::infinity()
                                          : std::numeric_limits<T>::lowest();
}

// Element-wise running min/max of a voxel row. The comparisons are written so that a NaN voxel
// leaves the accumulator unchanged (v < low is false for NaN).
template <typename T>
void AccumulateRow(
  const T* __restrict row, T* __restrict low, T* __restrict high, std::size_t count)
{
  std::size_t x = 0;
  for (; x + AccumulateBlock <= count; x += AccumulateBlock)
  {
    const T* v = row + x;
    T* lo = low + x;
    T* hi = high + x;
    for (int b = 0; b < AccumulateBlock; ++b)
    {
      lo[b] = v[b] < lo[b] ? v[b] : lo[b];
      hi[b] = v[b] > hi[b] ? v[b] : hi[b];
    }
  }
  for (; x < count; ++x)
  {
    low[x] = row[x] < low[x] ? row[x] : low[x];
    high[x] = row[x] > high[x] ? row[x] : high[x];
  }
}

// Leaf pass of BuildParallel. Work item k is the z-layer of leaves k: it streams the voxel planes
// [k*L, (k+1)*L] once (only the shared top plane is read again by layer k+1), folding each row
// element-wise into the accumulator row of its leaf row j (a row on a shared y boundary is folded
// into both, from cache). Each leaf then reduces its x segment of its accumulator row.
template <typename T>
void BuildLeaves(
  const T* data, const int dims[3], int leafSize, OctreeLevel& leaves, const ParallelFor& parallel)
{
  const std::size_t nx = static_cast<std::size_t>(dims[0]);
  const std::size_t ny = static_cast<std::size_t>(dims[1]);
  const std::size_t nz = static_cast<std::size_t>(dims[2]);
  const std::size_t bx = static_cast<std::size_t>(leaves.gridSize[0]);
  const std::size_t by = static_cast<std::size_t>(leaves.gridSize[1]);
  const std::size_t bz = static_cast<std::size_t>(leaves.gridSize[2]);
  const std::size_t L = static_cast<std::size_t>(leafSize);
  float* leafMinimum = leaves.minimum.data();
  float* leafMaximum = leaves.maximum.data();

  parallel(bz,
    [=](std::size_t kBegin, std::size_t kEnd)
    {
      std::vector<T> low(by * nx);
      std::vector<T> high(by * nx);
      for (std::size_t k = kBegin; k < kEnd; ++k)
      {
        std::fill(low.begin(), low.end(), LowestStart<T>());
        std::fill(high.begin(), high.end(), HighestStart<T>());
        const std::size_t zFirst = k * L;
        const std::size_t zLast = std::min((k + 1) * L, nz - 1);
        for (std::size_t z = zFirst; z <= zLast; ++z)
        {
          const T* plane = data + z * nx * ny;
          for (std::size_t y = 0; y < ny; ++y)
          {
            const T* row = plane + y * nx;
            const std::size_t j = y / L;
            if (j < by)
            {
              AccumulateRow(row, low.data() + j * nx, high.data() + j * nx, nx);
            }
            if (y % L == 0 && j > 0)
            {
              AccumulateRow(row, low.data() + (j - 1) * nx, high.data() + (j - 1) * nx, nx);
            }
          }
        }
        for (std::size_t j = 0; j < by; ++j)
        {
          const T* lowRow = low.data() + j * nx;
          const T* highRow = high.data() + j * nx;
          for (std::size_t i = 0; i < bx; ++i)
          {
            const std::size_t xFirst = i * L;
            const std::size_t xLast = std::min((i + 1) * L, nx - 1);
            T lo = LowestStart<T>();
            T hi = HighestStart<T>();
            for (std::size_t x = xFirst; x <= xLast; ++x)
            {
              lo = lowRow[x] < lo ? lowRow[x] : lo;
              hi = highRow[x] > hi ? highRow[x] : hi;
            }
            const std::uint64_t index = MortonEncode(static_cast<std::uint32_t>(i),
              static_cast<std::uint32_t>(j), static_cast<std::uint32_t>(k));
            leafMinimum[index] = RoundDown(static_cast<double>(lo));
            leafMaximum[index] = RoundUp(static_cast<double>(hi));
          }
        }
      }
    });
}

}

std::uint64_t MortonEncode(std::uint32_t x, std::uint32_t y, std::uint32_t z)
{
  return SpreadBits(x) | (SpreadBits(y) << 1) | (SpreadBits(z) << 2);
}

void MortonDecode(std::uint64_t code, std::uint32_t& x, std::uint32_t& y, std::uint32_t& z)
{
  x = CompactBits(code);
  y = CompactBits(code >> 1);
  z = CompactBits(code >> 2);
}

void SerialFor(std::size_t count, const std::function<void(std::size_t, std::size_t)>& body)
{
  if (count > 0)
  {
    body(0, count);
  }
}

bool MinMaxOctree::Configure(const int dims[3], int leafSize, std::string& error)
{
  this->Levels.clear();
  this->Transparent.clear();
  if (leafSize < MinimumLeafSize || leafSize > MaximumLeafSize || (leafSize & (leafSize - 1)))
  {
    error =
      "MinMaxOctree: leaf size " + std::to_string(leafSize) + " is not a power of two in [2, 64]";
    return false;
  }
  std::int64_t leafGrid[3];
  std::int64_t largest = 1;
  for (int axis = 0; axis < 3; ++axis)
  {
    if (dims[axis] < 1)
    {
      error = "MinMaxOctree: dimensions must be at least 1";
      return false;
    }
    leafGrid[axis] =
      std::max<std::int64_t>(1, (std::int64_t(dims[axis]) - 1 + leafSize - 1) / leafSize);
    if (leafGrid[axis] > static_cast<std::int64_t>(MortonAxisMask) + 1)
    {
      error = "MinMaxOctree: volume too large for 21-bit Morton coordinates";
      return false;
    }
    largest = std::max(largest, leafGrid[axis]);
  }
  int depth = 0;
  while ((std::int64_t(1) << depth) < largest)
  {
    ++depth;
  }
  std::vector<OctreeLevel> levels(static_cast<std::size_t>(depth) + 1);
  for (int level = 0; level <= depth; ++level)
  {
    OctreeLevel& current = levels[level];
    const std::int64_t divisor = std::int64_t(1) << level;
    for (int axis = 0; axis < 3; ++axis)
    {
      current.gridSize[axis] = static_cast<int>((leafGrid[axis] + divisor - 1) / divisor);
    }
    const std::uint64_t count = MortonEncode(static_cast<std::uint32_t>(current.gridSize[0] - 1),
                                  static_cast<std::uint32_t>(current.gridSize[1] - 1),
                                  static_cast<std::uint32_t>(current.gridSize[2] - 1)) +
      1;
    if (count > MaximumNodesPerLevel)
    {
      error = "MinMaxOctree: level " + std::to_string(level) + " would need " +
        std::to_string(count) + " nodes (more than 2^31)";
      return false;
    }
    current.minimum.assign(static_cast<std::size_t>(count), PositiveInfinity);
    current.maximum.assign(static_cast<std::size_t>(count), -PositiveInfinity);
  }
  for (int axis = 0; axis < 3; ++axis)
  {
    this->Dimensions[axis] = dims[axis];
  }
  this->LeafSize = leafSize;
  this->Levels = std::move(levels);
  return true;
}

bool MinMaxOctree::CheckVolume(const VolumeView& volume, std::string& error) const
{
  if (this->Levels.empty())
  {
    error = "MinMaxOctree: Configure was not called (or failed)";
    return false;
  }
  if (!volume.data)
  {
    error = "MinMaxOctree: volume has no data";
    return false;
  }
  for (int axis = 0; axis < 3; ++axis)
  {
    if (volume.dims[axis] != this->Dimensions[axis])
    {
      error = "MinMaxOctree: volume dimensions differ from the configured ones";
      return false;
    }
  }
  return true;
}

bool MinMaxOctree::BuildReference(const VolumeView& volume, std::string& error)
{
  if (!this->CheckVolume(volume, error))
  {
    return false;
  }
  this->Transparent.clear();
  DispatchScalarType(volume,
    [&](auto data)
    {
      for (int level = 0; level <= this->GetDepth(); ++level)
      {
        ReferenceLevel(data, this->Dimensions, this->LeafSize, level, this->Levels[level]);
      }
    });
  return true;
}

bool MinMaxOctree::BuildParallel(
  const VolumeView& volume, const ParallelFor& parallel, std::string& error)
{
  if (!this->CheckVolume(volume, error))
  {
    return false;
  }
  this->Transparent.clear();
  OctreeLevel& leaves = this->Levels[0];
  // Padding leaves are never written by the leaf pass.
  std::fill(leaves.minimum.begin(), leaves.minimum.end(), PositiveInfinity);
  std::fill(leaves.maximum.begin(), leaves.maximum.end(), -PositiveInfinity);
  DispatchScalarType(volume,
    [&](auto data) { BuildLeaves(data, this->Dimensions, this->LeafSize, leaves, parallel); });
  this->BuildUpperLevels(parallel);
  return true;
}

void MinMaxOctree::BuildUpperLevels(const ParallelFor& parallel)
{
  this->Transparent.clear();
  for (std::size_t level = 1; level < this->Levels.size(); ++level)
  {
    const OctreeLevel& children = this->Levels[level - 1];
    OctreeLevel& parents = this->Levels[level];
    const float* childMinimum = children.minimum.data();
    const float* childMaximum = children.maximum.data();
    float* parentMinimum = parents.minimum.data();
    float* parentMaximum = parents.maximum.data();
    const std::size_t childCount = children.minimum.size();
    parallel(parents.minimum.size(),
      [=](std::size_t begin, std::size_t end)
      {
        for (std::size_t p = begin; p < end; ++p)
        {
          // Children past the end of the child level do not exist (they would be padding).
          const std::size_t first = 8 * p;
          const std::size_t last = std::min(first + 8, childCount);
          float low = PositiveInfinity;
          float high = -PositiveInfinity;
          for (std::size_t c = first; c < last; ++c)
          {
            low = std::min(low, childMinimum[c]);
            high = std::max(high, childMaximum[c]);
          }
          parentMinimum[p] = low;
          parentMaximum[p] = high;
        }
      });
  }
}

std::size_t MinMaxOctree::GetNumberOfNodes() const
{
  std::size_t count = 0;
  for (const OctreeLevel& level : this->Levels)
  {
    count += level.minimum.size();
  }
  return count;
}

bool MinMaxOctree::IsPadding(int level, std::uint64_t index) const
{
  if (level < 0 || level > this->GetDepth() || index >= this->Levels[level].minimum.size())
  {
    return true;
  }
  std::uint32_t c[3];
  MortonDecode(index, c[0], c[1], c[2]);
  const int* grid = this->Levels[level].gridSize;
  return static_cast<int>(c[0]) >= grid[0] || static_cast<int>(c[1]) >= grid[1] ||
    static_cast<int>(c[2]) >= grid[2];
}

Box MinMaxOctree::NodeBox(int level, std::uint64_t index) const
{
  std::uint32_t c[3];
  MortonDecode(index, c[0], c[1], c[2]);
  const std::int64_t span = static_cast<std::int64_t>(this->LeafSize) << level;
  double lower[3], upper[3];
  for (int axis = 0; axis < 3; ++axis)
  {
    std::int64_t first, last;
    VoxelRange(c[axis], span, this->Dimensions[axis], first, last);
    // A padding node may start exactly on the far face; force it empty rather than flat there.
    if (static_cast<int>(c[axis]) >= this->Levels[level].gridSize[axis])
    {
      last = first - 1;
    }
    lower[axis] = static_cast<double>(first);
    upper[axis] = static_cast<double>(last);
  }
  return { { lower[0], lower[1], lower[2] }, { upper[0], upper[1], upper[2] } };
}

}
