// The ray-casting kernel for int8_t and uint8_t volumes (one file per scalar width, so that the
// kernel's instantiations compile in parallel).
#include "raycast/RayCastKernelTile.inl"

#include <cstdint>

namespace accelvolume
{
namespace detail
{

template void CastTileOf<std::int8_t>(
  const KernelFrame&, int, int, int, int, float*, RayCastCounters&);
template void CastTileOf<std::uint8_t>(
  const KernelFrame&, int, int, int, int, float*, RayCastCounters&);

}
}
