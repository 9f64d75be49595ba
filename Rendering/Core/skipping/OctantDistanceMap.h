// OctantDistanceMap: a distance map for the rays heading into one octant. The chessboard map
// (DistanceMap.h) bounds a leap by the empty cube centred on the ray's cell, so matter behind
// or beside the ray shortens it: a ray leaving a surface, or grazing one, leaps a cell or two
// at a time. A ray whose direction has fixed signs only ever moves into one octant, so the cube
// it may cross only has to extend that way: per octant, the side of the largest empty cube of
// cells that has the cell at its corner and extends in the octant's direction (Deakin &
// Knackstedt 2020, anisotropic chessboard distance). The ray leaps with the same formula
// (DistanceLeap), further.
#ifndef accelvolume_OctantDistanceMap_h
#define accelvolume_OctantDistanceMap_h

#include <cstdint>
#include <vector>

namespace accelvolume
{

// Bit a of an octant is set when the rays go towards decreasing coordinates along axis a (a
// zero direction component may take either sign: the cube always holds the ray's own cell).
inline int DirectionOctant(double x, double y, double z)
{
  return (x < 0 ? 1 : 0) | (y < 0 ? 2 : 0) | (z < 0 ? 4 : 0);
}

// distance: the chessboard map in CellBricks layout for cellDims cells (0 marks non-empty cells,
// the only thing read; of 16-bit entries, the packed cell table's, the low byte). Result, in the
// same layout: per cell 0 when non-empty, else min(side of the largest empty cube of cells {c + s *
// e : 0 <= e_a < side}, s the octant's signs, DistanceMapSaturation); cells outside the grid count
// as empty (rays never sample there). Exact: side(c) = 1 + min over the 7 neighbours c + s * e, e
// in {0, 1}^3 \ {0}, swept from the octant's far corner with two planes of state. Padding entries
// of the layout are left 0.
void ComputeOctantDistanceMap(const int cellDims[3], const std::uint8_t* distance, int octant,
  std::vector<std::uint8_t>& octantMap);
void ComputeOctantDistanceMap(const int cellDims[3], const std::uint16_t* distance, int octant,
  std::vector<std::uint8_t>& octantMap);
}

#endif
