// RayCastPackets: the types of the CPU ray caster's ray packets (internal to RayCastKernel;
// the kernel is RayCastKernelPackets.inl): sixteen composite rays, one per AVX-512 lane, built
// on x86-64 with GCC or Clang and run where the CPU has AVX-512 F, DQ, BW and VL.
#ifndef accelvolume_RayCastPackets_h
#define accelvolume_RayCastPackets_h

#include "common/Avx512.h"
#include "raycast/RayCastPixelRay.h"

#include <cstdint>
#include <type_traits>

#define ACCELVOLUME_PACKETS ACCELVOLUME_AVX512_BUILD

namespace accelvolume
{
namespace detail
{

#if ACCELVOLUME_PACKETS
constexpr int PacketSize = 16;

// Sixteen int64 lanes as two registers of eight.
struct PacketWide
{
  __m512i half[2];
};

// The scalar types whose corners the packets load (the others take the other paths).
template <typename T>
constexpr bool PacketScalar = std::is_same<T, std::uint8_t>::value ||
  std::is_same<T, std::int8_t>::value || std::is_same<T, std::uint16_t>::value ||
  std::is_same<T, std::int16_t>::value || std::is_same<T, float>::value;

// The packet's rays, lane by lane (structure of arrays).
struct PacketRays
{
  alignas(64) std::int64_t start[3][PacketSize];
  alignas(64) std::int64_t step[3][PacketSize];
  alignas(64) std::int64_t sample[PacketSize];
  alignas(64) std::int64_t last[PacketSize];
  alignas(64) double inverse[3][PacketSize]; // LeapSteps::inverse
  alignas(64) float forward[3][PacketSize];  // 1 where LeapSteps::along > 0
  alignas(64) float toLight[MaximumRayLights][3][PacketSize];
  alignas(64) float half[MaximumRayLights][3][PacketSize];
  float* out[PacketSize];
  const std::uint8_t* distance = nullptr; // every lane's distance map (DistanceMapOf)
};

// Sixteen pixels' rays set up together (SetUpPacketRays): per lane what AddToPacket takes from
// SetPixelRay, Intervals, IntervalSamples, LightRay, FixedSteps and LeapSteps.
struct PacketCandidates
{
  alignas(64) double x[PacketSize]; // the pixel centres (PixelCentre)
  alignas(64) double y[PacketSize];
  alignas(64) double direction[3][PacketSize]; // index space
  alignas(64) std::int64_t start[3][PacketSize];
  alignas(64) std::int64_t step[3][PacketSize];
  alignas(64) std::int64_t first[PacketSize]; // IntervalSamples
  alignas(64) std::int64_t last[PacketSize];
  alignas(64) std::int64_t cut[PacketSize]; // samples the opaque box cuts off
  alignas(64) double inverse[3][PacketSize];
  alignas(64) float forward[3][PacketSize];
  alignas(64) float toLight[MaximumRayLights][3][PacketSize];
  alignas(64) float half[MaximumRayLights][3][PacketSize];
  std::uint32_t hits = 0; // bit l: lane l's ray meets the region
};
#endif

}
}

#endif
