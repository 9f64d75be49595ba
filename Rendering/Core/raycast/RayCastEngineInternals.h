// RayCastEngineInternals: the ray caster's private state (its cached acceleration structures)
// and the per-frame plan both RayCastEngine.cxx and RayCastAcceleration.cxx use. Not installed.
#ifndef accelvolume_RayCastEngineInternals_h
#define accelvolume_RayCastEngineInternals_h

#include "raycast/RayCastEngine.h"
#include "skipping/CellClassification.h"
#include "skipping/MinMaxOctree.h"
#include "skipping/OpacityRange.h"
#include "skipping/ScreenFootprint.h"

#include <cstdint>
#include <vector>

namespace accelvolume
{
namespace detail
{
struct KernelFrame;

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

} // namespace detail

// The .cxx files that share this state use these unqualified.
using detail::LeapPlan;
using detail::PrepareProgress;
using detail::PrepareShare;

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
  // DistanceOnly's rebuilds, and per ray octant (OctantDistanceMap.h) the map built from the
  // DistanceOnly of that build, made when a frame's rays first head that way.
  std::uint64_t DistanceBuilds = 0;
  // Calls visit with the distance map last built: the packed table's (its low byte) when
  // Packed, else DistanceOnly (what the octant maps and the macro cells are made from).
  template <typename Visit>
  void VisitDistanceMap(Visit&& visit) const
  {
    if (this->Packed)
    {
      visit(this->CellInfo.data());
    }
    else
    {
      visit(this->DistanceOnly.data());
    }
  }
  std::vector<std::uint8_t> OctantDistance[8];
  std::uint64_t OctantDistanceBuild[8] = { 0, 0, 0, 0, 0, 0, 0, 0 };
  // The non-empty macro cells of DistanceOnly's (or the packed table's) build MacroBuild, and
  // the frame's screen footprint of them.
  MacroCells Macro;
  std::uint64_t MacroBuild = 0;
  ScreenFootprint Footprint;

  std::vector<std::uint32_t> Gradients; // EncodeGradient's words, one per voxel
  bool GradientsBuilt = false;
  std::uint64_t GradientsVolume = 0;
  float GradientScale = 1;

  std::vector<float> CorrectedAlpha;
  float MaximumCorrectedAlpha = 0;
  std::vector<float> SpecularTable;
  std::vector<float> LerpPairs; // KernelFrame's alphaPairs, colourPairs and specularPairs

  // Multi-component scalars: each component's octree (Octree then holds their combined
  // classification) and each table's per-frame arrays.
  std::vector<MinMaxOctree> ComponentOctrees;
  std::vector<float> ComponentCorrectedAlpha[4];
  std::vector<float> ComponentSpecular[4];
  LightModel ComponentModels[4];
  int CastRectangle[4] = { 0, -1, 0, -1 };
  double PrepareSeconds = 0;

  ProgressFunction Progress;

  // Frame preparation steps of RayCaster::Render (each rebuilds only what changed).
  bool UpdateOctree(const VolumeView& volume, std::uint64_t volumeVersion,
    std::uint64_t transferVersion, const std::vector<float>& alphas, double rangeMin,
    double rangeMax, const RayCastSettings& settings, const detail::LeapPlan& plan,
    const ParallelFor& parallel, detail::PrepareProgress& progress, std::string& error);
  void UpdateCells(const VolumeView& volume, std::uint64_t volumeVersion,
    std::uint64_t transferVersion, const OpacityRange& opacityRange, const detail::LeapPlan& plan,
    const std::uint8_t* mask, const ParallelFor& parallel, detail::PrepareProgress& progress);
  // The same for multi-component scalars: a node or cell is empty when every component that
  // can make a sample visible is transparent in it (each judged on its own range).
  bool UpdateComponentOctree(const VolumeView& volume, std::uint64_t volumeVersion,
    std::uint64_t transferVersion, const RayCastComponents& components,
    const RayCastSettings& settings, bool classify, const ParallelFor& parallel,
    detail::PrepareProgress& progress, std::string& error);
  void UpdateComponentCells(const VolumeView& volume, std::uint64_t volumeVersion,
    std::uint64_t transferVersion, const RayCastComponents& components,
    const std::uint8_t* mask, const ParallelFor& parallel, detail::PrepareProgress& progress);
  void FillComponentFrame(const RayCastTransfer& transfer, const RayCastLighting& lighting,
    const RayCastSettings& settings, const detail::LeapPlan& plan, detail::KernelFrame& frame);
  void PackCellInfo(const CellClassification& cells, const std::vector<std::uint8_t>& distance,
    const ParallelFor& parallel);
  bool UpdateGradients(const VolumeView& volume, std::uint64_t volumeVersion, double width,
    const RayCastTransfer& transfer, const RayCastLighting& lighting,
    const RayCastSettings& settings, const ParallelFor& parallel, detail::PrepareProgress& progress);
  // The octant maps of the directions the frame's rays take (built when missing, stale ones
  // freed) into frame.octantDistance; needs frame.visible.
  void UpdateOctantMaps(detail::KernelFrame& frame, const ParallelFor& parallel);
  // The screen footprint of the frame's non-empty cells into frame.footprint (nullptr when the
  // frame's rays do not approach together or no footprint bounds them); indexToClip maps
  // index-space points to clip space.
  void UpdateFootprint(
    detail::KernelFrame& frame, const double indexToClip[4][4], const ParallelFor& parallel);
  void FillLerpPairs(const RayCastTransfer& transfer, detail::KernelFrame& frame);
  void FillKernelFrame(const VolumeView& volume, double rangeMin, double rangeMax,
    const RayCastTransfer& transfer, const RayCastLighting& lighting, const RayCastView& view,
    const RayCastSettings& settings, const detail::LeapPlan& plan, bool useGradients, double exponent,
    detail::KernelFrame& frame);
};

} // namespace accelvolume

#endif
