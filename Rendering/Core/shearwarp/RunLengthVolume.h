// RunLengthVolume: a volume classified for one principal viewing axis and stored as runs of
// non-transparent voxels per scanline (Lacroute's run-length encoding; plain C++, no VTK).
//
// For axis k (i = (k + 1) % 3, j = (k + 2) % 3) scanline (j, k) runs along i. Each scanline keeps
// the runs of voxels that can contribute [begin, end) with the offset of their first voxel in
// one packed voxel array; transparent voxels are not stored at all. Encoding is parallel over
// slices and identical for any thread count. A dense encoding (one run covering every scanline;
// for MIP / MinIP, runs broken only at NaN voxels) serves as the "no run-length encoding"
// baseline with the same compositing code.
#ifndef accelvolume_RunLengthVolume_h
#define accelvolume_RunLengthVolume_h

#include "common/ParallelFor.h"
#include "common/VolumeView.h"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace accelvolume
{

// Opacity is quantized to 0..OpacityLevels (12 bits): the per-frame correction table then has
// 4096 entries and stays in the L1 cache, where 16 bits cost a cache miss per voxel.
inline constexpr int OpacityLevels = 4095;

// A classified voxel for compositing: opacity for a unit sample distance (0..OpacityLevels),
// quantized gradient direction (NoNormal when the gradient vanishes; in an unshaded encoding
// with a palette, the index of the voxel's palette entry) and colour (8 bits per channel).
struct ShadedVoxel
{
  std::uint16_t opacity;
  std::uint16_t normal;
  std::uint8_t colour[4]; // r, g, b, unused
};

// A voxel for MIP / MinIP: its scalar quantized to 0..65535 over the data range.
using ScalarVoxel = std::uint16_t;

// Octahedral normal code: NormalBits per coordinate, so the shading table has NormalCodes rows
// (6 bits: 1.4 degrees off on average, 3.8 at worst; 4096 rows that stay in cache; Lacroute
// used 13 bits).
inline constexpr int NormalBits = 6;
inline constexpr int NormalCodes = 1 << (2 * NormalBits);
inline constexpr std::uint16_t NoNormal = 0xFFFF;
std::uint16_t EncodeNormal(float x, float y, float z); // NoNormal for a zero vector
void DecodeNormal(std::uint16_t code, float normal[3]); // unit vector

// 8 bytes: compositing reads the runs of every scanline pair it visits, so their size is memory
// traffic (axes are limited to 65535 voxels and an encoding to 2^32 - 1 stored voxels and runs).
struct VoxelRun
{
  std::uint16_t begin, end; // voxel positions along i, end exclusive
  std::uint32_t offset;     // index of voxel `begin` in the voxel array
};
inline constexpr int MaximumRunLengthAxis = 65535;

template <typename Voxel>
struct RunLengthVolume
{
  int axis = -1;                  // principal axis k (object axis), -1 when empty
  int sliceDims[3] = { 0, 0, 0 }; // ni, nj, nk
  bool dense = false;             // one run per scanline, transparent voxels stored too
  std::vector<std::uint32_t> rowStart; // runs of scanline (j, k): [rowStart[r], rowStart[r + 1]), r = j + nj k
  std::vector<VoxelRun> runs;
  std::vector<Voxel> voxels; // the stored voxels; empty with a palette
  // Unshaded composite encodings (AssignPalette): the distinct classified voxels, each with
  // normal NoNormal. Empty: no palette.
  std::vector<Voxel> palette;
  // With a palette, the stored voxels as their palette indices (2 bytes where a voxel takes 8:
  // less memory, and less traffic for compositing and the transposes); voxel n is
  // palette[paletteIndices[n]].
  std::vector<std::uint16_t> paletteIndices;

  bool Indexed() const { return !this->palette.empty(); }
  std::size_t StoredVoxels() const
  {
    return this->Indexed() ? this->paletteIndices.size() : this->voxels.size();
  }
  // Stored voxel n (in storage order: slice, scanline, position).
  const Voxel& StoredVoxel(std::size_t n) const
  {
    return this->Indexed() ? this->palette[this->paletteIndices[n]] : this->voxels[n];
  }

  std::size_t Row(int j, int k) const { return static_cast<std::size_t>(j) + static_cast<std::size_t>(this->sliceDims[1]) * k; }
  const VoxelRun* RunsBegin(int j, int k) const { return this->runs.data() + this->rowStart[this->Row(j, k)]; }
  const VoxelRun* RunsEnd(int j, int k) const { return this->runs.data() + this->rowStart[this->Row(j, k) + 1]; }
  std::size_t Bytes() const
  {
    return this->rowStart.size() * sizeof(std::uint32_t) + this->runs.size() * sizeof(VoxelRun) +
      (this->voxels.size() + this->palette.size()) * sizeof(Voxel) +
      this->paletteIndices.size() * sizeof(std::uint16_t);
  }
  void Clear() { *this = RunLengthVolume(); }
};

// What makes a voxel contribute, and what it carries, for composite rendering.
struct CompositeClassification
{
  double rangeMin = 0, rangeMax = 1;
  // 4 N floats: colour and opacity over [rangeMin, rangeMax], interpolated linearly like
  // OpacityTable::Lookup (the ray caster's convention). N >= 2.
  std::vector<float> rgba;
  // Gradient opacity over [0, gradientOpacityMaximum] of |gradientAxisScale (*) g|, g the data
  // value's central difference per index step (RayCastTransfer's convention); empty: off.
  std::vector<float> gradientOpacity;
  double gradientOpacityMaximum = 1;
  double gradientAxisScale[3] = { 1, 1, 1 };
  bool normals = true; // quantize gradient directions (index space) for shading
};

// Classifies and encodes `volume` for principal axis `axis` (0, 1, 2). Voxels of zero opacity
// are left out (all kept when dense). NaN voxels are transparent. False with error on bad input.
bool EncodeComposite(const VolumeView& volume, const CompositeClassification& classification,
  int axis, bool dense, const ParallelFor& parallel, RunLengthVolume<ShadedVoxel>& encoded,
  std::string& error);

// For an encoding without normals (unshaded): lists its distinct classified voxels (opacity and
// colour) in `palette`, in ascending order of (opacity, colour), and replaces the stored voxels
// by their indices there (paletteIndices; `voxels` is emptied), from which compositing looks up
// one precomputed colour per voxel instead of converting it. False, and the encoding unchanged,
// when it has normals, a palette already, no voxels, or more than 65535 distinct voxels. The
// indices are stored in parallel.
bool AssignPalette(RunLengthVolume<ShadedVoxel>& encoded, const ParallelFor& parallel);

// Quantized scalar for MIP / MinIP: round(65535 (s - rangeMin) / (rangeMax - rangeMin)), clamped.
// Voxels that cannot decide a visible pixel are left out: for MIP those below `threshold`
// (quantized; no value below it is visible), for MinIP those above it; every kept voxel's
// in-slice 3x3 neighbours are kept too, so each bilinear sample that touches a kept voxel sees
// its four true corners (the image is exact). NaN voxels are never kept.
bool EncodeExtreme(const VolumeView& volume, double rangeMin, double rangeMax, bool maximum,
  std::uint16_t threshold, int axis, bool dense, const ParallelFor& parallel,
  RunLengthVolume<ScalarVoxel>& encoded, std::string& error);

// The encoding of the same classified volume for principal axis `axis` (not from.axis), from
// `from` alone: its stored voxels re-sorted into the other layout, never classified again. Equal
// to encoding the volume for that axis whenever the stored set does not depend on the axis (the
// composite encodings, dense or not; not MIP / MinIP, which keep in-slice neighbours). Holds
// only the two encodings (no copy in between). False with error on bad arguments or overflow.
template <typename Voxel>
bool TransposeEncoding(
  const RunLengthVolume<Voxel>& from, int axis, RunLengthVolume<Voxel>& to, std::string& error);

// The voxel at (i, j, k) of an encoding, or nullptr when not stored (tests and tools).
template <typename Voxel>
const Voxel* FindVoxel(const RunLengthVolume<Voxel>& encoded, int i, int j, int k)
{
  for (const VoxelRun* run = encoded.RunsBegin(j, k); run != encoded.RunsEnd(j, k); ++run)
  {
    if (static_cast<std::uint32_t>(i) >= run->begin && static_cast<std::uint32_t>(i) < run->end)
    {
      return &encoded.StoredVoxel(run->offset + (i - run->begin));
    }
  }
  return nullptr;
}

}

#endif
