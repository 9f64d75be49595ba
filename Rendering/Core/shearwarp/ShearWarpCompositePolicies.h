// The per-blend parts of shear-warp compositing (ShearWarpCompositor.cxx's band loop is a
// template over them): how a stored voxel becomes a resampling cell and how a sample composites
// into a pixel. Private to the compositor.
#ifndef accelvolume_ShearWarpCompositePolicies_h
#define accelvolume_ShearWarpCompositePolicies_h

#include "shearwarp/RunLengthVolume.h"
#include "shearwarp/ShearWarpCompositor.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace accelvolume
{
namespace compositing
{

// Premultiplied colours of classified voxels with the frame's tables, for a run of voxels at a
// time: the tables' pointers and modes are copied into locals once, so that the cell stores
// cannot make the compiler reload them for every voxel.
class VoxelShader
{
public:
  explicit VoxelShader(const CompositeTables& t)
    : Tables(t)
    , Opacity(t.opacity.data())
    , Shading(t.shading.data())
    , Shade(t.shade)
    // Unshaded and white-light table shading (the common cases) take one SSE register.
    , OneRegister(!t.shade || (!t.phong && t.shadingStride == 2))
  {
  }

  void operator()(const ShadedVoxel* voxel, int count, float* out) const
  {
#if defined(__SSE2__)
    if (this->OneRegister)
    {
      for (int n = 0; n < count; ++n, out += 4)
      {
        this->OnOneRegister(voxel[n], out);
      }
      return;
    }
#endif
    for (int n = 0; n < count; ++n, out += 4)
    {
      this->General(voxel[n], out);
    }
  }

private:
#if defined(__SSE2__)
  // The scalar code's operations per channel, so the same values.
  void OnOneRegister(const ShadedVoxel& voxel, float out[4]) const
  {
    const float opacity = this->Opacity[voxel.opacity];
    if (opacity <= 0)
    {
      _mm_storeu_ps(out, _mm_setzero_ps());
      return;
    }
    std::uint32_t bytes;
    std::memcpy(&bytes, voxel.colour, sizeof(bytes));
    const __m128i zero = _mm_setzero_si128();
    const __m128i channels =
      _mm_unpacklo_epi16(_mm_unpacklo_epi8(_mm_cvtsi32_si128(static_cast<int>(bytes)), zero), zero);
    __m128 rgb = _mm_mul_ps(_mm_cvtepi32_ps(channels), _mm_set1_ps(1.0f / 255.0f));
    if (this->Shade)
    {
      const std::size_t row = voxel.normal == NoNormal ? NormalCodes : voxel.normal;
      const float* s = this->Shading + 2 * row;
      rgb = _mm_min_ps(
        _mm_add_ps(_mm_mul_ps(rgb, _mm_set1_ps(s[0])), _mm_set1_ps(s[1])), _mm_set1_ps(1.0f));
    }
    _mm_storeu_ps(out, _mm_mul_ps(rgb, _mm_set1_ps(opacity)));
    out[3] = opacity;
  }
#endif

  void General(const ShadedVoxel& voxel, float out[4]) const
  {
    const CompositeTables& t = this->Tables;
    const float opacity = this->Opacity[voxel.opacity];
    if (opacity <= 0)
    {
      out[0] = out[1] = out[2] = out[3] = 0;
      return;
    }
    constexpr float toUnit = 1.0f / 255.0f;
    float rgb[3] = { voxel.colour[0] * toUnit, voxel.colour[1] * toUnit, voxel.colour[2] * toUnit };
    if (t.shade && !t.phong)
    {
      const std::size_t row = voxel.normal == NoNormal ? NormalCodes : voxel.normal;
      const float* s = this->Shading + static_cast<std::size_t>(t.shadingStride) * row;
      if (t.shadingStride == 2)
      {
        for (float& channel : rgb)
        {
          channel = std::min(channel * s[0] + s[1], 1.0f);
        }
      }
      else
      {
        for (int c = 0; c < 3; ++c)
        {
          rgb[c] = std::min(rgb[c] * s[c] + s[c + 3], 1.0f);
        }
      }
    }
    else if (t.shade)
    {
      float factor[3];
      float specular[3];
      AmbientTerms(t.lighting, factor, specular);
      if (voxel.normal != NoNormal)
      {
        float g[3];
        DecodeNormal(voxel.normal, g);
        PhongTerms(t, g, factor, specular);
      }
      for (int c = 0; c < 3; ++c)
      {
        rgb[c] = std::min(rgb[c] * factor[c] + specular[c], 1.0f);
      }
    }
    out[0] = rgb[0] * opacity;
    out[1] = rgb[1] * opacity;
    out[2] = rgb[2] * opacity;
    out[3] = opacity;
  }

  const CompositeTables& Tables;
  const float* Opacity;
  const float* Shading;
  bool Shade;
  bool OneRegister;
};

// Compositing of one blend, as a policy for the compositor's band loop.
struct CompositePolicy
{
  using Voxel = ShadedVoxel;
  static constexpr int Channels = 4;
  const CompositeTables& tables;
  VoxelShader shader; // of tables, made once per band
  // The encoding's stored voxels: its voxels, or with a palette their palette indices, from
  // which cells copy precomputed colours (unshaded tables) or convert the palette's voxels.
  const ShadedVoxel* voxels = nullptr;
  const std::uint16_t* paletteIndices = nullptr;
  const ShadedVoxel* palette = nullptr;
  const float* paletteColours = nullptr;
  float threshold = 1; // tables.terminationThreshold
  // `count` cells of no voxel. Most gaps are a few cells, for which a call to memset (what
  // compilers turn a plain clearing loop into) costs more than the stores: those are unrolled.
  void Clear(float* cells, int count) const
  {
    constexpr std::size_t cellBytes = 4 * sizeof(float);
    switch (count)
    {
      case 4:
        std::memset(cells + 12, 0, cellBytes);
        [[fallthrough]];
      case 3:
        std::memset(cells + 8, 0, cellBytes);
        [[fallthrough]];
      case 2:
        std::memset(cells + 4, 0, cellBytes);
        [[fallthrough]];
      case 1:
        std::memset(cells, 0, cellBytes);
        [[fallthrough]];
      case 0:
        return;
      default:
        std::memset(cells, 0, cellBytes * static_cast<std::size_t>(count));
    }
  }
  // Cells for `count` consecutive stored voxels from the one at `offset`.
  void Load(std::size_t offset, int count, float* cells) const
  {
    if (this->paletteColours)
    {
      const std::uint16_t* index = this->paletteIndices + offset;
      for (int n = 0; n < count; ++n)
      {
        std::memcpy(cells + 4 * n, this->paletteColours + 4 * static_cast<std::size_t>(index[n]),
          4 * sizeof(float));
      }
      return;
    }
    if (this->paletteIndices)
    {
      const std::uint16_t* index = this->paletteIndices + offset;
      for (int n = 0; n < count; ++n)
      {
        this->shader(this->palette + index[n], 1, cells + 4 * n);
      }
      return;
    }
    this->shader(this->voxels + offset, count, cells);
  }
  // A hint to start loading what Load reads for the stored voxel at `offset`.
  void Prefetch(std::size_t offset) const
  {
    if (this->paletteIndices)
    {
      __builtin_prefetch(this->paletteIndices + offset);
      return;
    }
    __builtin_prefetch(this->voxels + offset);
  }
  // Resamples the four corners (a: row j0 at i0, i0 + 1; b: row j0 + 1) and composites "over"
  // the pixel; true once the pixel is saturated.
  bool Sample(const float* a, const float* b, const float* w, float* pixel) const
  {
#if defined(__SSE2__)
    // One RGBA pixel per SSE register; same operation order as the scalar code below.
    const __m128 sample = _mm_add_ps(
      _mm_add_ps(_mm_add_ps(_mm_mul_ps(_mm_set1_ps(w[0]), _mm_loadu_ps(a)),
                   _mm_mul_ps(_mm_set1_ps(w[1]), _mm_loadu_ps(a + 4))),
        _mm_mul_ps(_mm_set1_ps(w[2]), _mm_loadu_ps(b))),
      _mm_mul_ps(_mm_set1_ps(w[3]), _mm_loadu_ps(b + 4)));
    const float transmit = 1.0f - pixel[3];
    const __m128 result =
      _mm_add_ps(_mm_loadu_ps(pixel), _mm_mul_ps(_mm_set1_ps(transmit), sample));
    _mm_storeu_ps(pixel, result);
#else
    float sample[4];
    for (int c = 0; c < 4; ++c)
    {
      sample[c] = ((w[0] * a[c] + w[1] * a[4 + c]) + w[2] * b[c]) + w[3] * b[4 + c];
    }
    const float transmit = 1.0f - pixel[3];
    for (int c = 0; c < 4; ++c)
    {
      pixel[c] += transmit * sample[c];
    }
#endif
    return pixel[3] >= this->threshold;
  }
};

struct ExtremePolicy
{
  using Voxel = ScalarVoxel;
  static constexpr int Channels = 1;
  bool maximum;
  float saturation;
  const ScalarVoxel* voxels; // the encoding's
  // A corner that is not stored is +-inf, which drops every sample it weighs.
  float Empty() const
  {
    return this->maximum ? -std::numeric_limits<float>::infinity()
                         : std::numeric_limits<float>::infinity();
  }
  void Clear(float* cells, int count) const { std::fill(cells, cells + count, this->Empty()); }
  void Load(std::size_t offset, int count, float* cells) const
  {
    const ScalarVoxel* voxel = this->voxels + offset;
    for (int n = 0; n < count; ++n)
    {
      cells[n] = static_cast<float>(voxel[n]);
    }
  }
  void Prefetch(std::size_t offset) const { __builtin_prefetch(this->voxels + offset); }
  bool Sample(const float* a, const float* b, const float* w, float* pixel) const
  {
    float sample = 0;
    sample += w[0] > 0 ? w[0] * a[0] : 0.0f;
    sample += w[1] > 0 ? w[1] * a[1] : 0.0f;
    sample += w[2] > 0 ? w[2] * b[0] : 0.0f;
    sample += w[3] > 0 ? w[3] * b[1] : 0.0f;
    if (this->maximum)
    {
      *pixel = std::max(*pixel, sample);
      return *pixel >= this->saturation;
    }
    *pixel = std::min(*pixel, sample);
    return *pixel <= this->saturation;
  }
};

}
}

#endif
