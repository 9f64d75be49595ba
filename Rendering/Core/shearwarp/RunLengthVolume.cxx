// Classification and run-length encoding of a volume for one principal axis.
#include "shearwarp/RunLengthVolume.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

namespace accelvolume
{

std::uint16_t EncodeNormal(float x, float y, float z)
{
  const float length = std::abs(x) + std::abs(y) + std::abs(z);
  if (!(length > 1e-30f) || !std::isfinite(length))
  {
    return NoNormal;
  }
  float px = x / length;
  float py = y / length;
  if (z < 0)
  {
    // Fold the lower hemisphere over the octahedron's diagonals.
    const float fx = (1.0f - std::abs(py)) * (px >= 0 ? 1.0f : -1.0f);
    const float fy = (1.0f - std::abs(px)) * (py >= 0 ? 1.0f : -1.0f);
    px = fx;
    py = fy;
  }
  constexpr float last = static_cast<float>((1 << NormalBits) - 1);
  const int qx = static_cast<int>(std::lround((px * 0.5f + 0.5f) * last));
  const int qy = static_cast<int>(std::lround((py * 0.5f + 0.5f) * last));
  return static_cast<std::uint16_t>(qx | (qy << NormalBits));
}

void DecodeNormal(std::uint16_t code, float normal[3])
{
  constexpr int mask = (1 << NormalBits) - 1;
  constexpr float last = static_cast<float>(mask);
  float x = (code & mask) / last * 2.0f - 1.0f;
  float y = ((code >> NormalBits) & mask) / last * 2.0f - 1.0f;
  const float z = 1.0f - std::abs(x) - std::abs(y);
  if (z < 0)
  {
    const float fx = (1.0f - std::abs(y)) * (x >= 0 ? 1.0f : -1.0f);
    const float fy = (1.0f - std::abs(x)) * (y >= 0 ? 1.0f : -1.0f);
    x = fx;
    y = fy;
  }
  const float length = std::sqrt(x * x + y * y + z * z);
  normal[0] = x / length;
  normal[1] = y / length;
  normal[2] = z / length;
}

namespace
{

// One slice's encoding before the slices are concatenated.
template <typename Voxel>
struct SliceEncoding
{
  std::vector<std::uint32_t> rowRuns; // runs per scanline j
  std::vector<VoxelRun> runs;         // offsets relative to the slice's first voxel
  std::vector<Voxel> voxels;
};

// Appends the runs of `keep` (ni flags) to the slice, voxels from voxelAt(i).
template <typename Voxel, typename Keep, typename VoxelAt>
void EncodeScanline(int ni, Keep keep, VoxelAt voxelAt, SliceEncoding<Voxel>& slice)
{
  std::uint32_t count = 0;
  int i = 0;
  while (i < ni)
  {
    while (i < ni && !keep(i))
    {
      ++i;
    }
    if (i == ni)
    {
      break;
    }
    VoxelRun run;
    run.begin = static_cast<std::uint16_t>(i);
    run.offset = static_cast<std::uint32_t>(slice.voxels.size()); // < 65535^2 per slice
    while (i < ni && keep(i))
    {
      slice.voxels.push_back(voxelAt(i));
      ++i;
    }
    run.end = static_cast<std::uint16_t>(i);
    slice.runs.push_back(run);
    ++count;
  }
  slice.rowRuns.push_back(count);
}

// Encodes every slice in parallel (encodeSlice(k, slice)) and concatenates them in slice order,
// so the result never depends on the thread count.
template <typename Voxel, typename EncodeSlice>
bool EncodeSlices(const int dims[3], int axis, bool dense, const ParallelFor& parallel,
  EncodeSlice encodeSlice, RunLengthVolume<Voxel>& encoded, std::string& error)
{
  encoded.Clear();
  encoded.axis = axis;
  encoded.dense = dense;
  encoded.sliceDims[0] = dims[(axis + 1) % 3];
  encoded.sliceDims[1] = dims[(axis + 2) % 3];
  encoded.sliceDims[2] = dims[axis];
  const int nj = encoded.sliceDims[1];
  const int nk = encoded.sliceDims[2];
  std::vector<SliceEncoding<Voxel>> slices(nk);
  parallel(static_cast<std::size_t>(nk),
    [&](std::size_t begin, std::size_t end)
    {
      for (std::size_t k = begin; k < end; ++k)
      {
        slices[k].rowRuns.reserve(nj);
        encodeSlice(static_cast<int>(k), slices[k]);
      }
    });
  std::size_t runCount = 0;
  std::size_t voxelCount = 0;
  for (const auto& slice : slices)
  {
    runCount += slice.runs.size();
    voxelCount += slice.voxels.size();
  }
  if (runCount > std::numeric_limits<std::uint32_t>::max() ||
    voxelCount > std::numeric_limits<std::uint32_t>::max())
  {
    encoded.Clear();
    error = "run-length encoding: more than 2^32 - 1 stored voxels or runs (volume too large)";
    return false;
  }
  encoded.rowStart.resize(static_cast<std::size_t>(nj) * nk + 1);
  encoded.runs.reserve(runCount);
  encoded.voxels.reserve(voxelCount);
  std::size_t row = 0;
  encoded.rowStart[0] = 0;
  for (auto& slice : slices)
  {
    const auto base = static_cast<std::uint32_t>(encoded.voxels.size());
    for (VoxelRun run : slice.runs)
    {
      run.offset += base;
      encoded.runs.push_back(run);
    }
    encoded.voxels.insert(encoded.voxels.end(), slice.voxels.begin(), slice.voxels.end());
    for (std::uint32_t count : slice.rowRuns)
    {
      encoded.rowStart[row + 1] = encoded.rowStart[row] + count;
      ++row;
    }
    slice = SliceEncoding<Voxel>(); // free as we go
  }
  return true;
}

bool CheckVolume(const VolumeView& volume, int axis, std::string& error)
{
  if (!volume.data || volume.dims[0] < 1 || volume.dims[1] < 1 || volume.dims[2] < 1)
  {
    error = "run-length encoding: the volume is empty";
    return false;
  }
  if (axis < 0 || axis > 2)
  {
    error = "run-length encoding: the principal axis must be 0, 1 or 2";
    return false;
  }
  if (volume.dims[0] > MaximumRunLengthAxis || volume.dims[1] > MaximumRunLengthAxis ||
    volume.dims[2] > MaximumRunLengthAxis)
  {
    error = "run-length encoding: an axis is longer than 65535 voxels";
    return false;
  }
  return true;
}

// Voxel access by object coordinates, with the slice walk's axis permutation.
template <typename T>
struct Grid
{
  const T* data;
  int dims[3];
  std::size_t strides[3];

  Grid(const VolumeView& volume, const T* typed)
    : data(typed)
  {
    std::copy(volume.dims, volume.dims + 3, this->dims);
    this->strides[0] = 1;
    this->strides[1] = static_cast<std::size_t>(this->dims[0]);
    this->strides[2] = this->strides[1] * static_cast<std::size_t>(this->dims[1]);
  }
  double At(const int p[3]) const
  {
    return static_cast<double>(
      this->data[p[0] * this->strides[0] + p[1] * this->strides[1] + p[2] * this->strides[2]]);
  }
  // Central differences, one-sided at the borders, zero across a one-voxel axis; NaN
  // neighbours give zero.
  void Gradient(const int p[3], double g[3]) const
  {
    for (int a = 0; a < 3; ++a)
    {
      int lo[3] = { p[0], p[1], p[2] };
      int hi[3] = { p[0], p[1], p[2] };
      lo[a] = std::max(0, p[a] - 1);
      hi[a] = std::min(this->dims[a] - 1, p[a] + 1);
      const int span = hi[a] - lo[a];
      const double d = span > 0 ? (this->At(hi) - this->At(lo)) / span : 0.0;
      g[a] = std::isfinite(d) ? d : 0.0;
    }
  }
};

}

bool EncodeComposite(const VolumeView& volume, const CompositeClassification& c, int axis,
  bool dense, const ParallelFor& parallel, RunLengthVolume<ShadedVoxel>& encoded,
  std::string& error)
{
  if (!CheckVolume(volume, axis, error))
  {
    return false;
  }
  const std::size_t entries = c.rgba.size() / 4;
  if (entries < 2 || c.rgba.size() % 4 != 0 || (!c.gradientOpacity.empty() && c.gradientOpacity.size() < 2))
  {
    error = "run-length encoding: the transfer function table needs at least 2 RGBA entries";
    return false;
  }
  const double width = c.rangeMax > c.rangeMin ? c.rangeMax - c.rangeMin : 1.0;
  const double scale = static_cast<double>(entries - 1) / width;
  const bool gradientOpacity = !c.gradientOpacity.empty();
  const bool needGradient = c.normals || gradientOpacity;
  const double gradientScale = gradientOpacity && c.gradientOpacityMaximum > 0
    ? (c.gradientOpacity.size() - 1) / c.gradientOpacityMaximum
    : 0.0;
  const int i = (axis + 1) % 3;
  const int j = (axis + 2) % 3;
  bool ok = false;
  DispatchScalarType(volume,
    [&](const auto* typed)
    {
      using T = std::remove_cv_t<std::remove_pointer_t<decltype(typed)>>;
      const Grid<T> grid(volume, typed);
      auto classify = [&](const int p[3], ShadedVoxel& voxel) -> bool
      {
        voxel = ShadedVoxel{ 0, NoNormal, { 0, 0, 0, 0 } };
        const double s = grid.At(p);
        if (std::isnan(s))
        {
          return false;
        }
        const double u = std::min(std::max((s - c.rangeMin) * scale, 0.0), double(entries - 1));
        const std::size_t e = std::min(static_cast<std::size_t>(u), entries - 2);
        const float f = static_cast<float>(u - e);
        const float* lo = &c.rgba[4 * e];
        float opacity = lo[3] + (lo[7] - lo[3]) * f;
        if (!(opacity > 0))
        {
          return false;
        }
        double g[3] = { 0, 0, 0 };
        if (needGradient)
        {
          grid.Gradient(p, g);
        }
        if (gradientOpacity)
        {
          double scaled[3];
          for (int a = 0; a < 3; ++a)
          {
            scaled[a] = c.gradientAxisScale[a] * g[a];
          }
          const double m =
            std::sqrt(scaled[0] * scaled[0] + scaled[1] * scaled[1] + scaled[2] * scaled[2]);
          const std::size_t last = c.gradientOpacity.size() - 1;
          const double gu = std::min(m * gradientScale, double(last));
          const std::size_t ge = std::min(static_cast<std::size_t>(gu), last - 1);
          const float gf = static_cast<float>(gu - ge);
          opacity *= c.gradientOpacity[ge] + (c.gradientOpacity[ge + 1] - c.gradientOpacity[ge]) * gf;
        }
        const long q = std::lround(std::min(opacity, 1.0f) * static_cast<float>(OpacityLevels));
        if (q <= 0)
        {
          return false;
        }
        voxel.opacity = static_cast<std::uint16_t>(q);
        for (int ch = 0; ch < 3; ++ch)
        {
          const float value = lo[ch] + (lo[ch + 4] - lo[ch]) * f;
          voxel.colour[ch] =
            static_cast<std::uint8_t>(std::lround(std::min(std::max(value, 0.0f), 1.0f) * 255.0f));
        }
        if (c.normals)
        {
          voxel.normal = EncodeNormal(
            static_cast<float>(g[0]), static_cast<float>(g[1]), static_cast<float>(g[2]));
        }
        return true;
      };
      ok = EncodeSlices<ShadedVoxel>(volume.dims, axis, dense, parallel,
        [&](int k, SliceEncoding<ShadedVoxel>& slice)
        {
          const int ni = volume.dims[i];
          std::vector<ShadedVoxel> row(ni);
          std::vector<unsigned char> keep(ni);
          for (int jj = 0; jj < volume.dims[j]; ++jj)
          {
            int p[3];
            p[axis] = k;
            p[j] = jj;
            for (int ii = 0; ii < ni; ++ii)
            {
              p[i] = ii;
              keep[ii] = classify(p, row[ii]) || dense;
            }
            EncodeScanline<ShadedVoxel>(
              ni, [&](int x) { return keep[x] != 0; }, [&](int x) { return row[x]; }, slice);
          }
        },
        encoded, error);
    });
  return ok;
}

namespace
{
// What a palette entry is told apart by: opacity and colour.
std::uint64_t PaletteKey(const ShadedVoxel& voxel)
{
  return static_cast<std::uint64_t>(voxel.opacity) << 24 |
    static_cast<std::uint64_t>(voxel.colour[0]) << 16 |
    static_cast<std::uint64_t>(voxel.colour[1]) << 8 | voxel.colour[2];
}

// Palette indices 0..65534: NoNormal stays apart.
constexpr std::size_t MaximumPaletteEntries = NoNormal;

// A set of palette keys: open addressing over twice the most entries allowed.
class PaletteKeySet
{
public:
  static constexpr std::size_t Slots = std::size_t(1) << 17;
  PaletteKeySet()
    : SlotKeys(Slots, 0)
  {
  }
  // False when the key is new and the set already holds MaximumPaletteEntries keys.
  bool Insert(std::uint64_t key)
  {
    const std::size_t slot = this->SlotOf(key);
    if (this->SlotKeys[slot] == 0)
    {
      if (this->InsertedKeys.size() == MaximumPaletteEntries)
      {
        return false;
      }
      this->SlotKeys[slot] = key + 1;
      this->InsertedKeys.push_back(key);
    }
    return true;
  }
  // The key's slot (0..Slots - 1): where it is, or where it would go.
  std::size_t SlotOf(std::uint64_t key) const
  {
    std::size_t slot = static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> 47);
    // key + 1: 0 is an empty slot
    while (this->SlotKeys[slot] != 0 && this->SlotKeys[slot] != key + 1)
    {
      slot = (slot + 1) & (Slots - 1);
    }
    return slot;
  }
  const std::vector<std::uint64_t>& Distinct() const { return this->InsertedKeys; }

private:
  std::vector<std::uint64_t> SlotKeys;
  std::vector<std::uint64_t> InsertedKeys; // in insertion order
};
}

bool AssignPalette(RunLengthVolume<ShadedVoxel>& encoded, const ParallelFor& parallel)
{
  if (encoded.Indexed() || encoded.voxels.empty())
  {
    return false;
  }
  // The distinct keys of fixed parts of the voxels in parallel, then merged: the set does not
  // depend on how the parts were shared out.
  constexpr std::size_t Parts = 16;
  const std::size_t count = encoded.voxels.size();
  std::vector<std::vector<std::uint64_t>> partKeys(Parts);
  std::atomic<bool> refused{ false };
  parallel(Parts,
    [&](std::size_t begin, std::size_t end)
    {
      for (std::size_t part = begin; part < end && !refused; ++part)
      {
        PaletteKeySet set;
        for (std::size_t n = count * part / Parts; n < count * (part + 1) / Parts; ++n)
        {
          const ShadedVoxel& voxel = encoded.voxels[n];
          if (voxel.normal != NoNormal || !set.Insert(PaletteKey(voxel)))
          {
            refused = true; // normals (a shaded encoding) or too many distinct voxels
            break;
          }
        }
        partKeys[part] = set.Distinct();
      }
    });
  if (refused)
  {
    return false;
  }
  PaletteKeySet all;
  for (const std::vector<std::uint64_t>& keys : partKeys)
  {
    for (std::uint64_t key : keys)
    {
      if (!all.Insert(key))
      {
        return false;
      }
    }
  }
  // Indices in key order, so that the palette never depends on how the encoding was built.
  std::vector<std::uint64_t> distinct = all.Distinct();
  std::sort(distinct.begin(), distinct.end());
  std::vector<std::uint16_t> index(PaletteKeySet::Slots, 0); // by the merged set's slot
  encoded.palette.resize(distinct.size());
  for (std::size_t n = 0; n < distinct.size(); ++n)
  {
    index[all.SlotOf(distinct[n])] = static_cast<std::uint16_t>(n);
    ShadedVoxel& entry = encoded.palette[n];
    entry.opacity = static_cast<std::uint16_t>(distinct[n] >> 24);
    entry.normal = NoNormal;
    entry.colour[0] = static_cast<std::uint8_t>(distinct[n] >> 16);
    entry.colour[1] = static_cast<std::uint8_t>(distinct[n] >> 8);
    entry.colour[2] = static_cast<std::uint8_t>(distinct[n]);
    entry.colour[3] = 0;
  }
  encoded.paletteIndices.resize(count);
  parallel(count,
    [&](std::size_t begin, std::size_t end)
    {
      for (std::size_t n = begin; n < end; ++n)
      {
        encoded.paletteIndices[n] = index[all.SlotOf(PaletteKey(encoded.voxels[n]))];
      }
    });
  encoded.voxels = std::vector<ShadedVoxel>(); // released: the indices stand for them
  return true;
}

bool EncodeExtreme(const VolumeView& volume, double rangeMin, double rangeMax, bool maximum,
  std::uint16_t threshold, int axis, bool dense, const ParallelFor& parallel,
  RunLengthVolume<ScalarVoxel>& encoded, std::string& error)
{
  if (!CheckVolume(volume, axis, error))
  {
    return false;
  }
  const double width = rangeMax > rangeMin ? rangeMax - rangeMin : 1.0;
  const double scale = 65535.0 / width;
  const int i = (axis + 1) % 3;
  const int j = (axis + 2) % 3;
  bool ok = false;
  DispatchScalarType(volume,
    [&](const auto* typed)
    {
      using T = std::remove_cv_t<std::remove_pointer_t<decltype(typed)>>;
      const Grid<T> grid(volume, typed);
      ok = EncodeSlices<ScalarVoxel>(volume.dims, axis, dense, parallel,
        [&](int k, SliceEncoding<ScalarVoxel>& slice)
        {
          const int ni = volume.dims[i];
          const int nj = volume.dims[j];
          const std::size_t count = static_cast<std::size_t>(ni) * nj;
          std::vector<ScalarVoxel> values(count);
          std::vector<unsigned char> valid(count); // not NaN
          std::vector<unsigned char> kept(count);  // can decide a visible pixel
          int p[3];
          p[axis] = k;
          for (int jj = 0; jj < nj; ++jj)
          {
            p[j] = jj;
            for (int ii = 0; ii < ni; ++ii)
            {
              p[i] = ii;
              const double s = grid.At(p);
              const std::size_t at = static_cast<std::size_t>(jj) * ni + ii;
              valid[at] = !std::isnan(s);
              const double q = std::min(std::max((s - rangeMin) * scale, 0.0), 65535.0);
              values[at] = valid[at] ? static_cast<ScalarVoxel>(std::lround(q)) : 0;
              kept[at] = valid[at] &&
                (dense || (maximum ? values[at] >= threshold : values[at] <= threshold));
            }
          }
          // Keep the 3x3 in-slice neighbours of kept voxels: every bilinear sample touching a
          // kept voxel then has its four true corners.
          std::vector<unsigned char> stored(count);
          for (int jj = 0; jj < nj; ++jj)
          {
            for (int ii = 0; ii < ni; ++ii)
            {
              bool any = false;
              for (int dj = -1; dj <= 1 && !any; ++dj)
              {
                const int y = jj + dj;
                for (int di = -1; di <= 1 && !any && y >= 0 && y < nj; ++di)
                {
                  const int x = ii + di;
                  any = x >= 0 && x < ni && kept[static_cast<std::size_t>(y) * ni + x];
                }
              }
              const std::size_t at = static_cast<std::size_t>(jj) * ni + ii;
              stored[at] = any && valid[at];
            }
          }
          for (int jj = 0; jj < nj; ++jj)
          {
            const std::size_t rowAt = static_cast<std::size_t>(jj) * ni;
            EncodeScanline<ScalarVoxel>(
              ni, [&](int x) { return stored[rowAt + x] != 0; },
              [&](int x) { return values[rowAt + x]; }, slice);
          }
        },
        encoded, error);
    });
  return ok;
}

}
