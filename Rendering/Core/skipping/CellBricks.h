// CellBricks: per-cell arrays stored as 4x4x4 bricks of cells, one 64-byte cache line per brick
// of byte-sized entries, so that the cells a ray (and its neighbours) passes share lines instead
// of one line per row of cells.
#ifndef accelvolume_CellBricks_h
#define accelvolume_CellBricks_h

#include "common/ParallelFor.h"

#include <cstddef>
#include <vector>

namespace accelvolume
{

class CellBricks
{
public:
  static constexpr int Shift = 2; // 4 cells per brick and axis
  static constexpr int Size = 1 << Shift;

  CellBricks() = default;
  explicit CellBricks(const int cellDims[3])
  {
    for (int a = 0; a < 3; ++a)
    {
      this->Bricks[a] = (cellDims[a] + Size - 1) >> Shift;
    }
  }

  // Bricks along axis a.
  int BricksAlong(int a) const { return this->Bricks[a]; }

  // Entries the bricked array holds (bricks are padded to whole bricks).
  std::size_t Entries() const
  {
    return static_cast<std::size_t>(this->Bricks[0]) * this->Bricks[1] * this->Bricks[2] *
      (Size * Size * Size);
  }

  std::size_t Index(int x, int y, int z) const
  {
    const std::size_t brick =
      (static_cast<std::size_t>(z >> Shift) * this->Bricks[1] + static_cast<std::size_t>(y >> Shift)) *
        this->Bricks[0] +
      static_cast<std::size_t>(x >> Shift);
    return (brick << (3 * Shift)) +
      static_cast<std::size_t>((((z & (Size - 1)) << Shift) | (y & (Size - 1))) << Shift |
        (x & (Size - 1)));
  }

  // Calls visit(rowMajorIndex, brickedIndex) for every cell of a cellDims grid, z-slices in
  // parallel.
  template <typename Visit>
  void ForEachCell(const int cellDims[3], const ParallelFor& parallel, Visit&& visit) const
  {
    parallel(static_cast<std::size_t>(cellDims[2]),
      [&](std::size_t begin, std::size_t end)
      {
        for (std::size_t z = begin; z < end; ++z)
        {
          std::size_t i = z * static_cast<std::size_t>(cellDims[0]) * static_cast<std::size_t>(cellDims[1]);
          for (int y = 0; y < cellDims[1]; ++y)
          {
            for (int x = 0; x < cellDims[0]; ++x, ++i)
            {
              visit(i, this->Index(x, y, static_cast<int>(z)));
            }
          }
        }
      });
  }

  // The bricked copy of a row-major array of cellDims[0] x cellDims[1] x cellDims[2] entries
  // (padding entries are zero).
  template <typename Entry>
  void Reorder(const int cellDims[3], const std::vector<Entry>& rowMajor, std::vector<Entry>& bricked,
    const ParallelFor& parallel) const
  {
    bricked.assign(this->Entries(), Entry(0));
    Entry* out = bricked.data();
    const Entry* in = rowMajor.data();
    this->ForEachCell(cellDims, parallel,
      [out, in](std::size_t i, std::size_t brickedIndex) { out[brickedIndex] = in[i]; });
  }

private:
  int Bricks[3] = { 0, 0, 0 };
};

} // namespace accelvolume

#endif
