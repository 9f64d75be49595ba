// RayCastKernelApproach.inl: composite rays cast a few neighbours at a time, included inside
// RayCasterTile. Before its first non-empty cell a ray only leaps: locate the sample's cell,
// read the distance map, work out the leap, move, locate again. That is one chain of
// dependent steps per leap, which a core cannot overlap within one ray. Leaping the empty
// space of a group of rays in turn overlaps their chains; each ray then resumes its own walk
// (Walk or CompositeBatched) at the sample it would have reached alone, so the image does not
// change (tests compare with approachTogether off). Pixels outside the frame's screen footprint
// (ScreenFootprint.h: their rays cannot meet a non-empty cell) get no ray at all.

template <typename T>
void RayCasterTile<T>::CastRowTogether(int j, int x0, int x1, float* row)
{
  const KernelFrame& frame = this->Frame;
  const double y = PixelCentre(j, frame.view->height);
  const std::uint8_t* covered = this->FootprintRow(j);
  for (int i = x0; i < x1;)
  {
    int n = 0;
    for (; i < x1 && n < ApproachGroup; ++i)
    {
      if (covered && !covered[i >> FootprintBlockShift])
      {
        float* out = row + 4 * static_cast<std::size_t>(i);
        out[0] = out[1] = out[2] = out[3] = 0.0f;
        ++this->Counters.culledPixels;
        continue;
      }
      this->GroupColumns[n] = i;
      SetPixelRay(frame, i, j, this->ColumnCentres[i - x0], y, this->GroupPixels[n]);
      this->GroupHits[n] = this->Intervals(this->GroupPixels[n].index, this->GroupIntervals[n]);
      ++n;
    }
    if (n == 0)
    {
      continue;
    }
    this->Approach(n);
    for (int g = 0; g < n; ++g)
    {
      float* out = row + 4 * static_cast<std::size_t>(this->GroupColumns[g]);
      if (!this->GroupHits[g])
      {
        out[0] = out[1] = out[2] = out[3] = 0.0f;
        continue;
      }
      std::swap(this->RayIntervals, this->GroupIntervals[g]);
      this->RayStart = this->GroupStarts[g];
      this->CastFromStart(this->GroupPixels[g], out);
    }
  }
}

// Moves lane g to the first interval from its current one that has samples to visit (as the
// walks count the opaque box's cut); false when the ray has none left.
template <typename T>
bool RayCasterTile<T>::ApproachInterval(int g)
{
  ApproachLane& lane = this->GroupLanes[g];
  const std::vector<Interval>& intervals = this->GroupIntervals[g];
  const IndexRay& ray = this->GroupPixels[g].index;
  const double h = this->Settings.sampleDistance;
  const bool opaqueBox = this->Frame.useOpaqueBox;
  for (; lane.interval < intervals.size(); ++lane.interval)
  {
    const Interval& interval = intervals[lane.interval];
    std::int64_t first, last;
    this->IntervalSamples(ray, interval, h, opaqueBox, first, last, this->Counters.leapedDistance);
    if (first < last)
    {
      lane.steps = FixedSteps(ray, interval.t0, h);
      lane.sample = first;
      lane.last = last;
      return true;
    }
  }
  return false;
}

// Leaps the group's rays [0, n) up to their first sample in a non-empty cell (GroupStarts),
// one leap of each ray in turn.
template <typename T>
void RayCasterTile<T>::Approach(int n)
{
  const double h = this->Settings.sampleDistance;
  int pending = 0;
  for (int g = 0; g < n; ++g)
  {
    ApproachLane& lane = this->GroupLanes[g];
    WalkStart& start = this->GroupStarts[g];
    start = WalkStart();
    lane.interval = 0;
    lane.going = this->GroupHits[g] && this->ApproachInterval(g);
    if (lane.going)
    {
      lane.leap = LeapSteps(this->GroupPixels[g].index.direction * h);
      lane.distance = this->DistanceMapOf(this->GroupPixels[g].index.direction);
      ++pending;
    }
    else
    {
      start.interval = this->GroupIntervals[g].size(); // nothing left to walk
    }
  }
  while (pending > 0)
  {
    for (int g = 0; g < n; ++g)
    {
      ApproachLane& lane = this->GroupLanes[g];
      if (!lane.going)
      {
        continue;
      }
      std::int64_t q[3];
      lane.steps.At(lane.sample, q);
      SampleCell cell;
      this->Sampling.LocateFixed(q, cell);
      const int d = this->LeapEntryIn(lane.distance, cell) & 0xff;
      WalkStart& start = this->GroupStarts[g];
      if (d == 0)
      {
        // The ray's walk starts here once the group has arrived: its first voxels (and
        // gradients) load meanwhile instead of stalling the walk's first sample.
        this->PrefetchCell(cell, this->Frame.gradients != nullptr);
        start.interval = lane.interval;
        start.sample = lane.sample;
        start.last = lane.last;
        lane.going = false;
        --pending;
        continue;
      }
      lane.sample += this->CountedDistanceLeap(cell, d, lane.leap, lane.last - lane.sample);
      if (lane.sample >= lane.last)
      {
        ++lane.interval;
        if (!this->ApproachInterval(g))
        {
          start.interval = lane.interval;
          lane.going = false;
          --pending;
        }
      }
    }
  }
}
