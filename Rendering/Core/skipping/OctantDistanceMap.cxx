// OctantDistanceMap: the sweep. Coordinates are mirrored so that the octant's direction is +x,
// +y, +z; plane w depends on plane w + 1 and, within a plane, row v on row v + 1 and cell u on
// cell u + 1, so the sweep runs from the far corner back with two padded planes of state (the
// padding holds the cap: outside the grid is empty).
#include "skipping/OctantDistanceMap.h"

#include "skipping/CellBricks.h"
#include "skipping/DistanceMap.h"

#include <algorithm>
#include <cstddef>

namespace accelvolume
{

namespace
{
constexpr std::uint8_t Cap = static_cast<std::uint8_t>(DistanceMapSaturation);

inline std::uint8_t Min(std::uint8_t a, std::uint8_t b)
{
  return a < b ? a : b;
}

template <typename Entry>
void ComputeOctantMap(
  const int cellDims[3], const Entry* distance, int octant, std::vector<std::uint8_t>& octantMap)
{
  const CellBricks bricks(cellDims);
  const int nx = cellDims[0], ny = cellDims[1], nz = cellDims[2];
  octantMap.assign(bricks.Entries(), std::uint8_t(0));
  if (nx < 1 || ny < 1 || nz < 1)
  {
    return;
  }
  const bool flip[3] = { (octant & 1) != 0, (octant & 2) != 0, (octant & 4) != 0 };
  // Plane state in mirrored coordinates, rows of nx + 1 (the last entry is padding) and one
  // padding row at ny.
  const std::size_t row = static_cast<std::size_t>(nx) + 1;
  const std::size_t plane = row * (static_cast<std::size_t>(ny) + 1);
  std::vector<std::uint8_t> next(plane, Cap), current(plane, Cap);
  std::vector<std::uint8_t> around(static_cast<std::size_t>(nx) + 1, Cap);
  std::vector<std::size_t> columns(static_cast<std::size_t>(nx));
  std::uint8_t* const map = octantMap.data(); // not reloaded after every store
  for (int w = nz - 1; w >= 0; --w)
  {
    const int z = flip[2] ? nz - 1 - w : w;
    for (int v = ny - 1; v >= 0; --v)
    {
      const int y = flip[1] ? ny - 1 - v : v;
      std::uint8_t* out = current.data() + static_cast<std::size_t>(v) * row;
      const std::uint8_t* above = out + row; // row v + 1 of this plane
      const std::uint8_t* behind = next.data() + static_cast<std::size_t>(v) * row;
      const std::uint8_t* behindAbove = behind + row;
      // The six neighbours off this row, independent of the row's own sweep (vectorizes).
      for (int u = 0; u < nx; ++u)
      {
        around[u] = Min(Min(Min(above[u], above[u + 1]), Min(behind[u], behind[u + 1])),
          Min(behindAbove[u], behindAbove[u + 1]));
      }
      for (int u = 0; u < nx; ++u)
      {
        columns[u] = bricks.Index(flip[0] ? nx - 1 - u : u, y, z);
      }
      std::uint8_t last = Cap; // cell u + 1 of this row
      for (int u = nx - 1; u >= 0; --u)
      {
        const std::size_t at = columns[u];
        const std::uint8_t smallest = Min(around[u], last);
        const std::uint8_t side = (distance[at] & 0xff) == 0
          ? 0
          : static_cast<std::uint8_t>(smallest + (smallest != Cap ? 1 : 0));
        out[u] = side;
        map[at] = side;
        last = side;
      }
    }
    next.swap(current);
  }
}

} // namespace

void ComputeOctantDistanceMap(const int cellDims[3], const std::uint8_t* distance, int octant,
  std::vector<std::uint8_t>& octantMap)
{
  ComputeOctantMap(cellDims, distance, octant, octantMap);
}

void ComputeOctantDistanceMap(const int cellDims[3], const std::uint16_t* distance, int octant,
  std::vector<std::uint8_t>& octantMap)
{
  ComputeOctantMap(cellDims, distance, octant, octantMap);
}
}
