// RayCastKernelPacketShade.inl: the ray packets' shading (included after
// RayCastKernelPackets.inl): the lanes' gradients, trilinearly interpolated from the precomputed
// gradient words or, for 8-bit volumes, from the voxels' central differences (the same values),
// then VTK's light model as ShadeBatchLanes computes it.

#if ACCELVOLUME_PACKETS

// Byte `i` of each lane's 32-bit word, as an integer.
ACCELVOLUME_AVX512 inline __m512i PacketByte(__m512i word, int i)
{
  return _mm512_and_si512(_mm512_srli_epi32(word, 8 * i), _mm512_set1_epi32(0xff));
}

// For 8-bit volumes whose gradients EncodeGradient keeps exact (half-value units: every central
// difference is an integer up to 255), the lanes `lanes` (cells with a voxel of margin) take the
// eight corners' central differences from the voxels instead of the gradient words: the same
// values, read from rows next to those the sample read (the gradient words, 4 bytes a voxel,
// miss the caches far more). g accumulates InterpolateGradient's sums in its order.
ACCELVOLUME_AVX512 inline void PacketVoxelGradients(const std::uint8_t* voxels, const __m512i& base,
  const __m512i sampleRows[4], int rowStride, int sliceStride, __mmask16 lanes, const __m512 wxy[4],
  const __m512 wz[2], __m512 g[3])
{
  // Rows (y + dy, z + dz), bytes x - 1 ... x + 2: window[dy + 1][dz + 1] for dy, dz in [-1, 2]
  // (the twelve the corners' differences read; the four corners of the 4 x 4 are unused). The
  // sample's own four rows came with its corners (PacketByteCorners, in PacketCorner's order).
  __m512i window[4][4];
  for (int dz = -1; dz <= 2; ++dz)
  {
    for (int dy = -1; dy <= 2; ++dy)
    {
      __m512i& row = window[dy + 1][dz + 1];
      if (dy >= 0 && dy <= 1 && dz >= 0 && dz <= 1)
      {
        row = sampleRows[dy + 2 * dz];
      }
      else if ((dy >= 0 && dy <= 1) || (dz >= 0 && dz <= 1))
      {
        const __m512i at =
          _mm512_add_epi32(base, _mm512_set1_epi32(dy * rowStride + dz * sliceStride - 1));
        row = _mm512_mask_i32gather_epi32(_mm512_setzero_si512(), lanes, at, voxels, 1);
      }
      else
      {
        row = _mm512_setzero_si512();
      }
    }
  }
  for (int c = 0; c < 8; ++c)
  {
    const int cx = c & 1, cy = (c >> 1) & 1, cz = c >> 2;
    const __m512i& row = window[cy + 1][cz + 1];
    const __m512 gx =
      _mm512_cvtepi32_ps(_mm512_sub_epi32(PacketByte(row, 2 + cx), PacketByte(row, cx)));
    const __m512 gy = _mm512_cvtepi32_ps(_mm512_sub_epi32(
      PacketByte(window[cy + 2][cz + 1], 1 + cx), PacketByte(window[cy][cz + 1], 1 + cx)));
    const __m512 gz = _mm512_cvtepi32_ps(_mm512_sub_epi32(
      PacketByte(window[cy + 1][cz + 2], 1 + cx), PacketByte(window[cy + 1][cz], 1 + cx)));
    const __m512 w = _mm512_mul_ps(wxy[c & 3], wz[c >> 2]);
    g[0] = _mm512_add_ps(g[0], _mm512_mul_ps(w, gx));
    g[1] = _mm512_add_ps(g[1], _mm512_mul_ps(w, gy));
    g[2] = _mm512_add_ps(g[2], _mm512_mul_ps(w, gz));
  }
}

// Shades the lanes' colours (ShadeBatchLanesIn's arithmetic) from their gradients.
template <typename T>
ACCELVOLUME_AVX512 void RayCasterTile<T>::PacketShade(__mmask16 lanes, const __m512i& base,
  __mmask16 interior, const __m512i sampleRows[4], const __m512 f[3], __m512 rgb[3])
{
  const KernelFrame& frame = this->Frame;
  const PacketRays& packet = this->Packet;
  const LightModel& model = frame.lighting->model;
  const std::uint32_t* gradients = frame.gradients;
  const __m512 one = _mm512_set1_ps(1.0f), zero = _mm512_setzero_ps();
  const __m512 wx[2] = { _mm512_sub_ps(one, f[0]), f[0] };
  const __m512 wy[2] = { _mm512_sub_ps(one, f[1]), f[1] };
  const __m512 wz[2] = { _mm512_sub_ps(one, f[2]), f[2] };
  __m512 g[3] = { zero, zero, zero };
  const __m512 wxy[4] = { _mm512_mul_ps(wx[0], wy[0]), _mm512_mul_ps(wx[1], wy[0]),
    _mm512_mul_ps(wx[0], wy[1]), _mm512_mul_ps(wx[1], wy[1]) };
  __mmask16 fromVoxels = 0;
  if constexpr (std::is_same<T, std::uint8_t>::value)
  {
    if (this->PacketGradientsFromVoxels)
    {
      fromVoxels = lanes & interior;
      if (fromVoxels)
      {
        __m512 fromRows[3] = { zero, zero, zero };
        PacketVoxelGradients(this->Sampling.Voxels(), base, sampleRows, frame.volume.dims[0],
          frame.volume.dims[0] * frame.volume.dims[1], fromVoxels, wxy, wz, fromRows);
        for (int a = 0; a < 3; ++a)
        {
          g[a] = _mm512_maskz_mov_ps(fromVoxels, fromRows[a]); // the others' rows are not theirs
        }
      }
    }
  }
  const __mmask16 fromWords = lanes & ~fromVoxels;
  for (int c = 0; c < 8 && fromWords; c += 2)
  {
    // Corners c and c + 1 (x neighbours) as one 64-bit load per lane, the lanes not shaded
    // left out.
    const __m512i at =
      _mm512_add_epi32(base, _mm512_set1_epi32(static_cast<int>(this->PacketCorner[c])));
    const __m512i low = _mm512_mask_i32gather_epi64(_mm512_setzero_si512(),
      static_cast<__mmask8>(fromWords), _mm512_castsi512_si256(at), gradients, 4);
    const __m512i high = _mm512_mask_i32gather_epi64(_mm512_setzero_si512(),
      static_cast<__mmask8>(fromWords >> 8), _mm512_extracti64x4_epi64(at, 1), gradients, 4);
    __m512i words[2];
    PacketSplitWords(low, high, words[0], words[1]);
    for (int k = 0; k < 2; ++k)
    {
      // InterpolateGradient's weight (wx * wy) * wz and DecodeGradient.
      const __m512 w = _mm512_mul_ps(wxy[(c + k) & 3], wz[(c + k) >> 2]);
      const __m512 scale = _mm512_castsi512_ps(_mm512_slli_epi32(
        _mm512_add_epi32(_mm512_and_si512(_mm512_srli_epi32(words[k], 29), _mm512_set1_epi32(6)),
          _mm512_set1_epi32(127)),
        23)); // 2^(2e)
      const __m512 gx = _mm512_mul_ps(
        _mm512_cvtepi32_ps(_mm512_srai_epi32(_mm512_slli_epi32(words[k], 22), 22)), scale);
      const __m512 gy = _mm512_mul_ps(
        _mm512_cvtepi32_ps(_mm512_srai_epi32(_mm512_slli_epi32(words[k], 12), 22)), scale);
      const __m512 gz = _mm512_mul_ps(
        _mm512_cvtepi32_ps(_mm512_srai_epi32(_mm512_slli_epi32(words[k], 2), 22)), scale);
      g[0] = _mm512_mask_add_ps(g[0], fromWords, g[0], _mm512_mul_ps(w, gx));
      g[1] = _mm512_mask_add_ps(g[1], fromWords, g[1], _mm512_mul_ps(w, gy));
      g[2] = _mm512_mask_add_ps(g[2], fromWords, g[2], _mm512_mul_ps(w, gz));
    }
  }
  const float(*m)[3] = frame.normalMatrix;
  __m512 eye[3];
  for (int r = 0; r < 3; ++r)
  {
    eye[r] = _mm512_add_ps(_mm512_add_ps(_mm512_mul_ps(_mm512_set1_ps(m[r][0]), g[0]),
                             _mm512_mul_ps(_mm512_set1_ps(m[r][1]), g[1])),
      _mm512_mul_ps(_mm512_set1_ps(m[r][2]), g[2]));
  }
  const __m512 squared =
    _mm512_add_ps(_mm512_add_ps(_mm512_mul_ps(eye[0], eye[0]), _mm512_mul_ps(eye[1], eye[1])),
      _mm512_mul_ps(eye[2], eye[2]));
  const __m512 tiny = _mm512_set1_ps(1.0e-16f);
  const __m512 candidate =
    _mm512_div_ps(_mm512_set1_ps(-1.0f), _mm512_sqrt_ps(PacketMax(squared, tiny)));
  const __m512 inverse =
    _mm512_maskz_mov_ps(_mm512_cmp_ps_mask(squared, tiny, _CMP_GT_OQ), candidate);
  const __m512 normal[3] = { _mm512_mul_ps(eye[0], inverse), _mm512_mul_ps(eye[1], inverse),
    _mm512_mul_ps(eye[2], inverse) };
  __m512 diffuse[3] = { zero, zero, zero }, specular[3] = { zero, zero, zero };
  float ambient[3] = { 0, 0, 0 };
  const int size = frame.specularTableSize;
  std::size_t index = 0;
  for (const SceneLight& light : model.lights)
  {
    const float(*l)[16] = packet.toLight[index];
    const float(*h)[16] = packet.half[index++];
    __m512 nDotL = _mm512_add_ps(_mm512_add_ps(_mm512_mul_ps(normal[0], _mm512_load_ps(l[0])),
                                   _mm512_mul_ps(normal[1], _mm512_load_ps(l[1]))),
      _mm512_mul_ps(normal[2], _mm512_load_ps(l[2])));
    __m512 nDotH = _mm512_add_ps(_mm512_add_ps(_mm512_mul_ps(normal[0], _mm512_load_ps(h[0])),
                                   _mm512_mul_ps(normal[1], _mm512_load_ps(h[1]))),
      _mm512_mul_ps(normal[2], _mm512_load_ps(h[2])));
    if (model.twoSided)
    {
      nDotL = _mm512_abs_ps(nDotL);
      nDotH = _mm512_abs_ps(nDotH);
    }
    const __m512 lit = PacketMax(nDotL, zero);
    const __m512 x = PacketMin(PacketMax(nDotH, zero), one);
    const __m512 u = _mm512_mul_ps(x, _mm512_set1_ps(static_cast<float>(size - 1)));
    // Clamped below too: lanes not sampling (their light vectors unset) must stay in the table.
    const __m512i k =
      _mm512_max_epi32(_mm512_min_epi32(_mm512_cvttps_epi32(u), _mm512_set1_epi32(size - 2)),
        _mm512_setzero_si512());
    const __m512 highlight =
      PacketLerpPairs(frame.specularPairs, k, _mm512_sub_ps(u, _mm512_cvtepi32_ps(k)), lanes);
    const __m512 term = _mm512_maskz_mov_ps(_mm512_cmp_ps_mask(nDotH, zero, _CMP_GT_OQ), highlight);
    for (int c = 0; c < 3; ++c)
    {
      ambient[c] += light.ambient[c];
      diffuse[c] = _mm512_add_ps(diffuse[c], _mm512_mul_ps(lit, _mm512_set1_ps(light.diffuse[c])));
      specular[c] =
        _mm512_add_ps(specular[c], _mm512_mul_ps(term, _mm512_set1_ps(light.specular[c])));
    }
  }
  for (int c = 0; c < 3; ++c)
  {
    const float base = model.ambient * (model.headlightOnly ? 1.0f : ambient[c]);
    const __m512 factor =
      _mm512_add_ps(_mm512_set1_ps(base), _mm512_mul_ps(_mm512_set1_ps(model.diffuse), diffuse[c]));
    const __m512 highlight = _mm512_mul_ps(_mm512_set1_ps(model.specular), specular[c]);
    rgb[c] = PacketMin(_mm512_add_ps(_mm512_mul_ps(rgb[c], factor), highlight), one);
  }
}

#endif
