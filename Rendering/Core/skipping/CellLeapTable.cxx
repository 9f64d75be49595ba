// CellLeapTable: the modified Marching Cubes table of semi-transparent cell leaping (Lim, Kim &
// Shin 2009), built programmatically so that no hand-typed 256-row table can hide a typo.
//
// Rules (derivation in docs/cell-leaping.md):
// - marchingCubesCase: the class of the configuration under the 24 rotations of the cube and
//   complement (opaque <-> transparent). Reflections are not used, so the two mirror-image
//   zig-zag cases stay apart (11 and 14, as in Lorensen & Cline). Complement keeps a zig-zag's
//   handedness, so case 11 and case 14 each hold 12 configurations.
// - edges (the paper's field): set for a crossing edge (exactly one opaque corner) unless its
//   axis is "fully covered", i.e. the axis has an opaque corner on its low side (coordinate 0)
//   and one on its high side (coordinate 1): then the paper's box spans [0, 1] on that axis for
//   any values, so the paper stores -1. This includes every axis with a fully opaque edge. On
//   an axis that is not covered every stored edge has the same direction, as the paper
//   describes (take the max of the crossings for direction 0, the min for direction 1).
// - axes (our exact test): an axis is usable iff no parallel edge has both corners opaque and
//   it has at least one crossing edge. Opaque corners on both sides do not disqualify an axis:
//   the sample test asks whether every crossing edge is below the threshold at the sample's
//   coordinate, which also holds in a gap between two opposite crossings that the paper's
//   single box per axis cannot express. Usable axes are sorted by crossing count (ties x, y, z)
//   and taken while the running count stays <= TrilinearLerps; cost is that count.
// - leapCase: marchingCubesCase when an axis was taken or the configuration is 0, else -1.
#include "skipping/CellLeapTable.h"

#include <algorithm>
#include <cassert>
#include <cstddef>
#include <vector>

namespace accelvolume
{

namespace
{
constexpr int CornerCount = 8;
constexpr int EdgeCount = 12;
constexpr int EdgesPerAxis = 4;
constexpr int AxisCount = 3;
constexpr int ConfigurationCount = 256;
constexpr int AllOpaque = ConfigurationCount - 1;
// The rotation group of the cube (orientation-preserving symmetries).
constexpr std::size_t CubeRotations = 24;

// Lorensen & Cline's 15 base configurations, one representative each (bit c = corner c opaque,
// corner c at (c & 1, (c >> 1) & 1, (c >> 2) & 1)).
constexpr int BaseCaseCount = 15;
constexpr int BaseConfigurations[BaseCaseCount] = {
  0x00, //  0: nothing opaque
  0x01, //  1: one corner {0}
  0x03, //  2: one edge {0, 1}
  0x09, //  3: face diagonal {0, 3}
  0x81, //  4: body diagonal {0, 7}
  0x07, //  5: three corners of a face, an L {0, 1, 2}
  0x83, //  6: an edge and a corner adjacent to neither end {0, 1} + {7}
  0x16, //  7: three corners, pairwise on face diagonals {1, 2, 4}
  0x0F, //  8: a whole face {0, 1, 2, 3}
  0x17, //  9: a corner and its three neighbours {0, 1, 2, 4}
  0xC3, // 10: two opposite parallel edges {0, 1} + {6, 7}
  0x8B, // 11: zig-zag path 0 -> 1 -> 3 -> 7 (+x, +y, +z: right-handed)
  0x87, // 12: an L and an isolated corner {0, 1, 2} + {7}
  0x69, // 13: four corners, pairwise on face diagonals {0, 3, 5, 6}
  0x47, // 14: mirror image of 11 (x -> 1 - x): path 1 -> 0 -> 2 -> 6
};

using CornerPermutation = std::array<int, CornerCount>;

// The corners of edge e in [0, 12): what CellEdgeCorners returns, as an internal function so
// the table build never calls through the exported symbol.
constexpr void EdgeCorners(int edge, int& lowCorner, int& highCorner)
{
  const int axis = edge / EdgesPerAxis;
  const int position = edge % EdgesPerAxis;
  // The two other axes in increasing order take the position's bits (first axis = bit 0).
  const int first = axis == 0 ? 1 : 0;
  const int second = axis == 2 ? 1 : 2;
  lowCorner = ((position & 1) << first) | (((position >> 1) & 1) << second);
  highCorner = lowCorner | (1 << axis);
}

int CornerAt(const int coordinates[AxisCount])
{
  return coordinates[0] | (coordinates[1] << 1) | (coordinates[2] << 2);
}

// A quarter turn about the axis through the cell centre: (u, v) -> (1 - v, u) in the plane of
// the two other axes.
CornerPermutation QuarterTurn(int axis)
{
  const int u = (axis + 1) % AxisCount;
  const int v = (axis + 2) % AxisCount;
  CornerPermutation result{};
  for (int c = 0; c < CornerCount; ++c)
  {
    int from[AxisCount] = { c & 1, (c >> 1) & 1, (c >> 2) & 1 };
    int to[AxisCount] = { from[0], from[1], from[2] };
    to[u] = 1 - from[v];
    to[v] = from[u];
    result[c] = CornerAt(to);
  }
  return result;
}

// Closes {identity} under quarter turns about x and y (which generate all rotations).
std::vector<CornerPermutation> RotationGroup()
{
  CornerPermutation identity{};
  for (int c = 0; c < CornerCount; ++c)
  {
    identity[c] = c;
  }
  const CornerPermutation generators[2] = { QuarterTurn(0), QuarterTurn(1) };
  std::vector<CornerPermutation> group = { identity };
  for (std::size_t i = 0; i < group.size(); ++i)
  {
    for (const CornerPermutation& generator : generators)
    {
      CornerPermutation composed{};
      for (int c = 0; c < CornerCount; ++c)
      {
        composed[c] = generator[group[i][c]];
      }
      if (std::find(group.begin(), group.end(), composed) == group.end())
      {
        group.push_back(composed);
      }
    }
  }
  return group;
}

int Permute(const CornerPermutation& permutation, int configuration)
{
  int result = 0;
  for (int c = 0; c < CornerCount; ++c)
  {
    if (configuration & (1 << c))
    {
      result |= 1 << permutation[c];
    }
  }
  return result;
}

// The smallest configuration reachable by a rotation, with or without complement.
int Canonical(const std::vector<CornerPermutation>& rotations, int configuration)
{
  int best = ConfigurationCount;
  for (const CornerPermutation& rotation : rotations)
  {
    best = std::min(
      { best, Permute(rotation, configuration), Permute(rotation, AllOpaque & ~configuration) });
  }
  return best;
}

CellLeapCase BuildCase(int configuration, int marchingCubesCase)
{
  CellLeapCase result;
  result.marchingCubesCase = static_cast<std::int8_t>(marchingCubesCase);
  const auto opaque = [configuration](int corner) { return ((configuration >> corner) & 1) != 0; };

  CellLeapAxis candidates[AxisCount];
  bool usable[AxisCount] = { false, false, false };
  for (int axis = 0; axis < AxisCount; ++axis)
  {
    bool lowSideOpaque = false, highSideOpaque = false, fullyOpaqueEdge = false;
    for (int i = 0; i < EdgesPerAxis; ++i)
    {
      int low, high;
      EdgeCorners(axis * EdgesPerAxis + i, low, high);
      lowSideOpaque = lowSideOpaque || opaque(low);
      highSideOpaque = highSideOpaque || opaque(high);
      fullyOpaqueEdge = fullyOpaqueEdge || (opaque(low) && opaque(high));
    }
    CellLeapAxis& candidate = candidates[axis];
    candidate.axis = static_cast<std::uint8_t>(axis);
    for (int i = 0; i < EdgesPerAxis; ++i)
    {
      const int edge = axis * EdgesPerAxis + i;
      int low, high;
      EdgeCorners(edge, low, high);
      if (opaque(low) == opaque(high))
      {
        continue; // no crossing: always below (both transparent) or the axis is unusable
      }
      candidate.lowCorner[candidate.count] = static_cast<std::uint8_t>(low);
      candidate.highCorner[candidate.count] = static_cast<std::uint8_t>(high);
      ++candidate.count;
      if (!(lowSideOpaque && highSideOpaque))
      {
        CellLeapEdge& field = result.edges[edge];
        field.lowCorner = static_cast<std::int8_t>(low);
        field.highCorner = static_cast<std::int8_t>(high);
        field.direction = opaque(low) ? 0 : 1;
      }
    }
    // A fully opaque edge puts an opaque point in every cross-section of this axis.
    usable[axis] = !fullyOpaqueEdge && candidate.count > 0;
  }

  int order[AxisCount] = { 0, 1, 2 };
  std::stable_sort(order, order + AxisCount,
    [&candidates](int a, int b) { return candidates[a].count < candidates[b].count; });
  int cost = 0;
  for (int axis : order)
  {
    if (!usable[axis])
    {
      continue;
    }
    if (cost + candidates[axis].count > TrilinearLerps)
    {
      break; // later axes have at least as many crossings
    }
    cost += candidates[axis].count;
    result.axes[result.axisCount++] = candidates[axis];
  }
  result.cost = static_cast<std::uint8_t>(cost);
  // Configuration 0 needs no test at all; any other configuration needs an axis.
  const bool leapable = configuration == 0 || result.axisCount > 0;
  result.leapCase = static_cast<std::int8_t>(leapable ? marchingCubesCase : -1);
  return result;
}

std::array<CellLeapCase, ConfigurationCount> BuildTable()
{
  const std::vector<CornerPermutation> rotations = RotationGroup();
  // The unit tests also check the class sizes this grouping produces.
  assert(rotations.size() == CubeRotations);
  int caseOfCanonical[ConfigurationCount];
  std::fill(caseOfCanonical, caseOfCanonical + ConfigurationCount, -1);
  for (int c = 0; c < BaseCaseCount; ++c)
  {
    caseOfCanonical[Canonical(rotations, BaseConfigurations[c])] = c;
  }
  std::array<CellLeapCase, ConfigurationCount> table;
  for (int configuration = 0; configuration < ConfigurationCount; ++configuration)
  {
    table[configuration] =
      BuildCase(configuration, caseOfCanonical[Canonical(rotations, configuration)]);
  }
  return table;
}

}

void CellEdgeCorners(int edge, int& lowCorner, int& highCorner)
{
  if (edge < 0 || edge >= EdgeCount)
  {
    lowCorner = highCorner = -1;
    return;
  }
  EdgeCorners(edge, lowCorner, highCorner);
}

const std::array<CellLeapCase, 256>& GetCellLeapTable()
{
  // Function-local static: built once, thread-safe since C++11.
  static const std::array<CellLeapCase, ConfigurationCount> table = BuildTable();
  return table;
}

int MarchingCubesCase(int configuration)
{
  if (configuration < 0 || configuration >= ConfigurationCount)
  {
    return -1;
  }
  return GetCellLeapTable()[configuration].marchingCubesCase;
}

void CellLeapBox(const CellLeapCase& leapCase, const float values[8], float threshold,
  float lower[3], float upper[3])
{
  // Configuration 0 is the only leapable configuration without an axis: nothing is opaque.
  const bool empty = leapCase.leapCase >= 0 && leapCase.axisCount == 0;
  for (int axis = 0; axis < AxisCount; ++axis)
  {
    if (empty)
    {
      lower[axis] = 1;
      upper[axis] = 0;
      continue;
    }
    double low = 1, high = 0;
    bool stored = false;
    for (int i = 0; i < EdgesPerAxis; ++i)
    {
      const CellLeapEdge& field = leapCase.edges[axis * EdgesPerAxis + i];
      if (field.lowCorner < 0)
      {
        continue;
      }
      stored = true;
      // Double keeps the crossing exact to float rounding even when the two values are close.
      const double v0 = values[field.lowCorner];
      const double v1 = values[field.highCorner];
      const double crossing = std::clamp((threshold - v0) / (v1 - v0), 0.0, 1.0);
      if (field.direction == 0)
      {
        low = 0;
        high = std::max(high, crossing);
      }
      else
      {
        low = std::min(low, crossing);
        high = 1;
      }
    }
    if (!stored)
    {
      // Every other configuration has an opaque corner on each axis, so an axis without a
      // stored edge is one the paper marks as fully covered.
      low = 0;
      high = 1;
    }
    lower[axis] = static_cast<float>(low);
    upper[axis] = static_cast<float>(high);
  }
}

}
