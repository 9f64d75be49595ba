// FuzzHeader: libFuzzer target for the CLI's MetaImage and NRRD header checks, the compressed and
// ASCII data checks behind them and the .vti sizing, each followed (when the checks pass) by VTK's
// own reader, end to end through LoadVolume.
// Input: [format][file bytes]; format % 5: 0 .mhd, 1 .mha, 2 .nrrd, 3 .nhdr, 4 .vti. Next to the
// file lie data files a header may name: data.raw (64 bytes), data4.raw (4 bytes), data.gz (gzip
// of 64 bytes), data.z (zlib of 64 bytes), values.txt ("1 2 ... 64") and a folder, dir.
// MakeBadInputs --fuzz-seeds writes seeds in this format.
#include "FuzzSupport.h"

#include <zlib.h>

#include <cstdint>
#include <filesystem>
#include <string>

namespace
{
std::string Deflate(const std::string& bytes, int windowBits)
{
  z_stream zlib{};
  deflateInit2(&zlib, 9, Z_DEFLATED, windowBits, 8, Z_DEFAULT_STRATEGY);
  std::string out(deflateBound(&zlib, static_cast<uLong>(bytes.size())), '\0');
  zlib.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data()));
  zlib.avail_in = static_cast<uInt>(bytes.size());
  zlib.next_out = reinterpret_cast<Bytef*>(&out[0]);
  zlib.avail_out = static_cast<uInt>(out.size());
  deflate(&zlib, Z_FINISH);
  out.resize(zlib.total_out);
  deflateEnd(&zlib);
  return out;
}
}

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
  using accelvolume::fuzz::Write;
  std::string bytes(64, '\0'), text;
  for (int i = 0; i < 64; ++i)
  {
    bytes[i] = static_cast<char>(i * 37 + 11);
    text += std::to_string(i + 1) + (i % 8 == 7 ? "\n" : " ");
  }
  Write("data.raw", bytes);
  Write("data4.raw", bytes.substr(0, 4));
  Write("data.gz", Deflate(bytes, 31));
  Write("data.z", Deflate(bytes, 15));
  Write("values.txt", text);
  std::filesystem::create_directories(accelvolume::fuzz::Folder() / "dir");
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  using namespace accelvolume;
  if (size < 1)
  {
    return 0;
  }
  static const char* const extensions[] = { ".mhd", ".mha", ".nrrd", ".nhdr", ".vti" };
  const std::string name = std::string("h") + extensions[data[0] % 5];
  fuzz::Write(name, std::string(reinterpret_cast<const char*>(data) + 1, size - 1));
  cli::VolumeRequest request;
  request.inputPath = (fuzz::Folder() / name).string();
  fuzz::LoadAndCheck(request);
  std::filesystem::remove(fuzz::Folder() / name);
  return 0;
}
