// The ray-casting kernel for int16_t and uint16_t volumes (one file per scalar width, so that the
// kernel's instantiations compile in parallel).
#include "raycast/RayCastKernelTile.inl"

#include <cstdint>

namespace accelvolume
{
namespace detail
{

template void CastTileOf<std::int16_t>(
  const KernelFrame&, int, int, int, int, float*, RayCastCounters&);
template void CastTileOf<std::uint16_t>(
  const KernelFrame&, int, int, int, int, float*, RayCastCounters&);

}
}
