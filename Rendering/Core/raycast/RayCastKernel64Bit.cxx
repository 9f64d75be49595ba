// The ray-casting kernel for double volumes (one file per scalar width, so that the
// kernel's instantiations compile in parallel).
#include "raycast/RayCastKernelTile.inl"

#include <cstdint>

namespace accelvolume
{
namespace detail
{

template void CastTileOf<double>(
  const KernelFrame&, int, int, int, int, float*, RayCastCounters&);

}
}
