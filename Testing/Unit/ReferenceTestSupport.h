// Volume builders shared by the reference-renderer unit tests.
#ifndef accelvolume_test_ReferenceTestSupport_h
#define accelvolume_test_ReferenceTestSupport_h

#include "reference/ReferenceRenderer.h"

#include <functional>

namespace accelvolume_test
{
// A volume whose voxel (i, j, k) holds value(i, j, k), identity index-to-world.
inline accelvolume::ScalarVolume MakeVolume(
  int nx, int ny, int nz, const std::function<float(int, int, int)>& value)
{
  accelvolume::ScalarVolume volume;
  volume.dims[0] = nx;
  volume.dims[1] = ny;
  volume.dims[2] = nz;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        volume.values.push_back(value(i, j, k));
  return volume;
}

// The whole volume as an index-space box.
inline accelvolume::Box IndexBox(const accelvolume::ScalarVolume& volume)
{
  return { { 0, 0, 0 }, { volume.dims[0] - 1.0, volume.dims[1] - 1.0, volume.dims[2] - 1.0 } };
}
}

#endif
