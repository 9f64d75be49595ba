// Volume scalar encodings for one-channel 3D textures, shared by the mapper and the octree.
#include "vtkAccelVolumeScalarEncoding.h"

#include "vtkDataArray.h"
#include "vtkType.h"

#include <algorithm>
#include <cmath>

namespace
{
template <typename Source, typename Target>
void OffsetCopy(const Source* source, size_t count, int offset, std::vector<Target>& target)
{
  target.resize(count);
  for (size_t i = 0; i < count; ++i)
  {
    target[i] = static_cast<Target>(static_cast<int>(source[i]) + offset);
  }
}

template <typename Source>
void NormalizeCopy(
  const Source* source, size_t count, const double range[2], std::vector<float>& target)
{
  const double width = range[1] > range[0] ? range[1] - range[0] : 1.0;
  target.resize(count);
  for (size_t i = 0; i < count; ++i)
  {
    const double value = static_cast<double>(source[i]);
    // NaN samples become the minimum; +/-Inf clamp to the ends of the finite range.
    target[i] = std::isnan(value)
      ? 0.0f
      : static_cast<float>(std::min(1.0, std::max(0.0, (value - range[0]) / width)));
  }
}
}

bool vtkAccelVolumeEncodeScalars(vtkDataArray* scalars, const double range[2],
  vtkAccelVolumeEncodedScalars& encoded, std::string& error)
{
  const size_t count = static_cast<size_t>(scalars->GetNumberOfTuples());
  const void* raw = scalars->GetVoidPointer(0);
  encoded.Range[0] = range[0];
  encoded.Range[1] = range[1];
  encoded.Normalized = false;
  encoded.DecodeScale = 1.0;
  encoded.DecodeOffset = 0.0;
  encoded.Data = raw;
  switch (scalars->GetDataType())
  {
    case VTK_UNSIGNED_CHAR:
      encoded.TextureType = VTK_UNSIGNED_CHAR;
      encoded.DecodeScale = 255.0;
      return true;
    case VTK_CHAR:
    case VTK_SIGNED_CHAR:
      OffsetCopy(static_cast<const signed char*>(raw), count, 128, encoded.Bytes);
      encoded.TextureType = VTK_UNSIGNED_CHAR;
      encoded.Data = encoded.Bytes.data();
      encoded.DecodeScale = 255.0;
      encoded.DecodeOffset = -128.0;
      return true;
    case VTK_UNSIGNED_SHORT:
      encoded.TextureType = VTK_UNSIGNED_SHORT;
      encoded.DecodeScale = 65535.0;
      return true;
    case VTK_SHORT:
      OffsetCopy(static_cast<const short*>(raw), count, 32768, encoded.Shorts);
      encoded.TextureType = VTK_UNSIGNED_SHORT;
      encoded.Data = encoded.Shorts.data();
      encoded.DecodeScale = 65535.0;
      encoded.DecodeOffset = -32768.0;
      return true;
    case VTK_INT:
      NormalizeCopy(static_cast<const int*>(raw), count, range, encoded.Floats);
      break;
    case VTK_FLOAT:
      NormalizeCopy(static_cast<const float*>(raw), count, range, encoded.Floats);
      break;
    case VTK_DOUBLE:
      NormalizeCopy(static_cast<const double*>(raw), count, range, encoded.Floats);
      break;
    default:
      error = std::string("unsupported scalar type ") + scalars->GetDataTypeAsString();
      return false;
  }
  encoded.TextureType = VTK_FLOAT;
  encoded.Data = encoded.Floats.data();
  encoded.Normalized = true;
  return true;
}

bool vtkAccelVolumeScalarEncodingOf(vtkDataArray* scalars, const double range[2],
  vtkAccelVolumeEncodedScalars& encoding, std::string& error)
{
  encoding = vtkAccelVolumeEncodedScalars();
  encoding.Range[0] = range[0];
  encoding.Range[1] = range[1];
  switch (scalars->GetDataType())
  {
    case VTK_UNSIGNED_CHAR:
    case VTK_CHAR:
    case VTK_SIGNED_CHAR:
      encoding.TextureType = VTK_UNSIGNED_CHAR;
      encoding.DecodeScale = 255.0;
      encoding.DecodeOffset = scalars->GetDataType() == VTK_UNSIGNED_CHAR ? 0.0 : -128.0;
      return true;
    case VTK_UNSIGNED_SHORT:
    case VTK_SHORT:
      encoding.TextureType = VTK_UNSIGNED_SHORT;
      encoding.DecodeScale = 65535.0;
      encoding.DecodeOffset = scalars->GetDataType() == VTK_SHORT ? -32768.0 : 0.0;
      return true;
    case VTK_INT:
    case VTK_FLOAT:
    case VTK_DOUBLE:
      encoding.TextureType = VTK_FLOAT;
      encoding.Normalized = true;
      return true;
    default:
      error = std::string("unsupported scalar type ") + scalars->GetDataTypeAsString();
      return false;
  }
}
