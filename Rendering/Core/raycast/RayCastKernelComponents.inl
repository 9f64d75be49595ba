// RayCastKernel's multi-component rays (RayCastComponents): members of RayCasterTile, included
// by RayCastKernelTile.inl inside its namespaces (not a header of its own). Samples are classified
// as the slice mapper's shader (AccelVolumeSliceComponentsFS.glsl) and vtkGPUVolumeRayCastMapper
// classify them.

// Table position of a raw value (TablePosition's rule with a table's own scale and bias).
inline void ComponentTablePosition(
  float value, float scale, float bias, int size, int& i, float& fraction)
{
  float u = value * scale + bias;
  const float last = static_cast<float>(size - 1);
  u = u > 0 ? (u < last ? u : last) : 0.0f;
  i = std::min(static_cast<int>(u), size - 2);
  fraction = u - static_cast<float>(i);
}

inline float TableChannel(const float* rgba, int i, float fraction, int channel)
{
  return Lerp(rgba[4 * i + channel], rgba[4 * i + 4 + channel], fraction);
}

template <typename T>
void RayCasterTile<T>::CastComponentsRay(const PixelRay& pixel, float* out)
{
  switch (this->Settings.blend)
  {
    case Blend::Maximum:
    case Blend::Minimum:
      this->ExtremeComponents(pixel, out);
      break;
    case Blend::Additive:
    case Blend::Average:
      this->IntegrateComponents(pixel, out);
      break;
    case Blend::Isosurface:
      this->IsoSurfaces(pixel, out);
      break;
    case Blend::Slice:
      this->SlicePlane(pixel, out);
      break;
    case Blend::Composite:
      this->CompositeComponents(pixel, out);
      break;
  }
}

template <typename T>
void RayCasterTile<T>::SampleComponents(
  const double p[3], const SampleCell& cell, float values[4]) const
{
  const bool nearest = this->Settings.nearest;
  for (int c = 0; c < this->Frame.components; ++c)
  {
    values[c] = nearest ? this->Channels[c].Nearest(p) : this->Channels[c].Trilinear(cell);
  }
}

// Central differences of the first `count` components one voxel apart (clamped like the
// texture), in each component's normalised units per index step.
template <typename T>
void RayCasterTile<T>::ComponentGradients(const double p[3], int count, float gradients[4][3]) const
{
  const KernelFrame& frame = this->Frame;
  SampleCell cell;
  for (int a = 0; a < 3; ++a)
  {
    double forward[3] = { p[0], p[1], p[2] };
    double backward[3] = { p[0], p[1], p[2] };
    forward[a] += 1.0;
    backward[a] -= 1.0;
    float ahead[4], behind[4];
    this->Sampling.Locate(forward, cell);
    this->SampleComponents(forward, cell, ahead);
    this->Sampling.Locate(backward, cell);
    this->SampleComponents(backward, cell, behind);
    for (int c = 0; c < count; ++c)
    {
      gradients[c][a] = 0.5f * (ahead[c] - behind[c]) * frame.componentScale[c];
    }
  }
}

// A table's gradient opacity at a normalised gradient (VTK's units: the table spans a quarter
// of the range per mean voxel step); 1 without one.
template <typename T>
float RayCasterTile<T>::ComponentGradientOpacity(
  const ComponentTableFrame& table, const float gradient[3]) const
{
  if (!table.gradientOpacity)
  {
    return 1.0f;
  }
  const float* scale = this->Frame.componentAxisScale;
  const float gx = gradient[0] * scale[0], gy = gradient[1] * scale[1], gz = gradient[2] * scale[2];
  const float magnitude = std::min(4.0f * std::sqrt(gx * gx + gy * gy + gz * gz), 1.0f);
  const int n = table.gradientOpacitySize;
  const float u = magnitude * static_cast<float>(n - 1);
  const int i = std::min(static_cast<int>(u), n - 2);
  return Lerp(table.gradientOpacity[i], table.gradientOpacity[i + 1], u - static_cast<float>(i));
}

// One sample's premultiplied colour and opacity (corrected to the sample distance); false when
// it is transparent. A plane sample (SLICE_BLEND) takes the tables' opacities as they are, with
// no correction and no gradient opacity (as one-component slices). Independent components: each
// classified, lit and corrected by its own table, combined with the weights (colour: sum of weight
// x opacity x colour; opacity: sum of the squared opacities over the weighted sum); dependent: one
// colour, one opacity.
template <typename T>
bool RayCasterTile<T>::ClassifyComponents(const PixelRay& pixel, const double p[3],
  const float values[4], bool needGradient, float premultiplied[4], bool planeSample) const
{
  const KernelFrame& frame = this->Frame;
  const bool shade = frame.lighting->shade;
  const int n = frame.components;
  float gradients[4][3];
  float eye[3];
  const auto toEye = [&frame, &eye](const float g[3])
  {
    const float(*m)[3] = frame.componentNormalMatrix;
    for (int r = 0; r < 3; ++r)
    {
      eye[r] = m[r][0] * g[0] + m[r][1] * g[1] + m[r][2] * g[2];
    }
  };
  if (!frame.independent)
  {
    const ComponentTableFrame& table = frame.tables[0];
    int i;
    float fraction;
    ComponentTablePosition(
      values[n - 1], table.opacityScale, table.opacityBias, table.tableSize, i, fraction);
    const float tableAlpha = TableChannel(table.rgba, i, fraction, 3);
    if (!(tableAlpha > 0.0f))
    {
      return false;
    }
    float alpha = planeSample
      ? tableAlpha
      : Lerp(table.correctedAlpha[i], table.correctedAlpha[i + 1], fraction);
    float rgb[3];
    if (n == 2)
    {
      ComponentTablePosition(
        values[0], table.colourScale, table.colourBias, table.tableSize, i, fraction);
      for (int c = 0; c < 3; ++c)
      {
        rgb[c] = TableChannel(table.rgba, i, fraction, c);
      }
    }
    else
    {
      for (int c = 0; c < 3; ++c)
      {
        rgb[c] = values[c] * frame.colourScale[c] + frame.colourBias[c];
      }
    }
    if (needGradient)
    {
      this->ComponentGradients(p, 1, gradients); // component 0's, as VTK
      if (table.gradientOpacity && !planeSample)
      {
        const float a = tableAlpha * this->ComponentGradientOpacity(table, gradients[0]);
        alpha = 1.0f - std::pow(std::max(1.0f - a, 0.0f), table.opacityExponent);
        if (!(alpha > 0.0f))
        {
          return false;
        }
      }
      if (shade)
      {
        toEye(gradients[0]);
        this->ShadeWith(*table.model, table.specularTable, pixel, p, eye, rgb);
      }
    }
    for (int c = 0; c < 3; ++c)
    {
      premultiplied[c] = rgb[c] * alpha;
    }
    premultiplied[3] = alpha;
    return true;
  }

  int entry[4];
  float fractions[4];
  float tableAlpha[4];
  bool visible = false;
  for (int c = 0; c < n; ++c)
  {
    const ComponentTableFrame& table = frame.tables[c];
    ComponentTablePosition(
      values[c], table.opacityScale, table.opacityBias, table.tableSize, entry[c], fractions[c]);
    tableAlpha[c] = TableChannel(table.rgba, entry[c], fractions[c], 3);
    visible = visible || tableAlpha[c] > 0.0f;
  }
  if (!visible)
  {
    return false; // no gradient, no lighting
  }
  bool gradientOpacity = false;
  for (int c = 0; c < n && !planeSample; ++c)
  {
    gradientOpacity = gradientOpacity || frame.tables[c].gradientOpacity;
  }
  if (needGradient)
  {
    this->ComponentGradients(p, n, gradients);
  }
  float rgbSum[3] = { 0, 0, 0 };
  float totalAlpha = 0;
  float alphaSquares = 0;
  for (int c = 0; c < n; ++c)
  {
    const ComponentTableFrame& table = frame.tables[c];
    float alpha = 0;
    if (gradientOpacity)
    {
      // VTK's GPU mapper: every component's function at this component's gradient, weighted.
      float a = tableAlpha[c];
      for (int k = 0; k < n; ++k)
      {
        a *= this->ComponentGradientOpacity(frame.tables[k], gradients[c]) * frame.tables[k].weight;
      }
      alpha = 1.0f - std::pow(std::max(1.0f - a, 0.0f), table.opacityExponent);
    }
    else
    {
      alpha = planeSample
        ? tableAlpha[c]
        : Lerp(table.correctedAlpha[entry[c]], table.correctedAlpha[entry[c] + 1], fractions[c]);
    }
    totalAlpha += alpha * table.weight;
    if (table.weight > 0.0f && alpha > 0.0f)
    {
      float rgb[3];
      for (int k = 0; k < 3; ++k)
      {
        rgb[k] = TableChannel(table.rgba, entry[c], fractions[c], k);
      }
      if (shade)
      {
        toEye(gradients[c]);
        this->ShadeWith(*table.model, table.specularTable, pixel, p, eye, rgb);
      }
      for (int k = 0; k < 3; ++k)
      {
        rgbSum[k] += rgb[k] * alpha * table.weight;
      }
      alphaSquares += alpha * alpha;
    }
  }
  if (!(totalAlpha > 0.0f))
  {
    return false;
  }
  std::copy(rgbSum, rgbSum + 3, premultiplied);
  premultiplied[3] = alphaSquares / totalAlpha;
  return premultiplied[3] > 0.0f;
}

template <typename T>
void RayCasterTile<T>::CompositeComponents(const PixelRay& pixel, float* out)
{
  const KernelFrame& frame = this->Frame;
  bool needGradient = frame.lighting->shade;
  for (int c = 0; c < frame.componentTables; ++c)
  {
    needGradient = needGradient || frame.tables[c].gradientOpacity;
  }
  const float threshold = static_cast<float>(this->Settings.terminationThreshold);
  const bool terminate = this->Settings.earlyTermination;
  float colour[3] = { 0, 0, 0 };
  float alpha = 0;
  this->Walk(pixel, true,
    [&](const double p[3], const SampleCell& cell, float)
    {
      float values[4];
      this->SampleComponents(p, cell, values);
      float sample[4];
      this->LastContributed = this->ClassifyComponents(pixel, p, values, needGradient, sample);
      if (!this->LastContributed)
      {
        return true;
      }
      const float remaining = 1.0f - alpha;
      colour[0] += remaining * sample[0];
      colour[1] += remaining * sample[1];
      colour[2] += remaining * sample[2];
      alpha += remaining * sample[3];
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

// MIP / MinIP as VTK's GPU mapper: independent components each keep their own extreme and add
// their weighted colour x opacity and opacity; dependent ones keep the whole sample whose last
// component is extreme (the first along the ray on ties). Table opacities, no correction.
template <typename T>
void RayCasterTile<T>::ExtremeComponents(const PixelRay& pixel, float* out)
{
  const KernelFrame& frame = this->Frame;
  const bool maximum = this->Settings.blend == Blend::Maximum;
  const int n = frame.components;
  float extreme[4];
  bool hit = false;
  const IndexRay& ray = pixel.index;
  const double h = this->Settings.sampleDistance;
  const Vec3 step = ray.direction * h;
  const bool leap = this->Frame.useOctree && frame.componentOctrees[0];
  const MinMaxOctree* const* trees = frame.componentOctrees;
  const bool independent = frame.independent;
  // A node leaps when no component that decides can beat its extreme there (independent: every
  // component; dependent: the last one, which picks the kept sample; ties keep the earlier one).
  const auto cannotBeat = [&](int level, std::uint64_t index)
  {
    for (int c = independent ? 0 : n - 1; c < n; ++c)
    {
      const OctreeLevel& l = trees[c]->GetLevel(level);
      if (maximum ? !(l.maximum[index] <= extreme[c]) : !(l.minimum[index] >= extreme[c]))
      {
        return false;
      }
    }
    return true;
  };
  this->ForgetRejectedLeaf();
  SampleCell cell;
  for (const Interval& interval : this->RayIntervals)
  {
    const std::int64_t count =
      static_cast<std::int64_t>(std::floor((interval.t1 - interval.t0) / h + 0.5));
    const FixedSteps steps(ray, interval.t0, h);
    for (std::int64_t k = 0; k < count; ++k)
    {
      std::int64_t q[3];
      steps.At(k, q);
      double p[3];
      FixedSteps::ToPoint(q, p);
      if (leap && hit)
      {
        const std::int64_t more = this->OctreeLeap(p, step, cannotBeat);
        if (more >= 0)
        {
          const std::int64_t skipped = std::min(more + 1, count - k);
          this->Counters.leapedOctree += static_cast<std::uint64_t>(skipped);
          ++this->Counters.octreeLeaps;
          k += skipped - 1;
          continue;
        }
      }
      if (this->Hidden(p))
      {
        continue;
      }
      ++this->Counters.samples;
      this->Sampling.LocateFixed(q, cell);
      float values[4];
      if (!independent && hit)
      {
        // Only the last component decides; the others are read when it wins.
        const Sampler<T>& last = this->Channels[n - 1];
        const float decider = this->Settings.nearest ? last.Nearest(p) : last.Trilinear(cell);
        if (!(maximum ? decider > extreme[n - 1] : decider < extreme[n - 1]))
        {
          continue;
        }
      }
      this->SampleComponents(p, cell, values);
      if (!hit)
      {
        std::copy(values, values + n, extreme);
        hit = true;
        this->ForgetRejectedLeaf();
        continue;
      }
      bool changed = false;
      if (independent)
      {
        for (int c = 0; c < n; ++c)
        {
          if (maximum ? values[c] > extreme[c] : values[c] < extreme[c])
          {
            extreme[c] = values[c];
            changed = true;
          }
        }
      }
      else if (maximum ? values[n - 1] > extreme[n - 1] : values[n - 1] < extreme[n - 1])
      {
        std::copy(values, values + n, extreme);
        changed = true;
      }
      if (changed)
      {
        this->ForgetRejectedLeaf(); // the leaf cache holds for one extreme
      }
    }
  }
  if (!hit)
  {
    return;
  }
  int i;
  float fraction;
  if (frame.independent)
  {
    for (int c = 0; c < n; ++c)
    {
      const ComponentTableFrame& table = frame.tables[c];
      ComponentTablePosition(
        extreme[c], table.opacityScale, table.opacityBias, table.tableSize, i, fraction);
      const float a = TableChannel(table.rgba, i, fraction, 3);
      for (int k = 0; k < 3; ++k)
      {
        out[k] += table.weight * TableChannel(table.rgba, i, fraction, k) * a;
      }
      out[3] += table.weight * a;
    }
    return;
  }
  const ComponentTableFrame& table = frame.tables[0];
  ComponentTablePosition(
    extreme[n - 1], table.opacityScale, table.opacityBias, table.tableSize, i, fraction);
  const float a = TableChannel(table.rgba, i, fraction, 3);
  float rgb[3];
  if (n == 2)
  {
    ComponentTablePosition(
      extreme[0], table.colourScale, table.colourBias, table.tableSize, i, fraction);
    for (int k = 0; k < 3; ++k)
    {
      rgb[k] = TableChannel(table.rgba, i, fraction, k);
    }
  }
  else
  {
    for (int k = 0; k < 3; ++k)
    {
      rgb[k] =
        std::min(std::max(extreme[k] * frame.colourScale[k] + frame.colourBias[k], 0.0f), 1.0f);
    }
  }
  for (int k = 0; k < 3; ++k)
  {
    out[k] = rgb[k] * a;
  }
  out[3] = a;
}

// Raysum / average as VTK's GPU mapper: independent components add their weighted
// opacity(value) x normalised value (the average keeps each component's own sum and count, in
// the average range, and adds the weighted averages); dependent ones take component 0's
// normalised value times the opacity of the last component.
template <typename T>
void RayCasterTile<T>::IntegrateComponents(const PixelRay& pixel, float* out)
{
  const KernelFrame& frame = this->Frame;
  const bool additive = this->Settings.blend == Blend::Additive;
  const int n = frame.components;
  const float lower = static_cast<float>(this->Settings.averageRange[0]);
  const float upper = static_cast<float>(this->Settings.averageRange[1]);
  double sums[4] = { 0, 0, 0, 0 };
  double counts[4] = { 0, 0, 0, 0 };
  const auto opacityOf = [&frame](const ComponentTableFrame& table, float value)
  {
    int i;
    float fraction;
    ComponentTablePosition(
      value, table.opacityScale, table.opacityBias, table.tableSize, i, fraction);
    return TableChannel(table.rgba, i, fraction, 3);
  };
  // Zero-opacity samples add nothing to the raysum; the average counts them, so it never leaps.
  this->Walk(pixel, additive,
    [&](const double p[3], const SampleCell& cell, float)
    {
      float values[4];
      this->SampleComponents(p, cell, values);
      this->LastContributed = false;
      if (!frame.independent)
      {
        if (!additive && !(values[0] >= lower && values[0] <= upper))
        {
          return true;
        }
        const float a = opacityOf(frame.tables[0], values[n - 1]);
        this->LastContributed = a > 0.0f;
        sums[0] +=
          static_cast<double>(a) * (values[0] * frame.componentScale[0] + frame.componentBias[0]);
        counts[0] += 1;
        return true;
      }
      for (int c = 0; c < n; ++c)
      {
        if (!additive && !(values[c] >= lower && values[c] <= upper))
        {
          continue;
        }
        const ComponentTableFrame& table = frame.tables[c];
        const float a = opacityOf(table, values[c]);
        const double s =
          static_cast<double>(a) * (values[c] * frame.componentScale[c] + frame.componentBias[c]);
        this->LastContributed = this->LastContributed || (a > 0.0f && table.weight > 0.0f);
        sums[c] += additive ? table.weight * s : s;
        counts[c] += 1;
      }
      return true;
    });
  double grey = 0;
  if (additive)
  {
    for (int c = 0; c < n; ++c)
    {
      grey += sums[c];
    }
    grey *= this->Settings.sampleDistance / this->Settings.additiveUnitDistance;
  }
  else if (!frame.independent)
  {
    if (counts[0] <= 0)
    {
      return;
    }
    grey = sums[0] / counts[0];
  }
  else
  {
    bool covered = false;
    for (int c = 0; c < n; ++c)
    {
      if (counts[c] > 0)
      {
        grey += frame.tables[c].weight * sums[c] / counts[c];
        covered = true;
      }
    }
    if (!covered)
    {
      return;
    }
  }
  const float value = std::min(std::max(static_cast<float>(grey), 0.0f), 1.0f);
  out[0] = out[1] = out[2] = value;
  out[3] = 1.0f;
}
