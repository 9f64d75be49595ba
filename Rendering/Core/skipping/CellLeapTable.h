// CellLeapTable: semi-transparent cell leaping (Lim, Kim and Shin 2009) through a modified
// Marching Cubes edge table.
//
// A cell is the cube between 8 voxels; corner c sits at (c & 1, (c >> 1) & 1, (c >> 2) & 1)
// (x fastest), and a cell's configuration is the Marching Cubes index: bit c set when corner c
// is "opaque" (value >= threshold). Edges: 0..3 run along x, 4..7 along y, 8..11 along z
// (see CellEdgeCorners). The transparent set must be {value < threshold}.
//
// Derivation (exact for trilinear interpolation, see docs/cell-leaping.md): for a fixed x the
// trilinear field is bilinear in (y, z), so its maximum over the cell's cross-section sits on
// one of the 4 x-parallel edges. Hence a sample at local x lies in the transparent part when
// the 4 x-edges all interpolate to < threshold at x. Edges with both corners transparent are
// always below; an edge with both corners opaque makes the axis useless; an edge with one
// opaque corner ("crossing edge", where Marching Cubes puts a vertex) is one lerp. The same
// holds for y and z. The bounding box of the opaque part of the cell along each usable axis
// is thus bounded by the crossings of its parallel edges: it is exactly the bounding box of
// the solid Marching Cubes encloses (triangles plus opaque corners).
#ifndef accelvolume_CellLeapTable_h
#define accelvolume_CellLeapTable_h

#include <array>
#include <cstdint>

namespace accelvolume
{

// The two corners of edge e (lower-coordinate corner first).
void CellEdgeCorners(int edge, int& lowCorner, int& highCorner);

// One axis test: the crossing edges parallel to `axis`.
struct CellLeapAxis
{
  std::uint8_t axis = 0;  // 0 x, 1 y, 2 z
  std::uint8_t count = 0; // crossing edges (1..4)
  std::uint8_t lowCorner[4] = { 0, 0, 0, 0 };
  std::uint8_t highCorner[4] = { 0, 0, 0, 0 };
};

// The paper's per-edge field: the two voxels (corners) whose interpolation gives the box
// bound and the direction flag. corner = -1 where the edge is unused.
struct CellLeapEdge
{
  std::int8_t lowCorner = -1;
  std::int8_t highCorner = -1;
  // 0: the opaque side is the low corner, the box is [0, crossing] (take the max over edges);
  // 1: the opaque side is the high corner, the box is [crossing, 1] (take the min).
  std::int8_t direction = -1;
};

struct CellLeapCase
{
  // Lorensen & Cline's case (0..14) of this configuration under rotations and complement.
  std::int8_t marchingCubesCase = -1;
  // The paper's first field: the case id when leaping is used, -1 when the sample must be
  // resampled (box covers the cell, or testing costs more than trilinear interpolation).
  std::int8_t leapCase = -1;
  // Usable axes, cheapest first, at most TrilinearLerps lerps in all. Configuration 0 (all
  // transparent) is leapable with no axis: every sample is transparent.
  std::uint8_t axisCount = 0;
  CellLeapAxis axes[3];
  std::uint8_t cost = 0; // lerps of the worst case (all axes tested)
  std::array<CellLeapEdge, 12> edges;
};

// Trilinear interpolation costs 7 lerps; a case whose test costs more is not used.
constexpr int TrilinearLerps = 7;

// The table for all 256 configurations (built once, thread-safe).
const std::array<CellLeapCase, 256>& GetCellLeapTable();

// Lorensen & Cline case (0..14) of a configuration; 11 and 14 are the two mirror images.
int MarchingCubesCase(int configuration);

// The paper's box from the edge table: per axis [lower, upper] in [0, 1] of the opaque part.
// values: the 8 corner values, threshold as in the configuration.
void CellLeapBox(const CellLeapCase& leapCase, const float values[8], float threshold,
  float lower[3], float upper[3]);

// True when the sample at local cell coordinates f (each in [0, 1]) is certainly transparent:
// on some usable axis every crossing edge interpolates to < threshold at f[axis]. Only the
// corners of the crossing edges are read (corner(c) returns corner c's value). Callers pass a
// threshold a little below the true one when rounding matters (see RayCastKernel).
template <typename CornerValue>
inline bool CellLeapSampleIsTransparent(
  const CellLeapCase& leapCase, const float f[3], float threshold, CornerValue&& corner)
{
  if (leapCase.leapCase < 0)
  {
    return false;
  }
  for (int a = 0; a < leapCase.axisCount; ++a)
  {
    const CellLeapAxis& axis = leapCase.axes[a];
    const float t = f[axis.axis];
    bool below = true;
    for (int e = 0; e < axis.count && below; ++e)
    {
      const float v0 = corner(axis.lowCorner[e]);
      const float v1 = corner(axis.highCorner[e]);
      below = v0 + t * (v1 - v0) < threshold;
    }
    if (below)
    {
      return true;
    }
  }
  return leapCase.axisCount == 0; // configuration 0
}

}

#endif
