// VolumeHeaderChecks: MetaImage / NRRD header validation, compressed-data checks and the small
// helpers VolumeIO shares with them. Internal to the CLI's volume loading
// (namespace accelvolume::cli::detail). Everything here reads untrusted bytes; the fuzz targets in
// Testing/Fuzz call it directly.
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
  ScalarType kind;
  const char* name;
  int vtkType;
  int size;
};

inline constexpr KindInfo Kinds[] = { { ScalarType::UInt8, "uint8", VTK_UNSIGNED_CHAR, 1 },
  { ScalarType::Int8, "int8", VTK_SIGNED_CHAR, 1 },
  { ScalarType::UInt16, "uint16", VTK_UNSIGNED_SHORT, 2 },
  { ScalarType::Int16, "int16", VTK_SHORT, 2 }, { ScalarType::Int32, "int32", VTK_INT, 4 },
  { ScalarType::Float32, "float32", VTK_FLOAT, 4 },
  { ScalarType::Float64, "float64", VTK_DOUBLE, 8 } };

// Deflate codes a 258-byte match in at least 2 bits, so n compressed bytes never inflate to more
// than n * 1032 bytes: a larger claim is refused before anything is allocated for it.
inline constexpr std::int64_t MaximumDeflateRatio = 1032;
// The most voxels and bytes the CLI loads; anything larger is refused from the header alone.
inline constexpr std::int64_t MaximumVoxels = std::int64_t(1) << 31;
inline constexpr std::int64_t MaximumBytes = std::int64_t(16) << 30;

// The Kinds entry of kind; nullptr for std::nullopt.
const KindInfo* FindKind(OptionalScalarType kind);
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
// A plain non-negative decimal integer of at most 12 digits (no sign, no spaces).
bool ParseCount(const std::string& text, std::int64_t& value);

enum class Wrapper
{
  Gzip,      // gzip members only (.raw.gz, NRRD "encoding: gzip")
  ZlibOrGzip // zlib or gzip, as MetaIO's CompressedData accepts
};

// Inflates `length` bytes of path from offset (length < 0: to the end of the file) and checks
// that they hold exactly `expected` bytes: no less, no more, no corrupt or truncated stream and no
// trailing bytes after the last gzip member. Writes the bytes to output, or only counts them when
// output is nullptr. `needs` ends the size-mismatch message ("4x4x4 uint8 needs 64 bytes").
bool InflateFile(const std::string& path, std::int64_t offset, std::int64_t length, Wrapper wrapper,
  char* output, std::int64_t expected, const std::string& needs, std::string& error);

// What a header says about its volume, once CheckHeader accepted it.
struct HeaderSummary
{
  Dimensions dims = { 1, 1, 1 };
  const KindInfo* kind = nullptr;
};

// Checks a MetaImage (nrrd false) or NRRD header, and its data, before a VTK reader sees the file:
// those readers trust headers and crash, hang, allocate absurd sizes or read garbage on malformed
// ones. The NRRD checks follow vtkNrrdReader's own parse (VTK 9.1) field by field, so what is
// checked is what VTK will read. On failure sets error to one line and returns false.
bool CheckHeader(const std::string& path, bool nrrd, HeaderSummary& summary, std::string& error);

} // namespace accelvolume::cli::detail

#endif
