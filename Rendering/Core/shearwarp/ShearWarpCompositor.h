// ShearWarpCompositor: composites the sheared slices into one intermediate-image scanline,
// front to back (plain C++, no VTK; internal to ShearWarpEngine, exposed for tests).
//
// Intermediate pixel (u, v) resamples slice k bilinearly at (u - offset[0], v - offset[1]); the
// two voxel scanlines it needs are walked by their runs, and the pixels they cover are walked
// with skip links that jump over saturated (opaque) pixels, so neither transparent voxels nor
// opaque pixels are touched. Each scanline depends only on the volume, the view and the tables,
// never on which worker composites it.
#ifndef accelvolume_ShearWarpCompositor_h
#define accelvolume_ShearWarpCompositor_h

#include "common/Lighting.h"
#include "common/ParallelFor.h"
#include "shearwarp/RunLengthVolume.h"
#include "shearwarp/ShearWarpFactorization.h"

#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

namespace accelvolume
{

// Per-frame tables for composite scanlines.
struct CompositeTables
{
  // Opacity for the frame's slice-to-slice ray length, by ShadedVoxel::opacity (OpacityLevels + 1
  // entries).
  std::vector<float> opacity;
  bool shade = false;
  bool phong = false; // true: Phong per voxel from the decoded normal; false: shading table
  // Shading table, NormalCodes + 1 rows (the last for NoNormal) of shadingStride floats: the
  // factor on the voxel colour (ambient + diffuse) and the specular term added, per channel
  // (stride 6: r, g, b factors then r, g, b terms) or, with white lights, once (stride 2).
  std::vector<float> shading;
  int shadingStride = 6;
  // Per-voxel Phong: eye-space lights, the index-gradient -> eye normal matrix (row-major) and
  // the material, as RayCastLighting.
  LightModel lighting;
  float lightingPoint[3] = { 0, 0, 0 }; // eye space: where positional lights are evaluated
  float normalMatrix[3][3] = { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } };
  // Unshaded, with an encoding that has a palette (AssignPalette): each entry's premultiplied
  // RGBA for this frame (4 floats per entry, the values its voxels would be converted to).
  // Empty: every voxel's colour is converted as it is read.
  std::vector<float> paletteColours;
  bool earlyTermination = true;
  float terminationThreshold = 0.99f;
  // Termination by skip links over saturated pixels; false: none is ever skipped (the baseline).
  bool terminationLinks = true;
};

// VTK's light model (common/Lighting.h) for an index-space gradient direction g (eye space
// through normalMatrix; parallel view, so the view vector is +z; positional lights evaluated at
// lightingPoint): the factor on the voxel colour and the specular term, per channel.
void PhongTerms(const CompositeTables& tables, const float g[3], float factor[3], float specular[3]);

// Lacroute's shading table over the quantized normals (tables.shading and shadingStride), rows
// built in parallel (the same values for any thread count).
void BuildShadingTable(CompositeTables& tables, const ParallelFor& parallel);

// tables.paletteColours for the palette of an unshaded encoding (tables.opacity set; cleared
// when tables.shade or the palette is empty), in parallel.
void BuildPaletteColours(
  const std::vector<ShadedVoxel>& palette, CompositeTables& tables, const ParallelFor& parallel);

struct ScanlineCounters
{
  std::uint64_t voxels = 0;         // voxel values read (a voxel serves up to four pixels)
  std::uint64_t samples = 0;        // intermediate pixels composited (per slice)
  std::uint64_t terminatedPixelVisits = 0; // pixel visits skipped by termination (skip links)
  void Add(const ScanlineCounters& other)
  {
    this->voxels += other.voxels;
    this->samples += other.samples;
    this->terminatedPixelVisits += other.terminatedPixelVisits;
  }
};

// The cells of a voxel scanline's buffer shaded in this slice. A buffer serves two intermediate
// scanlines in turn, each asking for cells in ascending order: the first one's shaded ranges are
// kept (ascending, disjoint), so that the second shades only the cells between them.
struct ShadedCells
{
  // Cells [first, last) of voxels, by the first user: the first `count` entries (room for every
  // range a scanline can hold is made once per band).
  std::vector<std::pair<int, int>> ranges;
  std::size_t count = 0;
  std::size_t cursor = 0; // a later user's position in ranges
  int requested = 0;      // the current user's cells so far end here
  int users = 0;          // intermediate scanlines that used the buffer
};

// Scratch space per worker: skip links per scanline, open pixels per scanline, and the two
// voxel scanlines of the current slice (voxel scanline j in buffer j & 1), shaded on first use.
struct ScanlineWorkspace
{
  std::unique_ptr<std::int32_t[]> next; // nextSize links
  std::size_t nextSize = 0;
  std::vector<std::int32_t> open;
  std::vector<float> rows[2];
  int rowIndex[2] = { 0, 0 }; // voxel scanline each buffer holds (set by the band loop)
  ShadedCells shaded[2];
};

// Composites every slice, front to back and slice by slice (the encoding is streamed in
// order), into intermediate scanlines [v0, v1): rgba holds (v1 - v0) scanlines of
// intermediateSize[0] premultiplied pixels (4 floats each), transparent on entry. work, when
// not null, receives a relative cost per scanline (clock ticks spent on it, over all slices),
// which turns the band's measured time into per-scanline times.
void CompositeBand(const RunLengthVolume<ShadedVoxel>& encoded,
  const ShearWarpFactorization& factorization, const CompositeTables& tables, int v0, int v1,
  float* rgba, ScanlineWorkspace& workspace, ScanlineCounters& counters, double* work);

// MIP (maximum) or MinIP over scanlines [v0, v1): value holds (v1 - v0) scanlines of
// intermediateSize[0] floats, the extreme quantized scalar of the samples whose weighted
// corners are all stored (-inf for MIP / +inf for MinIP on entry: no sample). A pixel that
// reaches `saturation` (the volume's extreme) can change no further and is skipped.
void ExtremeBand(const RunLengthVolume<ScalarVoxel>& encoded,
  const ShearWarpFactorization& factorization, bool maximum, float saturation, bool terminationLinks,
  int v0, int v1, float* value, ScanlineWorkspace& workspace, ScanlineCounters& counters,
  double* work);

// One scanline of the above (tests).
inline void CompositeScanline(const RunLengthVolume<ShadedVoxel>& encoded,
  const ShearWarpFactorization& factorization, const CompositeTables& tables, int v, float* rgba,
  ScanlineWorkspace& workspace, ScanlineCounters& counters)
{
  CompositeBand(encoded, factorization, tables, v, v + 1, rgba, workspace, counters, nullptr);
}
inline void ExtremeScanline(const RunLengthVolume<ScalarVoxel>& encoded,
  const ShearWarpFactorization& factorization, bool maximum, float saturation, bool terminationLinks,
  int v, float* value, ScanlineWorkspace& workspace, ScanlineCounters& counters)
{
  ExtremeBand(encoded, factorization, maximum, saturation, terminationLinks, v, v + 1, value, workspace,
    counters, nullptr);
}

}

#endif
