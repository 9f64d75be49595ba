// VolumeHeaderChecks: MetaImage / NRRD header validation and the small helpers VolumeIO shares with
// it. Internal to the CLI's volume loading (namespace accelvolume::cli::detail).
#ifndef accelvolume_cli_VolumeHeaderChecks_h
#define accelvolume_cli_VolumeHeaderChecks_h

#include "VolumeIO.h"

#include <vtkType.h>

#include <cstdint>
#include <filesystem>
#include <string>

namespace accelvolume::cli::detail
{
using Dimensions = std::int64_t[3];

struct KindInfo
{
  ScalarKind kind;
  const char* name;
  int vtkType;
  int size;
};

inline constexpr KindInfo Kinds[] = { { ScalarKind::UInt8, "uint8", VTK_UNSIGNED_CHAR, 1 },
  { ScalarKind::Int8, "int8", VTK_SIGNED_CHAR, 1 },
  { ScalarKind::UInt16, "uint16", VTK_UNSIGNED_SHORT, 2 },
  { ScalarKind::Int16, "int16", VTK_SHORT, 2 }, { ScalarKind::Int32, "int32", VTK_INT, 4 },
  { ScalarKind::Float32, "float32", VTK_FLOAT, 4 },
  { ScalarKind::Float64, "float64", VTK_DOUBLE, 8 } };

// The Kinds entry of kind; nullptr for ScalarKind::Unknown.
const KindInfo* FindKind(ScalarKind kind);
std::string Lower(std::string text);
std::string Trim(const std::string& text);
bool EndsWith(const std::string& text, const std::string& suffix);
// "256x256x113".
std::string DimensionsText(const Dimensions dims);
// Refuses absurd sizes from the header alone, before any allocation; bytes = voxels * type size.
bool CheckSize(
  const Dimensions dims, const KindInfo& kind, std::int64_t& bytes, std::string& error);
// -1 when the size cannot be read.
std::int64_t FileSize(const std::filesystem::path& path);

// Checks a MetaImage (nrrd false) or NRRD header against its data before a VTK reader sees the
// file, because those readers trust headers and can misbehave on malformed ones. On failure sets
// error to one line and returns false.
bool CheckHeader(const std::string& path, bool nrrd, std::string& error);

} // namespace accelvolume::cli::detail

#endif
