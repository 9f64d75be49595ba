// RayCastKernelPacketRays.inl: the rays of a packet's pixels set up eight lanes at a time in
// AVX-512 registers, included after RayCasterTile. One ray at a time, setting a ray up
// (SetPixelRay, Intervals, IntervalSamples, LightRay, FixedSteps, LeapSteps) is a chain of
// dependent divisions and square roots that costs about as much as casting an opaque ray; here
// every lane performs those functions' operations in the same order (no FMA contraction), so
// each ray gets the same bits. Frames with scene depth, several crop regions or lights other
// than directional ones and the headlight set their rays up one by one (AddToPacket).

#if ACCELVOLUME_PACKETS

// Whether the frame's packets may set their rays up together (SetUpPacketRays).
inline bool PacketRaysApply(const KernelFrame& frame, const RayCastSettings& settings)
{
  if (frame.view->depth != nullptr || settings.regions.size() != 1)
  {
    return false;
  }
  const RayCastLighting& lighting = *frame.lighting;
  if (!lighting.shade)
  {
    return true;
  }
  // FixLights' cases that fix a light on every ray of the frame.
  const bool eyeFixed = frame.raysThroughEye || frame.eyeLightsAtEntry;
  return lighting.model.lights.size() <= MaximumRayLights &&
    std::all_of(lighting.model.lights.begin(), lighting.model.lights.end(),
      [eyeFixed](const SceneLight& light)
      { return !light.positional || (eyeFixed && IsEyeLight(light)); });
}

namespace packet_rays
{
using Lanes = __m512d;

ACCELVOLUME_AVX512 inline Lanes Set(double x)
{
  return _mm512_set1_pd(x);
}

ACCELVOLUME_AVX512 inline Lanes Negate(Lanes a)
{
  return _mm512_xor_pd(a, _mm512_set1_pd(-0.0));
}

// (m[0] * x + m[1] * y) + m[2] * z: Affine::ApplyLinear's and Dot's order.
ACCELVOLUME_AVX512 inline Lanes Linear(const double* m, Lanes x, Lanes y, Lanes z)
{
  return _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(Set(m[0]), x), _mm512_mul_pd(Set(m[1]), y)),
    _mm512_mul_pd(Set(m[2]), z));
}

// ((m[0] * x + m[1] * y) + m[2] * z) + m[3]: a row of Unproject or Affine::Apply.
ACCELVOLUME_AVX512 inline Lanes Row(const double* m, Lanes x, Lanes y, Lanes z)
{
  return _mm512_add_pd(Linear(m, x, y, z), Set(m[3]));
}

ACCELVOLUME_AVX512 inline Lanes SquaredLength(const Lanes v[3])
{
  return _mm512_add_pd(
    _mm512_add_pd(_mm512_mul_pd(v[0], v[0]), _mm512_mul_pd(v[1], v[1])), _mm512_mul_pd(v[2], v[2]));
}

// std::floor(x) as an int64 (static_cast's truncation of an integral value).
ACCELVOLUME_AVX512 inline __m512i FloorToInt(Lanes x)
{
  return _mm512_cvttpd_epi64(_mm512_roundscale_pd(x, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC));
}

ACCELVOLUME_AVX512 inline __m512i CeilToInt(Lanes x)
{
  return _mm512_cvttpd_epi64(_mm512_roundscale_pd(x, _MM_FROUND_TO_POS_INF | _MM_FROUND_NO_EXC));
}

// FixedSteps::ToFixed.
ACCELVOLUME_AVX512 inline __m512i ToFixed(Lanes x)
{
  constexpr double Limit = 1073741824.0;
  const Lanes below =
    _mm512_mask_blend_pd(_mm512_cmp_pd_mask(x, Set(Limit), _CMP_LT_OQ), Set(Limit), x);
  const Lanes c =
    _mm512_mask_blend_pd(_mm512_cmp_pd_mask(x, Set(-Limit), _CMP_GT_OQ), Set(-Limit), below);
  return FloorToInt(_mm512_add_pd(_mm512_mul_pd(c, Set(FixedSteps::Scale)), Set(0.5)));
}

// IntersectRayRegion's slab narrowing (std::max / std::min as it evaluates them, NaN included).
struct Slab
{
  Lanes enter, leave;
  __mmask8 ok;

  ACCELVOLUME_AVX512 void NarrowBy(Lanes rate, Lanes value)
  {
    const Lanes t = _mm512_div_pd(Negate(value), rate);
    const __mmask8 positive = _mm512_cmp_pd_mask(rate, _mm512_setzero_pd(), _CMP_GT_OQ);
    const __mmask8 negative = _mm512_cmp_pd_mask(rate, _mm512_setzero_pd(), _CMP_LT_OQ);
    this->enter = _mm512_mask_max_pd(this->enter, positive, t, this->enter);
    this->leave = _mm512_mask_min_pd(this->leave, negative, t, this->leave);
    const __mmask8 outside = static_cast<__mmask8>(~(positive | negative)) &
      _mm512_cmp_pd_mask(value, _mm512_setzero_pd(), _CMP_LT_OQ);
    this->ok &=
      static_cast<__mmask8>(~outside) & _mm512_cmp_pd_mask(this->enter, this->leave, _CMP_LE_OQ);
  }
};

// IntersectRayRegion for eight rays: the lanes that meet the region, their [enter, leave].
ACCELVOLUME_AVX512 inline __mmask8 Intersect(const Lanes o[3], const Lanes d[3], const Box& box,
  const std::vector<HalfSpace>& clip, Lanes& enter, Lanes& leave)
{
  if (box.IsEmpty())
  {
    return 0;
  }
  const double lower[3] = { box.lower.x, box.lower.y, box.lower.z };
  const double upper[3] = { box.upper.x, box.upper.y, box.upper.z };
  Slab slab{ Set(-std::numeric_limits<double>::infinity()),
    Set(std::numeric_limits<double>::infinity()), 0xff };
  for (int a = 0; a < 3; ++a)
  {
    slab.NarrowBy(d[a], _mm512_add_pd(o[a], Set(-lower[a])));
    slab.NarrowBy(Negate(d[a]), _mm512_add_pd(Negate(o[a]), Set(upper[a])));
  }
  for (const HalfSpace& halfSpace : clip)
  {
    const double n[4] = { halfSpace.normal.x, halfSpace.normal.y, halfSpace.normal.z, 0 };
    slab.NarrowBy(Linear(n, d[0], d[1], d[2]),
      _mm512_add_pd(Linear(n, o[0], o[1], o[2]), Set(halfSpace.offset)));
  }
  enter = slab.enter;
  leave = slab.leave;
  return slab.ok;
}

// FixLights' half vector of every light (floats): normalize(toLight + toViewer).
ACCELVOLUME_AVX512 inline void HalfVector(
  const __m256 toLight[3], const __m256 toViewer[3], float* half[3], int at)
{
  __m256 h[3];
  for (int c = 0; c < 3; ++c)
  {
    h[c] = _mm256_add_ps(toLight[c], toViewer[c]);
  }
  const __m256 length = _mm256_sqrt_ps(
    _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(h[0], h[0]), _mm256_mul_ps(h[1], h[1])),
      _mm256_mul_ps(h[2], h[2])));
  const __m256 inverse = _mm256_maskz_div_ps(
    _mm256_cmp_ps_mask(length, _mm256_setzero_ps(), _CMP_GT_OQ), _mm256_set1_ps(1.0f), length);
  for (int c = 0; c < 3; ++c)
  {
    _mm256_store_ps(half[c] + at, _mm256_mul_ps(h[c], inverse));
  }
}
} // namespace packet_rays

// LightRay for lanes [at, at + 8): LightPixelRay's direction to the viewer and FixLights'
// lights (directional ones, the headlight through the eye or from the entry point at t0).
ACCELVOLUME_AVX512 inline void LightPacketRayLanes(const KernelFrame& frame,
  const packet_rays::Lanes o[3], const packet_rays::Lanes d[3], packet_rays::Lanes t0,
  PacketCandidates& rays, int at)
{
  using namespace packet_rays;
  const RayCastLighting& lighting = *frame.lighting;
  // LightRay: LightPixelRay's direction to the viewer, FixLights' lights.
  Lanes eye[3];
  for (int r = 0; r < 3; ++r)
  {
    const double m[3] = { lighting.indexToEye[r][0], lighting.indexToEye[r][1],
      lighting.indexToEye[r][2] };
    eye[r] = Linear(m, d[0], d[1], d[2]);
  }
  const Lanes eyeLength = _mm512_sqrt_pd(SquaredLength(eye));
  const Lanes eyeInverse = _mm512_maskz_div_pd(
    _mm512_cmp_pd_mask(eyeLength, _mm512_setzero_pd(), _CMP_GT_OQ), Set(1.0), eyeLength);
  __m256 toViewer[3];
  for (int r = 0; r < 3; ++r)
  {
    toViewer[r] = _mm512_cvtpd_ps(_mm512_mul_pd(Negate(eye[r]), eyeInverse));
  }
  __m256 fromEntry[3]; // towards a light at the eye from the entry point (eyeLightsAtEntry)
  if (frame.eyeLightsAtEntry)
  {
    Lanes entry[3], entryEye[3];
    for (int a = 0; a < 3; ++a)
    {
      entry[a] = _mm512_add_pd(o[a], _mm512_mul_pd(t0, d[a]));
    }
    for (int r = 0; r < 3; ++r)
    {
      const double m[4] = { lighting.indexToEye[r][0], lighting.indexToEye[r][1],
        lighting.indexToEye[r][2], lighting.indexToEyeOffset[r] };
      entryEye[r] = Row(m, entry[0], entry[1], entry[2]);
    }
    const Lanes distance = _mm512_sqrt_pd(SquaredLength(entryEye));
    const __mmask8 away = _mm512_cmp_pd_mask(distance, _mm512_setzero_pd(), _CMP_GT_OQ);
    for (int c = 0; c < 3; ++c)
    {
      fromEntry[c] = _mm512_cvtpd_ps(_mm512_maskz_div_pd(away, Negate(entryEye[c]), distance));
    }
  }
  std::size_t index = 0;
  for (const SceneLight& light : lighting.model.lights)
  {
    __m256 toLight[3];
    for (int c = 0; c < 3; ++c)
    {
      toLight[c] = !light.positional ? _mm256_set1_ps(-light.axis[c])
                                     : (frame.raysThroughEye ? toViewer[c] : fromEntry[c]);
      _mm256_store_ps(rays.toLight[index][c] + at, toLight[c]);
    }
    float* half[3] = { rays.half[index][0], rays.half[index][1], rays.half[index][2] };
    HalfVector(toLight, toViewer, half, at);
    ++index;
  }
}

// The rays of lanes [at, at + 8) of `rays` from their pixel centres (PacketCandidates).
ACCELVOLUME_AVX512 inline void SetUpPacketRayLanes(
  const KernelFrame& frame, const RayCastSettings& settings, PacketCandidates& rays, int at)
{
  using namespace packet_rays;
  const RayCastView& view = *frame.view;
  const Lanes x = _mm512_load_pd(rays.x + at), y = _mm512_load_pd(rays.y + at);
  // SetPixelRay: Unproject at the near and far planes, the normalised direction, index space.
  Lanes nearPoint[3], farPoint[3];
  for (int side = 0; side < 2; ++side)
  {
    const Lanes z = Set(side == 0 ? -1.0 : 1.0);
    Lanes* out = side == 0 ? nearPoint : farPoint;
    const Lanes inverse = _mm512_div_pd(Set(1.0), Row(view.clipToWorld[3], x, y, z));
    for (int r = 0; r < 3; ++r)
    {
      out[r] = _mm512_mul_pd(Row(view.clipToWorld[r], x, y, z), inverse);
    }
  }
  Lanes along[3];
  for (int a = 0; a < 3; ++a)
  {
    along[a] = _mm512_sub_pd(farPoint[a], nearPoint[a]);
  }
  const Lanes length = _mm512_sqrt_pd(SquaredLength(along));
  const __mmask8 nonZero = _mm512_cmp_pd_mask(length, _mm512_setzero_pd(), _CMP_GT_OQ);
  const Lanes scale = _mm512_div_pd(Set(1.0), length);
  Lanes world[3];
  for (int a = 0; a < 3; ++a)
  {
    world[a] = _mm512_maskz_mul_pd(nonZero, along[a], scale);
  }
  Lanes o[3], d[3];
  for (int r = 0; r < 3; ++r)
  {
    o[r] = Row(view.worldToIndex.m[r], nearPoint[0], nearPoint[1], nearPoint[2]);
    d[r] = Linear(view.worldToIndex.m[r], world[0], world[1], world[2]);
  }
  // Intervals (one region) and ClipRayToRegion (no scene depth: the ray's end is infinite).
  Lanes t0, t1;
  __mmask8 hits = Intersect(o, d, settings.regions.front(), settings.clip, t0, t1);
  t0 = _mm512_max_pd(_mm512_setzero_pd(), t0);
  t1 = _mm512_min_pd(Set(std::numeric_limits<double>::infinity()), t1);
  hits &= _mm512_cmp_pd_mask(t0, t1, _CMP_LE_OQ) &
    _mm512_cmp_pd_mask(_mm512_abs_pd(t1), Set(std::numeric_limits<double>::infinity()), _CMP_LT_OQ);
  // IntervalSamples and OpaqueSamples.
  const double h = settings.sampleDistance;
  const __m512i count =
    FloorToInt(_mm512_add_pd(_mm512_div_pd(_mm512_sub_pd(t1, t0), Set(h)), Set(0.5)));
  __m512i first = _mm512_setzero_si512(), last = count, cut = _mm512_setzero_si512();
  if (frame.useOpaqueBox)
  {
    static const std::vector<HalfSpace> noClip;
    Lanes enter, leave;
    const __mmask8 meets = Intersect(o, d, frame.opaqueBox, noClip, enter, leave);
    const __m512i from = _mm512_max_epi64(_mm512_setzero_si512(),
      FloorToInt(_mm512_sub_pd(_mm512_div_pd(_mm512_sub_pd(enter, t0), Set(h)), Set(0.5))));
    const __m512i to = _mm512_min_epi64(count,
      _mm512_add_epi64(
        CeilToInt(_mm512_sub_pd(_mm512_div_pd(_mm512_sub_pd(leave, t0), Set(h)), Set(0.5))),
        _mm512_set1_epi64(1)));
    first = _mm512_mask_blend_epi64(meets, count, _mm512_min_epi64(from, count));
    last = _mm512_mask_blend_epi64(meets, count, _mm512_max_epi64(to, first));
    cut = _mm512_add_epi64(first, _mm512_sub_epi64(count, last));
  }
  _mm512_store_si512(rays.first + at, first);
  _mm512_store_si512(rays.last + at, last);
  _mm512_store_si512(rays.cut + at, cut);
  // FixedSteps and LeapSteps.
  const Lanes t = _mm512_add_pd(t0, _mm512_mul_pd(Set(0.5), Set(h)));
  for (int a = 0; a < 3; ++a)
  {
    const Lanes step = _mm512_mul_pd(d[a], Set(h));
    _mm512_store_pd(rays.direction[a] + at, d[a]);
    _mm512_store_si512(rays.start[a] + at, ToFixed(_mm512_add_pd(o[a], _mm512_mul_pd(t, d[a]))));
    _mm512_store_si512(rays.step[a] + at, ToFixed(step));
    const __mmask8 moves = _mm512_cmp_pd_mask(step, _mm512_setzero_pd(), _CMP_NEQ_UQ);
    _mm512_store_pd(
      rays.inverse[a] + at, _mm512_maskz_div_pd(moves, Set(1.0), _mm512_abs_pd(step)));
    const __mmask8 forward = _mm512_cmp_pd_mask(step, _mm512_setzero_pd(), _CMP_GT_OQ);
    _mm256_store_ps(rays.forward[a] + at, _mm256_maskz_mov_ps(forward, _mm256_set1_ps(1.0f)));
  }
  rays.hits |= static_cast<std::uint32_t>(hits) << at;
  if (frame.lighting->shade)
  {
    LightPacketRayLanes(frame, o, d, t0, rays, at);
  }
}

// The rays of the 16 lanes' pixel centres (rays.x, rays.y).
ACCELVOLUME_AVX512 inline void SetUpPacketRays(
  const KernelFrame& frame, const RayCastSettings& settings, PacketCandidates& rays)
{
  rays.hits = 0;
  SetUpPacketRayLanes(frame, settings, rays, 0);
  SetUpPacketRayLanes(frame, settings, rays, 8);
}

// CastRowsInPackets' block of pixels [block, blockEnd) x rows [j0, j1) with the rays set up
// together: the same pixels, counters and packets as AddToPacket one pixel at a time. Returns
// the packet's new lane count.
template <typename T>
int RayCasterTile<T>::AddBlockToPackets(int n, const PacketBlock& block, float* rgba)
{
  const KernelFrame& frame = this->Frame;
  const int width = frame.view->width;
  PacketCandidates& rays = this->Candidates;
  const int columns = block.x1 - block.x0;
  const int pixels = columns * (block.j1 - block.j0);
  for (int l = 0; l < PacketSize; ++l)
  {
    const int k = std::min(l, pixels - 1); // lanes past the block repeat its last pixel (unused)
    rays.x[l] = this->ColumnCentres[block.x0 + k % columns - block.tileX0];
    rays.y[l] = block.rowCentres[k / columns];
  }
  SetUpPacketRays(frame, this->Settings, rays);
  PacketRays& packet = this->Packet;
  const std::size_t lights = frame.lighting->shade ? frame.lighting->model.lights.size() : 0;
  for (int j = block.j0; j < block.j1; ++j)
  {
    const std::uint8_t* covered = block.covered[j - block.j0];
    for (int i = block.x0; i < block.x1; ++i)
    {
      const int l = (j - block.j0) * columns + (i - block.x0);
      float* out = rgba + 4 * (static_cast<std::size_t>(j) * width + i);
      if (covered && !covered[i >> FootprintBlockShift])
      {
        out[0] = out[1] = out[2] = out[3] = 0.0f;
        ++this->Counters.culledPixels;
        continue;
      }
      if (!(rays.hits >> l & 1))
      {
        out[0] = out[1] = out[2] = out[3] = 0.0f;
        continue;
      }
      const std::uint8_t* distance = this->DistanceMapOf(
        Vec3{ rays.direction[0][l], rays.direction[1][l], rays.direction[2][l] });
      if (n > 0 && distance != packet.distance)
      {
        // Another octant's map than the packet's: one ray at a time.
        PixelRay& pixel = this->GroupPixels[0];
        SetPixelRay(frame, i, j, rays.x[l], rays.y[l], pixel);
        this->Intervals(pixel.index, this->RayIntervals);
        this->RayStart = WalkStart();
        this->CastFromStart(pixel, out);
        continue;
      }
      ++this->Counters.rays;
      this->Counters.leapedDistance += static_cast<std::uint64_t>(rays.cut[l]);
      if (rays.first[l] >= rays.last[l])
      {
        out[0] = out[1] = out[2] = out[3] = 0.0f;
        continue;
      }
      packet.distance = distance;
      for (int a = 0; a < 3; ++a)
      {
        packet.start[a][n] = rays.start[a][l];
        packet.step[a][n] = rays.step[a][l];
        packet.inverse[a][n] = rays.inverse[a][l];
        packet.forward[a][n] = rays.forward[a][l];
      }
      packet.sample[n] = rays.first[l];
      packet.last[n] = rays.last[l];
      packet.out[n] = out;
      for (std::size_t light = 0; light < lights; ++light)
      {
        for (int c = 0; c < 3; ++c)
        {
          packet.toLight[light][c][n] = rays.toLight[light][c][l];
          packet.half[light][c][n] = rays.half[light][c][l];
        }
      }
      if (++n == PacketSize)
      {
        this->CastPacket(n);
        n = 0;
      }
    }
  }
  return n;
}

#endif
