// RayCastKernelWalk.inl: the generic per-sample walk (every blend mode, leaping included) and
// the per-sample composite ray, included inside RayCasterTile's namespace.

// Walks the samples of every interval; visit(p, cell, value) returns false to stop the ray.
// Zero-opacity leaping (octree, distance map, cell table) happens here when `leapTransparent`.
template <typename T>
template <typename Visit>
void RayCasterTile<T>::Walk(const PixelRay& pixel, bool leapTransparent, Visit&& visit)
{
  const IndexRay& ray = pixel.index;
  const double h = this->Settings.sampleDistance;
  const Vec3 step = ray.direction * h;
  const LeapSteps leapSteps(step);
  const bool octree = leapTransparent && this->Frame.useOctree;
  const bool distance = leapTransparent && this->Frame.useDistance;
  const bool cellLeap = leapTransparent && this->Frame.useCellLeap;
  this->RayDistance = this->DistanceMapOf(ray.direction);
  this->ForgetRejectedLeaf();
  this->LastContributed = false;
  SampleCell cell;
  std::uint64_t& leapCounter =
    octree ? this->Counters.leapedOctree : this->Counters.leapedDistance;
  const bool opaqueBox = leapTransparent && this->Frame.useOpaqueBox && (octree || distance);
  for (std::size_t at = this->RayStart.interval; at < this->RayIntervals.size(); ++at)
  {
    const Interval& interval = this->RayIntervals[at];
    std::int64_t first, last;
    this->WalkSamples(ray, at, h, opaqueBox, first, last, leapCounter);
    const FixedSteps steps(ray, interval.t0, h);
    for (std::int64_t k = first; k < last; ++k)
    {
      std::int64_t q[3];
      steps.At(k, q);
      double p[3];
      FixedSteps::ToPoint(q, p);
      if (octree)
      {
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
      this->Sampling.LocateFixed(q, cell);
      // Right after a sample that contributed, the next one most likely does too: without
      // cell leaping the distance map is not read there (sampling an empty cell adds
      // nothing, so this is exact and saves a cache miss per sample in dense matter).
      const bool lookUp = cellLeap || (distance && !this->LastContributed);
      const std::uint16_t info = lookUp ? this->LeapEntry(cell) : 0;
      if (distance && lookUp)
      {
        const int d = info & 0xff;
        if (d > 0)
        {
          k += this->CountedDistanceLeap(cell, d, leapSteps, last - k) - 1;
          continue;
        }
      }
      if (cellLeap)
      {
        const int configuration = info >> 8;
        if (configuration == 0)
        {
          ++this->Counters.leapedEmptyCell;
          continue;
        }
        const CellLeapCase& leapCase = this->Table[configuration];
        if (leapCase.leapCase >= 0 &&
          CellLeapSampleIsTransparent(leapCase, cell.f, this->Frame.leapThreshold,
            [this, &cell](int c) { return this->Sampling.Corner(cell, c); }))
        {
          ++this->Counters.leapedCell;
          continue;
        }
      }
      if (this->Hidden(p))
      {
        this->LastContributed = false;
        ++this->HiddenSamples;
        continue;
      }
      ++this->Counters.samples;
      const float value =
        this->Settings.nearest ? this->Sampling.Nearest(p) : this->Sampling.Trilinear(cell);
      if (!visit(p, cell, value))
      {
        return;
      }
    }
  }
}

template <typename T>
void RayCasterTile<T>::Composite(const PixelRay& pixel, float* out)
{
  const KernelFrame& frame = this->Frame;
  const RayCastLighting& lighting = *frame.lighting;
  const bool gradientOpacity = frame.gradientOpacity != nullptr;
  const bool needGradient = gradientOpacity || lighting.shade;
  const float threshold = static_cast<float>(this->Settings.terminationThreshold);
  const bool terminate = this->Settings.earlyTermination;
  float colour[3] = { 0, 0, 0 };
  float alpha = 0;
  this->Walk(pixel, true,
    [&](const double p[3], const SampleCell& cell, float value)
    {
      if (value != value)
      {
        this->LastContributed = false;
        return true; // NaN samples are transparent
      }
      this->LastContributed = false;
      int i;
      float fraction;
      TablePosition(frame, value, i, fraction);
      float a = Lerp(frame.correctedAlpha[i], frame.correctedAlpha[i + 1], fraction);
      if (a <= 0.0f && !frame.labelMap)
      {
        return true;
      }
      const float* e0 = frame.rgba + 4 * i;
      const float* e1 = e0 + 4;
      float rgb[3] = { Lerp(e0[0], e1[0], fraction), Lerp(e0[1], e1[1], fraction),
        Lerp(e0[2], e1[2], fraction) };
      float labelledAlpha = -1.0f; // the label's mixed table opacity, when labelled
      if (frame.labelMap)
      {
        const int label = this->MaskAt(p);
        if (label > 0)
        {
          // vtkGPUVolumeRayCastMapper's rule: mix(classified, label's classified, blend).
          const float* l0 = frame.labelTables + 4 * (static_cast<std::size_t>(label) * frame.tableSize + i);
          const float* l1 = l0 + 4;
          const float blend = frame.labelBlend;
          for (int c = 0; c < 3; ++c)
          {
            rgb[c] += blend * (Lerp(l0[c], l1[c], fraction) - rgb[c]);
          }
          const float own = Lerp(e0[3], e1[3], fraction);
          labelledAlpha = own + blend * (Lerp(l0[3], l1[3], fraction) - own);
          a = 1.0f - std::pow(std::max(1.0f - labelledAlpha, 0.0f), frame.opacityExponent);
        }
      }
      if (a <= 0.0f)
      {
        return true;
      }
      if (needGradient)
      {
        float eyeGradient[3];
        float indexGradient[3];
        this->Gradient(p, cell, eyeGradient, indexGradient);
        if (gradientOpacity)
        {
          const float* scale = frame.gradientAxisScale;
          const float gx = indexGradient[0] * scale[0], gy = indexGradient[1] * scale[1],
                      gz = indexGradient[2] * scale[2];
          const float magnitude = std::sqrt(gx * gx + gy * gy + gz * gz) * frame.rangeWidth;
          const float tableAlpha =
            (labelledAlpha >= 0.0f ? labelledAlpha : Lerp(e0[3], e1[3], fraction)) *
            this->GradientOpacity(magnitude);
          a = 1.0f - std::pow(std::max(1.0f - tableAlpha, 0.0f), frame.opacityExponent);
          if (a <= 0.0f)
          {
            return true;
          }
        }
        if (lighting.shade)
        {
          this->Shade(pixel, p, eyeGradient, rgb);
        }
      }
      this->LastContributed = true;
      const float weight = (1.0f - alpha) * a;
      colour[0] += weight * rgb[0];
      colour[1] += weight * rgb[1];
      colour[2] += weight * rgb[2];
      alpha += weight;
      if (terminate && alpha >= threshold)
      {
        ++this->Counters.terminatedRays;
        return false;
      }
      return true;
    });
  out[0] = colour[0];
  out[1] = colour[1];
  out[2] = colour[2];
  out[3] = alpha;
}
