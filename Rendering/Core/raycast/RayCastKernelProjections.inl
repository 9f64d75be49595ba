// RayCastKernel's MIP / MinIP (Extreme) and raysum / average (Integrate) rays of
// single-component scalars: members of RayCasterTile, included by RayCastKernelTile.inl inside its
// namespaces (not a header of its own).

template <typename T>
void RayCasterTile<T>::Extreme(const PixelRay& pixel, float* out)
{
  const bool maximum = this->Settings.blend == Blend::Maximum;
  float extreme =
    maximum ? -std::numeric_limits<float>::infinity() : std::numeric_limits<float>::infinity();
  bool hit = false;
  const MinMaxOctree* tree = this->Frame.useOctree ? this->Frame.octree : nullptr;
  const IndexRay& ray = pixel.index;
  const double h = this->Settings.sampleDistance;
  const Vec3 step = ray.direction * h;
  this->ForgetRejectedLeaf();
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
      if (tree && hit)
      {
        // A node whose whole range cannot beat the current extreme adds nothing. The leaf
        // cache is only valid for one extreme, so it is reset whenever that changes.
        const std::int64_t more = this->OctreeLeap(p, step,
          [tree, maximum, extreme](int level, std::uint64_t index)
          {
            const OctreeLevel& l = tree->GetLevel(level);
            return maximum ? l.maximum[index] <= extreme : l.minimum[index] >= extreme;
          });
        if (more >= 0)
        {
          const std::int64_t skipped = std::min(more + 1, count - k);
          this->Counters.leapedOctree += static_cast<std::uint64_t>(skipped);
          k += skipped - 1;
          continue;
        }
      }
      if (this->Hidden(p))
      {
        continue;
      }
      ++this->Counters.samples;
      const float value = this->Sampling.Sample(p, this->Settings.nearest);
      if (value != value)
      {
        continue;
      }
      if (!hit || (maximum ? value > extreme : value < extreme))
      {
        extreme = value;
        this->ForgetRejectedLeaf();
      }
      hit = true;
    }
  }
  if (!hit)
  {
    return;
  }
  int i;
  float fraction;
  TablePosition(this->Frame, extreme, i, fraction);
  const float* e0 = this->Frame.rgba + 4 * i;
  const float* e1 = e0 + 4;
  const float a = Lerp(e0[3], e1[3], fraction);
  for (int c = 0; c < 3; ++c)
  {
    out[c] = Lerp(e0[c], e1[c], fraction) * a;
  }
  out[3] = a;
}

template <typename T>
void RayCasterTile<T>::Integrate(const PixelRay& pixel, float* out)
{
  const KernelFrame& frame = this->Frame;
  const bool additive = this->Settings.blend == Blend::Additive;
  const float lower = static_cast<float>(this->Settings.averageRange[0]);
  const float upper = static_cast<float>(this->Settings.averageRange[1]);
  double sum = 0;
  double count = 0;
  // Zero-opacity samples add nothing to the raysum; the average counts them, so it never
  // leaps.
  this->Walk(pixel, additive,
    [&](const double*, const SampleCell&, float value)
    {
      if (value != value || (!additive && !(value >= lower && value <= upper)))
      {
        this->LastContributed = false;
        return true;
      }
      int i;
      float fraction;
      TablePosition(frame, value, i, fraction);
      const float a = Lerp(frame.rgba[4 * i + 3], frame.rgba[4 * i + 7], fraction);
      this->LastContributed = a > 0.0f;
      const float s = value * frame.normalScale + frame.normalBias;
      sum += static_cast<double>(a) * s;
      count += 1;
      return true;
    });
  float grey = 0;
  if (additive)
  {
    grey =
      static_cast<float>(sum * this->Settings.sampleDistance / this->Settings.additiveUnitDistance);
  }
  else
  {
    if (count <= 0)
    {
      return;
    }
    grey = static_cast<float>(sum / count);
  }
  grey = std::min(std::max(grey, 0.0f), 1.0f);
  out[0] = out[1] = out[2] = grey;
  out[3] = 1.0f;
}
