// RayCasterTile: the per-tile ray loops, templated on the scalar type. Included only by the
// RayCastKernel<N>Bit.cxx files, each of which instantiates it for its scalar types, so that the
// kernel's instantiations compile in parallel (one translation unit held them all and was the
// build's longest by far).
#include "raycast/RayCastKernel.h"

#include "raycast/RayCastPackets.h"
#include "raycast/RayCastPixelRay.h"
#include "raycast/RayCastSampler.h"

#include "common/IndexRay.h"
#include "skipping/CellLeapTable.h"
#include "skipping/DistanceTemplate.h"
#include "skipping/OctantDistanceMap.h"
#include "skipping/ScreenFootprint.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>
#include <type_traits>

namespace accelvolume
{
namespace detail
{
namespace
{

// The composite kernel's lane loops (RayCastKernelBatch.inl): an AVX2 build besides the
// baseline on x86-64.
#if (defined(__GNUC__) || defined(__clang__)) && defined(__x86_64__)
#define ACCELVOLUME_AVX2_LANES 1
#define ACCELVOLUME_INLINE_LANES __attribute__((always_inline)) inline
#else
#define ACCELVOLUME_AVX2_LANES 0
#define ACCELVOLUME_INLINE_LANES inline
#endif

// Whether this CPU runs the AVX2 build of the lane loops.
inline bool LanesOnAvx2()
{
#if ACCELVOLUME_AVX2_LANES
  static const bool avx2 = __builtin_cpu_supports("avx2") != 0;
  return avx2;
#else
  return false;
#endif
}

// A hint to start loading the cache line at `address` (no effect on results).
inline void Prefetch(const void* address)
{
#if defined(__GNUC__) || defined(__clang__)
  __builtin_prefetch(address);
#else
  (void)address;
#endif
}

struct Interval
{
  double t0, t1;
};

// Table lookup with linear interpolation between entries (OpacityTable::Lookup convention).
inline void TablePosition(const KernelFrame& frame, float value, int& i, float& fraction)
{
  float u = value * frame.tableScale + frame.tableBias;
  const float last = static_cast<float>(frame.tableSize - 1);
  u = u > 0 ? (u < last ? u : last) : 0.0f;
  i = std::min(static_cast<int>(u), frame.tableSize - 2);
  fraction = u - static_cast<float>(i);
}

template <typename T>
class RayCasterTile
{
public:
  RayCasterTile(const KernelFrame& frame, RayCastCounters& counters)
    : Frame(frame)
    , Settings(*frame.settings)
    , Sampling(frame.volume, frame.components, 0)
    , Counters(counters)
    , Table(GetCellLeapTable())
  {
    for (int c = 0; c < frame.components && frame.components > 1; ++c)
    {
      this->Channels.emplace_back(frame.volume, frame.components, c);
    }
    this->Batching = this->CanBatch();
    this->ApproachTogether = RaysApproachTogether(frame);
    // The lanes shade directional and positional lights, not spot lights.
    for (const SceneLight& light : frame.lighting->model.lights)
    {
      this->LaneLights = this->LaneLights && !(light.positional && light.cosCone >= -1.0f);
    }
    this->Avx2Lanes = !this->Settings.baselineLanes && LanesOnAvx2();
    this->Packets = this->SetUpPackets();
  }

  void Cast(int x0, int y0, int x1, int y1, float* rgba)
  {
    const int width = this->Frame.view->width;
    // Only the pixels whose rays can meet the projected box.
    const int* visible = this->Frame.visible;
    x0 = std::max(x0, visible[0]);
    x1 = std::min(x1, visible[1] + 1);
    y0 = std::max(y0, visible[2]);
    y1 = std::min(y1, visible[3] + 1);
    if (x0 >= x1 || y0 >= y1)
    {
      return;
    }
    if (this->ApproachTogether)
    {
      this->ColumnCentres.resize(static_cast<std::size_t>(x1 - x0));
      for (int i = x0; i < x1; ++i)
      {
        this->ColumnCentres[static_cast<std::size_t>(i - x0)] = PixelCentre(i, width);
      }
#if ACCELVOLUME_PACKETS
      // Only the scalar types the packets load instantiate them (SetUpPackets refuses the others).
      if constexpr (PacketScalar<T>)
      {
        if (this->Packets)
        {
          for (int j = y0; j < y1; j += PacketRows)
          {
            this->CastRowsInPackets(j, std::min(j + PacketRows, y1), x0, x1, rgba);
          }
          return;
        }
      }
#endif
      for (int j = y0; j < y1; ++j)
      {
        this->CastRowTogether(j, x0, x1, rgba + 4 * static_cast<std::size_t>(j) * width);
      }
      return;
    }
    if (!this->Frame.useOctree)
    {
      // Each ray as it is cast (only the octree's distance template needs them all first).
      for (int j = y0; j < y1; ++j)
      {
        for (int i = x0; i < x1; ++i)
        {
          float* out = rgba + 4 * (static_cast<std::size_t>(j) * width + i);
          PixelRay pixel = MakePixelRay(this->Frame, i, j);
          this->CastRay(pixel, out);
        }
      }
      return;
    }
    std::vector<PixelRay>& rays = this->Rays;
    rays.clear();
    double maximumStep[3] = { 0, 0, 0 };
    const double h = this->Settings.sampleDistance;
    for (int j = y0; j < y1; ++j)
    {
      for (int i = x0; i < x1; ++i)
      {
        rays.push_back(MakePixelRay(this->Frame, i, j));
        const Vec3& d = rays.back().index.direction;
        maximumStep[0] = std::max(maximumStep[0], std::abs(d.x * h));
        maximumStep[1] = std::max(maximumStep[1], std::abs(d.y * h));
        maximumStep[2] = std::max(maximumStep[2], std::abs(d.z * h));
      }
    }
    const MinMaxOctree& octree = *this->Frame.octree;
    while ((1 << this->LeafShift) < octree.GetLeafSize())
    {
      ++this->LeafShift;
    }
    this->Template.Build(maximumStep, octree.GetLeafSize() << octree.GetDepth());
    std::size_t at = 0;
    for (int j = y0; j < y1; ++j)
    {
      for (int i = x0; i < x1; ++i)
      {
        float* out = rgba + 4 * (static_cast<std::size_t>(j) * width + i);
        this->CastRay(rays[at++], out);
      }
    }
  }

private:
  // The ray's region intervals in increasing t0; false when it misses them all.
  bool Intervals(const IndexRay& ray, std::vector<Interval>& intervals) const
  {
    intervals.clear();
    for (const Box& region : this->Settings.regions)
    {
      Interval interval;
      if (ClipRayToRegion(ray, region, this->Settings.clip, interval.t0, interval.t1))
      {
        intervals.push_back(interval);
      }
    }
    std::sort(intervals.begin(), intervals.end(),
      [](const Interval& a, const Interval& b) { return a.t0 < b.t0; });
    return !intervals.empty();
  }

  // Samples after the current one that stay in the largest node around p that the predicate
  // accepts, or -1 when the leaf itself is not accepted. Inline integer arithmetic (no Morton
  // decode, no bounds-checked queries): this runs once per sample while the ray is in
  // non-empty leaves.
  template <typename Accept>
  std::int64_t OctreeLeap(const double p[3], const Vec3& step, Accept&& accept)
  {
    const MinMaxOctree& octree = *this->Frame.octree;
    const int* grid = octree.GetLevel(0).gridSize;
    int c[3];
    for (int a = 0; a < 3; ++a)
    {
      const int voxel = p[a] > 0 ? static_cast<int>(p[a]) : 0;
      c[a] = std::min(voxel >> this->LeafShift, grid[a] - 1);
    }
    if (c[0] == this->RejectedLeaf[0] && c[1] == this->RejectedLeaf[1] &&
      c[2] == this->RejectedLeaf[2])
    {
      return -1;
    }
    const std::uint64_t code = MortonEncode(static_cast<std::uint32_t>(c[0]),
      static_cast<std::uint32_t>(c[1]), static_cast<std::uint32_t>(c[2]));
    if (!accept(0, code))
    {
      std::copy(c, c + 3, this->RejectedLeaf);
      return -1;
    }
    int level = 0;
    const int depth = octree.GetDepth();
    while (level < depth && accept(level + 1, code >> (3 * (level + 1))))
    {
      ++level;
    }
    // The node's index-space box [i * span, (i + 1) * span] clamped to the volume.
    const int* dims = this->Frame.volume.dims;
    const int shift = this->LeafShift + level;
    Box box;
    double* lower[3] = { &box.lower.x, &box.lower.y, &box.lower.z };
    double* upper[3] = { &box.upper.x, &box.upper.y, &box.upper.z };
    for (int a = 0; a < 3; ++a)
    {
      const std::int64_t first = (static_cast<std::int64_t>(c[a] >> level)) << shift;
      *lower[a] = static_cast<double>(first);
      *upper[a] = static_cast<double>(
        std::min<std::int64_t>(first + (std::int64_t(1) << shift), std::max(dims[a] - 1, 0)));
    }
    return this->Template.StepsInside(box, Vec3{ p[0], p[1], p[2] }, step);
  }

  // The mask value of the voxel nearest to p (as the slice mapper's texelFetch), 1 without one.
  int MaskAt(const double p[3]) const
  {
    const int* dims = this->Frame.volume.dims;
    std::size_t at = 0;
    std::size_t stride = 1;
    for (int a = 0; a < 3; ++a)
    {
      const double q = std::floor(p[a] + 0.5);
      const int i = q > 0 ? (q < dims[a] - 1 ? static_cast<int>(q) : dims[a] - 1) : 0;
      at += static_cast<std::size_t>(i) * stride;
      stride *= static_cast<std::size_t>(dims[a]);
    }
    return this->Frame.mask[at];
  }

  // A binary mask hides the sample; a ghost mask also when a point half a voxel away along an
  // axis is hidden (the slice mapper's rule: the points of the cells that share the sample).
  bool Hidden(const double p[3]) const
  {
    if (!this->Frame.mask || this->Frame.labelMap)
    {
      return false;
    }
    if (this->MaskAt(p) == 0)
    {
      return true;
    }
    if (this->Frame.maskNeighbours)
    {
      for (int a = 0; a < 3; ++a)
      {
        for (const double offset : { -0.5, 0.5 })
        {
          double q[3] = { p[0], p[1], p[2] };
          q[a] += offset;
          if (this->MaskAt(q) == 0)
          {
            return true;
          }
        }
      }
    }
    return false;
  }

  void ForgetRejectedLeaf()
  {
    this->RejectedLeaf[0] = this->RejectedLeaf[1] = this->RejectedLeaf[2] = -1;
  }

  void CastRay(PixelRay& pixel, float* out)
  {
    out[0] = out[1] = out[2] = out[3] = 0.0f;
    if (!this->Intervals(pixel.index, this->RayIntervals))
    {
      return;
    }
    this->RayStart = WalkStart();
    this->CastFromStart(pixel, out);
  }

  // Where the current ray's walk begins: sample `sample` of RayIntervals[interval], or the
  // first sample of the first interval (sample -1). The grouped approach sets it past the empty
  // space it has leaped already (RayCastKernelApproach.inl).
  struct WalkStart
  {
    std::size_t interval = 0;
    std::int64_t sample = -1;
    std::int64_t last = 0; // the end of that interval's samples, when sample >= 0
  };

  // The samples [first, last) of `interval` a walk visits; the opaque box's cut is added to
  // `leaped`.
  void IntervalSamples(const IndexRay& ray, const Interval& interval, double h, bool opaqueBox,
    std::int64_t& first, std::int64_t& last, std::uint64_t& leaped) const
  {
    const std::int64_t count =
      static_cast<std::int64_t>(std::floor((interval.t1 - interval.t0) / h + 0.5));
    first = 0;
    last = count;
    if (opaqueBox)
    {
      this->OpaqueSamples(ray, interval, h, count, first, last);
      leaped += static_cast<std::uint64_t>(first + (count - last));
    }
  }

  // IntervalSamples of RayIntervals[at] for the current ray's walk, which resumes at RayStart
  // (the approach has found that interval's samples and counted its cut).
  void WalkSamples(const IndexRay& ray, std::size_t at, double h, bool opaqueBox,
    std::int64_t& first, std::int64_t& last, std::uint64_t& leaped) const
  {
    if (at == this->RayStart.interval && this->RayStart.sample >= 0)
    {
      first = this->RayStart.sample;
      last = this->RayStart.last;
      return;
    }
    this->IntervalSamples(ray, this->RayIntervals[at], h, opaqueBox, first, last, leaped);
  }

  // The ray's lights (shading only), once RayIntervals holds its intervals.
  void LightRay(PixelRay& pixel) const
  {
    const RayCastLighting& lighting = *this->Frame.lighting;
    if (this->Frame.eyeLightsAtEntry)
    {
      const IndexRay& ray = pixel.index;
      const double t = this->RayIntervals.front().t0;
      const double entry[3] = { ray.origin.x + t * ray.direction.x,
        ray.origin.y + t * ray.direction.y, ray.origin.z + t * ray.direction.z };
      LightPixelRayAtEntry(lighting, entry, pixel);
    }
    else if (lighting.shade)
    {
      LightPixelRay(lighting, this->Frame.raysThroughEye, pixel);
    }
  }

  // CastRay once the ray's intervals and RayStart are set.
  void CastFromStart(PixelRay& pixel, float* out)
  {
    out[0] = out[1] = out[2] = out[3] = 0.0f;
    if (this->RayStart.interval >= this->RayIntervals.size())
    {
      ++this->Counters.rays; // leaped through by the grouped approach: adds nothing
      return;
    }
    this->LightRay(pixel);
    ++this->Counters.rays;
    if (this->Frame.components > 1)
    {
      this->CastComponentsRay(pixel, out);
      return;
    }
    switch (this->Settings.blend)
    {
      case Blend::Composite:
        if (this->Batching)
        {
          this->CompositeBatched(pixel, out);
        }
        else
        {
          this->Composite(pixel, out);
        }
        break;
      case Blend::Maximum:
      case Blend::Minimum:
        this->Extreme(pixel, out);
        break;
      case Blend::Additive:
      case Blend::Average:
        this->Integrate(pixel, out);
        break;
      case Blend::Slice:
        this->SlicePlane(pixel, out);
        break;
      case Blend::Isosurface:
        this->IsoSurfaces(pixel, out);
        break;
    }
  }

  // Composite rays of the common case in batches (RayCastKernelBatch.inl). 32 rather than 16:
  // longer lane loops pay for their set-up (measured 0-10 % faster on semi-transparent TFs).
  static constexpr int BatchSize = 32;
  struct BatchSample
  {
    SampleCell cell;
    std::int64_t q[3]; // its place (FixedSteps)
    float value, alpha, fraction;
    int entry; // table entry below the value
  };
  struct BatchedRay
  {
    float colour[3] = { 0, 0, 0 };
    float alpha = 0;
  };
  // Composite rays a few neighbours at a time (RayCastKernelApproach.inl).
  static constexpr int ApproachGroup = 4;
  struct ApproachLane
  {
    FixedSteps steps;
    LeapSteps leap;
    std::int64_t sample = 0, last = 0;
    std::size_t interval = 0;
    const std::uint8_t* distance = nullptr; // DistanceMapOf the lane's ray
    bool going = false;
  };
  void CastRowTogether(int j, int x0, int x1, float* row);
  void Approach(int n);
  // Composite rays sixteen at a time (RayCastKernelPackets.inl); false where they cannot.
  bool SetUpPackets();
#if ACCELVOLUME_PACKETS
  static constexpr int PacketRows = 4, PacketColumns = 4; // a packet's pixels, when all cast
  int AddToPacket(int n, PixelRay& pixel, float* out);
  void RememberLights(const PixelRay& pixel);
  void CastRowsInPackets(int j0, int j1, int x0, int x1, float* rgba);
  struct PacketBlock // pixels [x0, x1) x [j0, j1) of a tile whose columns start at tileX0
  {
    int x0, x1, j0, j1, tileX0;
    const double* rowCentres;           // of rows j0...
    const std::uint8_t* const* covered; // FootprintRow of rows j0...
  };
  int AddBlockToPackets(int n, const PacketBlock& block, float* rgba);
  ACCELVOLUME_AVX512 void CastPacket(int n);
  ACCELVOLUME_AVX512 void PacketLeap(
    __mmask16 leaping, const __m512i& d, const __m512 f[3], PacketWide& k, const PacketWide& last);
  ACCELVOLUME_AVX512 void PacketShade(__mmask16 lanes, const __m512i& base, __mmask16 interior,
    const __m512i sampleRows[4], const __m512 f[3], __m512 rgb[3]);
#endif
  bool ApproachInterval(int g);
  bool CanBatch() const;
  void CompositeBatched(const PixelRay& pixel, float* out);
  bool CompositeBatch(const PixelRay& pixel, int n, BatchedRay& state);
  // The shading lanes: one body, built for the x86-64 baseline and for AVX2.
  bool ShadeBatchLanes(const PixelRay& pixel, int n, BatchedRay& state);
  bool ShadeBatchLanesAvx2(const PixelRay& pixel, int n, BatchedRay& state);
  bool ShadeBatchLanesIn(const PixelRay& pixel, int n, BatchedRay& state);
  void FixedLightLanes(const PixelRay& pixel, int first, int last, float ambient[3]);
  void PointLightLanes(const PixelRay& pixel, int first, int last, float ambient[3]);
  bool BlendSample(BatchedRay& state, float r, float g, float b, float a);
  // Per-lane arrays of a batch (structure of arrays: the loops over them vectorise).
  struct BatchLanes
  {
    float corner[8][BatchSize];
    float fx[BatchSize], fy[BatchSize], fz[BatchSize];
    float interpolated[3][BatchSize]; // gradients in index space
    float eye[3][BatchSize];
    float rgb[3][BatchSize];
    float alpha[BatchSize];
    float normal[3][BatchSize];
    float diffuse[3][BatchSize], specular[3][BatchSize];
    int visible[BatchSize]; // batch indices of the visible samples, in order
    int count;              // how many
  };

  // MIP / MinIP and raysum / average rays (RayCastKernelProjections.inl).
  void Extreme(const PixelRay& pixel, float* out);
  void Integrate(const PixelRay& pixel, float* out);

  // ISOSURFACE_BLEND and SLICE_BLEND rays (RayCastKernelPlanes.inl).
  void IsoSurfaces(const PixelRay& pixel, float* out);
  void IsoClassify(float v, float rgba[4]) const;
  void IsoShade(const PixelRay& pixel, const double p[3], const SampleCell& cell,
    bool& haveGradient, float eyeGradient[3], float rgb[3]) const;
  void SlicePlane(const PixelRay& pixel, float* out);

  // Multi-component rays (RayCastKernelComponents.inl).
  void CastComponentsRay(const PixelRay& pixel, float* out);
  void SampleComponents(const double p[3], const SampleCell& cell, float values[4]) const;
  void ComponentGradients(const double p[3], int count, float gradients[4][3]) const;
  float ComponentGradientOpacity(const ComponentTableFrame& table, const float gradient[3]) const;
  bool ClassifyComponents(const PixelRay& pixel, const double p[3], const float values[4],
    bool needGradient, float premultiplied[4], bool planeSample = false) const;
  void CompositeComponents(const PixelRay& pixel, float* out);
  void ExtremeComponents(const PixelRay& pixel, float* out);
  void IntegrateComponents(const PixelRay& pixel, float* out);

  // The samples [first, last) of an interval of `count` samples that may meet the box of
  // possibly opaque cells; one sample of slack on each side keeps rounding from cutting a
  // visible one.
  void OpaqueSamples(const IndexRay& ray, const Interval& interval, double h, std::int64_t count,
    std::int64_t& first, std::int64_t& last) const
  {
    static const std::vector<HalfSpace> noClip;
    double enter, leave;
    if (!IntersectRayRegion(ray.origin, ray.direction, this->Frame.opaqueBox, noClip, enter, leave))
    {
      first = last = count;
      return;
    }
    first = std::max<std::int64_t>(
      0, static_cast<std::int64_t>(std::floor((enter - interval.t0) / h - 0.5)));
    last = std::min<std::int64_t>(
      count, static_cast<std::int64_t>(std::ceil((leave - interval.t0) / h - 0.5)) + 1);
    first = std::min(first, count);
    last = std::max(last, first);
  }

  // OctreeLeap over the octree's transparent nodes (the composite walks' zero-opacity leap).
  std::int64_t TransparentOctreeLeap(const double p[3], const Vec3& step)
  {
    const MinMaxOctree* tree = this->Frame.octree;
    return this->OctreeLeap(p, step,
      [tree](int level, std::uint64_t index)
      { return tree->GetTransparentFlags(level)[index] != 0; });
  }

  // Starts loading a cell's voxels and, with `gradients`, its precomputed gradients (the lines
  // of the cell's four x-edges); no effect on results.
  void PrefetchCell(const SampleCell& cell, bool gradients) const
  {
    const T* voxel = this->Sampling.Voxels() + cell.base;
    Prefetch(voxel);
    Prefetch(voxel + cell.offset[1]);
    Prefetch(voxel + cell.offset[2]);
    Prefetch(voxel + cell.offset[1] + cell.offset[2]);
    if (gradients)
    {
      const std::uint32_t* g = this->Frame.gradients + cell.base;
      Prefetch(g);
      Prefetch(g + cell.offset[1]);
      Prefetch(g + cell.offset[2]);
      Prefetch(g + cell.offset[1] + cell.offset[2]);
    }
  }

  // Row j's blocks of the frame's screen footprint (nullptr without one): pixels of uncovered
  // blocks stay empty without a ray.
  const std::uint8_t* FootprintRow(int j) const
  {
    const KernelFrame& frame = this->Frame;
    return frame.footprint
      ? frame.footprint + static_cast<std::size_t>(j >> FootprintBlockShift) * frame.footprintBlocks
      : nullptr;
  }

  // The cell's leaping entry: its distance-map value in the low byte, its cell-leap
  // configuration above (the distance map alone when cell leaping is off).
  std::uint16_t LeapEntry(const SampleCell& cell) const
  {
    return LeapEntryIn(this->RayDistance, cell);
  }
  // With cell leaping the configuration comes from the packed table, the distance from the
  // ray's octant map where there is one.
  std::uint16_t LeapEntryIn(const std::uint8_t* distance, const SampleCell& cell) const
  {
    if (const std::uint16_t* info = this->Frame.cellInfo)
    {
      const std::uint16_t entry = info[cell.cell];
      return distance ? static_cast<std::uint16_t>((entry & 0xff00) | distance[cell.cell]) : entry;
    }
    return distance[cell.cell];
  }
  // The distance map a ray reads: its octant's where built, else the chessboard map alone
  // (nullptr with cell leaping: the packed table's own byte, or without distance leaping).
  const std::uint8_t* DistanceMapOf(const Vec3& direction) const
  {
    const KernelFrame& frame = this->Frame;
    if (!frame.useDistance)
    {
      return nullptr;
    }
    const std::uint8_t* octant =
      frame.octantDistance[DirectionOctant(direction.x, direction.y, direction.z)];
    return octant ? octant : frame.distanceOnly;
  }

  // The samples a distance-map value d > 0 moves the ray on by (the current one included, at
  // most `left`), counted.
  std::int64_t CountedDistanceLeap(
    const SampleCell& cell, int d, const LeapSteps& steps, std::int64_t left)
  {
    const std::int64_t skipped = std::min(DistanceLeap(cell, d, steps) + 1, left);
    this->Counters.leapedDistance += static_cast<std::uint64_t>(skipped);
    ++this->Counters.distanceLeaps;
    return skipped;
  }

  // Walks the samples of every interval; visit(p, cell, value) returns false to stop the ray.
  // Zero-opacity leaping (octree, distance map, cell table) happens here when `leapTransparent`
  // (RayCastKernelWalk.inl).
  template <typename Visit>
  void Walk(const PixelRay& pixel, bool leapTransparent, Visit&& visit);
  // A composite ray sample by sample (RayCastKernelWalk.inl).
  void Composite(const PixelRay& pixel, float* out);

  // Central differences of trilinear samples one voxel apart (what the slice mapper's gradient
  // texture holds), in normalised units, taken to eye space. With precomputed per-voxel
  // differences this is one trilinear interpolation of them (equal inside the volume, as
  // interpolation is linear); without, six extra samples.
  // The eye-space gradient and the index-space one it comes from (in the gradients' units).
  void Gradient(const double p[3], const SampleCell& cell, float eyeGradient[3], float g[3]) const
  {
    if (const std::uint32_t* gradients = this->Frame.gradients)
    {
      // Interpolated per-voxel differences; their scale is folded into the normal matrix.
      const std::ptrdiff_t ox = cell.offset[0], oy = cell.offset[1], oz = cell.offset[2];
      const std::uint32_t* d = gradients + cell.base;
      // The 8 trilinear weights once for the three components.
      const float fx = cell.f[0], fy = cell.f[1], fz = cell.f[2];
      const float wy[2] = { (1 - fy), fy };
      const float wz[2] = { (1 - fz), fz };
      const std::ptrdiff_t at[8] = { 0, ox, oy, oy + ox, oz, oz + ox, oz + oy, oz + oy + ox };
      InterpolateGradient(d, at, fx, wy, wz, g);
    }
    else
    {
      for (int a = 0; a < 3; ++a)
      {
        double forward[3] = { p[0], p[1], p[2] };
        double backward[3] = { p[0], p[1], p[2] };
        forward[a] += 1.0;
        backward[a] -= 1.0;
        g[a] = 0.5f *
          (this->Sampling.Sample(forward, this->Settings.nearest) -
            this->Sampling.Sample(backward, this->Settings.nearest));
      }
    }
    const float(*m)[3] = this->Frame.normalMatrix;
    for (int r = 0; r < 3; ++r)
    {
      eyeGradient[r] = m[r][0] * g[0] + m[r][1] * g[1] + m[r][2] * g[2];
    }
  }

  float GradientOpacity(float magnitude) const
  {
    const int n = this->Frame.gradientOpacitySize;
    float u = magnitude / this->Frame.gradientOpacityMaximum * static_cast<float>(n - 1);
    u = u > 0 ? (u < n - 1 ? u : static_cast<float>(n - 1)) : 0.0f;
    const int i = std::min(static_cast<int>(u), n - 2);
    return Lerp(this->Frame.gradientOpacity[i], this->Frame.gradientOpacity[i + 1], u - i);
  }

  // VTK's light model (common/Lighting.h) at index point p, with the frame's coefficients.
  void Shade(
    const PixelRay& pixel, const double p[3], const float eyeGradient[3], float rgb[3]) const
  {
    this->ShadeWith(this->Frame.lighting->model, this->Frame.specularTable, pixel, p, eyeGradient,
      rgb);
  }

  // The same with a model's coefficients and its tabulated specular power.
  void ShadeWith(const LightModel& model, const float* table, const PixelRay& pixel,
    const double p[3], const float eyeGradient[3], float rgb[3]) const
  {
    const RayCastLighting& l = *this->Frame.lighting;
    const int size = this->Frame.specularTableSize;
    const auto power = [table, size](float x)
    {
      const float u = x * static_cast<float>(size - 1);
      const int k = std::min(static_cast<int>(u), size - 2);
      return Lerp(table[k], table[k + 1], u - static_cast<float>(k));
    };
    float factor[3];
    float highlight[3];
    const float squared = eyeGradient[0] * eyeGradient[0] + eyeGradient[1] * eyeGradient[1] +
      eyeGradient[2] * eyeGradient[2];
    // Component tables' models share the frame's lights (only their coefficients differ).
    if (pixel.fixedLights && model.lights.size() == l.model.lights.size())
    {
      // Without branches on the data (they mispredict from sample to sample): a vanishing
      // gradient gives a zero normal, hence the ambient terms alone, as AmbientTerms.
      const float inverse = squared > 1.0e-16f ? -1.0f / std::sqrt(squared) : 0.0f;
      const float normal[3] = { eyeGradient[0] * inverse, eyeGradient[1] * inverse,
        eyeGradient[2] * inverse };
      FixedLightingTerms(model, normal, pixel.toLight, pixel.half, power, factor, highlight);
    }
    else if (squared > 1.0e-16f)
    {
      const float inverse = -1.0f / std::sqrt(squared);
      const float normal[3] = { eyeGradient[0] * inverse, eyeGradient[1] * inverse,
        eyeGradient[2] * inverse };
      float eye[3] = { 0, 0, 0 };
      if (model.anyPositional)
      {
        for (int r = 0; r < 3; ++r)
        {
          eye[r] = static_cast<float>(l.indexToEye[r][0] * p[0] + l.indexToEye[r][1] * p[1] +
            l.indexToEye[r][2] * p[2] + l.indexToEyeOffset[r]);
        }
      }
      LightingTerms(model, normal, eye, pixel.toViewer, power, factor, highlight);
    }
    else
    {
      AmbientTerms(model, factor, highlight);
    }
    for (int c = 0; c < 3; ++c)
    {
      rgb[c] = std::min(rgb[c] * factor[c] + highlight[c], 1.0f);
    }
  }

  const KernelFrame& Frame;
  const RayCastSettings& Settings;
  Sampler<T> Sampling;
  std::vector<Sampler<T>> Channels; // multi-component scalars: one per component
  RayCastCounters& Counters;
  const std::array<CellLeapCase, 256>& Table;
  DistanceTemplate Template;
  std::vector<Interval> RayIntervals;
  WalkStart RayStart;
  bool ApproachTogether = false; // composite rays approach their first non-empty cell together
  PixelRay GroupPixels[ApproachGroup];
  int GroupColumns[ApproachGroup]; // the group's pixel columns (the footprint skips some)
  std::vector<Interval> GroupIntervals[ApproachGroup];
  bool GroupHits[ApproachGroup];
  WalkStart GroupStarts[ApproachGroup];
  ApproachLane GroupLanes[ApproachGroup];
  std::vector<PixelRay> Rays;
  std::vector<double> ColumnCentres;    // PixelCentre of the tile's columns (CastRowTogether)
  int RejectedLeaf[3] = { -1, -1, -1 }; // the last leaf found non-empty (per ray)
  int LeafShift = 0;                    // log2 of the octree leaf size
  bool LastContributed = false;         // the ray's last sample added something
  const std::uint8_t* RayDistance = nullptr; // DistanceMapOf the ray being walked
  bool Batching = false;                // composite rays take CompositeBatched
  bool Avx2Lanes = false;               // the shading lanes' AVX2 build
  bool LaneLights = true;               // the lanes can shade rays whose lights are not fixed
  BatchSample Batch[BatchSize];
  BatchLanes Lanes;
  bool Packets = false; // composite rays take CastRowsInPackets
#if ACCELVOLUME_PACKETS
  PacketRays Packet;
  PacketCandidates Candidates;
  bool PacketRaySetUp = false;         // packets set their rays up together (PacketRaysApply)
  bool PacketGradientsFromVoxels = false; // (PacketVoxelGradients)
  std::ptrdiff_t PacketCorner[8] = {}; // the corners' voxel offsets
  int PacketBricks[3] = {};            // CellBricks per axis of the cell grid
  PixelRay LitRay;                     // the direction and lights of the last ray lit
  bool LitRaySet = false;              // (RememberLights)
#endif
  std::uint64_t HiddenSamples = 0;      // samples Walk found masked (iso-surfaces restart there)
};

#include "raycast/RayCastKernelApproach.inl"
#include "raycast/RayCastKernelBatch.inl"
#include "raycast/RayCastKernelComponents.inl"
#include "raycast/RayCastKernelPacketRays.inl"
#include "raycast/RayCastKernelPackets.inl"
#include "raycast/RayCastKernelPacketShade.inl"
#include "raycast/RayCastKernelPlanes.inl"
#include "raycast/RayCastKernelProjections.inl"
#include "raycast/RayCastKernelWalk.inl"
}

// One tile of scalar type T (declared in RayCastKernel.h), for the file that includes this one
// to instantiate.
template <typename T>
void CastTileOf(
  const KernelFrame& frame, int x0, int y0, int x1, int y1, float* rgba, RayCastCounters& counters)
{
  RayCasterTile<T> tile(frame, counters);
  tile.Cast(x0, y0, x1, y1, rgba);
}

}
}
