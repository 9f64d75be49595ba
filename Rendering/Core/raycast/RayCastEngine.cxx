// RayCastEngine: frame setup, acceleration-structure caches and tiling of the CPU ray caster.
#include "raycast/RayCastEngine.h"
#include "raycast/RayCastEngineInternals.h"

#include "raycast/RayCastKernel.h"
#include "raycast/RayCastPixelRay.h"
#include "skipping/CellClassification.h"
#include "skipping/DistanceMap.h"
#include "skipping/OctantDistanceMap.h"
#include "skipping/OpacityRange.h"

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
    impl.Gradients.size() * sizeof(std::uint32_t) + impl.Macro.nonEmpty.size() +
    impl.Footprint.covered.size();
  for (const std::vector<std::uint8_t>& map : impl.OctantDistance)
  {
    bytes += map.size();
  }
  if (impl.OctreeBuilt)
  {
    bytes += impl.Octree.GetNumberOfNodes() * (2 * sizeof(float) + 1);
  }
  return bytes;
}

void RayCaster::Internals::UpdateOctantMaps(detail::KernelFrame& frame, const ParallelFor& parallel)
{
  // A ray direction's components are linear over the image plane before normalising, so the
  // corner pixels' rays show every sign the rays between them take.
  bool needed[8] = { false, false, false, false, false, false, false, false };
  if (frame.useDistance && frame.visible[0] <= frame.visible[1] &&
    frame.visible[2] <= frame.visible[3])
  {
    bool negative[3] = { false, false, false }, positive[3] = { false, false, false };
    for (int corner = 0; corner < 4; ++corner)
    {
      const Vec3 d =
        detail::MakePixelRay(frame, frame.visible[corner & 1], frame.visible[2 + (corner >> 1)])
          .index.direction;
      const double components[3] = { d.x, d.y, d.z };
      for (int a = 0; a < 3; ++a)
      {
        (components[a] < 0 ? negative : positive)[a] = true;
      }
    }
    for (int octant = 0; octant < 8; ++octant)
    {
      needed[octant] = true;
      for (int a = 0; a < 3; ++a)
      {
        needed[octant] = needed[octant] && ((octant >> a) & 1 ? negative[a] : positive[a]);
      }
    }
  }
  // Maps another view needed stay while current, up to MaximumHeld in all (a camera turning
  // back and forth does not rebuild them; memory stays at most that many bytes per cell, or
  // the eight of a view from inside the volume).
  constexpr int MaximumHeld = 4;
  std::vector<int> build;
  bool current[8];
  int held = 0;
  for (int octant = 0; octant < 8; ++octant)
  {
    current[octant] = this->OctantDistanceBuild[octant] == this->DistanceBuilds &&
      !this->OctantDistance[octant].empty();
    if (needed[octant] && !current[octant])
    {
      build.push_back(octant);
    }
    held += needed[octant] || current[octant] ? 1 : 0;
  }
  for (int octant = 0; octant < 8; ++octant)
  {
    if (!needed[octant] && (!current[octant] || held > MaximumHeld))
    {
      held -= current[octant] ? 1 : 0;
      std::vector<std::uint8_t>().swap(this->OctantDistance[octant]);
    }
  }
  parallel(build.size(),
    [&](std::size_t begin, std::size_t end)
    {
      for (std::size_t b = begin; b < end; ++b)
      {
        std::vector<std::uint8_t>& map = this->OctantDistance[build[b]];
        this->VisitDistanceMap([&](const auto* distance)
          { ComputeOctantDistanceMap(this->CellDims, distance, build[b], map); });
      }
    });
  for (int octant : build)
  {
    this->OctantDistanceBuild[octant] = this->DistanceBuilds;
  }
  for (int octant = 0; octant < 8; ++octant)
  {
    frame.octantDistance[octant] = needed[octant] ? this->OctantDistance[octant].data() : nullptr;
  }
}

namespace
{

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

// Index space (x, y, z, 1) to clip space: the view's projection after the volume's index to
// world map; false when the view's matrix is singular.
bool IndexToClip(const RayCastView& view, double indexToClip[4][4])
{
  double worldToClip[4][4];
  if (!Invert4x4(view.clipToWorld, worldToClip))
  {
    return false;
  }
  const Affine indexToWorld = view.worldToIndex.Inverse();
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      double sum = c == 3 ? worldToClip[r][3] : 0.0;
      for (int k = 0; k < 3; ++k)
      {
        sum += worldToClip[r][k] * indexToWorld.m[k][c];
      }
      indexToClip[r][c] = sum;
    }
  }
  return true;
}

// Pixels whose centres the index-space box projects over (ProjectBox); the whole image when
// there is no index-to-clip map or a corner is not in front of the camera. An empty box gives
// an empty rectangle.
void VisiblePixels(
  const Box& box, const double (*indexToClip)[4], const RayCastView& view, int visible[4])
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
  int pixels[4];
  if (indexToClip && ProjectBox(box, indexToClip, view.width, view.height, pixels))
  {
    const bool offImage = pixels[0] > pixels[1] || pixels[2] > pixels[3];
    const int none[4] = { 0, -1, 0, -1 };
    std::copy(offImage ? none : pixels, (offImage ? none : pixels) + 4, visible);
  }
}

bool CheckComponents(const RayCastComponents& components, std::string& error)
{
  const int count = components.count;
  if (count == 1)
  {
    return true;
  }
  if (count < 1 || count > 4 || (!components.independent && count != 2 && count != 4))
  {
    error = "multi-component scalars need 2-4 independent components, or 2 or 4 dependent ones";
    return false;
  }
  if (components.tables.size() != static_cast<std::size_t>(components.independent ? count : 1))
  {
    error = "multi-component scalars need one table per independent component (one when "
            "dependent)";
    return false;
  }
  for (const RayCastComponentTable& table : components.tables)
  {
    if (table.rgba.size() < 8 || table.rgba.size() % 4 != 0 ||
      (!table.gradientOpacity.empty() && table.gradientOpacity.size() < 2) ||
      !(table.opacityUnitDistance > 0))
    {
      error = "a component table needs at least 2 RGBA entries (gradient opacity too when "
              "given) and a positive unit distance";
      return false;
    }
  }
  return true;
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
  if (settings.labelTables && (!settings.mask || transfer.components.count > 1))
  {
    error = "a label map needs a mask and one-component scalars";
    return false;
  }
  return CheckComponents(transfer.components, error);
}

// Which accelerations are exact for this blend mode (see the header).
LeapPlan PlanLeaping(const RayCastSettings& settings, const OpacityRange& opacityRange,
  double rangeMin, double rangeMax, bool multiComponent)
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
  if (settings.labelTables && settings.mask && settings.blend == Blend::Composite)
  {
    // Labels may make values the transfer function hides visible: nothing is known empty.
    plan.useOctree = plan.useDistance = plan.useCellLeap = false;
  }
  if (multiComponent)
  {
    // Cells classify each component's range; the Marching Cubes table is a single-component
    // rule. Extremes leap by every component's octree (ExtremeComponents).
    plan.useCellLeap = false;
  }
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
  // Every ray writes its pixel; only the pixels outside the visible rectangle need clearing
  // (clearing the whole image cost a few percent of an opaque frame).
  rgba.resize(4 * static_cast<std::size_t>(view.width) * view.height);
  const int* visible = frame.visible;
  for (int y = 0; y < view.height; ++y)
  {
    float* row = rgba.data() + 4 * static_cast<std::size_t>(y) * view.width;
    if (y < visible[2] || y > visible[3] || visible[0] > visible[1])
    {
      std::fill(row, row + 4 * static_cast<std::size_t>(view.width), 0.0f);
      continue;
    }
    const int left = std::clamp(visible[0], 0, view.width);
    const int right = std::clamp(visible[1] + 1, left, view.width);
    std::fill(row, row + 4 * static_cast<std::size_t>(left), 0.0f);
    std::fill(row + 4 * static_cast<std::size_t>(right), row + 4 * static_cast<std::size_t>(view.width), 0.0f);
  }
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
    counters.culledPixels += c.culledPixels;
    counters.packetRays += c.packetRays;
  }
}

}

// KernelFrame's (value, next - value) pairs of the opacity, colour and specular tables.
void RayCaster::Internals::FillLerpPairs(
  const RayCastTransfer& transfer, detail::KernelFrame& frame)
{
  const std::size_t entries =
    frame.tableSize > 1 ? static_cast<std::size_t>(frame.tableSize - 1) : 0;
  const std::size_t highlights = static_cast<std::size_t>(frame.specularTableSize - 1);
  std::vector<float>& pairs = this->LerpPairs;
  pairs.resize(2 * (4 * entries + highlights));
  float* out = pairs.data();
  const auto fill = [&out](std::size_t count, const float* values, std::size_t stride)
  {
    const float* start = out;
    for (std::size_t i = 0; i < count; ++i)
    {
      *out++ = values[i * stride];
      *out++ = values[(i + 1) * stride] - values[i * stride];
    }
    return start;
  };
  frame.alphaPairs = entries ? fill(entries, this->CorrectedAlpha.data(), 1) : nullptr;
  for (int c = 0; c < 3; ++c)
  {
    frame.colourPairs[c] = entries ? fill(entries, transfer.rgba.data() + c, 4) : nullptr;
  }
  frame.specularPairs = fill(highlights, this->SpecularTable.data(), 1);
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
  frame.maximumCorrectedAlpha = this->MaximumCorrectedAlpha;
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
    frame.gradientAxisScale[r] = static_cast<float>(transfer.gradientAxisScale[r] * gradientUnits);
  }
  // pow(x, power) over x in [0, 1], linearly interpolated (errors ~1e-5 for power 10).
  constexpr int SpecularTableSize = 2048;
  this->SpecularTable.resize(SpecularTableSize);
  for (int i = 0; i < SpecularTableSize; ++i)
  {
    this->SpecularTable[i] = static_cast<float>(
      std::pow(static_cast<double>(i) / (SpecularTableSize - 1), lighting.model.specularPower));
  }
  frame.specularTable = this->SpecularTable.data();
  frame.specularTableSize = SpecularTableSize;
  this->FillLerpPairs(transfer, frame);
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
  frame.mask = settings.mask;
  frame.labelMap = settings.mask && settings.labelTables; // applies to composite only
  frame.maskNeighbours = settings.maskNeighbours && !frame.labelMap;
  frame.labelTables = frame.labelMap ? settings.labelTables : nullptr;
  frame.labelBlend = std::min(std::max(settings.labelBlend, 0.0f), 1.0f);
}

void RayCaster::Internals::FillComponentFrame(const RayCastTransfer& transfer,
  const RayCastLighting& lighting, const RayCastSettings& settings, const LeapPlan& plan,
  detail::KernelFrame& frame)
{
  const RayCastComponents& components = transfer.components;
  if (plan.useOctree && plan.extremum)
  {
    // Each component's own min-max octree (one layout): the extremes leap by their ranges.
    frame.octree = &this->ComponentOctrees[0];
    for (int c = 0; c < components.count; ++c)
    {
      frame.componentOctrees[c] = &this->ComponentOctrees[c];
    }
  }
  frame.components = components.count;
  frame.independent = components.independent;
  frame.componentTables = static_cast<int>(components.tables.size());
  const auto positions = [](const double range[2], int size, float& scale, float& bias)
  {
    const double width = range[1] - range[0];
    scale = width > 0 ? static_cast<float>((size - 1) / width) : 0.0f;
    bias = static_cast<float>(-range[0] * scale);
  };
  constexpr int SpecularTableSize = 2048; // FillKernelFrame's
  for (int t = 0; t < frame.componentTables; ++t)
  {
    const RayCastComponentTable& table = components.tables[t];
    detail::ComponentTableFrame& out = frame.tables[t];
    const int size = static_cast<int>(table.rgba.size() / 4);
    out.rgba = table.rgba.data();
    out.tableSize = size;
    positions(table.colourRange, size, out.colourScale, out.colourBias);
    positions(table.opacityRange, size, out.opacityScale, out.opacityBias);
    const double exponent = settings.sampleDistance / table.opacityUnitDistance;
    std::vector<float>& corrected = this->ComponentCorrectedAlpha[t];
    corrected.resize(size);
    for (int i = 0; i < size; ++i)
    {
      const double a = std::min(std::max(static_cast<double>(table.rgba[4 * i + 3]), 0.0), 1.0);
      corrected[i] = static_cast<float>(1.0 - std::pow(1.0 - a, exponent));
    }
    out.correctedAlpha = corrected.data();
    out.opacityExponent = static_cast<float>(exponent);
    out.gradientOpacity = table.gradientOpacity.empty() ? nullptr : table.gradientOpacity.data();
    out.gradientOpacitySize = static_cast<int>(table.gradientOpacity.size());
    out.weight = static_cast<float>(std::min(std::max(table.weight, 0.0), 1.0));
    LightModel& model = this->ComponentModels[t];
    model = lighting.model;
    model.ambient = table.ambient;
    model.diffuse = table.diffuse;
    model.specular = table.specular;
    model.specularPower = table.specularPower;
    out.model = &model;
    std::vector<float>& specular = this->ComponentSpecular[t];
    specular.resize(SpecularTableSize);
    for (int i = 0; i < SpecularTableSize; ++i)
    {
      specular[i] = static_cast<float>(
        std::pow(static_cast<double>(i) / (SpecularTableSize - 1), table.specularPower));
    }
    out.specularTable = specular.data();
  }
  frame.isoComponent = 0;
  for (int c = 1; c < frame.componentTables && components.independent; ++c)
  {
    if (components.tables[c].weight > components.tables[frame.isoComponent].weight)
    {
      frame.isoComponent = c;
    }
  }
  for (int c = 0; c < components.count; ++c)
  {
    const double* range = components.ranges[c];
    const double width = range[1] > range[0] ? range[1] - range[0] : 1.0;
    frame.componentScale[c] = static_cast<float>(1.0 / width);
    frame.componentBias[c] = static_cast<float>(-range[0] / width);
  }
  for (int a = 0; a < 3; ++a)
  {
    frame.colourScale[a] = static_cast<float>(components.colourScale[a]);
    frame.colourBias[a] = static_cast<float>(components.colourBias[a]);
    frame.componentAxisScale[a] = static_cast<float>(transfer.gradientAxisScale[a]);
    for (int b = 0; b < 3; ++b)
    {
      frame.componentNormalMatrix[a][b] = static_cast<float>(lighting.normalMatrix[a][b]);
    }
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
  PrepareProgress progress{ impl.Progress };
  const int tableSize = static_cast<int>(transfer.rgba.size() / 4);
  std::vector<float> alphas(tableSize);
  for (int i = 0; i < tableSize; ++i)
  {
    alphas[i] = transfer.rgba[4 * i + 3];
  }
  const double width = rangeMax > rangeMin ? rangeMax - rangeMin : 1.0;

  const OpacityRange opacityRange(alphas, rangeMin, rangeMax);
  const RayCastComponents& components = transfer.components;
  const bool multiComponent = components.count > 1;
  const LeapPlan plan = PlanLeaping(settings, opacityRange, rangeMin, rangeMax, multiComponent);
  if (multiComponent)
  {
    if (plan.useOctree &&
      !impl.UpdateComponentOctree(volume, volumeVersion, transferVersion, components, settings,
        plan.zeroOpacityAddsNothing, parallel, progress, error))
    {
      return false;
    }
    if (plan.useDistance)
    {
      impl.UpdateComponentCells(
        volume, volumeVersion, transferVersion, components, settings.mask, parallel, progress);
    }
  }
  else
  {
    if (plan.useOctree &&
      !impl.UpdateOctree(volume, volumeVersion, transferVersion, alphas, rangeMin, rangeMax,
        settings, plan, parallel, progress, error))
    {
      return false;
    }
    if (plan.useCellLeap || plan.useDistance)
    {
      impl.UpdateCells(volume, volumeVersion, transferVersion, opacityRange, plan, settings.mask,
        parallel, progress);
    }
  }
  // Multi-component gradients are taken on the fly (six extra samples per shaded one).
  const bool useGradients = !multiComponent &&
    impl.UpdateGradients(
      volume, volumeVersion, width, transfer, lighting, settings, parallel, progress);

  // The table opacities hold for the unit distance; samples stand for sampleDistance.
  const double exponent = settings.sampleDistance / transfer.opacityUnitDistance;
  impl.CorrectedAlpha.resize(tableSize);
  impl.MaximumCorrectedAlpha = 0.0f;
  for (int i = 0; i < tableSize; ++i)
  {
    const double a = std::min(std::max(static_cast<double>(alphas[i]), 0.0), 1.0);
    impl.CorrectedAlpha[i] = static_cast<float>(1.0 - std::pow(1.0 - a, exponent));
    impl.MaximumCorrectedAlpha = std::max(impl.MaximumCorrectedAlpha, impl.CorrectedAlpha[i]);
  }

  detail::KernelFrame frame;
  impl.FillKernelFrame(volume, rangeMin, rangeMax, transfer, lighting, view, settings, plan,
    useGradients, exponent, frame);
  if (multiComponent)
  {
    impl.FillComponentFrame(transfer, lighting, settings, plan, frame);
  }
  frame.raysThroughEye = detail::RaysPassThroughEye(frame);
  frame.eyeLightsAtEntry = detail::EyeLightsAtEntry(frame);
  double indexToClip[4][4];
  const bool projects = IndexToClip(view, indexToClip);
  VisiblePixels(ShownBox(settings, frame), projects ? indexToClip : nullptr, view, frame.visible);
  std::copy(frame.visible, frame.visible + 4, impl.CastRectangle);
  if (settings.octantDistanceMaps)
  {
    impl.UpdateOctantMaps(frame, parallel);
  }
  if (projects)
  {
    impl.UpdateFootprint(frame, indexToClip, parallel);
  }
  impl.PrepareSeconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - prepareStart).count();

  // With progress: the tiles as they finish, reported by this thread.
  const ParallelFor tiles = ReportingParallelFor(
    parallel, ProgressRange(impl.Progress, progress.prepared > 0 ? PrepareShare : 0.0, 1.0));
  CastTiles(frame, view, settings.tileSize, tiles, rgba, counters);
  return true;
}
}
