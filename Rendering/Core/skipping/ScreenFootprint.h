// ScreenFootprint: which pixels' rays can meet a non-empty cell. Empty-space leaping still sets
// up every ray of the projected volume box and leaps it through to the far side, yet under an
// opaque transfer function most of those rays meet no non-empty cell at all (the rays beside a
// skull's silhouette). The non-empty cells, grouped into macro cells and projected to the
// screen, bound the pixels whose rays can meet one: a conservative mask of pixel blocks. A ray
// that crosses empty cells only adds nothing to a composite pixel (the walks leap those cells
// without a sample), so leaving the other pixels empty gives the same image.
#ifndef accelvolume_ScreenFootprint_h
#define accelvolume_ScreenFootprint_h

#include "common/Geometry.h"
#include "common/ParallelFor.h"

#include <cstdint>
#include <vector>

namespace accelvolume
{

// 4 x 4 pixel blocks.
constexpr int FootprintBlockShift = 2;

// Per macro cell (a cube of 2^shift cells per axis, row-major), 1 when one of its cells is
// non-empty.
struct MacroCells
{
  int shift = 3;
  int dims[3] = { 0, 0, 0 };
  std::vector<std::uint8_t> nonEmpty;
};

// distance: a chessboard distance map in CellBricks layout over cellDims cells (0 marks the
// non-empty cells; of 16-bit entries, the packed cell table's, the low byte). The macro cells
// are the smallest (at least 8 cells a side) of which there are at most maximumMacroCells, so
// projecting them stays a small part of a frame for any volume size.
void ComputeMacroCells(const int cellDims[3], const std::uint8_t* distance,
  const ParallelFor& parallel, MacroCells& macro, std::size_t maximumMacroCells = 32768);
void ComputeMacroCells(const int cellDims[3], const std::uint16_t* distance,
  const ParallelFor& parallel, MacroCells& macro, std::size_t maximumMacroCells = 32768);

// Pixels of a width x height image whose centres the index-space box projects over, with one
// pixel of slack each way for rounding (inclusive: [pixels[0], pixels[1]] x [pixels[2],
// pixels[3]]; an empty range when the box is off the image). indexToClip maps index-space points
// (x, y, z, 1) to clip space (NDC = xy / w; pixel i has its centre at NDC 2 (i + 0.5) / size - 1).
// False when a corner is not in front of the camera (or does not project to a finite point): the
// projection of the box is then not bounded by its corners'.
bool ProjectBox(
  const Box& box, const double indexToClip[4][4], int width, int height, int pixels[4]);
// ProjectBox with the corners projected together where the CPU has AVX-512: the same pixels.
bool ProjectBoxFast(
  const Box& box, const double indexToClip[4][4], int width, int height, int pixels[4]);

// Pixel blocks of a width x height image (blocks[0] x blocks[1], row-major): covered[b] = 1 when
// a pixel centre's ray of block b may meet a non-empty cell, i.e. the block meets the projection
// of a non-empty macro cell's index-space box (grown by one voxel, for clamped samples and
// rounding; ProjectBox). False (and no mask) when ProjectBox fails for one of them.
struct ScreenFootprint
{
  int blocks[2] = { 0, 0 };
  std::vector<std::uint8_t> covered;
};
bool ProjectFootprint(const MacroCells& macro, const int volumeDims[3],
  const double indexToClip[4][4], int width, int height, ScreenFootprint& footprint);

} // namespace accelvolume

#endif
