// ReferenceComposite: CPU oracle for composite (direct volume rendering) ray casting.
#ifndef accelvolume_ReferenceComposite_h
#define accelvolume_ReferenceComposite_h

#include "reference/ReferenceRenderer.h"

#include <vector>

namespace accelvolume
{

struct CompositeOptions
{
  double stepWorld = 0.05; // integration step in world units (an upper bound: see below)
  // vtkVolumeProperty::ScalarOpacityUnitDistance: the table opacities hold for this world length.
  double opacityUnitDistance = 1.0;
  bool nearest = false;
  int threads = 0; // 0 = hardware concurrency; results never depend on it
};

// Premultiplied colour and alpha of the front-to-back composite.
struct CompositePixel
{
  float rgba[4] = { 0, 0, 0, 0 };
};

// VTK vtkGPUVolumeRayCastMapper composite semantics, rendered like RenderReference: width *
// height pixels at index i + j * width (j from the bottom), regions as boxes in INDEX coordinates,
// clip half-spaces in index coordinates, optional raysEnd (per-pixel world distance to opaque
// geometry; nullptr means infinite; throws std::invalid_argument when its size is wrong).
// colourTable: RGB triples (3 * N floats) over normalized [0, 1] scalars, interpolated with the
// OpacityTable::Lookup convention; empty means white. Throws std::invalid_argument when its size is
// not a multiple of 3.
// Per ray and region, the interval [t0, t1] of box ∩ clip ∩ [0, raysEnd] is split into
// n = ceil((t1 - t0) / stepWorld) equal steps h and sampled at the midpoints t0 + (i + 0.5) h.
// Each sample's table opacity a_table becomes a = 1 - (1 - a_table)^(h / opacityUnitDistance)
// and is composited front to back with its table colour c: C += (1 - A) a c; A += (1 - A) a.
// Region intervals are composited in increasing t0, so regions must not overlap (sharing
// boundaries is fine, e.g. CroppingRegionBoxes); overlapping regions would be counted twice.
std::vector<CompositePixel> RenderReferenceComposite(const ScalarVolume& volume,
  const std::vector<Box>& regions, const std::vector<HalfSpace>& clip,
  const std::vector<float>& colourTable, const OpacityTable& opacity, const Camera& camera,
  int width, int height, const CompositeOptions& options,
  const std::vector<double>* raysEnd = nullptr);

} // namespace accelvolume

#endif
