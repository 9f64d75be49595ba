// RayCastKernelBatch.inl: composite rays of the common case (one component, trilinear, no
// mask, any leaping, semi-transparent transfer functions) in batches, included inside
// RayCasterTile. The walk, leaps included, first collects up to BatchSize samples to visit;
// their trilinear values and opacities then come from tight loops over independent samples,
// and only then are the visible ones shaded and composited in order. Each sample's arithmetic
// is Walk's and Composite's, so images are bit-identical to theirs (and to every leaping
// configuration). The shading lane loops are compiled for AVX2 besides the x86-64 baseline
// and chosen at run time (LanesOnAvx2): IEEE adds, multiplies, divides and square roots in the
// same order on every target and no FMA contraction (-ffp-contract=off), so the same bits on
// every CPU (TestRayCastEngine compares the two). LanesOnAvx2: RayCastKernelTile.inl.

template <typename T>
bool RayCasterTile<T>::CanBatch() const
{
  const KernelFrame& frame = this->Frame;
  const bool needGradient = frame.gradientOpacity != nullptr || frame.lighting->shade;
  // Nearly opaque samples stop a ray a few samples after its first visible one: batches do not
  // pay there (measured: up to 20 % slower on opaque transfer functions), per-sample rays do.
  constexpr float OpaqueSample = 0.5f;
  return this->Settings.batchedComposite && frame.maximumCorrectedAlpha < OpaqueSample &&
    frame.components == 1 && this->Settings.blend == Blend::Composite &&
    !this->Settings.nearest && frame.mask == nullptr &&
    (!needGradient || frame.gradients != nullptr);
}

template <typename T>
void RayCasterTile<T>::CompositeBatched(const PixelRay& pixel, float* out)
{
  const KernelFrame& frame = this->Frame;
  const IndexRay& ray = pixel.index;
  const double h = this->Settings.sampleDistance;
  const Vec3 step = ray.direction * h;
  const LeapSteps leapSteps(step);
  const bool octree = frame.useOctree;
  const bool distance = frame.useDistance;
  const bool cellLeap = frame.useCellLeap;
  const bool opaqueBox = frame.useOpaqueBox && (distance || octree);
  this->RayDistance = this->DistanceMapOf(ray.direction);
  this->ForgetRejectedLeaf();
  BatchedRay state;
  int n = 0;
  int flushAt = BatchSize / 2;
  // The last cell the map found non-empty (its voxel offset): its samples need no second look.
  std::ptrdiff_t filledCell = -1;
  int skipLookUp = 0;
  const bool prefetchGradients = frame.gradients != nullptr && frame.lighting->shade;
  bool going = true;
  for (std::size_t at = this->RayStart.interval; going && at < this->RayIntervals.size(); ++at)
  {
    const Interval& interval = this->RayIntervals[at];
    std::int64_t first, last;
    this->WalkSamples(ray, at, h, opaqueBox, first, last,
      octree ? this->Counters.leapedOctree : this->Counters.leapedDistance);
    const FixedSteps steps(ray, interval.t0, h);
    for (std::int64_t k = first; k < last; ++k)
    {
      BatchSample& sample = this->Batch[n];
      std::int64_t* q = sample.q;
      steps.At(k, q);
      if (octree)
      {
        // Walk's octree leap: the largest transparent node around the sample.
        double p[3];
        FixedSteps::ToPoint(q, p);
        const std::int64_t more = this->TransparentOctreeLeap(p, step);
        if (more >= 0)
        {
          const std::int64_t skipped = std::min(more + 1, last - k);
          this->Counters.leapedOctree += static_cast<std::uint64_t>(skipped);
          ++this->Counters.octreeLeaps;
          k += skipped - 1;
          continue;
        }
      }
      SampleCell& cell = sample.cell;
      int coordinates[3];
      this->Sampling.LocateFixedCell(q, cell, coordinates);
      // In matter, the map is read every other sample only (reading it never changes the
      // image, only how far the ray may leap); the cell's index is needed only then.
      const bool lookUp = cellLeap || (distance && cell.base != filledCell && skipLookUp-- <= 0);
      if (lookUp)
      {
        cell.cell = this->Sampling.CellIndex(coordinates);
        const std::uint16_t info = this->LeapEntry(cell);
        const int d = info & 0xff;
        if (distance && d > 0)
        {
          k += this->CountedDistanceLeap(cell, d, leapSteps, last - k) - 1;
          continue;
        }
        if (cellLeap)
        {
          // Walk's cell test: every corner transparent, or the sample outside the box of the
          // cell's iso-surface (the modified Marching Cubes table).
          const int configuration = info >> 8;
          if (configuration == 0)
          {
            ++this->Counters.leapedEmptyCell;
            continue;
          }
          const CellLeapCase& leapCase = this->Table[configuration];
          if (leapCase.leapCase >= 0 &&
            CellLeapSampleIsTransparent(leapCase, cell.f, frame.leapThreshold,
              [this, &cell](int c) { return this->Sampling.Corner(cell, c); }))
          {
            ++this->Counters.leapedCell;
            continue;
          }
        }
        filledCell = cell.base;
        skipLookUp = 1;
      }
      // The batch's loads start now: its voxels, and its gradients when shading needs them,
      // arrive while the walk goes on.
      this->PrefetchCell(cell, prefetchGradients);
      // Batches grow along the ray and shrink near termination: a ray that stops (an opaque
      // surface after a few samples) wastes at most the rest of a small one.
      if (++n == flushAt)
      {
        going = this->CompositeBatch(pixel, n, state);
        n = 0;
        flushAt = state.alpha < 0.5f ? BatchSize : BatchSize / 4;
        if (!going)
        {
          break;
        }
      }
    }
  }
  if (going && n > 0)
  {
    this->CompositeBatch(pixel, n, state);
  }
  out[0] = state.colour[0];
  out[1] = state.colour[1];
  out[2] = state.colour[2];
  out[3] = state.alpha;
}

template <typename T>
bool RayCasterTile<T>::CompositeBatch(const PixelRay& pixel, int n, BatchedRay& state)
{
  const KernelFrame& frame = this->Frame;
  BatchSample* batch = this->Batch;
  BatchLanes& lanes = this->Lanes;
  // Sampler::Trilinear lane by lane: the loads first, then the same lerps in the same order.
  const T* voxels = this->Sampling.Voxels();
  const std::ptrdiff_t ox = batch[0].cell.offset[0], oy = batch[0].cell.offset[1],
                       oz = batch[0].cell.offset[2];
  const std::ptrdiff_t corners[8] = { 0, ox, oy, oy + ox, oz, oz + ox, oz + oy, oz + oy + ox };
  for (int s = 0; s < n; ++s)
  {
    const T* d = voxels + batch[s].cell.base;
    for (int c = 0; c < 8; ++c)
    {
      lanes.corner[c][s] = static_cast<float>(d[corners[c]]);
    }
    lanes.fx[s] = batch[s].cell.f[0];
    lanes.fy[s] = batch[s].cell.f[1];
    lanes.fz[s] = batch[s].cell.f[2];
  }
  float values[BatchSize];
  for (int s = 0; s < n; ++s)
  {
    const float fx = lanes.fx[s], fy = lanes.fy[s];
    const float c00 = Lerp(lanes.corner[0][s], lanes.corner[1][s], fx);
    const float c10 = Lerp(lanes.corner[2][s], lanes.corner[3][s], fx);
    const float c01 = Lerp(lanes.corner[4][s], lanes.corner[5][s], fx);
    const float c11 = Lerp(lanes.corner[6][s], lanes.corner[7][s], fx);
    values[s] = Lerp(Lerp(c00, c10, fy), Lerp(c01, c11, fy), lanes.fz[s]);
  }
  for (int s = 0; s < n; ++s)
  {
    BatchSample& sample = batch[s];
    sample.value = values[s];
    TablePosition(frame, sample.value, sample.entry, sample.fraction);
    const float a = Lerp(frame.correctedAlpha[sample.entry], frame.correctedAlpha[sample.entry + 1],
      sample.fraction);
    sample.alpha = sample.value != sample.value ? 0.0f : a; // NaN samples are transparent
  }
  // The visible samples, in order, without a branch per sample.
  int& count = lanes.count;
  count = 0;
  for (int s = 0; s < n; ++s)
  {
    lanes.visible[count] = s;
    count += batch[s].alpha > 0.0f ? 1 : 0;
  }
  const RayCastLighting& lighting = *frame.lighting;
  // Lane by lane pays from a few samples on (its loops' set-up costs more than a short batch).
  if (n >= 4 && frame.gradientOpacity == nullptr &&
    (!lighting.shade || pixel.fixedLights || this->LaneLights))
  {
#if ACCELVOLUME_AVX2_LANES
    if (this->Avx2Lanes)
    {
      return this->ShadeBatchLanesAvx2(pixel, n, state);
    }
#endif
    return this->ShadeBatchLanes(pixel, n, state);
  }
  const bool gradientOpacity = frame.gradientOpacity != nullptr;
  const bool needGradient = gradientOpacity || lighting.shade;
  const int* visible = lanes.visible;
  // Shaded a few at a time, then composited: independent samples overlap, and a ray that
  // terminates wastes at most the rest of its group.
  constexpr int Group = 4;
  float rgba[Group][4];
  for (int first = 0; first < count; first += Group)
  {
    const int last = std::min(first + Group, count);
    for (int v = first; v < last; ++v)
    {
      const BatchSample& sample = batch[visible[v]];
      float* colour = rgba[v - first];
      const float* e0 = frame.rgba + 4 * sample.entry;
      const float* e1 = e0 + 4;
      const float fraction = sample.fraction;
      colour[0] = Lerp(e0[0], e1[0], fraction);
      colour[1] = Lerp(e0[1], e1[1], fraction);
      colour[2] = Lerp(e0[2], e1[2], fraction);
      float a = sample.alpha;
      if (needGradient)
      {
        float eyeGradient[3];
        float indexGradient[3];
        double p[3];
        FixedSteps::ToPoint(sample.q, p);
        this->Gradient(p, sample.cell, eyeGradient, indexGradient);
        if (gradientOpacity)
        {
          const float* scale = frame.gradientAxisScale;
          const float gx = indexGradient[0] * scale[0], gy = indexGradient[1] * scale[1],
                      gz = indexGradient[2] * scale[2];
          const float magnitude = std::sqrt(gx * gx + gy * gy + gz * gz) * frame.rangeWidth;
          const float tableAlpha = Lerp(e0[3], e1[3], fraction) * this->GradientOpacity(magnitude);
          a = 1.0f - std::pow(std::max(1.0f - tableAlpha, 0.0f), frame.opacityExponent);
        }
        if (lighting.shade)
        {
          this->Shade(pixel, p, eyeGradient, colour);
        }
      }
      colour[3] = a;
    }
    for (int v = first; v < last; ++v)
    {
      const float* colour = rgba[v - first];
      // A sample transparent after gradient opacity adds nothing.
      if (colour[3] > 0.0f && this->BlendSample(state, colour[0], colour[1], colour[2], colour[3]))
      {
        this->Counters.samples += static_cast<std::uint64_t>(visible[v] + 1);
        return false;
      }
    }
  }
  this->Counters.samples += static_cast<std::uint64_t>(n);
  return true;
}

// CompositeBatch's common case (no gradient opacity; no shading or lights fixed along the ray)
// lane by lane: Gradient and ShadeWith's arithmetic in the same order, so the same bits.
#if ACCELVOLUME_AVX2_LANES
template <typename T>
__attribute__((target("avx2"))) bool RayCasterTile<T>::ShadeBatchLanesAvx2(
  const PixelRay& pixel, int n, BatchedRay& state)
{
  return this->ShadeBatchLanesIn(pixel, n, state);
}
#endif

template <typename T>
bool RayCasterTile<T>::ShadeBatchLanes(const PixelRay& pixel, int n, BatchedRay& state)
{
  return this->ShadeBatchLanesIn(pixel, n, state);
}

template <typename T>
ACCELVOLUME_INLINE_LANES bool RayCasterTile<T>::ShadeBatchLanesIn(
  const PixelRay& pixel, int n, BatchedRay& state)
{
  const KernelFrame& frame = this->Frame;
  const BatchSample* batch = this->Batch;
  BatchLanes& lanes = this->Lanes;
  const int count = lanes.count; // the visible samples (CompositeBatch)
  // A few lanes at a time, composited before the next: a ray that terminates early shades
  // (and fetches the gradients of) few samples it does not need.
  for (int first = 0, group = 8; first < count; first += group, group = BatchSize)
  {
    const int last = std::min(first + group, count);
    for (int v = first; v < last; ++v)
    {
      const BatchSample& sample = batch[lanes.visible[v]];
      const float* e0 = frame.rgba + 4 * sample.entry;
      const float* e1 = e0 + 4;
      lanes.rgb[0][v] = Lerp(e0[0], e1[0], sample.fraction);
      lanes.rgb[1][v] = Lerp(e0[1], e1[1], sample.fraction);
      lanes.rgb[2][v] = Lerp(e0[2], e1[2], sample.fraction);
      lanes.alpha[v] = sample.alpha;
      lanes.fx[v] = sample.cell.f[0];
      lanes.fy[v] = sample.cell.f[1];
      lanes.fz[v] = sample.cell.f[2];
    }
    const LightModel& model = frame.lighting->model;
    if (frame.lighting->shade)
    {
      const std::ptrdiff_t ox = batch[0].cell.offset[0], oy = batch[0].cell.offset[1],
                           oz = batch[0].cell.offset[2];
      const std::ptrdiff_t at[8] = { 0, ox, oy, oy + ox, oz, oz + ox, oz + oy, oz + oy + ox };
      const float(*m)[3] = frame.normalMatrix;
      for (int v = first; v < last; ++v)
      {
        const std::uint32_t* d = frame.gradients + batch[lanes.visible[v]].cell.base;
        const float fx = lanes.fx[v], fy = lanes.fy[v], fz = lanes.fz[v];
        const float wy[2] = { (1 - fy), fy };
        const float wz[2] = { (1 - fz), fz };
        float g[3];
        InterpolateGradient(d, at, fx, wy, wz, g);
        lanes.interpolated[0][v] = g[0];
        lanes.interpolated[1][v] = g[1];
        lanes.interpolated[2][v] = g[2];
      }
      for (int v = first; v < last; ++v)
      {
        const float g0 = lanes.interpolated[0][v], g1 = lanes.interpolated[1][v],
                    g2 = lanes.interpolated[2][v];
        for (int r = 0; r < 3; ++r)
        {
          lanes.eye[r][v] = m[r][0] * g0 + m[r][1] * g1 + m[r][2] * g2;
        }
      }
      // ShadeWith's terms (FixedLightingTerms or LightingTerms), light by light over the lanes.
      for (int v = first; v < last; ++v)
      {
        const float e0 = lanes.eye[0][v], e1 = lanes.eye[1][v], e2 = lanes.eye[2][v];
        const float squared = e0 * e0 + e1 * e1 + e2 * e2;
        // Both arms computed (no branch: the loop vectorises); equal to ShadeWith's where used.
        const float candidate = -1.0f / std::sqrt(std::max(squared, 1.0e-16f));
        const float inverse = squared > 1.0e-16f ? candidate : 0.0f;
        lanes.normal[0][v] = e0 * inverse;
        lanes.normal[1][v] = e1 * inverse;
        lanes.normal[2][v] = e2 * inverse;
      }
      float ambient[3] = { 0, 0, 0 };
      for (int c = 0; c < 3; ++c)
      {
        std::fill(lanes.diffuse[c] + first, lanes.diffuse[c] + last, 0.0f);
        std::fill(lanes.specular[c] + first, lanes.specular[c] + last, 0.0f);
      }
      if (pixel.fixedLights)
      {
        this->FixedLightLanes(pixel, first, last, ambient);
      }
      else
      {
        this->PointLightLanes(pixel, first, last, ambient);
      }
      for (int c = 0; c < 3; ++c)
      {
        const float base = model.ambient * (model.headlightOnly ? 1.0f : ambient[c]);
        for (int v = first; v < last; ++v)
        {
          const float factor = base + model.diffuse * lanes.diffuse[c][v];
          const float highlight = model.specular * lanes.specular[c][v];
          lanes.rgb[c][v] = std::min(lanes.rgb[c][v] * factor + highlight, 1.0f);
        }
      }
    }
    for (int v = first; v < last; ++v)
    {
      if (this->BlendSample(state, lanes.rgb[0][v], lanes.rgb[1][v], lanes.rgb[2][v], lanes.alpha[v]))
      {
        this->Counters.samples += static_cast<std::uint64_t>(lanes.visible[v] + 1);
        return false;
      }
    }
  }
  this->Counters.samples += static_cast<std::uint64_t>(n);
  return true;
}

// ShadeBatchLanes' lights fixed along the ray (FixedLightingTerms, lane by lane): adds every
// light's diffuse and specular terms of lanes [first, last) and its ambient colour.
template <typename T>
ACCELVOLUME_INLINE_LANES void RayCasterTile<T>::FixedLightLanes(
  const PixelRay& pixel, int first, int last, float ambient[3])
{
  const KernelFrame& frame = this->Frame;
  const LightModel& model = frame.lighting->model;
  BatchLanes& lanes = this->Lanes;
  const float* table = frame.specularTable;
  const int size = frame.specularTableSize;
  std::size_t index = 0;
  for (const SceneLight& light : model.lights)
  {
    const float* l = pixel.toLight[index];
    const float* h = pixel.half[index++];
    float term[BatchSize], lit[BatchSize];
    for (int v = first; v < last; ++v)
    {
      const float n0 = lanes.normal[0][v], n1 = lanes.normal[1][v], n2 = lanes.normal[2][v];
      float nDotL = n0 * l[0] + n1 * l[1] + n2 * l[2];
      float nDotH = n0 * h[0] + n1 * h[1] + n2 * h[2];
      if (model.twoSided)
      {
        nDotL = std::abs(nDotL);
        nDotH = std::abs(nDotH);
      }
      lit[v] = std::max(nDotL, 0.0f);
      term[v] = nDotH; // the highlight's power follows (a table lookup per lane)
    }
    for (int v = first; v < last; ++v)
    {
      const float nDotH = term[v];
      const float x = std::min(std::max(nDotH, 0.0f), 1.0f);
      const float u = x * static_cast<float>(size - 1);
      const int k = std::min(static_cast<int>(u), size - 2);
      const float highlightTerm = Lerp(table[k], table[k + 1], u - static_cast<float>(k));
      term[v] = nDotH > 0 ? highlightTerm : 0.0f;
    }
    for (int c = 0; c < 3; ++c)
    {
      ambient[c] += light.ambient[c];
      for (int v = first; v < last; ++v)
      {
        lanes.diffuse[c][v] += lit[v] * light.diffuse[c];
        lanes.specular[c][v] += term[v] * light.specular[c];
      }
    }
  }
}

// The same for lights not fixed along the ray (LightingTerms, no spot lights): each sample's own
// direction to every positional light, attenuation and half vector, without data branches.
template <typename T>
ACCELVOLUME_INLINE_LANES void RayCasterTile<T>::PointLightLanes(
  const PixelRay& pixel, int first, int last, float ambient[3])
{
  const KernelFrame& frame = this->Frame;
  const LightModel& model = frame.lighting->model;
  const BatchSample* batch = this->Batch;
  BatchLanes& lanes = this->Lanes;
  const float* table = frame.specularTable;
  const int size = frame.specularTableSize;
  float point[3][BatchSize];
  const RayCastLighting& l = *frame.lighting;
  for (int v = first; v < last; ++v)
  {
    double p[3];
    FixedSteps::ToPoint(batch[lanes.visible[v]].q, p);
    for (int r = 0; r < 3; ++r)
    {
      point[r][v] = model.anyPositional
        ? static_cast<float>(l.indexToEye[r][0] * p[0] + l.indexToEye[r][1] * p[1] +
            l.indexToEye[r][2] * p[2] + l.indexToEyeOffset[r])
        : 0.0f;
    }
  }
  const float* viewer = pixel.toViewer;
  for (const SceneLight& light : model.lights)
  {
    float term[BatchSize], lit[BatchSize], attenuated[BatchSize];
    for (int v = first; v < last; ++v)
    {
      float toLight[3] = { -light.axis[0], -light.axis[1], -light.axis[2] };
      float attenuation = 1.0f;
      if (light.positional)
      {
        const float d[3] = { light.position[0] - point[0][v],
          light.position[1] - point[1][v], light.position[2] - point[2][v] };
        const float distance = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        for (int c = 0; c < 3; ++c)
        {
          toLight[c] = distance > 0 ? d[c] / distance : toLight[c];
        }
        const float* a = light.attenuation;
        const float denominator = a[0] + a[1] * distance + a[2] * distance * distance;
        attenuation = denominator > 0 ? 1.0f / denominator : 1.0f;
      }
      const float n0 = lanes.normal[0][v], n1 = lanes.normal[1][v], n2 = lanes.normal[2][v];
      float nDotL = n0 * toLight[0] + n1 * toLight[1] + n2 * toLight[2];
      const float half[3] = { toLight[0] + viewer[0], toLight[1] + viewer[1],
        toLight[2] + viewer[2] };
      const float halfLength =
        std::sqrt(half[0] * half[0] + half[1] * half[1] + half[2] * half[2]);
      const float dotHalf = n0 * half[0] + n1 * half[1] + n2 * half[2];
      float nDotH = halfLength > 0 ? dotHalf / halfLength : 0.0f;
      if (model.twoSided)
      {
        nDotL = std::abs(nDotL);
        nDotH = std::abs(nDotH);
      }
      lit[v] = nDotL > 0 && attenuation > 0 ? attenuation * nDotL : 0.0f;
      term[v] = attenuation > 0 ? nDotH : 0.0f;
      attenuated[v] = attenuation;
    }
    for (int v = first; v < last; ++v)
    {
      const float nDotH = term[v];
      const float x = std::min(std::max(nDotH, 0.0f), 1.0f);
      const float u = x * static_cast<float>(size - 1);
      const int k = std::min(static_cast<int>(u), size - 2);
      const float highlightTerm = Lerp(table[k], table[k + 1], u - static_cast<float>(k));
      term[v] = nDotH > 0 ? attenuated[v] * highlightTerm : 0.0f;
    }
    for (int c = 0; c < 3; ++c)
    {
      ambient[c] += light.ambient[c];
      for (int v = first; v < last; ++v)
      {
        lanes.diffuse[c][v] += lit[v] * light.diffuse[c];
        lanes.specular[c][v] += term[v] * light.specular[c];
      }
    }
  }
}

// Composites one visible sample front to back; true when the ray terminates on it (counted).
template <typename T>
inline bool RayCasterTile<T>::BlendSample(BatchedRay& state, float r, float g, float b, float a)
{
  const float weight = (1.0f - state.alpha) * a;
  state.colour[0] += weight * r;
  state.colour[1] += weight * g;
  state.colour[2] += weight * b;
  state.alpha += weight;
  if (this->Settings.earlyTermination &&
    state.alpha >= static_cast<float>(this->Settings.terminationThreshold))
  {
    ++this->Counters.terminatedRays;
    return true;
  }
  return false;
}
