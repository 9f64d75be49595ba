// RunLengthVolume: the octahedral normal code round trip, and the composite encoding decoded back
// exactly equals a brute-force classification written here from the documented formulas (every
// scalar type, every principal axis, sparse and dense, NaN / infinite voxels, gradient
// opacity), with a well-formed run structure and identical arrays for any parallel split.
#include "RunLengthTestSupport.h"

#include "shearwarp/RunLengthVolume.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

using namespace accelvolume;
using namespace accelvolume_test;

namespace
{

// Angle between two directions; atan2 stays accurate for tiny angles (acos of a dot product of
// float vectors near 1 would read 0.03 degrees of noise).
double AngleDegrees(const float a[3], const double b[3])
{
  const double dot = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  const double cross[3] = { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
    a[0] * b[1] - a[1] * b[0] };
  const double sine = std::sqrt(cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]);
  return std::atan2(sine, dot) * 180.0 / 3.14159265358979323846;
}

// Transfer table with zero-opacity stretches, tiny (quantized-to-zero) and over-one opacities,
// colours a little outside [0, 1] (classification clamps them).
std::vector<float> RandomTable(std::mt19937& random, int entries)
{
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<float> rgba(4 * static_cast<std::size_t>(entries));
  int zeros = 0;
  for (int e = 0; e < entries; ++e)
  {
    for (int c = 0; c < 3; ++c)
    {
      rgba[4 * e + c] = -0.1f + 1.2f * unit(random);
    }
    if (zeros == 0 && unit(random) < 0.35f)
    {
      zeros = 1 + static_cast<int>(random() % 6);
    }
    float opacity;
    if (zeros > 0)
    {
      opacity = 0.0f;
      --zeros;
    }
    else
    {
      const float pick = unit(random);
      opacity = pick < 0.1f ? 1e-6f : pick < 0.2f ? 1.0f + unit(random) : unit(random);
    }
    rgba[4 * e + 3] = opacity;
  }
  return rgba;
}

// The documented classification of one voxel, from the raw volume.
template <typename T>
bool Classify(const RandomVolume<T>& volume, const CompositeClassification& c, const int p[3],
  ShadedVoxel& voxel)
{
  voxel = ShadedVoxel{ 0, NoNormal, { 0, 0, 0, 0 } };
  const double s = volume.At(p);
  if (std::isnan(s))
  {
    return false;
  }
  const std::size_t entries = c.rgba.size() / 4;
  const double scale = static_cast<double>(entries - 1) / (c.rangeMax - c.rangeMin);
  const double x = std::min(std::max((s - c.rangeMin) * scale, 0.0), double(entries - 1));
  const std::size_t e = std::min(static_cast<std::size_t>(x), entries - 2);
  const float f = static_cast<float>(x - e);
  float opacity = c.rgba[4 * e + 3] + (c.rgba[4 * e + 7] - c.rgba[4 * e + 3]) * f;
  if (!(opacity > 0))
  {
    return false;
  }
  double g[3] = { 0, 0, 0 };
  for (int a = 0; a < 3; ++a)
  {
    int lo[3] = { p[0], p[1], p[2] }, hi[3] = { p[0], p[1], p[2] };
    lo[a] = std::max(p[a] - 1, 0);
    hi[a] = std::min(p[a] + 1, volume.view.dims[a] - 1);
    if (hi[a] > lo[a])
    {
      const double difference = (volume.At(hi) - volume.At(lo)) / (hi[a] - lo[a]);
      g[a] = std::isfinite(difference) ? difference : 0.0;
    }
  }
  if (!c.gradientOpacity.empty())
  {
    double m2 = 0;
    for (int a = 0; a < 3; ++a)
    {
      const double w = c.gradientAxisScale[a] * g[a];
      m2 += w * w;
    }
    const std::size_t last = c.gradientOpacity.size() - 1;
    const double gx = std::min(
      std::sqrt(m2) * (static_cast<double>(last) / c.gradientOpacityMaximum), double(last));
    const std::size_t ge = std::min(static_cast<std::size_t>(gx), last - 1);
    const float gf = static_cast<float>(gx - ge);
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
    const float value = c.rgba[4 * e + ch] + (c.rgba[4 * e + 4 + ch] - c.rgba[4 * e + ch]) * f;
    voxel.colour[ch] =
      static_cast<std::uint8_t>(std::lround(std::min(std::max(value, 0.0f), 1.0f) * 255.0f));
  }
  if (c.normals)
  {
    voxel.normal =
      EncodeNormal(static_cast<float>(g[0]), static_cast<float>(g[1]), static_cast<float>(g[2]));
  }
  return true;
}

bool SameVoxel(const ShadedVoxel& a, const ShadedVoxel& b)
{
  return a.opacity == b.opacity && a.normal == b.normal && a.colour[0] == b.colour[0] &&
    a.colour[1] == b.colour[1] && a.colour[2] == b.colour[2];
}

// AssignPalette on `encoded` (classified by c for axis): given exactly when no voxel has a normal
// and there are voxels; then the voxels are released (only their indices kept), each voxel's
// entry is its opacity and colour, the entries ascend and differ, a second call refuses, and a
// transposed palette encoding equals the other axis's own palette encoding.
void ExpectPalette(const VolumeView& view, const CompositeClassification& c, int axis, bool dense,
  const RunLengthVolume<ShadedVoxel>& encoded)
{
  auto key = [](const ShadedVoxel& v)
  { return std::uint64_t(v.opacity) << 24 | v.colour[0] << 16 | v.colour[1] << 8 | v.colour[2]; };
  RunLengthVolume<ShadedVoxel> paletted = encoded;
  const bool normalFree = std::all_of(encoded.voxels.begin(), encoded.voxels.end(),
    [](const ShadedVoxel& v) { return v.normal == NoNormal; });
  ASSERT_EQ(AssignPalette(paletted, UnevenThreadedFor(3)), normalFree && !encoded.voxels.empty());
  if (!normalFree || encoded.voxels.empty())
  {
    ExpectSameArrays(encoded, paletted, SameVoxel); // unchanged
    EXPECT_TRUE(paletted.palette.empty());
    return;
  }
  EXPECT_FALSE(AssignPalette(paletted, UnevenThreadedFor(3)));
  EXPECT_TRUE(paletted.Indexed());
  EXPECT_TRUE(paletted.voxels.empty()) << "the indices stand for the voxels";
  for (std::size_t n = 0; n < paletted.palette.size(); ++n)
  {
    EXPECT_EQ(paletted.palette[n].normal, NoNormal);
    if (n > 0)
    {
      ASSERT_LT(key(paletted.palette[n - 1]), key(paletted.palette[n]));
    }
  }
  ASSERT_EQ(paletted.StoredVoxels(), encoded.voxels.size());
  ASSERT_EQ(paletted.paletteIndices.size(), encoded.voxels.size());
  ExpectSameArrays(encoded, paletted, SameVoxel);
  for (std::size_t n = 0; n < encoded.voxels.size(); ++n)
  {
    ASSERT_LT(paletted.paletteIndices[n], paletted.palette.size());
    ASSERT_TRUE(SameVoxel(paletted.palette[paletted.paletteIndices[n]], encoded.voxels[n]))
      << "voxel " << n;
  }
  const int other = (axis + 1) % 3;
  RunLengthVolume<ShadedVoxel> direct;
  RunLengthVolume<ShadedVoxel> transposed;
  std::string error;
  ASSERT_TRUE(EncodeComposite(view, c, other, dense, UnevenThreadedFor(2), direct, error));
  ASSERT_TRUE(AssignPalette(direct, UnevenThreadedFor(3)));
  ASSERT_TRUE(TransposeEncoding(paletted, other, transposed, error)) << error;
  ExpectSameArrays(direct, transposed, SameVoxel);
  ASSERT_EQ(direct.palette.size(), transposed.palette.size());
  for (std::size_t n = 0; n < direct.palette.size(); ++n)
  {
    EXPECT_TRUE(SameVoxel(direct.palette[n], transposed.palette[n]));
  }
  EXPECT_EQ(direct.paletteIndices, transposed.paletteIndices);
}

template <typename T>
void CompositeTrial(std::mt19937& random, double low, double high, Totals& totals)
{
  const RandomVolume<T> volume(random, low, high);
  CompositeClassification c;
  c.rangeMin = volume.rangeMin;
  c.rangeMax = volume.rangeMax;
  c.rgba = RandomTable(random, 2 + static_cast<int>(random() % 40));
  c.normals = random() % 2 == 0;
  if (random() % 2 == 0)
  {
    c.gradientOpacity.resize(2 + random() % 6);
    for (float& value : c.gradientOpacity)
    {
      value = random() % 4 == 0 ? 0.0f : static_cast<float>(random() % 1000) / 800.0f;
    }
    c.gradientOpacityMaximum = (high - low) * (0.05 + 0.5 * (random() % 100) / 100.0);
    for (int a = 0; a < 3; ++a)
    {
      c.gradientAxisScale[a] = 0.3 + (random() % 100) / 40.0;
    }
  }
  const int axis = static_cast<int>(random() % 3);
  const bool dense = random() % 3 == 0;
  RunLengthVolume<ShadedVoxel> encoded;
  std::string error;
  ASSERT_TRUE(EncodeComposite(volume.view, c, axis, dense, SerialParallelFor, encoded, error))
    << error;
  const std::vector<const ShadedVoxel*> decoded = Decode(encoded, axis, volume.view.dims, true);
  ASSERT_FALSE(decoded.empty());
  const int ni = encoded.sliceDims[0], nj = encoded.sliceDims[1], nk = encoded.sliceDims[2];
  for (int k = 0; k < nk; ++k)
  {
    for (int j = 0; j < nj; ++j)
    {
      for (int i = 0; i < ni; ++i)
      {
        int p[3];
        SliceToObject(axis, i, j, k, p);
        ShadedVoxel expected;
        const bool visible = Classify(volume, c, p, expected);
        const ShadedVoxel* got = decoded[(static_cast<std::size_t>(k) * nj + j) * ni + i];
        totals.nanVoxels += std::isnan(volume.At(p));
        if (dense)
        {
          ASSERT_NE(got, nullptr) << "dense encoding lacks voxel " << i << " " << j << " " << k;
          if (!visible)
          {
            EXPECT_EQ(got->opacity, 0);
            continue;
          }
        }
        else
        {
          ASSERT_EQ(got != nullptr, visible)
            << "voxel (" << p[0] << ", " << p[1] << ", " << p[2] << ") value " << volume.At(p);
        }
        if (visible)
        {
          ASSERT_TRUE(SameVoxel(*got, expected))
            << "voxel (" << p[0] << ", " << p[1] << ", " << p[2] << "): opacity " << got->opacity
            << " vs " << expected.opacity << ", normal " << got->normal << " vs " << expected.normal
            << ", colour " << int(got->colour[0]) << " vs " << int(expected.colour[0]);
          ++totals.stored;
        }
      }
    }
  }
  totals.total += decoded.size();
  totals.runs += encoded.runs.size();

  // The same arrays from uneven chunks on several threads.
  RunLengthVolume<ShadedVoxel> threaded;
  ASSERT_TRUE(EncodeComposite(volume.view, c, axis, dense, UnevenThreadedFor(3), threaded, error));
  ExpectSameArrays(encoded, threaded, SameVoxel);

  // Every other axis from this encoding alone (the renderer's background encodings): the same
  // arrays as classifying the volume for that axis.
  for (int other = 0; other < 3; ++other)
  {
    if (other == axis)
    {
      continue;
    }
    RunLengthVolume<ShadedVoxel> direct;
    RunLengthVolume<ShadedVoxel> transposed;
    ASSERT_TRUE(EncodeComposite(volume.view, c, other, dense, UnevenThreadedFor(2), direct, error));
    ASSERT_TRUE(TransposeEncoding(encoded, other, transposed, error)) << error;
    EXPECT_EQ(transposed.axis, other);
    EXPECT_EQ(transposed.dense, dense);
    for (int a = 0; a < 3; ++a)
    {
      EXPECT_EQ(transposed.sliceDims[a], direct.sliceDims[a]);
    }
    ExpectSameArrays(direct, transposed, SameVoxel);
  }
  ExpectPalette(volume.view, c, axis, dense, encoded);
}

} // namespace

TEST(RunLengthVolume, NormalCodeRoundTrip)
{
  std::mt19937 random(17);
  std::normal_distribution<double> normal;
  double worst = 0, sum = 0;
  const int samples = 200000;
  for (int n = 0; n < samples; ++n)
  {
    double v[3] = { normal(random), normal(random), normal(random) };
    if (n < 6)
    {
      v[0] = v[1] = v[2] = 0;
      v[n / 2] = n % 2 ? -1.0 : 1.0; // the axes, both signs
    }
    else if (n % 7 == 0)
    {
      v[2] *= 1e-3; // near the fold (z = 0)
    }
    const double length = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (double& value : v)
    {
      value /= length;
    }
    const double scale = n % 3 == 0 ? 1.0 : n % 3 == 1 ? 37.0 : 1e-3; // codes ignore length
    const std::uint16_t code = EncodeNormal(static_cast<float>(v[0] * scale),
      static_cast<float>(v[1] * scale), static_cast<float>(v[2] * scale));
    ASSERT_LT(code, NormalCodes);
    float decoded[3];
    DecodeNormal(code, decoded);
    const double error = AngleDegrees(decoded, v);
    worst = std::max(worst, error);
    sum += error;
  }
  // Measured with per-coordinate rounding: worst 1.89 degrees for 7 bits per coordinate, 3.83
  // for 6 (both hemispheres alike: the octahedral map stretches the grid near the face
  // centres), mean 0.67 / 1.36; i.e. about 240 / (2^bits - 1) degrees at worst.
  const double levels = static_cast<double>((1 << NormalBits) - 1);
  std::printf("[ measured ] normal code round trip (%d bits): worst angular error %.3f degrees, "
              "mean %.3f\n",
    NormalBits, worst, sum / samples);
  EXPECT_LT(worst, 254.0 / levels);        // 2.0 degrees for 7 bits, 4.03 for 6
  EXPECT_LT(sum / samples, 95.0 / levels); // 0.75 degrees for 7 bits

  // Every code decodes to a unit vector that encodes back to the same direction: the same code
  // inside the square; on its border (x or y = +-1) the octahedral map glues mirrored codes
  // together, so a twin code of the same direction is fine there.
  constexpr int last = (1 << NormalBits) - 1;
  for (int code = 0; code < NormalCodes; ++code)
  {
    float n[3];
    DecodeNormal(static_cast<std::uint16_t>(code), n);
    ASSERT_NEAR(n[0] * n[0] + n[1] * n[1] + n[2] * n[2], 1.0f, 1e-5f);
    const std::uint16_t again = EncodeNormal(n[0], n[1], n[2]);
    const int qx = code & last, qy = code >> NormalBits;
    if (qx != 0 && qx != last && qy != 0 && qy != last)
    {
      ASSERT_EQ(again, code);
    }
    else
    {
      float twin[3];
      DecodeNormal(again, twin);
      const double direction[3] = { n[0], n[1], n[2] };
      ASSERT_LT(AngleDegrees(twin, direction), 1e-3) << "code " << code;
    }
  }
  EXPECT_EQ(EncodeNormal(0, 0, 0), NoNormal);
  EXPECT_EQ(EncodeNormal(-0.0f, 0, 0), NoNormal);
  EXPECT_EQ(EncodeNormal(std::numeric_limits<float>::quiet_NaN(), 1, 0), NoNormal);
}

TEST(RunLengthVolume, CompositeEncodingDecodesToTheBruteForceClassification)
{
  std::mt19937 random(424242);
  Totals totals;
  for (int round = 0; round < 12; ++round)
  {
    EveryType(
      random,
      [](auto zero, double low, double high, std::mt19937& r, Totals& t)
      {
        using T = decltype(zero);
        CompositeTrial<T>(r, low, high, t);
      },
      totals);
    if (HasFatalFailure())
    {
      return;
    }
  }
  // The random cases must have had both stored and left-out voxels, and NaNs.
  EXPECT_GT(totals.stored, totals.total / 10);
  EXPECT_LT(totals.stored, totals.total * 9 / 10);
  EXPECT_GT(totals.nanVoxels, 0u);
  EXPECT_GT(totals.runs, 100u);
}

TEST(RunLengthVolume, TransposeRejectsItsOwnAxisAndAnEmptyEncoding)
{
  RunLengthVolume<ShadedVoxel> empty;
  RunLengthVolume<ShadedVoxel> out;
  std::string error;
  EXPECT_FALSE(TransposeEncoding(empty, 1, out, error));
  EXPECT_FALSE(error.empty());
  RunLengthVolume<ShadedVoxel> one;
  one.axis = 2;
  one.sliceDims[0] = one.sliceDims[1] = one.sliceDims[2] = 1;
  one.rowStart = { 0, 0 };
  error.clear();
  EXPECT_FALSE(TransposeEncoding(one, 2, out, error));
  EXPECT_FALSE(error.empty());
  error.clear();
  EXPECT_TRUE(TransposeEncoding(one, 0, out, error)) << error;
  EXPECT_EQ(out.rowStart.size(), 2u);
  EXPECT_TRUE(out.runs.empty());
}

TEST(RunLengthVolume, BadInputFails)
{
  const std::uint8_t values[8] = { 0, 10, 20, 30, 40, 50, 60, 70 };
  VolumeView view;
  view.data = values;
  view.type = ScalarType::UInt8;
  view.dims[0] = view.dims[1] = view.dims[2] = 2;
  CompositeClassification c;
  c.rgba = { 0, 0, 0, 0, 1, 1, 1, 1 };
  c.rangeMax = 70;
  RunLengthVolume<ShadedVoxel> encoded;
  RunLengthVolume<ScalarVoxel> extreme;
  std::string error;
  ASSERT_TRUE(EncodeComposite(view, c, 2, false, SerialParallelFor, encoded, error)) << error;
  EXPECT_EQ(encoded.voxels.size(), 7u); // all but the zero voxel
  for (int axis : { -1, 3 })
  {
    error.clear();
    EXPECT_FALSE(EncodeComposite(view, c, axis, false, SerialParallelFor, encoded, error));
    EXPECT_FALSE(error.empty());
    error.clear();
    EXPECT_FALSE(
      EncodeExtreme(view, 0, 70, true, 0, axis, false, SerialParallelFor, extreme, error));
    EXPECT_FALSE(error.empty());
  }
  CompositeClassification shortTable = c;
  shortTable.rgba = { 1, 1, 1, 1 };
  error.clear();
  EXPECT_FALSE(EncodeComposite(view, shortTable, 0, false, SerialParallelFor, encoded, error));
  EXPECT_FALSE(error.empty());
  shortTable.rgba = { 1, 1, 1, 1, 1, 1 };
  error.clear();
  EXPECT_FALSE(EncodeComposite(view, shortTable, 0, false, SerialParallelFor, encoded, error));
  EXPECT_FALSE(error.empty());
  VolumeView empty = view;
  empty.dims[1] = 0;
  error.clear();
  EXPECT_FALSE(EncodeComposite(empty, c, 0, false, SerialParallelFor, encoded, error));
  EXPECT_FALSE(error.empty());
  error.clear();
  EXPECT_FALSE(EncodeExtreme(empty, 0, 70, false, 0, 0, false, SerialParallelFor, extreme, error));
  EXPECT_FALSE(error.empty());
  empty = view;
  empty.data = nullptr;
  error.clear();
  EXPECT_FALSE(EncodeComposite(empty, c, 0, false, SerialParallelFor, encoded, error));
  EXPECT_FALSE(error.empty());
}

TEST(RunLengthVolume, PaletteRefusesMoreThan65535DistinctVoxels)
{
  // Two full scanlines of 65536 distinct voxels in all (opacity and red vary), then one fewer.
  for (const int count : { 65536, 65535 })
  {
    const int half = 32768;
    RunLengthVolume<ShadedVoxel> encoded;
    encoded.axis = 2;
    encoded.sliceDims[0] = half;
    encoded.sliceDims[1] = 2;
    encoded.sliceDims[2] = 1;
    encoded.rowStart = { 0, 1, 2 };
    encoded.runs = { VoxelRun{ 0, half, 0 },
      VoxelRun{ 0, static_cast<std::uint16_t>(count - half), static_cast<std::uint32_t>(half) } };
    for (int n = 0; n < count; ++n)
    {
      const auto opacity = static_cast<std::uint16_t>(1 + n / 256);
      const auto red = static_cast<std::uint8_t>(n % 256);
      encoded.voxels.push_back(ShadedVoxel{ opacity, NoNormal, { red, 7, 9, 0 } });
    }
    const std::vector<ShadedVoxel> before = encoded.voxels;
    const bool assigned = AssignPalette(encoded, UnevenThreadedFor(3));
    EXPECT_EQ(assigned, count == 65535) << count;
    EXPECT_EQ(encoded.palette.size(), assigned ? 65535u : 0u);
    for (int n = 0; n < count; ++n)
    {
      const ShadedVoxel& got = encoded.StoredVoxel(static_cast<std::size_t>(n));
      ASSERT_EQ(got.opacity, before[n].opacity);
      ASSERT_EQ(got.colour[0], before[n].colour[0]);
      ASSERT_EQ(got.normal, NoNormal);
    }
  }
}
