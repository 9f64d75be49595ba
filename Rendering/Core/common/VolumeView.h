// VolumeView: a read-only, typed view of a volume's scalars (no copy), and the one scalar-type
// enum of Core, shared by the octree, cell classification, ray caster and shear-warp.
#ifndef accelvolume_VolumeView_h
#define accelvolume_VolumeView_h

#include <cstdint>

namespace accelvolume
{

enum class ScalarType
{
  Int8,
  UInt8,
  Int16,
  UInt16,
  Int32,
  Float32,
  Float64
};

// A read-only view of the volume's scalars (no copy).
struct VolumeView
{
  const void* data = nullptr;
  ScalarType type = ScalarType::UInt8;
  int dims[3] = { 0, 0, 0 };
};

// Calls f(typed pointer) for the volume's scalar type (f takes `const auto*`).
template <typename Function>
void DispatchScalarType(const VolumeView& volume, Function&& f)
{
  switch (volume.type)
  {
    case ScalarType::Int8:
      f(static_cast<const std::int8_t*>(volume.data));
      break;
    case ScalarType::UInt8:
      f(static_cast<const std::uint8_t*>(volume.data));
      break;
    case ScalarType::Int16:
      f(static_cast<const std::int16_t*>(volume.data));
      break;
    case ScalarType::UInt16:
      f(static_cast<const std::uint16_t*>(volume.data));
      break;
    case ScalarType::Int32:
      f(static_cast<const std::int32_t*>(volume.data));
      break;
    case ScalarType::Float32:
      f(static_cast<const float*>(volume.data));
      break;
    case ScalarType::Float64:
      f(static_cast<const double*>(volume.data));
      break;
  }
}

} // namespace accelvolume

#endif
