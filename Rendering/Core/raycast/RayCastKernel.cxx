// RayCastKernel: a tile's rays, by the volume's scalar type (the kernel itself: RayCastKernelTile.inl,
// instantiated per type by RayCastKernel8Bit.cxx ... RayCastKernel64Bit.cxx).
#include "raycast/RayCastKernel.h"

#include <type_traits>

namespace accelvolume
{
namespace detail
{

void CastTile(
  const KernelFrame& frame, int x0, int y0, int x1, int y1, float* rgba, RayCastCounters& counters)
{
  DispatchScalarType(frame.volume,
    [&](const auto* data)
    {
      using T = std::remove_const_t<std::remove_pointer_t<decltype(data)>>;
      CastTileOf<T>(frame, x0, y0, x1, y1, rgba, counters);
    });
}

}
}
