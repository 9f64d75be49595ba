// The ray-casting kernel for int32_t and float volumes (one file per scalar width, so that the
// kernel's instantiations compile in parallel).
#include "raycast/RayCastKernelTile.inl"

#include <cstdint>

namespace accelvolume
{
namespace detail
{

template void CastTileOf<std::int32_t>(
  const KernelFrame&, int, int, int, int, float*, RayCastCounters&);
template void CastTileOf<float>(
  const KernelFrame&, int, int, int, int, float*, RayCastCounters&);

}
}
