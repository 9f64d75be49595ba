// FuzzRawVolume: libFuzzer target for the CLI's headerless raw and .raw.gz loading (size checks,
// the gzip stream checks and inflation into the volume) and its datasets.json sidecar parser.
// Input: [flags][x][y][z][payload]
//   flags bit 0   gzip: the file is .raw.gz
//         bits 1-3 scalar type: uint8 int8 uint16 int16 int32 float32 float64 (mod 7)
//         bit 4   sidecar: the payload starts with [n][n bytes of datasets.json] and the file is
//                 v.raw[.gz], so dims and type come from the sidecar
//         bit 5   dims and type as --dims / --type flags instead of in the file name
//   x, y, z dims codes: below 200 give code % 16 + 1, 200-249 give (code - 199) * 1000 and
//           250-255 give 2^30 ... 2^35 (absurd claims that must be refused before allocating).
// MakeBadInputs --fuzz-seeds writes seeds in this format.
#include "FuzzSupport.h"

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <string>

namespace
{
std::int64_t Dimension(unsigned char code)
{
  return code < 200 ? code % 16 + 1
    : code < 250    ? (code - 199) * std::int64_t(1000)
                    : std::int64_t(1) << (code - 220);
}
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  using namespace accelvolume;
  if (size < 4)
  {
    return 0;
  }
  static const char* const types[] = { "uint8", "int8", "uint16", "int16", "int32", "float32",
    "float64" };
  const unsigned flags = data[0];
  const char* type = types[((flags >> 1) & 7) % 7];
  std::int64_t dims[3];
  for (int axis = 0; axis < 3; ++axis)
  {
    dims[axis] = Dimension(data[axis + 1]);
  }
  std::string payload(reinterpret_cast<const char*>(data) + 4, size - 4);
  cli::VolumeRequest request;
  std::string name = "v_" + std::to_string(dims[0]) + "x" + std::to_string(dims[1]) + "x" +
    std::to_string(dims[2]) + "_" + type + ".raw";
  std::filesystem::remove(fuzz::Folder() / "datasets.json");
  if (flags & 16)
  {
    const std::size_t length =
      payload.empty() ? 0 : std::min<std::size_t>(std::uint8_t(payload[0]), payload.size() - 1);
    fuzz::Write("datasets.json", payload.empty() ? "" : payload.substr(1, length));
    payload = payload.substr(std::min(payload.size(), length + 1));
    name = "v.raw";
  }
  else if (flags & 32)
  {
    // The CLI's --dims parser accepts at most 2^30 per axis.
    request.haveDims = true;
    for (int axis = 0; axis < 3; ++axis)
    {
      request.dims[axis] = static_cast<int>(std::min<std::int64_t>(dims[axis], 1 << 30));
    }
    request.kind = cli::ParseScalarType(type);
    name = "v.raw";
  }
  name += flags & 1 ? ".gz" : "";
  fuzz::Write(name, payload);
  request.inputPath = (fuzz::Folder() / name).string();
  fuzz::LoadAndCheck(request);
  std::filesystem::remove(fuzz::Folder() / name);
  return 0;
}
