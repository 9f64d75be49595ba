// RayCastAcceleration: the ray caster's cached acceleration structures (min-max octree, cell
// classification and distance map, the packed cell table, precomputed gradients), rebuilt only
// when the scalars or the transfer function change.
#include "raycast/RayCastEngineInternals.h"
#include "raycast/RayCastKernel.h"
#include "raycast/RayCastSampler.h"
#include "skipping/CellBricks.h"

#include "skipping/DistanceMap.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>
#include <utility>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace accelvolume
{
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
  const T* data, const int dims[3], float scale, std::uint32_t* out, const ParallelFor& parallel)
{
  const std::ptrdiff_t nx = dims[0], ny = dims[1], nz = dims[2];
  const float inverse = 0.5f / scale;
  auto encode = [](float gx, float gy, float gz)
  {
    const float g[3] = { gx, gy, gz };
    return detail::EncodeGradient(g);
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
          std::uint32_t* o = out + (z * ny + y) * nx;
          for (std::ptrdiff_t x = 0; x < nx; ++x)
          {
            const std::ptrdiff_t xDown = x > 0 ? x - 1 : x, xUp = x + 1 < nx ? x + 1 : x;
            o[x] = encode((static_cast<float>(row[xUp]) - static_cast<float>(row[xDown])) * inverse,
              (static_cast<float>(rowYUp[x]) - static_cast<float>(rowYDown[x])) * inverse,
              (static_cast<float>(rowZUp[x]) - static_cast<float>(rowZDown[x])) * inverse);
          }
        }
      }
    });
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

// The components whose opacity can make a multi-component sample visible, each with the table
// it is classified by: independent, those of positive weight; dependent, the last one.
struct OpacitySource
{
  int component;
  const RayCastComponentTable* table;
};

std::vector<OpacitySource> OpacitySources(const RayCastComponents& components)
{
  std::vector<OpacitySource> sources;
  if (!components.independent)
  {
    sources.push_back({ components.count - 1, &components.tables[0] });
    return sources;
  }
  for (int c = 0; c < components.count; ++c)
  {
    if (components.tables[c].weight > 0)
    {
      sources.push_back({ c, &components.tables[c] });
    }
  }
  return sources;
}

std::vector<float> TableOpacities(const RayCastComponentTable& table)
{
  std::vector<float> alphas(table.rgba.size() / 4);
  for (std::size_t i = 0; i < alphas.size(); ++i)
  {
    alphas[i] = table.rgba[4 * i + 3];
  }
  return alphas;
}

// Component c of interleaved scalars as a contiguous single-component volume in `buffer`.
VolumeView ComponentView(const VolumeView& volume, int count, int component,
  std::vector<std::uint8_t>& buffer, const ParallelFor& parallel)
{
  VolumeView view = volume;
  const std::size_t voxels =
    static_cast<std::size_t>(volume.dims[0]) * volume.dims[1] * volume.dims[2];
  DispatchScalarType(volume,
    [&](const auto* data)
    {
      using T = std::remove_const_t<std::remove_pointer_t<decltype(data)>>;
      buffer.resize(voxels * sizeof(T));
      T* out = reinterpret_cast<T*>(buffer.data());
      parallel(voxels,
        [&](std::size_t begin, std::size_t end)
        {
          for (std::size_t i = begin; i < end; ++i)
          {
            out[i] = data[i * count + component];
          }
        });
    });
  view.data = buffer.data();
  return view;
}

// A binary mask as a skipping source: a cell whose 8 voxels are all hidden holds no visible
// sample (samples read the nearest voxel, one of the cell's corners), so it is empty.
void MaskCells(const std::uint8_t* mask, const int dims[3], const int cellDims[3],
  std::vector<std::uint8_t>& nonEmpty, const ParallelFor& parallel)
{
  if (!mask)
  {
    return;
  }
  const std::ptrdiff_t sx = 1, sy = dims[0], sz = static_cast<std::ptrdiff_t>(dims[0]) * dims[1];
  const std::ptrdiff_t ox = dims[0] > 1 ? sx : 0, oy = dims[1] > 1 ? sy : 0,
                       oz = dims[2] > 1 ? sz : 0;
  parallel(static_cast<std::size_t>(cellDims[2]),
    [&](std::size_t begin, std::size_t end)
    {
      for (std::size_t k = begin; k < end; ++k)
      {
        for (int j = 0; j < cellDims[1]; ++j)
        {
          std::uint8_t* flags =
            nonEmpty.data() + (k * cellDims[1] + static_cast<std::size_t>(j)) * cellDims[0];
          const std::uint8_t* m = mask + static_cast<std::ptrdiff_t>(k) * sz + j * sy;
          for (int i = 0; i < cellDims[0]; ++i, ++m)
          {
            const bool shown = m[0] | m[ox] | m[oy] | m[oy + ox] | m[oz] | m[oz + ox] |
              m[oz + oy] | m[oz + oy + ox];
            flags[i] = static_cast<std::uint8_t>(flags[i] && shown);
          }
        }
      }
    });
}

// The distance map of the classified cells, bricked (the layout the rays read) into `map`;
// the classification's buffers serve as scratch (both are dead afterwards).
void BuildDistanceOnly(
  CellClassification& cells, const ParallelFor& parallel, std::vector<std::uint8_t>& map)
{
  ComputeDistanceMap(cells.cellDims, cells.nonEmpty, parallel, cells.configuration);
  CellBricks(cells.cellDims).Reorder(cells.cellDims, cells.configuration, cells.nonEmpty, parallel);
  map.swap(cells.nonEmpty);
}

} // namespace

bool RayCaster::Internals::UpdateComponentOctree(const VolumeView& volume,
  std::uint64_t volumeVersion, std::uint64_t transferVersion, const RayCastComponents& components,
  const RayCastSettings& settings, bool classify, const ParallelFor& parallel,
  PrepareProgress& progress, std::string& error)
{
  if (!this->OctreeBuilt || this->OctreeVolume != volumeVersion ||
    this->OctreeLeafSize != settings.octreeLeafSize ||
    this->ComponentOctrees.size() != static_cast<std::size_t>(components.count))
  {
    this->OctreeBuilt = this->OctreeClassified = false;
    this->ComponentOctrees.assign(components.count, MinMaxOctree());
    std::vector<std::uint8_t> buffer;
    for (int c = 0; c < components.count; ++c)
    {
      const VolumeView view = ComponentView(volume, components.count, c, buffer, parallel);
      if (!this->ComponentOctrees[c].Configure(volume.dims, settings.octreeLeafSize, error) ||
        !this->ComponentOctrees[c].BuildParallel(view, parallel, error))
      {
        return false;
      }
    }
    this->OctreeBuilt = true;
    this->OctreeVolume = volumeVersion;
    this->OctreeLeafSize = settings.octreeLeafSize;
    progress.Rebuilt();
  }
  if (classify && (!this->OctreeClassified || this->OctreeTransfer != transferVersion))
  {
    const std::vector<OpacitySource> sources = OpacitySources(components);
    this->Octree = this->ComponentOctrees[0];
    if (sources.empty())
    {
      this->Octree.Classify({}, 0.0, 1.0); // nothing can be seen
    }
    for (std::size_t s = 0; s < sources.size(); ++s)
    {
      const RayCastComponentTable& table = *sources[s].table;
      MinMaxOctree& octree = this->ComponentOctrees[sources[s].component];
      octree.Classify(TableOpacities(table), table.opacityRange[0], table.opacityRange[1]);
      if (s == 0)
      {
        this->Octree = octree;
      }
      else
      {
        this->Octree.IntersectTransparency(octree);
      }
    }
    this->OctreeOpaqueBox = NonTransparentLeafBox(this->Octree, volume.dims);
    this->OctreeClassified = true;
    this->OctreeTransfer = transferVersion;
    progress.Rebuilt();
  }
  return true;
}

void RayCaster::Internals::UpdateComponentCells(const VolumeView& volume,
  std::uint64_t volumeVersion, std::uint64_t transferVersion, const RayCastComponents& components,
  const std::uint8_t* mask, const ParallelFor& parallel, PrepareProgress& progress)
{
  if (this->CellsBuilt && this->CellsVolume == volumeVersion &&
    this->CellsTransfer == transferVersion && !this->Packed)
  {
    return;
  }
  std::vector<std::uint16_t>().swap(this->CellInfo);
  const std::vector<OpacitySource> sources = OpacitySources(components);
  CellClassification cells;
  std::vector<std::uint8_t> nonEmpty;
  std::vector<std::uint8_t> buffer;
  for (const OpacitySource& source : sources)
  {
    const VolumeView view = ComponentView(volume, components.count, source.component, buffer, parallel);
    const OpacityRange range(
      TableOpacities(*source.table), source.table->opacityRange[0], source.table->opacityRange[1]);
    ClassifyCells(view, range, 0.0, parallel, cells);
    if (nonEmpty.empty())
    {
      nonEmpty.swap(cells.nonEmpty);
      continue;
    }
    const std::uint8_t* flags = cells.nonEmpty.data();
    std::uint8_t* merged = nonEmpty.data();
    parallel(nonEmpty.size(),
      [&](std::size_t begin, std::size_t end)
      {
        for (std::size_t i = begin; i < end; ++i)
        {
          merged[i] = static_cast<std::uint8_t>(merged[i] | flags[i]);
        }
      });
  }
  std::vector<std::uint8_t>().swap(buffer);
  for (int a = 0; a < 3; ++a)
  {
    cells.cellDims[a] = std::max(volume.dims[a] - 1, 1);
  }
  if (nonEmpty.empty())
  {
    nonEmpty.assign(static_cast<std::size_t>(cells.cellDims[0]) * cells.cellDims[1] *
        cells.cellDims[2],
      0); // no component can be seen
  }
  cells.nonEmpty.swap(nonEmpty);
  MaskCells(mask, volume.dims, cells.cellDims, cells.nonEmpty, parallel);
  std::vector<std::uint8_t>().swap(cells.configuration);
  this->CellsOpaqueBox = NonEmptyCellBox(cells, volume.dims, parallel);
  BuildDistanceOnly(cells, parallel, this->DistanceOnly);
  ++this->DistanceBuilds;
  this->Packed = false;
  std::copy(cells.cellDims, cells.cellDims + 3, this->CellDims);
  this->CellInfoHasDistance = true;
  this->CellsBuilt = true;
  this->CellsVolume = volumeVersion;
  this->CellsTransfer = transferVersion;
  progress.Rebuilt();
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
  const std::uint8_t* mask, const ParallelFor& parallel, PrepareProgress& progress)
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
    MaskCells(mask, volume.dims, cells.cellDims, cells.nonEmpty, parallel);
    this->CellsOpaqueBox = NonEmptyCellBox(cells, volume.dims, parallel);
    BuildDistanceOnly(cells, parallel, this->DistanceOnly);
  }
  else
  {
    std::vector<std::uint8_t>().swap(this->DistanceOnly);
    ClassifyCells(volume, opacityRange, plan.leapThreshold, parallel, cells);
    MaskCells(mask, volume.dims, cells.cellDims, cells.nonEmpty, parallel);
    this->CellsOpaqueBox = NonEmptyCellBox(cells, volume.dims, parallel);
    std::vector<std::uint8_t> distance;
    if (useDistance)
    {
      distance = ComputeDistanceMap(cells.cellDims, cells.nonEmpty, parallel);
    }
    std::vector<std::uint8_t>().swap(cells.nonEmpty); // dead before the packed table grows
    this->PackCellInfo(cells, distance, parallel);
  }
  this->DistanceBuilds += useDistance ? 1 : 0; // the octant maps are stale then
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
  // Bricked (CellBricks) like the distance map alone: the layout the rays read.
  const CellBricks bricks(cells.cellDims);
  ResizeWithHugePages(this->CellInfo, bricks.Entries());
  std::fill(this->CellInfo.begin(), this->CellInfo.end(), std::uint16_t(0));
  const std::uint8_t* configuration = cells.configuration.data();
  const std::uint8_t* distances = distance.empty() ? nullptr : distance.data();
  std::uint16_t* info = this->CellInfo.data();
  bricks.ForEachCell(cells.cellDims, parallel,
    [&](std::size_t i, std::size_t brickedIndex)
    {
      info[brickedIndex] =
        static_cast<std::uint16_t>((configuration[i] << 8) | (distances ? distances[i] : 0));
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
    needGradients && settings.precomputeGradients && 4 * voxels <= GradientBudget;
  if (useGradients && (!this->GradientsBuilt || this->GradientsVolume != volumeVersion))
  {
    // |central difference| <= the range width: in these units every component is within
    // +-32767, EncodeGradient's range. Integer scalars take half-voxel-value units where the
    // range allows: their differences are integers, exact up to 511.
    const bool integral = volume.type != ScalarType::Float32 && volume.type != ScalarType::Float64;
    this->GradientScale =
      static_cast<float>(integral ? std::max(0.5, width / 32767.0) : width / 32767.0);
    ResizeWithHugePages(this->Gradients, voxels);
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

void RayCaster::Internals::UpdateFootprint(
  detail::KernelFrame& frame, const double indexToClip[4][4], const ParallelFor& parallel)
{
  frame.footprint = nullptr;
  const RayCastSettings& settings = *frame.settings;
  // Only the grouped approach reads it (composite rays of one component that leap by the
  // distance map: there a ray through empty cells only adds nothing).
  if (!settings.screenFootprint || !detail::RaysApproachTogether(frame) ||
    frame.visible[0] > frame.visible[1] || frame.visible[2] > frame.visible[3])
  {
    return;
  }
  if (this->MacroBuild != this->DistanceBuilds || this->Macro.nonEmpty.empty())
  {
    this->VisitDistanceMap([&](const auto* distance)
      { ComputeMacroCells(this->CellDims, distance, parallel, this->Macro); });
    this->MacroBuild = this->DistanceBuilds;
  }
  if (ProjectFootprint(this->Macro, frame.volume.dims, indexToClip, frame.view->width,
        frame.view->height, this->Footprint))
  {
    frame.footprint = this->Footprint.covered.data();
    frame.footprintBlocks = this->Footprint.blocks[0];
  }
}

} // namespace accelvolume
