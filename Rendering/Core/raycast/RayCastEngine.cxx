// RayCastEngine: frame setup, acceleration-structure caches and tiling of the CPU ray caster.
#include "raycast/RayCastEngine.h"

#include "skipping/CellClassification.h"
#include "skipping/DistanceMap.h"
#include "skipping/OpacityRange.h"
#include "raycast/RayCastKernel.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <utility>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace accelvolume
{

namespace
{
// Which accelerations are exact for a frame's blend mode (see the header), and the threshold
// the cells are classified with.
struct LeapPlan
{
  bool zeroOpacityAddsNothing = false;
  bool extremum = false;
  bool useOctree = false;
  bool useDistance = false;
  bool useCellLeap = false;
  double leapThreshold = 0;
};

// Rebuilds take [0, PrepareShare] of the frame; each one done halves what is left of it (which
// rebuilds a frame needs is known only as they run).
constexpr double PrepareShare = 0.25;

struct PrepareProgress
{
  const ProgressFunction& report;
  double prepared = 0;

  void Rebuilt()
  {
    this->prepared += (PrepareShare - this->prepared) / 2;
    if (this->report)
    {
      this->report(this->prepared);
    }
  }
};
}

struct RayCaster::Internals
{
  MinMaxOctree Octree;
  bool OctreeBuilt = false;
  std::uint64_t OctreeVolume = 0;
  int OctreeLeafSize = 0;
  bool OctreeClassified = false;
  std::uint64_t OctreeTransfer = 0;

  int CellDims[3] = { 0, 0, 0 };
  bool CellsBuilt = false;
  Box CellsOpaqueBox;  // index-space box of the cells that may be opaque
  Box OctreeOpaqueBox; // index-space box of the non-transparent leaves
  std::uint64_t CellsVolume = 0, CellsTransfer = 0;

  // Per cell: distance-map value (low byte, 0 without a distance map) and Marching Cubes
  // configuration (high byte), packed so one load serves both leaps. The sources are freed
  // once packed.
  std::vector<std::uint16_t> CellInfo;
  bool CellInfoHasDistance = false;
  // Without cell leaping only the distance map is read: one byte per cell halves the memory
  // the rays pull through the caches.
  std::vector<std::uint8_t> DistanceOnly;
  bool Packed = false; // which of the two layouts is built

  std::vector<std::int16_t> Gradients;
  bool GradientsBuilt = false;
  std::uint64_t GradientsVolume = 0;
  float GradientScale = 1;

  std::vector<float> CorrectedAlpha;
  std::vector<float> SpecularTable;
  int CastRectangle[4] = { 0, -1, 0, -1 };
  double PrepareSeconds = 0;

  ProgressFunction Progress;

  // Frame preparation steps of RayCaster::Render (each rebuilds only what changed).
  bool UpdateOctree(const VolumeView& volume, std::uint64_t volumeVersion,
    std::uint64_t transferVersion, const std::vector<float>& alphas, double rangeMin,
    double rangeMax, const RayCastSettings& settings, const LeapPlan& plan,
    const ParallelFor& parallel, PrepareProgress& progress, std::string& error);
  void UpdateCells(const VolumeView& volume, std::uint64_t volumeVersion,
    std::uint64_t transferVersion, const OpacityRange& opacityRange, const LeapPlan& plan,
    const ParallelFor& parallel, PrepareProgress& progress);
  void PackCellInfo(const CellClassification& cells, const std::vector<std::uint8_t>& distance,
    const ParallelFor& parallel);
  bool UpdateGradients(const VolumeView& volume, std::uint64_t volumeVersion, double width,
    const RayCastTransfer& transfer, const RayCastLighting& lighting,
    const RayCastSettings& settings, const ParallelFor& parallel, PrepareProgress& progress);
  void FillKernelFrame(const VolumeView& volume, double rangeMin, double rangeMax,
    const RayCastTransfer& transfer, const RayCastLighting& lighting, const RayCastView& view,
    const RayCastSettings& settings, const LeapPlan& plan, bool useGradients, double exponent,
    detail::KernelFrame& frame);
};

RayCaster::RayCaster()
  : Impl(new Internals)
{
}

RayCaster::~RayCaster() = default;

void RayCaster::SetProgressFunction(ProgressFunction report)
{
  this->Impl->Progress = std::move(report);
}

void RayCaster::GetLastCastRectangle(int rectangle[4]) const
{
  std::copy(this->Impl->CastRectangle, this->Impl->CastRectangle + 4, rectangle);
}

double RayCaster::GetLastPrepareSeconds() const
{
  return this->Impl->PrepareSeconds;
}

std::size_t RayCaster::GetAccelerationBytes() const
{
  const Internals& impl = *this->Impl;
  std::size_t bytes = impl.CellInfo.size() * sizeof(std::uint16_t) + impl.DistanceOnly.size() +
    impl.Gradients.size() * sizeof(std::int16_t);
  if (impl.OctreeBuilt)
  {
    bytes += impl.Octree.GetNumberOfNodes() * (2 * sizeof(float) + 1);
  }
  return bytes;
}

namespace
{

// Grows [lower, upper] (per axis, integer grid coordinates) to hold (i, j, k).
struct GridBounds
{
  int lower[3] = { std::numeric_limits<int>::max(), std::numeric_limits<int>::max(),
    std::numeric_limits<int>::max() };
  int upper[3] = { -1, -1, -1 };
  void Add(int i, int j, int k)
  {
    const int c[3] = { i, j, k };
    for (int a = 0; a < 3; ++a)
    {
      lower[a] = std::min(lower[a], c[a]);
      upper[a] = std::max(upper[a], c[a]);
    }
  }
  void Merge(const GridBounds& other)
  {
    for (int a = 0; a < 3; ++a)
    {
      lower[a] = std::min(lower[a], other.lower[a]);
      upper[a] = std::max(upper[a], other.upper[a]);
    }
  }
  bool Empty() const { return upper[0] < lower[0]; }
};

// Index-space box covering grid cells [lower, upper] of `size` voxels each (cell i spans
// [i * size, (i + 1) * size]), clamped to the volume box; empty when no cell was added.
Box GridBox(const GridBounds& bounds, int size, const int dims[3])
{
  Box box;
  if (bounds.Empty())
  {
    box.lower = { 1, 1, 1 };
    box.upper = { 0, 0, 0 };
    return box;
  }
  double* lower[3] = { &box.lower.x, &box.lower.y, &box.lower.z };
  double* upper[3] = { &box.upper.x, &box.upper.y, &box.upper.z };
  for (int a = 0; a < 3; ++a)
  {
    if (dims[a] > 1)
    {
      *lower[a] = static_cast<double>(bounds.lower[a]) * size;
      *upper[a] = std::min(static_cast<double>(bounds.upper[a] + 1) * size, dims[a] - 1.0);
    }
    else
    {
      *lower[a] = -0.5; // a one-voxel axis is a slab one voxel thick
      *upper[a] = 0.5;
    }
  }
  return box;
}

Box NonEmptyCellBox(const CellClassification& cells, const int dims[3], const ParallelFor& parallel)
{
  const int* n = cells.cellDims;
  std::vector<GridBounds> slabs(static_cast<std::size_t>(n[2]));
  parallel(slabs.size(),
    [&](std::size_t begin, std::size_t end)
    {
      for (std::size_t k = begin; k < end; ++k)
      {
        const std::uint8_t* flags = cells.nonEmpty.data() + k * n[0] * n[1];
        for (int j = 0; j < n[1]; ++j)
        {
          for (int i = 0; i < n[0]; ++i)
          {
            if (flags[static_cast<std::size_t>(j) * n[0] + i])
            {
              slabs[k].Add(i, j, static_cast<int>(k));
            }
          }
        }
      }
    });
  GridBounds all;
  for (const GridBounds& slab : slabs)
  {
    all.Merge(slab);
  }
  return GridBox(all, 1, dims);
}

Box NonTransparentLeafBox(const MinMaxOctree& octree, const int dims[3])
{
  const int* grid = octree.GetLevel(0).gridSize;
  const std::vector<std::uint8_t>& transparent = octree.GetTransparentFlags(0);
  GridBounds all;
  for (int k = 0; k < grid[2]; ++k)
  {
    for (int j = 0; j < grid[1]; ++j)
    {
      for (int i = 0; i < grid[0]; ++i)
      {
        if (!transparent[MortonEncode(i, j, k)])
        {
          all.Add(i, j, k);
        }
      }
    }
  }
  return GridBox(all, octree.GetLeafSize(), dims);
}

// Per-voxel central differences (neighbours clamped to the volume, NaN as 0) quantised to
// int16 with step `scale` raw units. Rows are handled with clamped neighbour rows and a
// branch-free interior, since this runs over every voxel when the scalars change.
template <typename T>
void ComputeGradients(
  const T* data, const int dims[3], float scale, std::int16_t* out, const ParallelFor& parallel)
{
  const std::ptrdiff_t nx = dims[0], ny = dims[1], nz = dims[2];
  const float inverse = 0.5f / scale;
  auto quantise = [](float g) -> std::int16_t
  {
    // NaN fails both comparisons and becomes 0; round half away from zero.
    g = g > -32767.0f ? (g < 32767.0f ? g : 32767.0f) : (g <= -32767.0f ? -32767.0f : 0.0f);
    return static_cast<std::int16_t>(g + (g >= 0 ? 0.5f : -0.5f));
  };
  parallel(static_cast<std::size_t>(nz),
    [&](std::size_t begin, std::size_t end)
    {
      for (std::size_t k = begin; k < end; ++k)
      {
        const std::ptrdiff_t z = static_cast<std::ptrdiff_t>(k);
        const std::ptrdiff_t zDown = z > 0 ? z - 1 : z, zUp = z + 1 < nz ? z + 1 : z;
        for (std::ptrdiff_t y = 0; y < ny; ++y)
        {
          const std::ptrdiff_t yDown = y > 0 ? y - 1 : y, yUp = y + 1 < ny ? y + 1 : y;
          const T* row = data + (z * ny + y) * nx;
          const T* rowYDown = data + (z * ny + yDown) * nx;
          const T* rowYUp = data + (z * ny + yUp) * nx;
          const T* rowZDown = data + (zDown * ny + y) * nx;
          const T* rowZUp = data + (zUp * ny + y) * nx;
          std::int16_t* o = out + 3 * (z * ny + y) * nx;
          for (std::ptrdiff_t x = 0; x < nx; ++x)
          {
            const std::ptrdiff_t xDown = x > 0 ? x - 1 : x, xUp = x + 1 < nx ? x + 1 : x;
            o[3 * x] =
              quantise((static_cast<float>(row[xUp]) - static_cast<float>(row[xDown])) * inverse);
            o[3 * x + 1] =
              quantise((static_cast<float>(rowYUp[x]) - static_cast<float>(rowYDown[x])) * inverse);
            o[3 * x + 2] =
              quantise((static_cast<float>(rowZUp[x]) - static_cast<float>(rowZDown[x])) * inverse);
          }
        }
      }
    });
}

// Inverse of a 4x4 matrix by Gauss-Jordan elimination; false when singular.
bool Invert4x4(const double in[4][4], double out[4][4])
{
  double a[4][8];
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      a[r][c] = in[r][c];
      a[r][c + 4] = r == c ? 1.0 : 0.0;
    }
  }
  for (int c = 0; c < 4; ++c)
  {
    int pivot = c;
    for (int r = c + 1; r < 4; ++r)
    {
      pivot = std::abs(a[r][c]) > std::abs(a[pivot][c]) ? r : pivot;
    }
    if (!(std::abs(a[pivot][c]) > 0))
    {
      return false;
    }
    std::swap(a[c], a[pivot]);
    const double scale = 1.0 / a[c][c];
    for (double& v : a[c])
    {
      v *= scale;
    }
    for (int r = 0; r < 4; ++r)
    {
      if (r != c)
      {
        const double f = a[r][c];
        for (int k = 0; k < 8; ++k)
        {
          a[r][k] -= f * a[c][k];
        }
      }
    }
  }
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      out[r][c] = a[r][c + 4];
    }
  }
  return true;
}

// Pixels whose centres the index-space box projects over (inclusive, clamped to the image);
// the whole image when a corner is not in front of the camera (the projection of the box
// is then not bounded by its corners'). An empty box gives an empty rectangle.
void VisiblePixels(const Box& box, const RayCastView& view, int visible[4])
{
  visible[0] = 0;
  visible[1] = view.width - 1;
  visible[2] = 0;
  visible[3] = view.height - 1;
  if (box.IsEmpty())
  {
    visible[1] = visible[3] = -1;
    return;
  }
  double worldToClip[4][4];
  if (!Invert4x4(view.clipToWorld, worldToClip))
  {
    return;
  }
  const Affine indexToWorld = view.worldToIndex.Inverse();
  double lower[2] = { std::numeric_limits<double>::infinity(),
    std::numeric_limits<double>::infinity() };
  double upper[2] = { -lower[0], -lower[1] };
  for (int corner = 0; corner < 8; ++corner)
  {
    const Vec3 world = indexToWorld.Apply({ corner & 1 ? box.upper.x : box.lower.x,
      corner & 2 ? box.upper.y : box.lower.y, corner & 4 ? box.upper.z : box.lower.z });
    double clip[4];
    for (int r = 0; r < 4; ++r)
    {
      clip[r] = worldToClip[r][0] * world.x + worldToClip[r][1] * world.y +
        worldToClip[r][2] * world.z + worldToClip[r][3];
    }
    if (!(clip[3] > 1.0e-12))
    {
      return;
    }
    const int size[2] = { view.width, view.height };
    for (int a = 0; a < 2; ++a)
    {
      // Pixel i has its centre at NDC 2 (i + 0.5) / size - 1.
      const double pixel = (clip[a] / clip[3] + 1.0) * 0.5 * size[a] - 0.5;
      lower[a] = std::min(lower[a], pixel);
      upper[a] = std::max(upper[a], pixel);
    }
  }
  // One pixel of slack on each side absorbs rounding.
  const int size[2] = { view.width, view.height };
  for (int a = 0; a < 2; ++a)
  {
    const double first = std::floor(lower[a]) - 1.0;
    const double last = std::ceil(upper[a]) + 1.0;
    visible[2 * a] = static_cast<int>(std::max(0.0, std::min(first, size[a] - 1.0)));
    visible[2 * a + 1] = static_cast<int>(std::max(-1.0, std::min(last, size[a] - 1.0)));
    if (last < 0 || first > size[a] - 1.0)
    {
      visible[0] = visible[2] = 0;
      visible[1] = visible[3] = -1;
      return;
    }
  }
}

// Resizes v to n elements, asking Linux for transparent huge pages first: the ray caster reads
// these arrays at random along rays, and 2 MiB pages cut its TLB misses (a hint only).
template <typename T>
void ResizeWithHugePages(std::vector<T>& v, std::size_t n)
{
  if (v.capacity() < n)
  {
    std::vector<T>().swap(v);
    v.reserve(n);
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    constexpr std::uintptr_t Huge = std::uintptr_t(1) << 21;
    const auto begin = reinterpret_cast<std::uintptr_t>(v.data());
    const std::uintptr_t first = (begin + Huge - 1) & ~(Huge - 1);
    const std::uintptr_t end = begin + n * sizeof(T);
    if (end > first + Huge)
    {
      madvise(reinterpret_cast<void*>(first), (end - first) & ~(Huge - 1), MADV_HUGEPAGE);
    }
#endif
  }
  v.resize(n);
}

bool CheckArguments(const VolumeView& volume, const RayCastTransfer& transfer,
  const RayCastView& view, const RayCastSettings& settings, std::string& error)
{
  if (!volume.data || volume.dims[0] < 1 || volume.dims[1] < 1 || volume.dims[2] < 1)
  {
    error = "empty volume";
    return false;
  }
  if (transfer.rgba.size() < 8 || transfer.rgba.size() % 4 != 0)
  {
    error = "the colour/opacity table needs at least 2 RGBA entries";
    return false;
  }
  if (view.width < 1 || view.height < 1)
  {
    error = "empty image";
    return false;
  }
  if (view.depth &&
    view.depth->size() !=
      static_cast<std::size_t>(view.width) * static_cast<std::size_t>(view.height))
  {
    error = "depth buffer size does not match the image";
    return false;
  }
  if (!(settings.sampleDistance > 0) || !std::isfinite(settings.sampleDistance))
  {
    error = "the sample distance must be positive";
    return false;
  }
  const int leaf = settings.octreeLeafSize;
  if (leaf < 2 || leaf > 64 || (leaf & (leaf - 1)) != 0)
  {
    error = "the octree leaf size must be a power of two in [2, 64]";
    return false;
  }
  if (settings.tileSize < 1)
  {
    error = "the tile size must be positive";
    return false;
  }
  if (!(settings.additiveUnitDistance > 0) || !(transfer.opacityUnitDistance > 0))
  {
    error = "unit distances must be positive";
    return false;
  }
  return true;
}

// Which accelerations are exact for this blend mode (see the header).
LeapPlan PlanLeaping(const RayCastSettings& settings, const OpacityRange& opacityRange,
  double rangeMin, double rangeMax)
{
  LeapPlan plan;
  plan.zeroOpacityAddsNothing =
    settings.blend == Blend::Composite || settings.blend == Blend::Additive;
  plan.extremum = settings.blend == Blend::Maximum || settings.blend == Blend::Minimum;
  plan.useOctree =
    settings.leap == LeapMode::Octree && (plan.zeroOpacityAddsNothing || plan.extremum);
  plan.useDistance = settings.leap == LeapMode::DistanceMap && plan.zeroOpacityAddsNothing;
  const double transparentBelow = opacityRange.TransparentBelow();
  // Corners are classified a little below the true threshold so float rounding in the
  // interpolation can never turn a leaped sample opaque (integer data interpolate exactly
  // within their corners; the margin covers the rest).
  const double magnitude = std::max({ std::abs(rangeMin), std::abs(rangeMax),
    std::isfinite(transparentBelow) ? std::abs(transparentBelow) : 0.0, 1.0e-30 });
  plan.leapThreshold = transparentBelow - 1.0e-5 * magnitude;
  plan.useCellLeap = settings.cellLeap && plan.zeroOpacityAddsNothing && !settings.nearest &&
    transparentBelow > -std::numeric_limits<double>::infinity();
  return plan;
}

// Rays outside the projection of what can show (the opaque box, or the regions' bounds) are
// not cast at all.
Box ShownBox(const RayCastSettings& settings, const detail::KernelFrame& frame)
{
  Box shown;
  shown.lower = { std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
    std::numeric_limits<double>::infinity() };
  shown.upper = -shown.lower;
  for (const Box& region : settings.regions)
  {
    if (!region.IsEmpty())
    {
      shown.lower = { std::min(shown.lower.x, region.lower.x),
        std::min(shown.lower.y, region.lower.y), std::min(shown.lower.z, region.lower.z) };
      shown.upper = { std::max(shown.upper.x, region.upper.x),
        std::max(shown.upper.y, region.upper.y), std::max(shown.upper.z, region.upper.z) };
    }
  }
  // Composite only: a raysum / average pixel is drawn (alpha 1) wherever its ray meets the
  // volume, even where nothing in it is opaque.
  if (frame.useOpaqueBox && settings.blend == Blend::Composite && !shown.IsEmpty())
  {
    const Box& o = frame.opaqueBox;
    shown.lower = { std::max(shown.lower.x, o.lower.x), std::max(shown.lower.y, o.lower.y),
      std::max(shown.lower.z, o.lower.z) };
    shown.upper = { std::min(shown.upper.x, o.upper.x), std::min(shown.upper.y, o.upper.y),
      std::min(shown.upper.z, o.upper.z) };
  }
  return shown;
}

// Casts the frame's tiles (in parallel) into rgba and sums their counters.
void CastTiles(const detail::KernelFrame& frame, const RayCastView& view, int tile,
  const ParallelFor& tiles, std::vector<float>& rgba, RayCastCounters& counters)
{
  const int tilesX = (view.width + tile - 1) / tile;
  const int tilesY = (view.height + tile - 1) / tile;
  const std::size_t tileCount = static_cast<std::size_t>(tilesX) * tilesY;
  rgba.assign(4 * static_cast<std::size_t>(view.width) * view.height, 0.0f);
  std::vector<RayCastCounters> tileCounters(tileCount);
  float* image = rgba.data();
  tiles(tileCount,
    [&](std::size_t begin, std::size_t end)
    {
      for (std::size_t t = begin; t < end; ++t)
      {
        const int x0 = static_cast<int>(t % tilesX) * tile;
        const int y0 = static_cast<int>(t / tilesX) * tile;
        detail::CastTile(frame, x0, y0, std::min(x0 + tile, view.width),
          std::min(y0 + tile, view.height), image, tileCounters[t]);
      }
    });
  for (const RayCastCounters& c : tileCounters)
  {
    counters.rays += c.rays;
    counters.samples += c.samples;
    counters.leapedOctree += c.leapedOctree;
    counters.leapedDistance += c.leapedDistance;
    counters.leapedCell += c.leapedCell;
    counters.leapedEmptyCell += c.leapedEmptyCell;
    counters.terminatedRays += c.terminatedRays;
    counters.octreeLeaps += c.octreeLeaps;
    counters.distanceLeaps += c.distanceLeaps;
  }
}

}

bool RayCaster::Internals::UpdateOctree(const VolumeView& volume, std::uint64_t volumeVersion,
  std::uint64_t transferVersion, const std::vector<float>& alphas, double rangeMin, double rangeMax,
  const RayCastSettings& settings, const LeapPlan& plan, const ParallelFor& parallel,
  PrepareProgress& progress, std::string& error)
{
  if (!this->OctreeBuilt || this->OctreeVolume != volumeVersion ||
    this->OctreeLeafSize != settings.octreeLeafSize)
  {
    this->OctreeBuilt = this->OctreeClassified = false;
    if (!this->Octree.Configure(volume.dims, settings.octreeLeafSize, error) ||
      !this->Octree.BuildParallel(volume, parallel, error))
    {
      return false;
    }
    this->OctreeBuilt = true;
    this->OctreeVolume = volumeVersion;
    this->OctreeLeafSize = settings.octreeLeafSize;
    progress.Rebuilt();
  }
  if (plan.zeroOpacityAddsNothing &&
    (!this->OctreeClassified || this->OctreeTransfer != transferVersion))
  {
    this->Octree.Classify(alphas, rangeMin, rangeMax);
    this->OctreeOpaqueBox = NonTransparentLeafBox(this->Octree, volume.dims);
    this->OctreeClassified = true;
    this->OctreeTransfer = transferVersion;
    progress.Rebuilt();
  }
  return true;
}

void RayCaster::Internals::UpdateCells(const VolumeView& volume, std::uint64_t volumeVersion,
  std::uint64_t transferVersion, const OpacityRange& opacityRange, const LeapPlan& plan,
  const ParallelFor& parallel, PrepareProgress& progress)
{
  const bool useCellLeap = plan.useCellLeap;
  const bool useDistance = plan.useDistance;
  const bool stale = !this->CellsBuilt || this->CellsVolume != volumeVersion ||
    this->CellsTransfer != transferVersion || this->Packed != useCellLeap ||
    (useDistance && useCellLeap && !this->CellInfoHasDistance);
  if (!stale)
  {
    return;
  }
  // Cell-sized arrays (one byte per cell: half a 16-bit volume) are reused or freed as soon
  // as they are dead, so that a rebuild of the distance map needs 2 bytes per cell, the map
  // included, and one with cell leaping 4 (5 when the packed table is reused).
  CellClassification cells;
  if (!useCellLeap)
  {
    // The configurations are not needed here: the map's own buffer holds them until the
    // map overwrites them, so a rebuild allocates only the flags.
    std::vector<std::uint16_t>().swap(this->CellInfo);
    std::size_t cellCount = 1;
    for (int a = 0; a < 3; ++a)
    {
      cellCount *= static_cast<std::size_t>(std::max(volume.dims[a] - 1, 1));
    }
    ResizeWithHugePages(this->DistanceOnly, cellCount);
    cells.configuration.swap(this->DistanceOnly);
    ClassifyCells(volume, opacityRange, plan.leapThreshold, parallel, cells);
    this->CellsOpaqueBox = NonEmptyCellBox(cells, volume.dims, parallel);
    ComputeDistanceMap(cells.cellDims, cells.nonEmpty, parallel, cells.configuration);
    this->DistanceOnly.swap(cells.configuration);
  }
  else
  {
    std::vector<std::uint8_t>().swap(this->DistanceOnly);
    ClassifyCells(volume, opacityRange, plan.leapThreshold, parallel, cells);
    this->CellsOpaqueBox = NonEmptyCellBox(cells, volume.dims, parallel);
    std::vector<std::uint8_t> distance;
    if (useDistance)
    {
      distance = ComputeDistanceMap(cells.cellDims, cells.nonEmpty, parallel);
    }
    std::vector<std::uint8_t>().swap(cells.nonEmpty); // dead before the packed table grows
    this->PackCellInfo(cells, distance, parallel);
  }
  this->Packed = useCellLeap;
  std::copy(cells.cellDims, cells.cellDims + 3, this->CellDims);
  this->CellInfoHasDistance = useDistance;
  this->CellsBuilt = true;
  this->CellsVolume = volumeVersion;
  this->CellsTransfer = transferVersion;
  progress.Rebuilt();
}

void RayCaster::Internals::PackCellInfo(const CellClassification& cells,
  const std::vector<std::uint8_t>& distance, const ParallelFor& parallel)
{
  ResizeWithHugePages(this->CellInfo, cells.configuration.size());
  const std::uint8_t* configuration = cells.configuration.data();
  const std::uint8_t* distances = distance.empty() ? nullptr : distance.data();
  std::uint16_t* info = this->CellInfo.data();
  parallel(cells.configuration.size(),
    [&](std::size_t begin, std::size_t end)
    {
      for (std::size_t i = begin; i < end; ++i)
      {
        info[i] =
          static_cast<std::uint16_t>((configuration[i] << 8) | (distances ? distances[i] : 0));
      }
    });
}

bool RayCaster::Internals::UpdateGradients(const VolumeView& volume, std::uint64_t volumeVersion,
  double width, const RayCastTransfer& transfer, const RayCastLighting& lighting,
  const RayCastSettings& settings, const ParallelFor& parallel, PrepareProgress& progress)
{
  const bool needGradients = settings.blend == Blend::Composite &&
    (lighting.shade || transfer.gradientOpacity.size() >= 2);
  const std::size_t voxels =
    static_cast<std::size_t>(volume.dims[0]) * volume.dims[1] * volume.dims[2];
  constexpr std::size_t GradientBudget = std::size_t(1) << 30; // bytes
  const bool useGradients =
    needGradients && settings.precomputeGradients && 6 * voxels <= GradientBudget;
  if (useGradients && (!this->GradientsBuilt || this->GradientsVolume != volumeVersion))
  {
    // |central difference| <= the range width, so this step keeps every value in int16.
    this->GradientScale = static_cast<float>(width / 32767.0);
    ResizeWithHugePages(this->Gradients, 3 * voxels);
    DispatchScalarType(volume,
      [&](const auto* data) {
        ComputeGradients(data, volume.dims, this->GradientScale, this->Gradients.data(), parallel);
      });
    this->GradientsBuilt = true;
    this->GradientsVolume = volumeVersion;
    progress.Rebuilt();
  }
  return useGradients;
}

void RayCaster::Internals::FillKernelFrame(const VolumeView& volume, double rangeMin,
  double rangeMax, const RayCastTransfer& transfer, const RayCastLighting& lighting,
  const RayCastView& view, const RayCastSettings& settings, const LeapPlan& plan, bool useGradients,
  double exponent, detail::KernelFrame& frame)
{
  const int tableSize = static_cast<int>(transfer.rgba.size() / 4);
  const double width = rangeMax > rangeMin ? rangeMax - rangeMin : 1.0;
  frame.volume = volume;
  frame.tableSize = tableSize;
  frame.tableScale = static_cast<float>((tableSize - 1) / (rangeMax - rangeMin));
  if (!(rangeMax > rangeMin))
  {
    frame.tableScale = 0; // a constant volume reads the first entry
  }
  frame.tableBias = static_cast<float>(-rangeMin * frame.tableScale);
  frame.rgba = transfer.rgba.data();
  frame.correctedAlpha = this->CorrectedAlpha.data();
  frame.normalScale = static_cast<float>(1.0 / width);
  frame.normalBias = static_cast<float>(-rangeMin / width);
  frame.rangeWidth = static_cast<float>(width);
  if (settings.blend == Blend::Composite && transfer.gradientOpacity.size() >= 2)
  {
    frame.gradientOpacity = transfer.gradientOpacity.data();
    frame.gradientOpacitySize = static_cast<int>(transfer.gradientOpacity.size());
    frame.gradientOpacityMaximum = static_cast<float>(
      transfer.gradientOpacityMaximum > 0 ? transfer.gradientOpacityMaximum : 1.0);
  }
  frame.opacityExponent = static_cast<float>(exponent);
  frame.lighting = &lighting;
  frame.gradients = useGradients ? this->Gradients.data() : nullptr;
  frame.gradientScale = this->GradientScale;
  // Normal matrix with the gradient's units folded in: per-voxel differences are stored in
  // steps of GradientScale raw units, on-the-fly ones are raw; both become normalised units.
  const double gradientUnits = (useGradients ? this->GradientScale : 1.0) / width;
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      frame.normalMatrix[r][c] = static_cast<float>(lighting.normalMatrix[r][c] * gradientUnits);
    }
  }
  // pow(x, power) over x in [0, 1], linearly interpolated (errors ~1e-5 for power 10).
  constexpr int SpecularTableSize = 2048;
  this->SpecularTable.resize(SpecularTableSize);
  for (int i = 0; i < SpecularTableSize; ++i)
  {
    this->SpecularTable[i] = static_cast<float>(
      std::pow(static_cast<double>(i) / (SpecularTableSize - 1), lighting.specularPower));
  }
  frame.specularTable = this->SpecularTable.data();
  frame.specularTableSize = SpecularTableSize;
  frame.view = &view;
  frame.settings = &settings;
  frame.octree = plan.useOctree ? &this->Octree : nullptr;
  frame.cellInfo = plan.useCellLeap ? this->CellInfo.data() : nullptr;
  frame.distanceOnly = plan.useDistance && !plan.useCellLeap ? this->DistanceOnly.data() : nullptr;
  frame.leapThreshold = static_cast<float>(plan.leapThreshold);
  frame.useOctree = plan.useOctree;
  frame.useDistance = plan.useDistance;
  frame.useCellLeap = plan.useCellLeap;
  // Composite / additive only: there transparent samples add nothing.
  frame.useOpaqueBox = plan.zeroOpacityAddsNothing && (plan.useOctree || plan.useDistance);
  frame.opaqueBox = plan.useDistance ? this->CellsOpaqueBox : this->OctreeOpaqueBox;
}

bool RayCaster::Render(const VolumeView& volume, double rangeMin, double rangeMax,
  std::uint64_t volumeVersion, const RayCastTransfer& transfer, std::uint64_t transferVersion,
  const RayCastLighting& lighting, const RayCastView& view, const RayCastSettings& settings,
  const ParallelFor& parallel, std::vector<float>& rgba, RayCastCounters& counters,
  std::string& error)
{
  counters = RayCastCounters();
  if (!CheckArguments(volume, transfer, view, settings, error))
  {
    return false;
  }
  Internals& impl = *this->Impl;
  const auto prepareStart = std::chrono::steady_clock::now();
  PrepareProgress progress{ impl.Progress };
  const int tableSize = static_cast<int>(transfer.rgba.size() / 4);
  std::vector<float> alphas(tableSize);
  for (int i = 0; i < tableSize; ++i)
  {
    alphas[i] = transfer.rgba[4 * i + 3];
  }
  const double width = rangeMax > rangeMin ? rangeMax - rangeMin : 1.0;

  const OpacityRange opacityRange(alphas, rangeMin, rangeMax);
  const LeapPlan plan = PlanLeaping(settings, opacityRange, rangeMin, rangeMax);
  if (plan.useOctree &&
    !impl.UpdateOctree(volume, volumeVersion, transferVersion, alphas, rangeMin, rangeMax, settings,
      plan, parallel, progress, error))
  {
    return false;
  }
  if (plan.useCellLeap || plan.useDistance)
  {
    impl.UpdateCells(
      volume, volumeVersion, transferVersion, opacityRange, plan, parallel, progress);
  }
  const bool useGradients = impl.UpdateGradients(
    volume, volumeVersion, width, transfer, lighting, settings, parallel, progress);

  // The table opacities hold for the unit distance; samples stand for sampleDistance.
  const double exponent = settings.sampleDistance / transfer.opacityUnitDistance;
  impl.CorrectedAlpha.resize(tableSize);
  for (int i = 0; i < tableSize; ++i)
  {
    const double a = std::min(std::max(static_cast<double>(alphas[i]), 0.0), 1.0);
    impl.CorrectedAlpha[i] = static_cast<float>(1.0 - std::pow(1.0 - a, exponent));
  }
  impl.PrepareSeconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - prepareStart).count();

  detail::KernelFrame frame;
  impl.FillKernelFrame(volume, rangeMin, rangeMax, transfer, lighting, view, settings, plan,
    useGradients, exponent, frame);
  VisiblePixels(ShownBox(settings, frame), view, frame.visible);
  std::copy(frame.visible, frame.visible + 4, impl.CastRectangle);

  // With progress: the tiles as they finish, reported by this thread.
  const ParallelFor tiles = ReportingParallelFor(
    parallel, ProgressRange(impl.Progress, progress.prepared > 0 ? PrepareShare : 0.0, 1.0));
  CastTiles(frame, view, settings.tileSize, tiles, rgba, counters);
  return true;
}
}
