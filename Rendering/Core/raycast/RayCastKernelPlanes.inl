// RayCastKernel's ISOSURFACE_BLEND and SLICE_BLEND rays: members of RayCasterTile, included by
// RayCastKernel.cxx inside its namespaces (not a header of its own).

// ISOSURFACE_BLEND (as VTK's GPU mapper and the slice mapper): every iso-value crossed between
// a sample and the one before it (in ray order) adds the tables' colour and opacity at that
// value (no opacity correction), shaded with the sample's gradient, composited front to back.
// The first sample of a ray has nothing to cross from.
template <typename T>
void RayCasterTile<T>::IsoSurfaces(const PixelRay& pixel, float* out)
{
  const KernelFrame& frame = this->Frame;
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
    [&](const double p[3], const SampleCell& cell, float value)
    {
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
        int i;
        float fraction;
        TablePosition(frame, static_cast<float>(v), i, fraction);
        const float* e0 = frame.rgba + 4 * i;
        const float* e1 = e0 + 4;
        const float a = Lerp(e0[3], e1[3], fraction);
        float rgb[3] = { Lerp(e0[0], e1[0], fraction), Lerp(e0[1], e1[1], fraction),
          Lerp(e0[2], e1[2], fraction) };
        if (shade)
        {
          if (!haveGradient)
          {
            float indexGradient[3];
            this->Gradient(p, cell, eyeGradient, indexGradient);
            haveGradient = true;
          }
          this->Shade(pixel, p, eyeGradient, rgb);
        }
        const float weight = (1.0f - alpha) * a;
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
// regions, coloured and opaque as the tables say (no opacity correction), shaded as composite.
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
