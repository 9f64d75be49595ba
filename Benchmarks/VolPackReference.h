// VolPackReference: the brute-force renderer VolPackRendererCheck compares VolPack with (see the
// check's header comment for what it models and why the images are not identical).
#ifndef accelvolume_bench_VolPackReference_h
#define accelvolume_bench_VolPackReference_h

#include "VolPackRenderer.h"

#include <vector>

namespace accelvolume
{
namespace bench
{
void Normalize(double v[3]);

// One ray per pixel centre, samples on the principal axis' integer slices, trilinear scalar ->
// tables, opacity corrected for the step, front to back with early termination; shaded scenes
// shade each voxel as VolPack does. Premultiplied RGBA, rows from the bottom.
std::vector<float> Reference(const VolPackScene& scene);
}
}

#endif
