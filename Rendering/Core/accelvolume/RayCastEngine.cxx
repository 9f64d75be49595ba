// RayCastEngine: frame setup, acceleration-structure caches and tiling of the CPU ray caster.
#include "accelvolume/RayCastEngine.h"

#include "accelvolume/CellClassification.h"
#include "accelvolume/DistanceMap.h"
#include "accelvolume/OpacityRange.h"
#include "accelvolume/RayCastKernel.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace accelvolume
{

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
  std::uint64_t CellsVolume = 0, CellsTransfer = 0;

  // Per cell: distance-map value (low byte, 0 without a distance map) and Marching Cubes
  // configuration (high byte), packed so one load serves both leaps. The sources are freed
  // once packed.
  std::vector<std::uint16_t> CellInfo;
  bool CellInfoHasDistance = false;

  std::vector<float> CorrectedAlpha;
  double PrepareSeconds = 0;
};

RayCaster::RayCaster()
  : Impl(new Internals)
{
}

RayCaster::~RayCaster() = default;

double RayCaster::GetLastPrepareSeconds() const
{
  return this->Impl->PrepareSeconds;
}

std::size_t RayCaster::GetAccelerationBytes() const
{
  const Internals& impl = *this->Impl;
  std::size_t bytes = impl.CellInfo.size() * sizeof(std::uint16_t);
  if (impl.OctreeBuilt)
  {
    bytes += impl.Octree.GetNumberOfNodes() * (2 * sizeof(float) + 1);
  }
  return bytes;
}

namespace
{

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
  const int tableSize = static_cast<int>(transfer.rgba.size() / 4);
  std::vector<float> alphas(tableSize);
  for (int i = 0; i < tableSize; ++i)
  {
    alphas[i] = transfer.rgba[4 * i + 3];
  }
  const double width = rangeMax > rangeMin ? rangeMax - rangeMin : 1.0;

  // Which accelerations are exact for this blend mode (see the header).
  const bool zeroOpacityAddsNothing =
    settings.blend == RayCastBlend::Composite || settings.blend == RayCastBlend::Additive;
  const bool extremum =
    settings.blend == RayCastBlend::Maximum || settings.blend == RayCastBlend::Minimum;
  const bool useOctree = settings.leap == LeapMode::Octree && (zeroOpacityAddsNothing || extremum);
  const bool useDistance = settings.leap == LeapMode::DistanceMap && zeroOpacityAddsNothing;
  const OpacityRange opacityRange(alphas, rangeMin, rangeMax);
  const double transparentBelow = opacityRange.TransparentBelow();
  // Corners are classified a little below the true threshold so float rounding in the
  // interpolation can never turn a leaped sample opaque (integer data interpolate exactly
  // within their corners; the margin covers the rest).
  const double magnitude = std::max({ std::abs(rangeMin), std::abs(rangeMax),
    std::isfinite(transparentBelow) ? std::abs(transparentBelow) : 0.0, 1.0e-30 });
  const double leapThreshold = transparentBelow - 1.0e-5 * magnitude;
  const bool useCellLeap = settings.cellLeap && zeroOpacityAddsNothing && !settings.nearest &&
    transparentBelow > -std::numeric_limits<double>::infinity();

  if (useOctree)
  {
    if (!impl.OctreeBuilt || impl.OctreeVolume != volumeVersion ||
      impl.OctreeLeafSize != settings.octreeLeafSize)
    {
      impl.OctreeBuilt = impl.OctreeClassified = false;
      if (!impl.Octree.Configure(volume.dims, settings.octreeLeafSize, error) ||
        !impl.Octree.BuildParallel(volume, parallel, error))
      {
        return false;
      }
      impl.OctreeBuilt = true;
      impl.OctreeVolume = volumeVersion;
      impl.OctreeLeafSize = settings.octreeLeafSize;
    }
    if (zeroOpacityAddsNothing &&
      (!impl.OctreeClassified || impl.OctreeTransfer != transferVersion))
    {
      impl.Octree.Classify(alphas, rangeMin, rangeMax);
      impl.OctreeClassified = true;
      impl.OctreeTransfer = transferVersion;
    }
  }
  if (useCellLeap || useDistance)
  {
    const bool stale = !impl.CellsBuilt || impl.CellsVolume != volumeVersion ||
      impl.CellsTransfer != transferVersion || (useDistance && !impl.CellInfoHasDistance);
    if (stale)
    {
      CellClassification cells = ClassifyCells(volume, opacityRange, leapThreshold, parallel);
      std::vector<std::uint8_t> distance;
      if (useDistance)
      {
        distance = ComputeDistanceMap(cells.cellDims, cells.nonEmpty, parallel);
      }
      impl.CellInfo.resize(cells.configuration.size());
      const std::uint8_t* configuration = cells.configuration.data();
      const std::uint8_t* distances = distance.empty() ? nullptr : distance.data();
      std::uint16_t* info = impl.CellInfo.data();
      parallel(cells.configuration.size(),
        [&](std::size_t begin, std::size_t end)
        {
          for (std::size_t i = begin; i < end; ++i)
          {
            info[i] =
              static_cast<std::uint16_t>((configuration[i] << 8) | (distances ? distances[i] : 0));
          }
        });
      std::copy(cells.cellDims, cells.cellDims + 3, impl.CellDims);
      impl.CellInfoHasDistance = useDistance;
      impl.CellsBuilt = true;
      impl.CellsVolume = volumeVersion;
      impl.CellsTransfer = transferVersion;
    }
  }

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
  frame.volume = volume;
  frame.tableSize = tableSize;
  frame.tableScale = static_cast<float>((tableSize - 1) / (rangeMax - rangeMin));
  if (!(rangeMax > rangeMin))
  {
    frame.tableScale = 0; // a constant volume reads the first entry
  }
  frame.tableBias = static_cast<float>(-rangeMin * frame.tableScale);
  frame.rgba = transfer.rgba.data();
  frame.correctedAlpha = impl.CorrectedAlpha.data();
  frame.normalScale = static_cast<float>(1.0 / width);
  frame.normalBias = static_cast<float>(-rangeMin / width);
  frame.rangeWidth = static_cast<float>(width);
  if (settings.blend == RayCastBlend::Composite && transfer.gradientOpacity.size() >= 2)
  {
    frame.gradientOpacity = transfer.gradientOpacity.data();
    frame.gradientOpacitySize = static_cast<int>(transfer.gradientOpacity.size());
    frame.gradientOpacityMaximum = static_cast<float>(
      transfer.gradientOpacityMaximum > 0 ? transfer.gradientOpacityMaximum : 1.0);
  }
  frame.opacityExponent = static_cast<float>(exponent);
  frame.lighting = &lighting;
  frame.view = &view;
  frame.settings = &settings;
  frame.octree = useOctree ? &impl.Octree : nullptr;
  frame.cellInfo = (useCellLeap || useDistance) ? impl.CellInfo.data() : nullptr;
  frame.leapThreshold = static_cast<float>(leapThreshold);
  frame.useOctree = useOctree;
  frame.useDistance = useDistance;
  frame.useCellLeap = useCellLeap;

  const int tile = settings.tileSize;
  const int tilesX = (view.width + tile - 1) / tile;
  const int tilesY = (view.height + tile - 1) / tile;
  const std::size_t tileCount = static_cast<std::size_t>(tilesX) * tilesY;
  rgba.assign(4 * static_cast<std::size_t>(view.width) * view.height, 0.0f);
  std::vector<RayCastCounters> tileCounters(tileCount);
  float* image = rgba.data();
  parallel(tileCount,
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
  return true;
}

}
