// RayCastKernel: the per-tile inner loops of the CPU ray caster (internal to RayCastEngine).
#ifndef accelvolume_RayCastKernel_h
#define accelvolume_RayCastKernel_h

#include "skipping/CellClassification.h"
#include "raycast/RayCastEngine.h"

#include <cstdint>
#include <vector>

namespace accelvolume
{
namespace detail
{

// A multi-component classification table (RayCastComponentTable), prepared per frame.
struct ComponentTableFrame
{
  const float* rgba = nullptr;           // 4 * tableSize
  const float* correctedAlpha = nullptr; // tableSize, opacity corrected to the sample distance
  int tableSize = 0;
  // Table positions of raw values: u = value * scale + bias (colour, then opacity component).
  float colourScale = 0, colourBias = 0;
  float opacityScale = 0, opacityBias = 0;
  const float* gradientOpacity = nullptr; // over normalised gradient magnitudes [0, 1/4]
  int gradientOpacitySize = 0;
  float opacityExponent = 1;
  float weight = 1;
  const LightModel* model = nullptr; // the frame's lights with this table's coefficients
  const float* specularTable = nullptr;
};

// Everything a tile reads, prepared once per frame by RayCaster::Render.
struct KernelFrame
{
  // RayCastSettings' mask: binary (hides samples) or a label map (composite).
  const std::uint8_t* mask = nullptr;
  bool labelMap = false;
  bool maskNeighbours = false; // RayCastSettings::maskNeighbours
  const float* labelTables = nullptr;
  float labelBlend = 1.0f;
  // Multi-component scalars (components > 1, interleaved): RayCastComponents' tables; the
  // single-component tables below are then unused.
  int components = 1;
  bool independent = true;
  int componentTables = 0;
  ComponentTableFrame tables[4];
  // Per data component: its normalised value s = value * scale + bias (raysum / average).
  float componentScale[4] = { 1, 1, 1, 1 }, componentBias[4] = { 0, 0, 0, 0 };
  float colourScale[3] = { 1, 1, 1 }, colourBias[3] = { 0, 0, 0 }; // dependent RGBA
  float componentAxisScale[3] = { 1, 1, 1 };                       // gradientAxisScale
  float componentNormalMatrix[3][3] = {}; // index gradient (normalised units) -> eye space
  // MIP / MinIP with octree leaping: each component's min-max octree (octree is the first).
  const MinMaxOctree* componentOctrees[4] = { nullptr, nullptr, nullptr, nullptr };
  // ISOSURFACE_BLEND: the component whose values cross the iso-values (independent: the one of
  // the largest weight, the first of equals, as VTK; dependent: component 0).
  int isoComponent = 0;

  VolumeView volume;
  // Table position of a raw value: u = value * tableScale + tableBias, in [0, tableSize - 1].
  float tableScale = 1, tableBias = 0;
  int tableSize = 0;
  const float* rgba = nullptr;           // 4 * tableSize, colour + table opacity
  const float* correctedAlpha = nullptr; // tableSize, opacity corrected to the sample distance
  float maximumCorrectedAlpha = 0;       // of correctedAlpha
  bool raysThroughEye = false;           // every ray passes through the eye (RaysPassThroughEye)
  bool eyeLightsAtEntry = false;         // lights at the eye fixed per ray at its entry point
  // Normalised scalar: s = value * normalScale + normalBias.
  float normalScale = 1, normalBias = 0;
  float rangeWidth = 1; // data units per normalised unit
  const float* gradientOpacity = nullptr;
  int gradientOpacitySize = 0;
  float gradientOpacityMaximum = 1;
  // Per index axis: turns Gradient()'s index-space difference into RayCastTransfer's
  // gradient-opacity magnitude (its gradientAxisScale times the gradients' units).
  float gradientAxisScale[3] = { 1, 1, 1 };
  float opacityExponent = 1; // sample distance / opacity unit distance
  const RayCastLighting* lighting = nullptr;
  // Optional per-voxel central differences (x, y, z interleaved, raw units times
  // 1 / gradientScale), interpolated trilinearly instead of six extra samples per shaded one.
  const std::uint32_t* gradients = nullptr; // EncodeGradient's words
  float gradientScale = 1;
  // Shading, prepared once per frame: the gradient-to-eye matrix in float with the gradient
  // scale folded in, and the specular term pow(x, power) tabulated over x in [0, 1].
  float normalMatrix[3][3] = {};
  const float* specularTable = nullptr;
  int specularTableSize = 0;
  // The same tables as (value, next value - value) pairs per entry, for the ray packets: one
  // 64-bit load gives what Lerp(table[i], table[i + 1], t) = value + t * difference reads, with
  // the same bits (alphaPairs: correctedAlpha; colourPairs: rgba's r, g, b).
  const float* alphaPairs = nullptr;
  const float* colourPairs[3] = { nullptr, nullptr, nullptr };
  const float* specularPairs = nullptr;
  const RayCastView* view = nullptr;
  const RayCastSettings* settings = nullptr;
  const MinMaxOctree* octree = nullptr; // built; classified for composite / additive
  // Per cell: distance map (low byte) and Marching Cubes configuration (high byte).
  const std::uint16_t* cellInfo = nullptr;    // with cell leaping
  const std::uint8_t* distanceOnly = nullptr; // distance map alone, without cell leaping
  // With distance-map leaping: per ray octant (DirectionOctant) its map where the frame built it
  // (OctantDistanceMap.h: longer leaps), else nullptr and the rays read the chessboard map.
  const std::uint8_t* octantDistance[8] = {};
  float leapThreshold = 0; // cell-leap threshold (raw value, a rounding margin below the true one)
  bool useOctree = false, useDistance = false, useCellLeap = false;
  // With octree or distance-map leaping: the index-space box of everything that may be
  // opaque; samples outside it are leaped without visiting them. Empty box: nothing visible.
  bool useOpaqueBox = false;
  Box opaqueBox;
  // Pixels [visible[0], visible[1]] x [visible[2], visible[3]] (inclusive) hold every ray that
  // can meet what is drawn (the projected box); the others stay empty without a ray.
  int visible[4] = { 0, -1, 0, -1 };
  // With the grouped approach (composite, distance-map leaping): per block of pixels
  // (ScreenFootprint.h, footprintBlocks per row) 1 when its rays may meet a non-empty cell; the
  // others stay empty without a ray. nullptr: every pixel of the rectangle casts its ray.
  const std::uint8_t* footprint = nullptr;
  int footprintBlocks = 0;
};

// Whether composite rays approach their first non-empty cell a few at a time
// (RayCastKernelApproach.inl; the screen footprint serves those rays only).
inline bool RaysApproachTogether(const KernelFrame& frame)
{
  const RayCastSettings& settings = *frame.settings;
  return settings.approachTogether && settings.blend == Blend::Composite && frame.components == 1 &&
    frame.useDistance && !frame.useOctree;
}

// Casts the rays of pixels [x0, x1) x [y0, y1) into rgba (the whole image's buffer).
void CastTile(
  const KernelFrame& frame, int x0, int y0, int x1, int y1, float* rgba, RayCastCounters& counters);

// CastTile for volumes of scalar type T: instantiated for each scalar type of VolumeView by
// RayCastKernel8Bit.cxx ... RayCastKernel64Bit.cxx (RayCastKernelTile.inl).
template <typename T>
void CastTileOf(
  const KernelFrame& frame, int x0, int y0, int x1, int y1, float* rgba, RayCastCounters& counters);

}
}

#endif
