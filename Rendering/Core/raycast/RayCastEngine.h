// RayCastEngine: the CPU ray caster behind vtkAccelVolumeRayCastMapper (plain C++, no VTK).
//
// Rays leave the near plane through the pixel centres of a width x height image (NDC
// ((2 (i + 0.5) / w) - 1, (2 (j + 0.5) / h) - 1), j from the bottom), travel in world units and
// are resampled in index space. Per ray and region (box ∩ clip half-spaces ∩ [0, geometry]),
// samples sit at t0 + (k + 0.5) h for k < floor((t1 - t0) / h + 0.5), h = the sample distance,
// with trilinear (or nearest) interpolation, clamped to the volume like GL_CLAMP_TO_EDGE.
// Blend modes follow vtkAccelVolumeSliceMapper / vtkGPUVolumeRayCastMapper semantics.
//
// Accelerations, each exact (the image is identical with and without it):
// - empty-space leaping by the min-max octree with a distance template (composite / additive:
//   transparent nodes; MIP / MinIP: nodes whose range cannot beat the ray's current extreme),
//   or by a chessboard distance map (composite / additive);
// - semi-transparent cell leaping with the modified Marching Cubes table (CellLeapTable);
// - early ray termination (composite; changes the image by at most 1 - threshold, identically
//   with and without leaping).
// Multi-component scalars (RayCastTransfer::components: every blend mode; iso-surfaces of the
// independent component of the largest weight, or of dependent component 0) leap with the
// octree or the distance map classified per component (a node or cell is empty when every
// component that can make a sample visible is transparent there); they have no cell
// leaping and no precomputed gradients; MIP / MinIP leap by every component's own octree (a
// node whose ranges cannot beat the ray's extremes).
// Work is split into fixed square tiles; results never depend on the thread count.
#ifndef accelvolume_RayCastEngine_h
#define accelvolume_RayCastEngine_h

#include "common/Affine.h"
#include "common/Blend.h"
#include "common/Camera.h"
#include "common/Lighting.h"
#include "common/Progress.h"
#include "skipping/MinMaxOctree.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

// Types with non-trivial members that the VTK module instantiates templates of (vector copies):
// hidden, so those instantiations are not exported from the module either
// (Testing/Symbols/CheckHiddenCore.py).
#if defined(__GNUC__)
#define ACCELVOLUME_CORE_HIDDEN __attribute__((visibility("hidden")))
#else
#define ACCELVOLUME_CORE_HIDDEN
#endif

namespace accelvolume
{

enum class LeapMode
{
  None,
  Octree,     // min-max octree + distance template
  DistanceMap // chessboard distance map (composite / additive only)
};

// One classification table of multi-component scalars (RayCastComponents), as
// vtkGPUVolumeRayCastMapper's: colour over colourRange of the colour component's raw values,
// opacity over opacityRange of the opacity component's raw values, N >= 2 entries each.
struct ACCELVOLUME_CORE_HIDDEN RayCastComponentTable
{
  std::vector<float> rgba; // 4 N floats
  double colourRange[2] = { 0, 1 };
  double opacityRange[2] = { 0, 1 };
  // Gradient opacity over a normalised gradient magnitude in [0, 1/4] (the magnitude of the
  // component's central difference per index step, scaled by RayCastTransfer's
  // gradientAxisScale and divided by its range width); empty: a factor of 1.
  std::vector<float> gradientOpacity;
  double opacityUnitDistance = 1.0;
  double weight = 1.0; // vtkVolumeProperty::ComponentWeight (independent components)
  // Shading coefficients (vtkVolumeProperty's of this component).
  float ambient = 0.1f, diffuse = 0.7f, specular = 0.2f, specularPower = 10.0f;
};

// Multi-component scalars: count (2-4) components per voxel, interleaved (x fastest, component
// fastest of all). Independent: count tables, table c classifies component c; a sample's
// colour and opacity combine them with the weights as vtkGPUVolumeRayCastMapper does.
// Dependent: one table; 2 components: colour of component 0, opacity of component 1; 4: RGB
// from components 0-2 (raw * colourScale[c] + colourBias[c]), opacity of component 3.
// count 1: the single-component path (RayCastTransfer's own table).
struct ACCELVOLUME_CORE_HIDDEN RayCastComponents
{
  int count = 1;
  bool independent = true;
  std::vector<RayCastComponentTable> tables;
  double ranges[4][2] = { { 0, 1 }, { 0, 1 }, { 0, 1 }, { 0, 1 } }; // each component's range
  double colourScale[3] = { 1, 1, 1 };
  double colourBias[3] = { 0, 0, 0 };
};

struct ACCELVOLUME_CORE_HIDDEN RayCastTransfer
{
  // 4 N floats: colour and scalar opacity over [rangeMin, rangeMax] of the raw scalars, linearly
  // interpolated (OpacityTable::Lookup convention). N >= 2.
  std::vector<float> rgba;
  // Gradient opacity over [0, gradientOpacityMaximum] of the gradient magnitude VTK's GPU mapper
  // uses: |(dv/di_a * gradientAxisScale[a])_a|, dv/di_a the central difference of the data value
  // per index step along axis a (VTK: gradientAxisScale[a] = mean spacing / spacing[a]); empty:
  // off.
  std::vector<float> gradientOpacity;
  double gradientOpacityMaximum = 1.0;
  double gradientAxisScale[3] = { 1, 1, 1 };
  double opacityUnitDistance = 1.0; // vtkVolumeProperty::ScalarOpacityUnitDistance
  // Multi-component scalars (count > 1): their tables replace the ones above, which stay
  // required (N >= 2) but unused.
  RayCastComponents components;
};

struct RayCastLighting
{
  bool shade = false;
  LightModel model; // coefficients and eye-space lights
  // index-space gradient -> eye space (inverse transpose of index -> eye), row-major
  double normalMatrix[3][3] = { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } };
  // index-space direction -> eye space (linear part of index -> eye), row-major
  double indexToEye[3][3] = { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } };
  double indexToEyeOffset[3] = { 0, 0, 0 };
  // Eye space: the volume's centre, where shear-warp's per-normal shading evaluates positional
  // lights.
  double centre[3] = { 0, 0, 0 };
};

struct RayCastView
{
  int width = 0, height = 0;
  double clipToWorld[4][4] = {}; // inverse of projection * view, row-major, NDC z in [-1, 1]
  Affine worldToIndex = Affine::Identity();
  // Optional window depth in [0, 1] per pixel (1: no geometry), width * height values.
  const std::vector<float>* depth = nullptr;
};

struct RayCastSettings
{
  Blend blend = Blend::Composite;
  double sampleDistance = 1.0; // world units
  bool nearest = false;
  LeapMode leap = LeapMode::Octree;
  bool cellLeap = true;
  bool earlyTermination = true;
  double terminationThreshold = 0.99;
  double additiveUnitDistance = 1.0;
  double averageRange[2] = { 0, 1 }; // raw scalar range counted by Average
  int octreeLeafSize = 8;
  int tileSize = 16;
  // The composite kernel's lane loops take AVX2 where the CPU has it; true forces the x86-64
  // baseline (SSE2) build of them (tests: both give the same bits).
  bool baselineLanes = false;
  // Composite rays of the common case run in batches (RayCastKernelBatch.inl); false forces
  // the per-sample walk (tests: both give the same bits).
  bool batchedComposite = true;
  // Composite rays leap the empty space before their first non-empty cell a few neighbours at
  // a time, the leaps' dependent chains overlapping (RayCastKernelApproach.inl); false: one
  // ray at a time (tests: both give the same bits).
  bool approachTogether = true;
  // Distance-map leaping reads, per ray, a map of its direction's octant (OctantDistanceMap.h:
  // longer leaps, one byte per cell per octant the frame's rays take); false: the chessboard
  // map alone (tests: both give the same bits).
  bool octantDistanceMaps = true;
  // With the grouped approach, the pixels whose rays cannot meet a non-empty cell (the
  // non-empty macro cells projected to the screen, ScreenFootprint.h) stay empty without a ray;
  // false: every pixel of the projected box casts one (tests: both give the same bits).
  bool screenFootprint = true;
  // With the grouped approach, composite rays of the common case go sixteen at a time, one
  // per AVX-512 lane, where the CPU has AVX-512 (RayCastKernelPackets.inl); false (or
  // baselineLanes): the other paths (tests: all give the same bits).
  bool rayPackets = true;
  // The packets' rays set up eight at a time in AVX-512 lanes where the frame allows
  // (RayCastKernelPacketRays.inl); false: one by one (tests: the same bits).
  bool packetRaySetUp = true;
  // Shading / gradient opacity: per-voxel central differences precomputed (4 bytes per voxel,
  // rebuilt when the scalars change; volumes past 1 GiB of them fall back to six extra samples
  // per shaded sample).
  bool precomputeGradients = true;
  std::vector<Box> regions;    // index space, non-overlapping
  std::vector<HalfSpace> clip; // index space
  HalfSpace slicePlane;        // Blend::Slice: the plane Dot(normal, p) + offset == 0, index space
  std::vector<double> isoValues; // Blend::Isosurface: raw scalar values, ascending
  // Optional mask (vtkGPUVolumeRayCastMapper's SetMaskInput): one byte per voxel, read at the
  // voxel nearest to a sample. Binary (no label tables): 0 hides the sample in every blend mode,
  // and cells whose 8 voxels are all hidden are empty space for the distance map (exact: a
  // mask only removes samples). Label map (composite, one component): a sample whose voxel has
  // label l > 0 takes row l of labelTables (256 rows laid out as RayCastTransfer::rgba, over the
  // same range), mixed with the transfer function by labelBlend; no leaping then (the labels'
  // functions may make transparent values visible); other blend modes ignore a label map.
  // maskNeighbours (a binary mask from ghost arrays): a sample is also hidden when a point half
  // a voxel away along an axis is. ISOSURFACE_BLEND crosses no iso-value across a hidden sample.
  // Change volumeVersion when the mask changes.
  const std::uint8_t* mask = nullptr;
  bool maskNeighbours = false;
  const float* labelTables = nullptr;
  float labelBlend = 1.0f;
};

struct RayCastCounters
{
  std::uint64_t rays = 0;            // rays cast that met a region (leaping culls rays that
                                     // cannot meet a possibly opaque cell)
  std::uint64_t samples = 0;         // samples resampled (interpolated)
  std::uint64_t leapedOctree = 0;    // samples skipped by octree leaps
  std::uint64_t leapedDistance = 0;  // samples skipped by distance-map leaps
  std::uint64_t leapedCell = 0;      // semi-transparent cell samples skipped by the MC table
  std::uint64_t leapedEmptyCell = 0; // samples in all-transparent cells skipped by the table
  std::uint64_t terminatedRays = 0;  // rays closed by early ray termination
  std::uint64_t octreeLeaps = 0;     // octree leaps taken (each skips >= 1 sample)
  std::uint64_t distanceLeaps = 0;   // distance-map leaps taken
  std::uint64_t culledPixels = 0;    // pixels left empty by the screen footprint, without a ray
  std::uint64_t packetRays = 0;      // rays cast sixteen at a time (RayCastSettings::rayPackets)
};

class RayCaster
{
public:
  RayCaster();
  ~RayCaster();
  RayCaster(const RayCaster&) = delete;
  RayCaster& operator=(const RayCaster&) = delete;

  // Renders premultiplied RGBA (4 floats per pixel, i + j * width). volumeVersion and
  // transferVersion identify the scalars and the transfer function: change them when those
  // change so the octree, cell classification and distance map are rebuilt (only what the
  // settings need is built). False with error on bad arguments.
  bool Render(const VolumeView& volume, double rangeMin, double rangeMax,
    std::uint64_t volumeVersion, const RayCastTransfer& transfer, std::uint64_t transferVersion,
    const RayCastLighting& lighting, const RayCastView& view, const RayCastSettings& settings,
    const ParallelFor& parallel, std::vector<float>& rgba, RayCastCounters& counters,
    std::string& error);

  // Progress of every later Render, reported from the thread that calls Render: the rebuild of
  // acceleration structures (when any) up to 0.25, then the tiles as they finish
  // (ReportingParallelFor: no extra barrier). The image does not depend on it. Empty: none.
  void SetProgressFunction(ProgressFunction report);

  // Image pixels [x0, x1] x [y0, y1] (inclusive; x1 < x0 when none) whose rays the last frame
  // cast: every pixel outside it is transparent.
  void GetLastCastRectangle(int rectangle[4]) const;

  // Seconds spent on the last (re)build of the acceleration structures (0 when reused).
  double GetLastPrepareSeconds() const;
  // Bytes held by the acceleration structures.
  std::size_t GetAccelerationBytes() const;

  struct Internals;

private:
  std::unique_ptr<Internals> Impl;
};

}

#endif
