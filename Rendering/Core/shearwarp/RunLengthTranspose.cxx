// An encoding for another principal axis built from an existing one: the stored voxels re-sorted,
// never classified again, with memory for the two encodings only.
#include "shearwarp/RunLengthVolume.h"

#include <algorithm>
#include <limits>
#include <vector>

namespace accelvolume
{
namespace
{

// Walks every stored voxel of `from` in its storage order (slice k, scanline j, position i),
// calling visit(row, position, element) with the voxel's scanline and position in the layout of
// `to` (whose axis and slice dimensions are set) and its element of `elements` (from's voxels or
// palette indices). In that order each target scanline receives its voxels by increasing
// position: its position runs along one of from's j or k axes, and the voxels of one target
// scanline share from's other two coordinates.
template <typename Voxel, typename Element, typename Visit>
void ForEachStoredVoxel(const RunLengthVolume<Voxel>& from, const Element* elements,
  const RunLengthVolume<Voxel>& to, Visit visit)
{
  const int fromAxes[3] = { (from.axis + 1) % 3, (from.axis + 2) % 3, from.axis };
  const int toAxes[3] = { (to.axis + 1) % 3, (to.axis + 2) % 3, to.axis };
  const std::size_t toRows = static_cast<std::size_t>(to.sliceDims[1]);
  for (int k = 0; k < from.sliceDims[2]; ++k)
  {
    for (int j = 0; j < from.sliceDims[1]; ++j)
    {
      for (const VoxelRun* run = from.RunsBegin(j, k); run != from.RunsEnd(j, k); ++run)
      {
        const Element* element = elements + run->offset;
        for (int i = run->begin; i < run->end; ++i, ++element)
        {
          int p[3];
          p[fromAxes[0]] = i;
          p[fromAxes[1]] = j;
          p[fromAxes[2]] = k;
          const std::size_t row = static_cast<std::size_t>(p[toAxes[1]]) +
            toRows * static_cast<std::size_t>(p[toAxes[2]]);
          visit(row, p[toAxes[0]], *element);
        }
      }
    }
  }
}

// The runs of `to` and its copy of `elements` (from's voxels or palette indices) in its layout.
template <typename Voxel, typename Element>
bool TransposeElements(const RunLengthVolume<Voxel>& from, const Element* elements,
  RunLengthVolume<Voxel>& to, std::vector<Element>& out, std::string& error)
{
  const std::size_t rows = static_cast<std::size_t>(to.sliceDims[1]) * to.sliceDims[2];
  // First pass: runs and voxels per target scanline (a run starts wherever a voxel does not
  // follow the scanline's last one), so that both arrays are allocated once, at their size.
  std::vector<std::int32_t> last(rows, -2);
  std::vector<std::uint32_t> runCount(rows, 0);
  std::vector<std::uint32_t> nextVoxel(rows, 0); // voxels per scanline, then where the next goes
  std::size_t voxelCount = 0;
  ForEachStoredVoxel(from, elements, to,
    [&](std::size_t row, int position, const Element&)
    {
      runCount[row] += last[row] != position - 1 ? 1 : 0;
      last[row] = position;
      ++nextVoxel[row];
      ++voxelCount;
    });
  to.rowStart.resize(rows + 1);
  to.rowStart[0] = 0;
  std::size_t runTotal = 0;
  for (std::size_t r = 0; r < rows; ++r)
  {
    runTotal += runCount[r];
    if (runTotal > std::numeric_limits<std::uint32_t>::max())
    {
      break;
    }
    to.rowStart[r + 1] = static_cast<std::uint32_t>(runTotal);
  }
  if (runTotal > std::numeric_limits<std::uint32_t>::max() ||
    voxelCount > std::numeric_limits<std::uint32_t>::max())
  {
    to.Clear();
    error = "run-length encoding: more than 2^32 - 1 stored voxels or runs (volume too large)";
    return false;
  }
  // Each scanline's voxels start where the previous scanlines' end (storage order: slice, then
  // scanline), as in an encoding built from the volume.
  std::uint32_t offset = 0;
  for (std::uint32_t& next : nextVoxel)
  {
    const std::uint32_t count = next;
    next = offset;
    offset += count;
  }
  to.runs.resize(runTotal);
  out.resize(voxelCount);
  std::vector<std::uint32_t> nextRun(to.rowStart.begin(), to.rowStart.end() - 1);
  std::fill(last.begin(), last.end(), -2);
  ForEachStoredVoxel(from, elements, to,
    [&](std::size_t row, int position, const Element& element)
    {
      if (last[row] != position - 1)
      {
        VoxelRun& run = to.runs[nextRun[row]++];
        run.begin = static_cast<std::uint16_t>(position);
        run.offset = nextVoxel[row];
      }
      to.runs[nextRun[row] - 1].end = static_cast<std::uint16_t>(position + 1);
      out[nextVoxel[row]++] = element;
      last[row] = position;
    });
  return true;
}

}

template <typename Voxel>
bool TransposeEncoding(
  const RunLengthVolume<Voxel>& from, int axis, RunLengthVolume<Voxel>& to, std::string& error)
{
  if (from.axis < 0 || axis < 0 || axis > 2 || axis == from.axis)
  {
    error = "run-length transpose: needs an encoding and another axis (0, 1 or 2)";
    return false;
  }
  to.Clear();
  int dims[3];
  for (int a = 0; a < 3; ++a)
  {
    dims[(from.axis + 1 + a) % 3] = from.sliceDims[a];
  }
  to.axis = axis;
  to.dense = from.dense;
  to.palette = from.palette; // the voxels keep their indices
  to.sliceDims[0] = dims[(axis + 1) % 3];
  to.sliceDims[1] = dims[(axis + 2) % 3];
  to.sliceDims[2] = dims[axis];
  return from.Indexed()
    ? TransposeElements(from, from.paletteIndices.data(), to, to.paletteIndices, error)
    : TransposeElements(from, from.voxels.data(), to, to.voxels, error);
}

template bool TransposeEncoding(
  const RunLengthVolume<ShadedVoxel>&, int, RunLengthVolume<ShadedVoxel>&, std::string&);

}
