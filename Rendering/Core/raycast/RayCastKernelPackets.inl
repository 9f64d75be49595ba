// RayCastKernelPackets.inl: composite rays sixteen at a time, one per lane of an AVX-512
// register (ray packets), included after RayCasterTile. One ray at a time, a sample is a chain
// of dependent steps (locate, read the map, load eight corners, classify, load eight gradient
// values, shade, blend) that leaves most of the core idle; sixteen neighbouring rays take each
// step together, their loads as gathers. Each lane leaps or samples on its own: a lane in an
// empty cell leaps (the distance map, as the walks do) while the others sample. Every lane's
// arithmetic is CompositeBatch's and ShadeBatchLanes' (the same operations in the same order,
// no FMA contraction), so images are bit-identical to the other paths (tests compare them).
// Used for the common case only (RayCasterTile::SetUpPackets); built only on x86-64 and run
// only on CPUs with AVX-512 (F, DQ, BW, VL).

template <typename T>
bool RayCasterTile<T>::SetUpPackets()
{
#if ACCELVOLUME_PACKETS
  const KernelFrame& frame = this->Frame;
  const RayCastSettings& settings = this->Settings;
  const RayCastLighting& lighting = *frame.lighting;
  const int* dims = frame.volume.dims;
  int cells[3];
  std::int64_t voxels = 1;
  for (int a = 0; a < 3; ++a)
  {
    if (dims[a] < 2)
    {
      return false; // the corner pairs need an x neighbour, the locating two voxels per axis
    }
    cells[a] = dims[a] - 1;
    voxels *= dims[a];
  }
  const CellBricks bricks(cells);
  // Voxel, gradient and cell indices are 32-bit lanes.
  constexpr std::int64_t Lanes32 = std::numeric_limits<std::int32_t>::max();
  if (!PacketScalar<T> || !settings.rayPackets || settings.baselineLanes || !CpuHasAvx512() ||
    !this->ApproachTogether || settings.nearest || frame.mask != nullptr ||
    frame.gradientOpacity != nullptr || frame.useCellLeap || frame.tableSize < 2 ||
    voxels + 8 > Lanes32 || static_cast<std::int64_t>(bricks.Entries()) > Lanes32 ||
    (lighting.shade &&
      (frame.gradients == nullptr || frame.specularTableSize < 2 ||
        lighting.model.lights.size() > MaximumRayLights)))
  {
    return false;
  }
  for (int a = 0; a < 3; ++a)
  {
    this->PacketBricks[a] = bricks.BricksAlong(a);
  }
  const std::ptrdiff_t oy = dims[0], oz = static_cast<std::ptrdiff_t>(dims[0]) * dims[1];
  const std::ptrdiff_t corners[8] = { 0, 1, oy, oy + 1, oz, oz + 1, oz + oy, oz + oy + 1 };
  std::copy(corners, corners + 8, this->PacketCorner);
  this->PacketRaySetUp = settings.packetRaySetUp && PacketRaysApply(frame, settings);
  // 8-bit differences in half-value units are EncodeGradient's exact integers.
  this->PacketGradientsFromVoxels = std::is_same<T, std::uint8_t>::value && lighting.shade &&
    frame.gradients != nullptr && frame.gradientScale == 0.5f;
  return true;
#else
  return false;
#endif
}

#if ACCELVOLUME_PACKETS

// Lane-wise std::min / std::max as the scalar code evaluates them (a < b ? b : a), NaN
// included.
ACCELVOLUME_AVX512 inline __m512 PacketMax(__m512 a, __m512 b)
{
  return _mm512_mask_blend_ps(_mm512_cmp_ps_mask(a, b, _CMP_LT_OQ), a, b);
}

ACCELVOLUME_AVX512 inline __m512 PacketMin(__m512 a, __m512 b)
{
  return _mm512_mask_blend_ps(_mm512_cmp_ps_mask(b, a, _CMP_LT_OQ), a, b);
}

// Lerp(a, b, t) = a + t * (b - a).
ACCELVOLUME_AVX512 inline __m512 PacketLerp(__m512 a, __m512 b, __m512 t)
{
  return _mm512_add_ps(a, _mm512_mul_ps(t, _mm512_sub_ps(b, a)));
}

// The low and high 32-bit words of sixteen 64-bit lanes (`first`: lanes 0-7, `second`: 8-15),
// lane by lane.
ACCELVOLUME_AVX512 inline void PacketSplitWords(
  const __m512i& first, const __m512i& second, __m512i& low, __m512i& high)
{
  const __m512i lowWords =
    _mm512_setr_epi32(0, 2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22, 24, 26, 28, 30);
  low = _mm512_permutex2var_epi32(first, lowWords, second);
  high = _mm512_permutex2var_epi32(first, _mm512_add_epi32(lowWords, _mm512_set1_epi32(1)), second);
}

// Lerp(table[i], table[i + 1], t) lane by lane from the table's (value, difference) pairs
// (KernelFrame::alphaPairs...): value + t * difference, the same bits; lanes outside `lanes`
// read nothing and give garbage.
ACCELVOLUME_AVX512 inline __m512 PacketLerpPairs(
  const float* pairs, const __m512i& i, const __m512& t, __mmask16 lanes)
{
  const __m512i first = _mm512_mask_i32gather_epi64(_mm512_setzero_si512(),
    static_cast<__mmask8>(lanes), _mm512_castsi512_si256(i), pairs, 8);
  const __m512i second = _mm512_mask_i32gather_epi64(_mm512_setzero_si512(),
    static_cast<__mmask8>(lanes >> 8), _mm512_extracti64x4_epi64(i, 1), pairs, 8);
  __m512i value, difference;
  PacketSplitWords(first, second, value, difference);
  return _mm512_add_ps(
    _mm512_castsi512_ps(value), _mm512_mul_ps(t, _mm512_castsi512_ps(difference)));
}

// The `width` (1 or 2) bytes at byte offsets `offset` of `base`, from the 32-bit word that ends
// with them (or starts the buffer, of at least 4 bytes): no load passes the buffer's end.
ACCELVOLUME_AVX512 inline __m512i PacketBytes(const void* base, __m512i offset, int width)
{
  const __m512i start =
    _mm512_max_epi32(_mm512_sub_epi32(offset, _mm512_set1_epi32(4 - width)), _mm512_setzero_si512());
  const __m512i word = _mm512_i32gather_epi32(start, base, 1);
  return _mm512_srlv_epi32(word, _mm512_slli_epi32(_mm512_sub_epi32(offset, start), 3));
}

// Corners `at` and `at + 1` (x neighbours) of every lane as floats, as static_cast<float>.
template <typename T>
struct PacketCorners;

// Corners `at` and `at + 1` of 8-bit voxels from the 32-bit word of bytes at - 1 ... at + 2
// (moved inside the buffer of `voxels` bytes at its ends), kept in `word` for
// PacketVoxelGradients.
ACCELVOLUME_AVX512 inline void PacketByteCorners(
  const std::uint8_t* v, __m512i at, int voxels, __m512i& word, __m512& lo, __m512& hi)
{
  const __m512i start = _mm512_min_epi32(
    _mm512_max_epi32(_mm512_sub_epi32(at, _mm512_set1_epi32(1)), _mm512_setzero_si512()),
    _mm512_set1_epi32(voxels - 4));
  word = _mm512_i32gather_epi32(start, v, 1);
  const __m512i pair = _mm512_srlv_epi32(word, _mm512_slli_epi32(_mm512_sub_epi32(at, start), 3));
  lo = _mm512_cvtepi32_ps(_mm512_and_si512(pair, _mm512_set1_epi32(0xff)));
  hi = _mm512_cvtepi32_ps(_mm512_and_si512(_mm512_srli_epi32(pair, 8), _mm512_set1_epi32(0xff)));
}

template <>
struct PacketCorners<std::int8_t>
{
  ACCELVOLUME_AVX512 static void Load(const std::int8_t* v, __m512i at, __m512& lo, __m512& hi)
  {
    const __m512i pair = PacketBytes(v, at, 2);
    lo = _mm512_cvtepi32_ps(_mm512_srai_epi32(_mm512_slli_epi32(pair, 24), 24));
    hi = _mm512_cvtepi32_ps(_mm512_srai_epi32(_mm512_slli_epi32(pair, 16), 24));
  }
};

template <>
struct PacketCorners<std::uint16_t>
{
  ACCELVOLUME_AVX512 static void Load(const std::uint16_t* v, __m512i at, __m512& lo, __m512& hi)
  {
    const __m512i pair = _mm512_i32gather_epi32(at, v, 2);
    lo = _mm512_cvtepi32_ps(_mm512_and_si512(pair, _mm512_set1_epi32(0xffff)));
    hi = _mm512_cvtepi32_ps(_mm512_srli_epi32(pair, 16));
  }
};

template <>
struct PacketCorners<std::int16_t>
{
  ACCELVOLUME_AVX512 static void Load(const std::int16_t* v, __m512i at, __m512& lo, __m512& hi)
  {
    const __m512i pair = _mm512_i32gather_epi32(at, v, 2);
    lo = _mm512_cvtepi32_ps(_mm512_srai_epi32(_mm512_slli_epi32(pair, 16), 16));
    hi = _mm512_cvtepi32_ps(_mm512_srai_epi32(pair, 16));
  }
};

template <>
struct PacketCorners<float>
{
  ACCELVOLUME_AVX512 static void Load(const float* v, __m512i at, __m512& lo, __m512& hi)
  {
    lo = _mm512_i32gather_ps(at, v, 4);
    hi = _mm512_i32gather_ps(_mm512_add_epi32(at, _mm512_set1_epi32(1)), v, 4);
  }
};

ACCELVOLUME_AVX512 inline PacketWide PacketLoadWide(const std::int64_t* lanes)
{
  return { { _mm512_load_si512(lanes), _mm512_load_si512(lanes + 8) } };
}

// Sampler::LocateFixedCell along one axis of n > 1 voxels for sixteen 32.32 positions: the
// cell index and the fraction. The clamped position's high word is the cell and its low word
// the fraction's numerator (converted to float as the int64 would be: the same integer),
// except at the last voxel, which lies in cell n - 2 at fraction 1.
ACCELVOLUME_AVX512 inline void PacketLocate(const PacketWide& q, int n, __m512i& cell, __m512& f)
{
  const __m512i top = _mm512_set1_epi64(static_cast<std::int64_t>(n - 1) << 32);
  const __m512i clamped[2] = {
    _mm512_max_epi64(_mm512_min_epi64(q.half[0], top), _mm512_setzero_si512()),
    _mm512_max_epi64(_mm512_min_epi64(q.half[1], top), _mm512_setzero_si512())
  };
  __m512i low, high;
  PacketSplitWords(clamped[0], clamped[1], low, high);
  const __mmask16 atTop = _mm512_cmpeq_epi32_mask(high, _mm512_set1_epi32(n - 1));
  cell = _mm512_mask_blend_epi32(atTop, high, _mm512_set1_epi32(n - 2));
  f = _mm512_mask_blend_ps(atTop,
    _mm512_mul_ps(_mm512_cvtepu32_ps(low), _mm512_set1_ps(1.0f / 4294967296.0f)),
    _mm512_set1_ps(1.0f));
}

// Where the lanes' samples lie: the cells' fractions and base voxels, and the distance map there.
struct PacketPlace
{
  __m512 f[3];
  __m512i base;
  __m512i d;
  __mmask16 interior; // cells with a voxel of margin around their corners (PacketGradientsFromVoxels)
};

// The fixed geometry PacketPlaceAt needs (per frame and packet).
struct PacketGrid
{
  PacketWide start[3], step[3];
  int dims[3];
  __m512i strideY, strideZ, bricksX, bricksY;
  const std::uint8_t* distance;
};

// FixedSteps::At for samples k of the lanes `lanes` (the others keep q).
ACCELVOLUME_AVX512 inline void PacketPositions(
  const PacketGrid& grid, const PacketWide& k, __mmask16 lanes, PacketWide q[3])
{
  for (int a = 0; a < 3; ++a)
  {
    for (int h = 0; h < 2; ++h)
    {
      q[a].half[h] = _mm512_mask_add_epi64(q[a].half[h], static_cast<__mmask8>(lanes >> (8 * h)),
        grid.start[a].half[h], _mm512_mullo_epi64(k.half[h], grid.step[a].half[h]));
    }
  }
}

// Sampler::LocateFixedCell and CellBricks::Index for the lanes' positions q, and their
// distance-map values.
ACCELVOLUME_AVX512 __attribute__((always_inline)) inline void PacketPlaceAt(
  const PacketGrid& grid, const PacketWide q[3], PacketPlace& place)
{
  __m512i cell[3];
  for (int a = 0; a < 3; ++a)
  {
    PacketLocate(q[a], grid.dims[a], cell[a], place.f[a]);
  }
  constexpr int Shift = CellBricks::Shift;
  const __m512i inside = _mm512_set1_epi32(CellBricks::Size - 1);
  const __m512i brick = _mm512_add_epi32(
    _mm512_mullo_epi32(
      _mm512_add_epi32(_mm512_mullo_epi32(_mm512_srli_epi32(cell[2], Shift), grid.bricksY),
        _mm512_srli_epi32(cell[1], Shift)),
      grid.bricksX),
    _mm512_srli_epi32(cell[0], Shift));
  const __m512i inBrick = _mm512_or_si512(
    _mm512_or_si512(_mm512_slli_epi32(_mm512_and_si512(cell[2], inside), 2 * Shift),
      _mm512_slli_epi32(_mm512_and_si512(cell[1], inside), Shift)),
    _mm512_and_si512(cell[0], inside));
  const __m512i cellIndex = _mm512_or_si512(_mm512_slli_epi32(brick, 3 * Shift), inBrick);
  place.d = _mm512_and_si512(PacketBytes(grid.distance, cellIndex, 1), _mm512_set1_epi32(0xff));
  // Cells [1, n - 3] along every axis: their corners' neighbours lie inside the volume.
  place.interior = 0xffff;
  for (int a = 0; a < 3; ++a)
  {
    place.interior &= _mm512_cmpge_epi32_mask(cell[a], _mm512_set1_epi32(1)) &
      _mm512_cmple_epi32_mask(cell[a], _mm512_set1_epi32(grid.dims[a] - 3));
  }
  place.base = _mm512_add_epi32(cell[0],
    _mm512_add_epi32(
      _mm512_mullo_epi32(cell[1], grid.strideY), _mm512_mullo_epi32(cell[2], grid.strideZ)));
}

// Fills `packet` lane `n` with the ray whose intervals RayIntervals holds: 1 when added, 0 when
// it has nothing to walk (its pixel is set), -1 when it needs the other paths (several
// intervals, a distance map of another octant than the packet's, lights not fixed).
template <typename T>
int RayCasterTile<T>::AddToPacket(int n, PixelRay& pixel, float* out)
{
  const KernelFrame& frame = this->Frame;
  const IndexRay& ray = pixel.index;
  const std::uint8_t* distance = this->DistanceMapOf(ray.direction);
  if (this->RayIntervals.size() != 1 || (n > 0 && distance != this->Packet.distance))
  {
    return -1;
  }
  const PixelRay* lit = &pixel;
  if (frame.lighting->shade)
  {
    // Without lights taken at the entry point a ray's lights depend on its direction alone:
    // parallel rays share the last ray's.
    const bool sameDirection = this->LitRaySet &&
      std::memcmp(&this->LitRay.index.direction, &ray.direction, sizeof(Vec3)) == 0;
    if (!frame.eyeLightsAtEntry && sameDirection)
    {
      lit = &this->LitRay;
    }
    else
    {
      this->LightRay(pixel);
      if (!frame.eyeLightsAtEntry)
      {
        this->RememberLights(pixel);
      }
    }
    if (!lit->fixedLights)
    {
      return -1;
    }
  }
  ++this->Counters.rays;
  const double h = this->Settings.sampleDistance;
  const Interval& interval = this->RayIntervals.front();
  std::int64_t first, last;
  this->IntervalSamples(
    ray, interval, h, frame.useOpaqueBox, first, last, this->Counters.leapedDistance);
  if (first >= last)
  {
    out[0] = out[1] = out[2] = out[3] = 0.0f;
    return 0;
  }
  PacketRays& packet = this->Packet;
  packet.distance = distance;
  const FixedSteps steps(ray, interval.t0, h);
  const LeapSteps leap(ray.direction * h);
  for (int a = 0; a < 3; ++a)
  {
    packet.start[a][n] = steps.start[a];
    packet.step[a][n] = steps.step[a];
    packet.inverse[a][n] = leap.inverse[a];
    packet.forward[a][n] = leap.along[a] > 0 ? 1 : 0;
  }
  packet.sample[n] = first;
  packet.last[n] = last;
  packet.out[n] = out;
  for (std::size_t l = 0; frame.lighting->shade && l < frame.lighting->model.lights.size(); ++l)
  {
    for (int c = 0; c < 3; ++c)
    {
      packet.toLight[l][c][n] = lit->toLight[l][c];
      packet.half[l][c][n] = lit->half[l][c];
    }
  }
  return 1;
}

// Keeps a lit ray's lights for the rays of the same direction (AddToPacket).
template <typename T>
void RayCasterTile<T>::RememberLights(const PixelRay& pixel)
{
  this->LitRay.index.direction = pixel.index.direction;
  this->LitRaySet = true;
  this->LitRay.fixedLights = pixel.fixedLights;
  const std::size_t lights = std::min(this->Frame.lighting->model.lights.size(), MaximumRayLights);
  for (std::size_t l = 0; l < lights; ++l)
  {
    std::copy(pixel.toLight[l], pixel.toLight[l] + 3, this->LitRay.toLight[l]);
    std::copy(pixel.half[l], pixel.half[l] + 3, this->LitRay.half[l]);
  }
}

// CastRowTogether with packets, for rows [j0, j1) (at most PacketRows): the rays of blocks of
// PacketRows x PacketColumns pixels go together (neighbours in both directions meet the same
// cells more often than a row of sixteen), the screen footprint as there.
template <typename T>
void RayCasterTile<T>::CastRowsInPackets(int j0, int j1, int x0, int x1, float* rgba)
{
  const KernelFrame& frame = this->Frame;
  const int width = frame.view->width;
  double rowCentres[PacketRows];
  const std::uint8_t* covered[PacketRows];
  for (int j = j0; j < j1; ++j)
  {
    rowCentres[j - j0] = PixelCentre(j, frame.view->height);
    covered[j - j0] = this->FootprintRow(j);
  }
  PixelRay& pixel = this->GroupPixels[0];
  int n = 0;
  for (int block = x0; block < x1; block += PacketColumns)
  {
    const int blockEnd = std::min(block + PacketColumns, x1);
    if (this->PacketRaySetUp)
    {
      const PacketBlock pixels{ block, blockEnd, j0, j1, x0, rowCentres, covered };
      n = this->AddBlockToPackets(n, pixels, rgba);
      continue;
    }
    for (int j = j0; j < j1; ++j)
    {
      for (int i = block; i < blockEnd; ++i)
      {
        float* out = rgba + 4 * (static_cast<std::size_t>(j) * width + i);
        if (covered[j - j0] && !covered[j - j0][i >> FootprintBlockShift])
        {
          out[0] = out[1] = out[2] = out[3] = 0.0f;
          ++this->Counters.culledPixels;
          continue;
        }
        SetPixelRay(frame, i, j, this->ColumnCentres[i - x0], rowCentres[j - j0], pixel);
        if (!this->Intervals(pixel.index, this->RayIntervals))
        {
          out[0] = out[1] = out[2] = out[3] = 0.0f;
          continue;
        }
        const int added = this->AddToPacket(n, pixel, out);
        if (added < 0)
        {
          this->RayStart = WalkStart();
          this->CastFromStart(pixel, out);
        }
        else if (added > 0 && ++n == PacketSize)
        {
          this->CastPacket(n);
          n = 0;
        }
      }
    }
  }
  if (n > 0)
  {
    this->CastPacket(n);
  }
}

// The packet's leaps: lanes `leaping` move on by CountedDistanceLeap's samples (DistanceLeap's
// arithmetic; their fractions `f`, map values `d`).
template <typename T>
ACCELVOLUME_AVX512 void RayCasterTile<T>::PacketLeap(
  __mmask16 leaping, const __m512i& d, const __m512 f[3], PacketWide& k, const PacketWide& last)
{
  const PacketRays& packet = this->Packet;
  const __m512 df = _mm512_cvtepi32_ps(d);
  const __m512 dBack = _mm512_cvtepi32_ps(_mm512_sub_epi32(d, _mm512_set1_epi32(1)));
  __m512d room[2] = { _mm512_set1_pd(1.0e30), _mm512_set1_pd(1.0e30) };
  for (int a = 0; a < 3; ++a)
  {
    const __mmask16 forward =
      _mm512_cmp_ps_mask(_mm512_load_ps(packet.forward[a]), _mm512_setzero_ps(), _CMP_GT_OQ);
    const __m512 along = _mm512_mask_blend_ps(
      forward, _mm512_add_ps(dBack, f[a]), _mm512_sub_ps(df, f[a]));
    for (int h = 0; h < 2; ++h)
    {
      const __m512d inverse = _mm512_load_pd(packet.inverse[a] + 8 * h);
      const __m512d wide = _mm512_cvtps_pd(h == 0 ? _mm512_castps512_ps256(along)
                                                  : _mm512_extractf32x8_ps(along, 1));
      const __m512d term = _mm512_mul_pd(_mm512_sub_pd(wide, _mm512_set1_pd(1.0e-4)), inverse);
      const __mmask8 moves = _mm512_cmp_pd_mask(inverse, _mm512_setzero_pd(), _CMP_GT_OQ);
      room[h] = _mm512_mask_min_pd(room[h], moves, term, room[h]); // std::min(room, term)
    }
  }
  std::uint64_t skippedTotal = 0;
  alignas(64) std::int64_t skipped[16];
  for (int h = 0; h < 2; ++h)
  {
    // std::max(0.0, std::min(room, 1.0e18)).
    const __m512d bounded =
      _mm512_max_pd(_mm512_min_pd(_mm512_set1_pd(1.0e18), room[h]), _mm512_setzero_pd());
    const __m512i leap = _mm512_add_epi64(_mm512_cvttpd_epi64(bounded), _mm512_set1_epi64(1));
    const __mmask8 lanes = static_cast<__mmask8>(leaping >> (8 * h));
    const __m512i moved =
      _mm512_maskz_min_epi64(lanes, leap, _mm512_sub_epi64(last.half[h], k.half[h]));
    k.half[h] = _mm512_add_epi64(k.half[h], moved);
    _mm512_store_si512(skipped + 8 * h, moved);
  }
  for (int l = 0; l < 16; ++l)
  {
    skippedTotal += static_cast<std::uint64_t>(skipped[l]);
  }
  this->Counters.leapedDistance += skippedTotal;
  this->Counters.distanceLeaps += static_cast<std::uint64_t>(__builtin_popcount(leaping));
}

// Walks the packet's lanes [0, n) to their ends (or early termination) and writes their pixels.
template <typename T>
ACCELVOLUME_AVX512 void RayCasterTile<T>::CastPacket(int n)
{
  const KernelFrame& frame = this->Frame;
  PacketRays& packet = this->Packet;
  for (int l = n; l < PacketSize; ++l)
  {
    packet.sample[l] = packet.last[l] = 0;
    for (int a = 0; a < 3; ++a)
    {
      packet.start[a][l] = packet.step[a][l] = 0;
      packet.inverse[a][l] = 0;
      packet.forward[a][l] = 0;
    }
    for (std::size_t light = 0; light < MaximumRayLights; ++light)
    {
      for (int c = 0; c < 3; ++c)
      {
        packet.toLight[light][c][l] = packet.half[light][c][l] = 0.0f;
      }
    }
  }
  PacketGrid grid;
  for (int a = 0; a < 3; ++a)
  {
    grid.start[a] = PacketLoadWide(packet.start[a]);
    grid.step[a] = PacketLoadWide(packet.step[a]);
    grid.dims[a] = frame.volume.dims[a];
  }
  grid.strideY = _mm512_set1_epi32(grid.dims[0]);
  grid.strideZ = _mm512_set1_epi32(grid.dims[0] * grid.dims[1]);
  grid.bricksX = _mm512_set1_epi32(this->PacketBricks[0]);
  grid.bricksY = _mm512_set1_epi32(this->PacketBricks[1]);
  grid.distance = packet.distance;
  const PacketWide last = PacketLoadWide(packet.last);
  PacketWide k = PacketLoadWide(packet.sample);
  const T* voxels = this->Sampling.Voxels();
  const int voxelCount = grid.dims[0] * grid.dims[1] * grid.dims[2]; // (SetUpPackets: < 2^31)
  const bool shade = frame.lighting->shade;
  const bool terminate = this->Settings.earlyTermination;
  const __m512 threshold = _mm512_set1_ps(static_cast<float>(this->Settings.terminationThreshold));
  const __m512 one = _mm512_set1_ps(1.0f), zero = _mm512_setzero_ps();
  const float lastEntry = static_cast<float>(frame.tableSize - 1);
  __m512 colour[3] = { zero, zero, zero };
  __m512 alpha = zero;
  __mmask16 alive = static_cast<__mmask16>((1u << n) - 1);
  std::uint64_t samples = 0, terminated = 0;
  // Software-pipelined: the lanes' next places (and their distance-map reads, which miss the
  // caches after a leap) are asked for before this step's samples are worked on.
  PacketWide q[3];
  PacketPositions(grid, k, 0xffff, q);
  PacketPlace place;
  PacketPlaceAt(grid, q, place);
  for (;;)
  {
    const __mmask16 going = alive &
      static_cast<__mmask16>(_mm512_cmplt_epi64_mask(k.half[0], last.half[0]) |
        (_mm512_cmplt_epi64_mask(k.half[1], last.half[1]) << 8));
    if (going == 0)
    {
      break;
    }
    const __m512* f = place.f;
    const __m512i base = place.base;
    const __mmask16 interior = place.interior;
    const __mmask16 leaping = going & _mm512_cmpgt_epi32_mask(place.d, _mm512_setzero_si512());
    if (leaping)
    {
      this->PacketLeap(leaping, place.d, f, k, last);
      PacketPositions(grid, k, leaping, q);
    }
    // The sampling lanes move on by one step: start + (k + 1) * step = q + step, exactly.
    const __mmask16 sampling = going & ~leaping;
    for (int h = 0; h < 2; ++h)
    {
      const __mmask8 moving = static_cast<__mmask8>(sampling >> (8 * h));
      k.half[h] = _mm512_mask_add_epi64(k.half[h], moving, k.half[h], _mm512_set1_epi64(1));
      for (int a = 0; a < 3; ++a)
      {
        q[a].half[h] = _mm512_mask_add_epi64(q[a].half[h], moving, q[a].half[h], grid.step[a].half[h]);
      }
    }
    const __m512 here[3] = { f[0], f[1], f[2] };
    PacketPlaceAt(grid, q, place);
    f = here;
    if (sampling == 0)
    {
      continue;
    }
    samples += static_cast<std::uint64_t>(__builtin_popcount(sampling));
    // Sampler::Trilinear.
    __m512 corner[8];
    __m512i sampleRows[4];
    for (int c = 0; c < 8; c += 2)
    {
      const __m512i at =
        _mm512_add_epi32(base, _mm512_set1_epi32(static_cast<int>(this->PacketCorner[c])));
      if constexpr (std::is_same<T, std::uint8_t>::value)
      {
        PacketByteCorners(voxels, at, voxelCount, sampleRows[c / 2], corner[c], corner[c + 1]);
      }
      else if constexpr (PacketScalar<T>) // the others never get here (SetUpPackets)
      {
        PacketCorners<T>::Load(voxels, at, corner[c], corner[c + 1]);
      }
    }
    const __m512 c00 = PacketLerp(corner[0], corner[1], f[0]);
    const __m512 c10 = PacketLerp(corner[2], corner[3], f[0]);
    const __m512 c01 = PacketLerp(corner[4], corner[5], f[0]);
    const __m512 c11 = PacketLerp(corner[6], corner[7], f[0]);
    const __m512 value =
      PacketLerp(PacketLerp(c00, c10, f[1]), PacketLerp(c01, c11, f[1]), f[2]);
    // TablePosition and the corrected opacity (NaN samples are transparent).
    __m512 u = _mm512_add_ps(
      _mm512_mul_ps(value, _mm512_set1_ps(frame.tableScale)), _mm512_set1_ps(frame.tableBias));
    const __m512 lastU = _mm512_set1_ps(lastEntry);
    u = _mm512_maskz_mov_ps(_mm512_cmp_ps_mask(u, zero, _CMP_GT_OQ),
      _mm512_mask_blend_ps(_mm512_cmp_ps_mask(u, lastU, _CMP_LT_OQ), lastU, u));
    const __m512i entry =
      _mm512_min_epi32(_mm512_cvttps_epi32(u), _mm512_set1_epi32(frame.tableSize - 2));
    const __m512 fraction = _mm512_sub_ps(u, _mm512_cvtepi32_ps(entry));
    const __m512 a = _mm512_maskz_mov_ps(sampling & _mm512_cmp_ps_mask(value, value, _CMP_ORD_Q),
      PacketLerpPairs(frame.alphaPairs, entry, fraction, sampling));
    const __mmask16 visible = sampling & _mm512_cmp_ps_mask(a, zero, _CMP_GT_OQ);
    if (visible)
    {
      __m512 rgb[3];
      for (int c = 0; c < 3; ++c)
      {
        rgb[c] = PacketLerpPairs(frame.colourPairs[c], entry, fraction, visible);
      }
      if (shade)
      {
        this->PacketShade(visible, base, interior, sampleRows, f, rgb);
      }
      // BlendSample.
      const __m512 weight = _mm512_mul_ps(_mm512_sub_ps(one, alpha), a);
      for (int c = 0; c < 3; ++c)
      {
        colour[c] =
          _mm512_mask_add_ps(colour[c], visible, colour[c], _mm512_mul_ps(weight, rgb[c]));
      }
      alpha = _mm512_mask_add_ps(alpha, visible, alpha, weight);
      if (terminate)
      {
        const __mmask16 done = visible & _mm512_cmp_ps_mask(alpha, threshold, _CMP_GE_OQ);
        terminated += static_cast<std::uint64_t>(__builtin_popcount(done));
        alive &= static_cast<__mmask16>(~done);
      }
    }
  }
  this->Counters.samples += samples;
  this->Counters.terminatedRays += terminated;
  this->Counters.packetRays += static_cast<std::uint64_t>(n);
  alignas(64) float out[4][16];
  _mm512_store_ps(out[0], colour[0]);
  _mm512_store_ps(out[1], colour[1]);
  _mm512_store_ps(out[2], colour[2]);
  _mm512_store_ps(out[3], alpha);
  for (int l = 0; l < n; ++l)
  {
    for (int c = 0; c < 4; ++c)
    {
      packet.out[l][c] = out[c][l];
    }
  }
}

#endif
