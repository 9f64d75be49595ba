// Front-to-back compositing of sheared slices into one intermediate scanline, walking voxel runs
// and skip links over saturated pixels together.
#include "shearwarp/ShearWarpCompositor.h"
#include "shearwarp/ShearWarpCompositePolicies.h"

#include <algorithm>
#include <cmath>
#include <limits>

#if defined(__x86_64__) || defined(__i386__)
#include <x86intrin.h>
#endif
#include <chrono>

namespace accelvolume
{
namespace
{

// A cheap clock for per-scanline costs: the time-stamp counter where there is one (a few
// cycles a read, so every scanline of every slice can be timed), else a steady clock.
inline std::uint64_t Ticks()
{
#if defined(__x86_64__) || defined(__i386__)
  return __rdtsc();
#else
  return static_cast<std::uint64_t>(std::chrono::steady_clock::now().time_since_epoch().count());
#endif
}

// Skip links: next[u] == u for a pixel still open, else a link towards the next open pixel
// (path-compressed as it is followed); next[width] == width closes the scanline.
inline int FindOpen(std::int32_t* next, int u)
{
  int open = u;
  while (next[open] != open)
  {
    open = next[open];
  }
  while (next[u] != open)
  {
    const int link = next[u];
    next[u] = open;
    u = link;
  }
  return open;
}

// The first pixel of [u, end) that is not open (end if all are): open pixels link to
// themselves, so four links at a time are compared with their own indices.
inline int OpenStretchEnd(const std::int32_t* links, int u, int end)
{
#if defined(__SSE2__)
  __m128i index = _mm_add_epi32(_mm_set1_epi32(u), _mm_setr_epi32(0, 1, 2, 3));
  const __m128i four = _mm_set1_epi32(4);
  for (; u + 4 <= end; u += 4)
  {
    const __m128i same = _mm_cmpeq_epi32(
      _mm_loadu_si128(reinterpret_cast<const __m128i*>(links + u)), index);
    const int open = _mm_movemask_ps(_mm_castsi128_ps(same));
    if (open != 0xF)
    {
      return u + __builtin_ctz(~open & 0xF);
    }
    index = _mm_add_epi32(index, four);
  }
#endif
  while (u < end && links[u] == u)
  {
    ++u;
  }
  return u;
}

}

void BuildPaletteColours(
  const std::vector<ShadedVoxel>& palette, CompositeTables& tables, const ParallelFor& parallel)
{
  tables.paletteColours.clear();
  if (tables.shade || palette.empty())
  {
    return;
  }
  std::vector<float> colours(4 * palette.size());
  // Converted by the same code as a voxel without a palette, so the same values.
  const compositing::VoxelShader shader(tables);
  parallel(palette.size(),
    [&](std::size_t begin, std::size_t end)
    { shader(palette.data() + begin, static_cast<int>(end - begin), colours.data() + 4 * begin); });
  tables.paletteColours = std::move(colours);
}

namespace
{
using compositing::CompositePolicy;
using compositing::ExtremePolicy;

// The band loop shared by every blend: slices front to back (the encoding streams in order);
// in each, the scanlines of the band, each resampling two voxel scanlines shaded once into
// dense buffers (padded by one cell on each side), walking the pixels their runs cover with
// skip links over saturated pixels. Its steps below are inline templates over the policy, so
// that each blend's loop compiles as one; each copies what it reads of the band into locals.
// Marks a row buffer that holds no voxel scanline of the current slice (-1 is a real row: the
// empty one above the slice).
constexpr int NoRow = std::numeric_limits<int>::min();

// One band's inputs and the scratch space it works in.
template <typename Policy>
struct BandContext
{
  const RunLengthVolume<typename Policy::Voxel>& encoded;
  const ShearWarpFactorization& f;
  const Policy& policy;
  bool skip;
  int v0;
  int v1;
  ScanlineWorkspace& ws;
  ScanlineCounters& counters;
};

// Where slice k lands in the intermediate image, and its four resampling weights.
struct SlicePlacement
{
  int k;
  int shiftI;
  int shiftJ;
  float w[4];
};

inline SlicePlacement PlaceSlice(const ShearWarpFactorization& f, int s)
{
  SlicePlacement p;
  p.k = f.firstSlice + s * f.sliceStep;
  double offset[2];
  f.SliceOffset(p.k, offset);
  const double floorI = std::floor(offset[0]);
  const double floorJ = std::floor(offset[1]);
  p.shiftI = static_cast<int>(floorI);
  p.shiftJ = static_cast<int>(floorJ);
  const float aI = static_cast<float>(offset[0] - floorI);
  const float aJ = static_cast<float>(offset[1] - floorJ);
  // Corners (j0, i0), (j0, i0 + 1), (j0 + 1, i0), (j0 + 1, i0 + 1) of pixel u: i0 = u - shiftI - 1.
  p.w[0] = aJ * aI;
  p.w[1] = aJ * (1.0f - aI);
  p.w[2] = (1.0f - aJ) * aI;
  p.w[3] = (1.0f - aJ) * (1.0f - aI);
  return p;
}

// Every pixel of the band open, the row buffers empty, the work times zero.
template <typename Policy>
inline void ResetBandWorkspace(const BandContext<Policy>& c, double* work)
{
  constexpr int C = Policy::Channels;
  const int width = c.f.intermediateSize[0];
  const int ni = c.f.sliceDims[0];
  const int rows = c.v1 - c.v0;
  ScanlineWorkspace& ws = c.ws;
  const std::size_t stride = static_cast<std::size_t>(width) + 1;
  // Left uninitialised when made: the loop below writes every link (a vector would zero them
  // first, for every band of every frame).
  if (ws.nextSize < stride * rows)
  {
    ws.next.reset(new std::int32_t[stride * rows]);
    ws.nextSize = stride * rows;
  }
  for (int r = 0; r < rows; ++r)
  {
    std::int32_t* links = ws.next.get() + stride * r;
    for (int u = 0; u <= width; ++u)
    {
      links[u] = u;
    }
  }
  ws.open.assign(static_cast<std::size_t>(rows), width);
  for (int b = 0; b < 2; ++b)
  {
    ws.rows[b].resize(static_cast<std::size_t>(C) * (ni + 2));
    // Disjoint ranges of the ni + 2 cells, apart: at most half of them, rounded up.
    ws.shaded[b].ranges.resize(static_cast<std::size_t>(ni) / 2 + 2);
    ws.rowIndex[b] = NoRow;
  }
  if (work)
  {
    std::fill(work, work + rows, 0.0);
  }
}

// The first run of [run, end) that ends after voxel i. Runs are sorted and disjoint; the walks
// below pass one or two at a time while pixels are open and jump over many at once behind
// saturated pixels, so the runs there cost a binary search instead of a visit each.
inline const VoxelRun* FirstRunEndingAfter(const VoxelRun* run, const VoxelRun* end, int i)
{
  for (int n = 0; n < 2; ++n, ++run)
  {
    if (run == end || static_cast<int>(run->end) > i)
    {
      return run;
    }
  }
  return std::partition_point(
    run, end, [i](const VoxelRun& r) { return static_cast<int>(r.end) <= i; });
}

// The buffer of voxel scanline j in this slice (j & 1: a pair's two scanlines never share one),
// its shaded ranges dropped when it held another scanline; one more user either way.
inline int BufferOfRow(ScanlineWorkspace& ws, int j)
{
  const int b = j & 1;
  ShadedCells& shaded = ws.shaded[b];
  if (ws.rowIndex[b] != j)
  {
    ws.rowIndex[b] = j;
    shaded.count = 0;
    shaded.users = 0;
  }
  ++shaded.users;
  shaded.cursor = 0;
  shaded.requested = std::numeric_limits<int>::min();
  return b;
}

// One voxel scanline of a pair as the pixel walk sees it: the first run that ends after the
// current pixel's first voxel, the shaded cells (cell i + 1 holds voxel i) and which are valid.
struct RowCursor
{
  const VoxelRun* run;
  const VoxelRun* end;
  float* cells;
  ShadedCells* shaded;
};

// Shades the cells of voxels [from, to) of a row, from the voxel where a run stores it, else
// the policy's empty value: tight loops over the gaps and the runs' voxels. The row's cursor is
// a run that ends after `from` or before it.
template <typename Policy>
__attribute__((always_inline)) inline void ShadeRange(
  const Policy& policy, const RowCursor& row, int from, int to, std::uint64_t& shaded)
{
  constexpr int C = Policy::Channels;
  const VoxelRun* run = row.run;
  int i = from;
  while (i < to)
  {
    while (run != row.end && static_cast<int>(run->end) <= i)
    {
      ++run;
    }
    const int gapEnd = run == row.end ? to : std::min(to, static_cast<int>(run->begin));
    if (i < gapEnd)
    {
      policy.Clear(row.cells + C * (i + 1), gapEnd - i);
      i = gapEnd;
    }
    if (i >= to)
    {
      break;
    }
    const int runEnd = std::min(to, static_cast<int>(run->end));
    policy.Load(run->offset + static_cast<std::size_t>(i - static_cast<int>(run->begin)),
      runEnd - i, row.cells + C * (i + 1));
    shaded += static_cast<std::uint64_t>(runEnd - i);
    i = runEnd;
  }
}

// Makes the cells of voxels [from, to) of a row valid, each shaded once per slice, when the
// first open pixel reads it, so voxels behind saturated pixels are never touched. A user asks
// in ascending order (consecutive stretches may overlap by one cell); the buffer's first user
// records what it shaded, a later one shades only what lies between those ranges.
template <typename Policy>
inline void ShadeCells(
  const Policy& policy, const RowCursor& row, int from, int to, std::uint64_t& shaded)
{
  ShadedCells& cells = *row.shaded;
  from = std::max(from, cells.requested);
  if (from >= to)
  {
    return;
  }
  cells.requested = to;
  if (cells.users == 1)
  {
    ShadeRange(policy, row, from, to, shaded);
    std::pair<int, int>* ranges = cells.ranges.data();
    if (cells.count > 0 && ranges[cells.count - 1].second == from)
    {
      ranges[cells.count - 1].second = to;
    }
    else
    {
      ranges[cells.count++] = { from, to };
    }
    return;
  }
  const std::pair<int, int>* ranges = cells.ranges.data();
  const std::size_t count = cells.count;
  int i = from;
  while (i < to)
  {
    while (cells.cursor < count && ranges[cells.cursor].second <= i)
    {
      ++cells.cursor;
    }
    if (cells.cursor < count && ranges[cells.cursor].first <= i)
    {
      i = ranges[cells.cursor].second; // shaded by the first user
      continue;
    }
    const int gapEnd = cells.cursor < count ? std::min(to, ranges[cells.cursor].first) : to;
    ShadeRange(policy, row, i, gapEnd, shaded);
    i = gapEnd;
  }
}

// Composites the open pixels the two voxel scanlines' runs reach into scanline r, in order:
// voxel run [b, e) reaches pixels u whose i0 = u - shiftI - 1 or i0 + 1 lies in it,
// [b + shiftI, e + shiftI + 1). The walk goes from open pixel to open pixel (skip links) and,
// in each row, to the first run that ends after the pixel's voxels (Lacroute's walk of pixel
// runs and voxel runs together): saturated pixels, the runs behind them and their voxels are
// jumped over. A pixel's four corners are shaded on first use into the rows' buffers, which
// serve the next scanline too. Kept out of line (GCC): inlined into the slice loop, its pixel
// loop lost registers to the loop's state.
template <typename Policy>
__attribute__((noinline)) void CompositeRuns(const BandContext<Policy>& c,
  const SlicePlacement& slice, int r, int j0, float* row, int& openRows)
{
  constexpr int C = Policy::Channels;
  using Voxel = typename Policy::Voxel;
  const RunLengthVolume<Voxel>& encoded = c.encoded;
  // A local copy: the pixel stores below cannot alias its members (the termination threshold),
  // so they stay in registers.
  const Policy policy = c.policy;
  ScanlineWorkspace& ws = c.ws;
  ScanlineCounters& counters = c.counters;
  const bool skip = c.skip;
  const int width = c.f.intermediateSize[0];
  const int nj = c.f.sliceDims[1];
  const std::size_t stride = static_cast<std::size_t>(width) + 1;
  const int k = slice.k;
  const int shiftI = slice.shiftI;
  // A local copy: the pixel stores below cannot alias it, so it stays in registers.
  const float w[4] = { slice.w[0], slice.w[1], slice.w[2], slice.w[3] };
  std::int32_t* links = ws.next.get() + stride * r;
  RowCursor rows[2];
  for (int q = 0; q < 2; ++q)
  {
    const int j = j0 + q;
    const int b = BufferOfRow(ws, j);
    rows[q] = { nullptr, nullptr, ws.rows[b].data(), &ws.shaded[b] };
    if (j >= 0 && j < nj)
    {
      rows[q].run = encoded.RunsBegin(j, k);
      rows[q].end = encoded.RunsEnd(j, k);
    }
  }
  std::uint64_t samples = 0;
  std::uint64_t shaded = 0;
  std::uint64_t skipped = 0;
  int u = 0;
  while (true)
  {
    if (skip)
    {
      u = FindOpen(links, std::min(u, width));
    }
    if (u >= width)
    {
      break;
    }
    // Pixel u reads voxels i0 and i0 + 1; runs ending at or before i0 reach only pixels
    // before u.
    int reached = std::numeric_limits<int>::max(); // first pixel >= u a run reaches
    for (RowCursor& cursor : rows)
    {
      cursor.run = FirstRunEndingAfter(cursor.run, cursor.end, u - shiftI - 1);
      if (cursor.run != cursor.end)
      {
        reached = std::min(reached, std::max(u, static_cast<int>(cursor.run->begin) + shiftI));
      }
    }
    if (reached >= width)
    {
      break;
    }
    if (reached > u)
    {
      // Every run the cursors point at begins at or after `reached`, so they stay the first
      // runs that end after its voxels: when that pixel is open, its span follows from them
      // without another pass over the skip links and runs.
      u = reached;
      if (skip && links[u] != u)
      {
        continue;
      }
    }
    // Where the runs reaching u (those beginning at or before it) stop reaching.
    int spanEnd = 0;
    for (const RowCursor& cursor : rows)
    {
      if (cursor.run != cursor.end && static_cast<int>(cursor.run->begin) + shiftI <= u)
      {
        spanEnd = std::max(spanEnd, static_cast<int>(cursor.run->end) + shiftI + 1);
      }
    }
    spanEnd = std::min(spanEnd, width);
    // The stretch of open pixels from u: its voxels are shaded first (tight loops over the two
    // rows), then its pixels composited.
    int stretchEnd = spanEnd;
    if (skip && ws.open[r] != width) // else no pixel of the scanline is saturated yet
    {
      stretchEnd = OpenStretchEnd(links, u + 1, spanEnd);
    }
    for (const RowCursor& cursor : rows)
    {
      ShadeCells(policy, cursor, u - shiftI - 1, stretchEnd - shiftI, shaded);
    }
    for (; u < stretchEnd; ++u)
    {
      // Cell i sits at i + 1: pixel u's corner i0 = u - shiftI - 1 is cell u - shiftI.
      const int cell = u - shiftI;
      ++samples;
      if (policy.Sample(rows[0].cells + C * cell, rows[1].cells + C * cell, w, row + C * u) && skip)
      {
        links[u] = u + 1;
        if (--ws.open[r] == 0)
        {
          --openRows;
        }
      }
    }
    if (skip && u < spanEnd)
    {
      const int found = FindOpen(links, u);
      skipped += static_cast<std::uint64_t>(std::min(found, spanEnd) - u);
      u = found;
    }
  }
  counters.samples += samples;
  counters.voxels += shaded;
  counters.terminatedPixelVisits += skipped;
}

// Whether voxel scanlines j0 and j0 + 1 of slice k store no voxel (either may lie outside the
// slice): the common case in sparse volumes, decided before anything else is read.
template <typename Voxel>
inline bool PairIsEmpty(const RunLengthVolume<Voxel>& encoded, int j0, int k)
{
  const int nj = encoded.sliceDims[1];
  const int first = std::max(j0, 0);
  const int last = std::min(j0 + 2, nj); // exclusive
  if (first >= last)
  {
    return true;
  }
  // The scanlines of a slice are consecutive in rowStart.
  const std::uint32_t* start = encoded.rowStart.data() + encoded.Row(first, k);
  return start[0] == start[last - first];
}

// The voxel scanlines [first, last) of slice k that hold the slice's stored voxels (first ==
// last: none), by binary search over its run starts: bands skip the empty margins of each slice
// without visiting them.
template <typename Voxel>
inline void OccupiedScanlines(const RunLengthVolume<Voxel>& encoded, int k, int& first, int& last)
{
  const int nj = encoded.sliceDims[1];
  const std::uint32_t* start = encoded.rowStart.data() + encoded.Row(0, k);
  const std::uint32_t* end = start + nj; // start[j + 1]: where scanline j's runs end
  // First scanline whose runs end past the slice's first run; last one that starts before
  // the slice's last run ends.
  first = static_cast<int>(std::upper_bound(start + 1, end + 1, start[0]) - (start + 1));
  last = static_cast<int>(std::lower_bound(start, end, *end) - start);
  if (first >= last)
  {
    first = last = 0;
  }
}

// Intermediate scanline v of this slice: from voxel scanlines j0 = v - shiftJ - 1 and j0 + 1.
template <typename Policy>
inline void CompositeScanlinePair(
  const BandContext<Policy>& c, const SlicePlacement& slice, int v, float* pixels, int& openRows)
{
  constexpr int C = Policy::Channels;
  const RunLengthVolume<typename Policy::Voxel>& encoded = c.encoded;
  ScanlineWorkspace& ws = c.ws;
  const bool skip = c.skip;
  const int width = c.f.intermediateSize[0];
  const int nj = c.f.sliceDims[1];
  const std::size_t stride = static_cast<std::size_t>(width) + 1;
  const int k = slice.k;
  const int shiftI = slice.shiftI;
  const int r = v - c.v0;
  const int j0 = v - slice.shiftJ - 1;
  if (ws.open[r] == 0 || PairIsEmpty(encoded, j0, k))
  {
    return;
  }
  // Ahead of use, without waiting for any of it: the run records of the scanline after next,
  // and the first and last voxels of the next one (whose records came one pair ago), where an
  // opaque object's open silhouette pixels read.
  if (j0 + 3 < nj)
  {
    __builtin_prefetch(encoded.RunsBegin(j0 + 3, k));
    __builtin_prefetch(encoded.RunsEnd(j0 + 3, k) - 1);
  }
  if (j0 + 2 >= 0 && j0 + 2 < nj)
  {
    const VoxelRun* first = encoded.RunsBegin(j0 + 2, k);
    const VoxelRun* last = encoded.RunsEnd(j0 + 2, k);
    if (first != last)
    {
      --last;
      c.policy.Prefetch(first->offset);
      c.policy.Prefetch(last->offset + (last->end - last->begin) - 1);
    }
  }
  // The pixels the two voxel scanlines can reach at all; when every one of them is already
  // saturated (the common case behind an opaque surface), nothing of this pair is touched.
  int reachBegin = std::numeric_limits<int>::max();
  int reachEnd = std::numeric_limits<int>::min();
  for (int q = 0; q < 2; ++q)
  {
    const int j = j0 + q;
    if (j >= 0 && j < nj && encoded.RunsBegin(j, k) != encoded.RunsEnd(j, k))
    {
      reachBegin = std::min(reachBegin, static_cast<int>(encoded.RunsBegin(j, k)->begin) + shiftI);
      reachEnd =
        std::max(reachEnd, static_cast<int>((encoded.RunsEnd(j, k) - 1)->end) + shiftI + 1);
    }
  }
  if (reachEnd <= reachBegin)
  {
    return;
  }
  if (skip)
  {
    std::int32_t* links = ws.next.get() + stride * r;
    const int first = std::max(reachBegin, 0);
    const int last = std::min(reachEnd, width);
    const int found = first < last ? FindOpen(links, first) : last;
    if (found >= last)
    {
      c.counters.terminatedPixelVisits += static_cast<std::uint64_t>(std::max(0, last - first));
      return;
    }
  }
  CompositeRuns(c, slice, r, j0, pixels + static_cast<std::size_t>(C) * width * r, openRows);
}

// The band's scanlines of slice s, each timed into work when it is given.
template <typename Policy>
inline void CompositeSlice(
  const BandContext<Policy>& c, int s, float* pixels, int& openRows, double* work)
{
  const SlicePlacement slice = PlaceSlice(c.f, s);
  c.ws.rowIndex[0] = c.ws.rowIndex[1] = NoRow; // last slice's scanlines
  // Scanline v reads voxel scanlines v - shiftJ - 1 and v - shiftJ: those that reach a stored
  // voxel of this slice.
  int firstJ = 0;
  int lastJ = 0;
  OccupiedScanlines(c.encoded, slice.k, firstJ, lastJ);
  if (firstJ == lastJ)
  {
    return;
  }
  const int vBegin = std::max(c.v0, slice.shiftJ + firstJ);
  const int vEnd = std::min(c.v1, slice.shiftJ + lastJ + 1);
  std::uint64_t previousTicks = work ? Ticks() : 0;
  int previousRow = -1;
  for (int v = vBegin; v < vEnd; ++v)
  {
    if (work)
    {
      // The time since the last mark belongs to the scanline worked on before it.
      const std::uint64_t now = Ticks();
      if (previousRow >= 0)
      {
        work[previousRow] += static_cast<double>(now - previousTicks);
      }
      previousTicks = now;
      previousRow = v - c.v0;
    }
    CompositeScanlinePair(c, slice, v, pixels, openRows);
  }
  if (work && previousRow >= 0)
  {
    work[previousRow] += static_cast<double>(Ticks() - previousTicks);
  }
}

template <typename Policy>
void Band(const RunLengthVolume<typename Policy::Voxel>& encoded, const ShearWarpFactorization& f,
  const Policy& policy, bool skip, int v0, int v1, float* pixels, ScanlineWorkspace& ws,
  ScanlineCounters& counters, double* work)
{
  const int rows = v1 - v0;
  if (rows <= 0)
  {
    return;
  }
  const BandContext<Policy> context{ encoded, f, policy, skip, v0, v1, ws, counters };
  ResetBandWorkspace(context, work);
  int openRows = rows;
  for (int s = 0; s < f.sliceDims[2] && openRows > 0; ++s)
  {
    // Every fourth slice is timed: reading the clock around every scanline of every slice cost
    // more than a cheap scanline's work, and a quarter of the slices ranks scanlines as well.
    CompositeSlice(context, s, pixels, openRows, s % 4 == 0 ? work : nullptr);
  }
}
}

void CompositeBand(const RunLengthVolume<ShadedVoxel>& encoded, const ShearWarpFactorization& f,
  const CompositeTables& tables, int v0, int v1, float* rgba, ScanlineWorkspace& workspace,
  ScanlineCounters& counters, double* work)
{
  CompositePolicy policy{ tables, compositing::VoxelShader(tables) };
  policy.threshold = tables.terminationThreshold;
  if (encoded.Indexed())
  {
    policy.paletteIndices = encoded.paletteIndices.data();
    policy.palette = encoded.palette.data();
    if (!tables.shade && tables.paletteColours.size() == 4 * encoded.palette.size())
    {
      policy.paletteColours = tables.paletteColours.data();
    }
  }
  else
  {
    policy.voxels = encoded.voxels.data();
  }
  Band(encoded, f, policy, tables.terminationLinks && tables.earlyTermination, v0, v1, rgba, workspace,
    counters, work);
}

void ExtremeBand(const RunLengthVolume<ScalarVoxel>& encoded, const ShearWarpFactorization& f,
  bool maximum, float saturation, bool terminationLinks, int v0, int v1, float* value,
  ScanlineWorkspace& workspace, ScanlineCounters& counters, double* work)
{
  const ExtremePolicy policy{ maximum, saturation, encoded.voxels.data() };
  Band(encoded, f, policy, terminationLinks, v0, v1, value, workspace, counters, work);
}

}
