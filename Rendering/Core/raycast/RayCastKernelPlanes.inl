// RayCastKernel's ISOSURFACE_BLEND and SLICE_BLEND rays: members of RayCasterTile, included by
// RayCastKernelTile.inl inside its namespaces (not a header of its own).

// The colour and opacity of iso-value v (raw, of the iso component), no opacity correction.
// Multi-component scalars as VTK's GPU mapper looks them up: an independent component in its own
// table; dependent luminance-alpha colour and opacity at v's place in component 0's range;
// dependent RGBA grey v (normalised to component 0's range) with the opacity there.
template <typename T>
void RayCasterTile<T>::IsoClassify(float v, float rgba[4]) const
{
  const KernelFrame& frame = this->Frame;
  int i;
  float fraction;
  if (frame.components == 1)
  {
    TablePosition(frame, v, i, fraction);
    for (int c = 0; c < 4; ++c)
    {
      rgba[c] = TableChannel(frame.rgba, i, fraction, c);
    }
    return;
  }
  const ComponentTableFrame& table = frame.tables[frame.independent ? frame.isoComponent : 0];
  if (frame.independent || frame.components == 2)
  {
    ComponentTablePosition(v, table.colourScale, table.colourBias, table.tableSize, i, fraction);
    for (int c = 0; c < 4; ++c)
    {
      rgba[c] = TableChannel(table.rgba, i, fraction, c);
    }
    return;
  }
  const float s = v * frame.componentScale[0] + frame.componentBias[0];
  ComponentTablePosition(
    s, static_cast<float>(table.tableSize - 1), 0.0f, table.tableSize, i, fraction);
  rgba[0] = rgba[1] = rgba[2] = std::min(std::max(s, 0.0f), 1.0f);
  rgba[3] = TableChannel(table.rgba, i, fraction, 3);
}

// Lights an iso-surface colour with the iso component's gradient at p (eye space, computed once
// per sample) and, with several components, that component's shading coefficients.
template <typename T>
void RayCasterTile<T>::IsoShade(const PixelRay& pixel, const double p[3], const SampleCell& cell,
  bool& haveGradient, float eyeGradient[3], float rgb[3]) const
{
  const KernelFrame& frame = this->Frame;
  if (frame.components == 1)
  {
    if (!haveGradient)
    {
      float indexGradient[3];
      this->Gradient(p, cell, eyeGradient, indexGradient);
      haveGradient = true;
    }
    this->Shade(pixel, p, eyeGradient, rgb);
    return;
  }
  const int k = frame.isoComponent;
  if (!haveGradient)
  {
    float gradients[4][3];
    this->ComponentGradients(p, k + 1, gradients);
    const float(*m)[3] = frame.componentNormalMatrix;
    for (int r = 0; r < 3; ++r)
    {
      eyeGradient[r] =
        m[r][0] * gradients[k][0] + m[r][1] * gradients[k][1] + m[r][2] * gradients[k][2];
    }
    haveGradient = true;
  }
  const ComponentTableFrame& table = frame.tables[frame.independent ? k : 0];
  this->ShadeWith(*table.model, table.specularTable, pixel, p, eyeGradient, rgb);
}

// ISOSURFACE_BLEND (as VTK's GPU mapper and the slice mapper): every iso-value crossed between
// a sample and the one before it (in ray order) adds the tables' colour and opacity at that
// value (no opacity correction), shaded with the sample's gradient, composited front to back.
// The first sample of a ray has nothing to cross from.
template <typename T>
void RayCasterTile<T>::IsoSurfaces(const PixelRay& pixel, float* out)
{
  const KernelFrame& frame = this->Frame;
  const Sampler<T>* isoChannel =
    frame.components > 1 ? &this->Channels[frame.isoComponent] : nullptr;
  const std::vector<double>& iso = this->Settings.isoValues;
  const bool shade = frame.lighting && frame.lighting->shade;
  const bool terminate = this->Settings.earlyTermination;
  const float threshold = static_cast<float>(this->Settings.terminationThreshold);
  float colour[3] = { 0, 0, 0 };
  float alpha = 0;
  bool havePrevious = false;
  float previous = 0;
  std::uint64_t hiddenBefore = this->HiddenSamples;
  this->Walk(pixel, false,
    [&](const double p[3], const SampleCell& cell, float sampled)
    {
      const float value = !isoChannel
        ? sampled
        : (this->Settings.nearest ? isoChannel->Nearest(p) : isoChannel->Trilinear(cell));
      // A masked sample between two visible ones: nothing is crossed across it.
      const bool afterHidden = this->HiddenSamples != hiddenBefore;
      hiddenBefore = this->HiddenSamples;
      if (value != value)
      {
        havePrevious = false;
        return true;
      }
      havePrevious = havePrevious && !afterHidden;
      const float before = previous;
      const bool crossedFrom = havePrevious;
      previous = value;
      havePrevious = true;
      if (!crossedFrom)
      {
        return true;
      }
      const double low = std::min(value, before);
      const double high = std::max(value, before);
      const bool rising = value >= before;
      float eyeGradient[3] = { 0, 0, 0 };
      bool haveGradient = false;
      for (size_t k = 0; k < iso.size(); ++k)
      {
        const double v = iso[rising ? k : iso.size() - 1 - k];
        if (!(v > low && v <= high))
        {
          continue;
        }
        float rgba[4];
        this->IsoClassify(static_cast<float>(v), rgba);
        float* rgb = rgba;
        if (shade)
        {
          this->IsoShade(pixel, p, cell, haveGradient, eyeGradient, rgb);
        }
        const float weight = (1.0f - alpha) * rgba[3];
        colour[0] += weight * rgb[0];
        colour[1] += weight * rgb[1];
        colour[2] += weight * rgb[2];
        alpha += weight;
      }
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

// SLICE_BLEND (as VTK's GPU mapper): the sample where the ray meets the plane inside the
// regions, coloured and opaque as the tables say (no opacity correction), shaded as composite;
// multi-component samples as ClassifyComponents classifies a plane sample.
template <typename T>
void RayCasterTile<T>::SlicePlane(const PixelRay& pixel, float* out)
{
  const IndexRay& ray = pixel.index;
  const HalfSpace& plane = this->Settings.slicePlane;
  const double denominator = Dot(plane.normal, ray.direction);
  if (std::abs(denominator) < 1.0e-12)
  {
    return;
  }
  const double t = -(Dot(plane.normal, ray.origin) + plane.offset) / denominator;
  bool inside = false;
  for (const Interval& interval : this->RayIntervals)
  {
    inside = inside || (t >= interval.t0 && t <= interval.t1);
  }
  if (!inside)
  {
    return;
  }
  const double p[3] = { ray.origin.x + t * ray.direction.x, ray.origin.y + t * ray.direction.y,
    ray.origin.z + t * ray.direction.z };
  if (this->Hidden(p))
  {
    return;
  }
  SampleCell cell;
  this->Sampling.Locate(p, cell);
  ++this->Counters.samples;
  if (this->Frame.components > 1)
  {
    // The sample classified as composite classifies it (independent components combined with
    // their weights; VTK 9.1's GPU shader has no single-opacity lookup for them and fails).
    float values[4];
    this->SampleComponents(p, cell, values);
    const bool shade = this->Frame.lighting && this->Frame.lighting->shade;
    if (!this->ClassifyComponents(pixel, p, values, shade, out, true))
    {
      out[0] = out[1] = out[2] = out[3] = 0.0f;
    }
    return;
  }
  const float value =
    this->Settings.nearest ? this->Sampling.Nearest(p) : this->Sampling.Trilinear(cell);
  if (value != value)
  {
    return;
  }
  int i;
  float fraction;
  TablePosition(this->Frame, value, i, fraction);
  const float* e0 = this->Frame.rgba + 4 * i;
  const float* e1 = e0 + 4;
  const float a = Lerp(e0[3], e1[3], fraction);
  float rgb[3] = { Lerp(e0[0], e1[0], fraction), Lerp(e0[1], e1[1], fraction),
    Lerp(e0[2], e1[2], fraction) };
  if (this->Frame.lighting && this->Frame.lighting->shade)
  {
    float eyeGradient[3];
    float indexGradient[3];
    this->Gradient(p, cell, eyeGradient, indexGradient);
    this->Shade(pixel, p, eyeGradient, rgb);
  }
  for (int c = 0; c < 3; ++c)
  {
    out[c] = rgb[c] * a;
  }
  out[3] = a;
}
