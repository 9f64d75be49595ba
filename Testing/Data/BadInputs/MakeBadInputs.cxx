// MakeBadInputs: writes the malformed volume files the CLI's bad-input tests load
// (Testing/CLI/CliInputTests.cmake), and the seed corpora of the fuzz targets in Testing/Fuzz.
// Generated rather than committed, so the repository holds no binary test files.
//   MakeBadInputs DIR                 every input below under DIR
//   MakeBadInputs --fuzz-seeds DIR    DIR/raw/ and DIR/header/ seeds in the fuzz targets' formats
// Plain C++17 and zlib: no VTK, so the fuzz build (clang) and the main build (gcc) both compile it.
#include <zlib.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

namespace
{
namespace fs = std::filesystem;

struct Input
{
  std::string name; // relative path; a name ending in '/' is a folder
  std::string bytes;
};

// Deflated bytes in a gzip (windowBits 31) or zlib (15) wrapper.
std::string Deflate(const std::string& bytes, bool gzip = true)
{
  z_stream zlib{};
  deflateInit2(&zlib, 9, Z_DEFLATED, gzip ? 31 : 15, 8, Z_DEFAULT_STRATEGY);
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

// Deterministic bytes that compress poorly (a multiplicative hash of the index).
std::string Noise(std::size_t size, unsigned seed)
{
  std::string bytes(size, '\0');
  for (std::size_t i = 0; i < size; ++i)
  {
    bytes[i] = static_cast<char>(((i + seed) * 2654435761u) >> 13);
  }
  return bytes;
}

std::string Flip(std::string bytes, std::size_t fromEnd)
{
  bytes[bytes.size() - fromEnd] = static_cast<char>(~bytes[bytes.size() - fromEnd]);
  return bytes;
}

std::string Vti(
  const std::string& wholeExtent, const std::string& spacing, const std::string& array)
{
  return "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" version=\"0.1\" "
         "byte_order=\"LittleEndian\">\n<ImageData WholeExtent=\"" +
    wholeExtent + "\" Origin=\"0 0 0\" Spacing=\"" + spacing + "\">\n<Piece Extent=\"" +
    wholeExtent + "\">\n<PointData Scalars=\"s\">\n" + array +
    "\n</PointData>\n</Piece>\n</ImageData>\n</VTKFile>\n";
}

std::vector<Input> Inputs()
{
  const std::string v64 = Noise(64, 1), gz64 = Deflate(v64), d40 = Noise(40, 2);
  const std::string zeros = Deflate(std::string(4096, '\0')),
                    zlibZeros = Deflate(std::string(4096, '\0'), false),
                    ten = Deflate(std::string(10, 'x'), false);
  // MetaImage: a 2x2x2 uchar header around `body`; NRRD: 10x2x2 uchar unless replaced.
  auto mhd = [](const std::string& dims, const std::string& more, const std::string& data)
  {
    return "ObjectType = Image\nNDims = 3\nDimSize = " + dims + "\n" + more +
      "ElementDataFile = " + data + "\n";
  };
  const std::string uchar = "ElementType = MET_UCHAR\n";
  const std::string nrrd10 = "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 10 2 2\n";
  const std::string compressed = "CompressedData = True\n";
  std::vector<Input> inputs = {
    // Headerless raw and gzip-compressed raw (dims and type from the name or --dims / --type).
    { "good_4x4x4_uint8.raw", v64 },
    { "plain.raw", v64 },
    { "truncated_4x4x4_uint8.raw", v64.substr(0, 40) },
    { "good_4x4x4_uint8.raw.gz", gz64 },
    { "truncated_4x4x4_uint8.raw.gz", gz64.substr(0, gz64.size() - 12) },
    { "short_4x4x4_uint8.raw.gz", Deflate(v64.substr(0, 40)) },
    { "long_4x4x4_uint8.raw.gz", Deflate(v64 + v64) },
    { "notgzip_4x4x4_uint8.raw.gz", v64 },
    { "crc_4x4x4_uint8.raw.gz", Flip(gz64, 8) },
    { "garbage_4x4x4_uint8.raw.gz", gz64.substr(0, 10) + Noise(200, 3) },
    { "trailing_4x4x4_uint8.raw.gz", gz64 + "trailing junk" },
    { "bomb_1024x1024x2048_float64.raw.gz", zeros },
    { "huge_100000x100000x100000_uint8.raw", "x" },
    // MetaImage (.mhd / .mha)
    { "data8.raw", Noise(8, 4) },
    { "data4.raw", Noise(4, 5) },
    { "good.mhd", mhd("2 2 2", uchar, "data8.raw") },
    { "no_dimsize.mhd", "NDims = 3\n" + uchar + "ElementDataFile = data8.raw\n" },
    { "negative_dimsize.mhd", mhd("2 -2 2", uchar, "data8.raw") },
    { "zero_dimsize.mhd", mhd("2 0 2", uchar, "data8.raw") },
    { "text_dimsize.mhd", mhd("2 two 2", uchar, "data8.raw") },
    { "huge_dimsize.mhd", mhd("100000 100000 100000", uchar, "data8.raw") },
    { "overflow_dimsize.mhd", mhd("3000000000 3000000000 3000000000", uchar, "data8.raw") },
    { "ndims4.mhd", "NDims = 4\nDimSize = 2 2 2 1\n" + uchar + "ElementDataFile = data8.raw\n" },
    { "bad_elementtype.mhd", mhd("2 2 2", "ElementType = MET_BOGUS\n", "data8.raw") },
    { "ulong_elementtype.mhd", mhd("2 2 2", "ElementType = MET_ULONG\n", "data8.raw") },
    { "missing_datafile.mhd", mhd("2 2 2", uchar, "nothere.raw") },
    { "short_datafile.mhd", mhd("2 2 2", uchar, "data4.raw") },
    { "no_elementdatafile.mhd", "NDims = 3\nDimSize = 2 2 2\n" + uchar },
    { "channels3.mhd", mhd("2 2 2", uchar + "ElementNumberOfChannels = 3\n", "data8.raw") },
    { "channels_negative.mhd",
      mhd("2 2 2", uchar + "ElementNumberOfChannels = -3\n", "data8.raw") },
    { "duplicate_key.mhd", mhd("2 2 2", "DimSize = 100000 100000 100000\n" + uchar, "data8.raw") },
    { "zero_spacing.mhd", mhd("2 2 2", "ElementSpacing = 0 0 0\n" + uchar, "data8.raw") },
    { "list.mhd", mhd("2 2 2", uchar, "LIST") + "data8.raw\n" },
    { "binary.mhd", Noise(300, 6) },
    { "compressed_bomb.mha",
      mhd("1024 1024 2048",
        "ElementType = MET_DOUBLE\n" + compressed +
          "CompressedDataSize = " + std::to_string(zlibZeros.size()) + "\n",
        "LOCAL") +
        zlibZeros },
    { "compressed_corrupt.mha",
      mhd("2 2 2", uchar + compressed + "CompressedDataSize = 20\n", "LOCAL") +
        std::string(20, 'x') },
    { "compressed_short.mha",
      mhd("20 20 20",
        uchar + compressed + "CompressedDataSize = " + std::to_string(ten.size()) + "\n", "LOCAL") +
        ten },
    // MetaIO reads "Tx" as true and hung on the garbage it then inflated.
    { "compressed_truthy.mha",
      mhd("2 2 2", uchar + "CompressedData = Tx\nCompressedDataSize = 20\n", "LOCAL") +
        std::string(20, 'R') },
    { "compressed_unsized.mha", mhd("2 2 2", uchar + compressed, "LOCAL") + Deflate(v64, false) },
    // NRRD (.nrrd attached, .nhdr detached)
    { "data40.raw", d40 },
    { "good.nrrd", nrrd10 + "encoding: raw\n\n" + d40 },
    { "good.nhdr", nrrd10 + "encoding: raw\ndata file: data40.raw\n" },
    { "bad_magic.nrrd", "NRRX0004\ntype: uchar\ndimension: 3\nsizes: 10 2 2\n\n" + d40 },
    { "no_sizes.nrrd", "NRRD0004\ntype: uchar\ndimension: 3\nencoding: raw\n\n" + d40 },
    { "sizes_before_dimension.nrrd",
      "NRRD0004\ntype: uchar\nsizes: 10 2 2\ndimension: 3\n\n" + d40 },
    { "bzip2.nrrd", nrrd10 + "encoding: bzip2\n\n" + d40 },
    { "uint64.nrrd", "NRRD0004\ntype: uint64\ndimension: 3\nsizes: 10 2 2\n\n" + d40 },
    { "short.nrrd", nrrd10 + "encoding: raw\n\n" + d40.substr(0, 20) },
    { "dimension1.nrrd", "NRRD0004\ntype: uchar\ndimension: 1\nsizes: 40\n\n" + d40 },
    { "ascii_attached.nrrd", nrrd10 + "encoding: ascii\n\n1 2 3 4 5\n" },
    { "gzip_corrupt.nrrd", nrrd10 + "encoding: gzip\n\n" + Flip(Deflate(d40), 8) },
    { "gzip_short.nrrd", nrrd10 + "encoding: gzip\n\n" + Deflate(d40.substr(0, 10)) },
    { "huge_sizes.nrrd",
      "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 100000 100000 100000\n\n" + d40 },
    { "rgb.nrrd", "NRRD0004\ntype: uchar\ndimension: 4\nsizes: 3 10 2 2\n\n" + d40 },
    { "nan_spacing.nrrd", nrrd10 + "spacings: nan 1 1\n\n" + d40 },
    { "empty_datafile.nhdr", nrrd10 + "data file: \n" },
    { "detached_missing.nhdr", nrrd10 + "data file: nothere.raw\n" },
    { "detached_short.nhdr", nrrd10 + "data file: data4.raw\n" },
    { "detached_none.nhdr", nrrd10 + "encoding: raw\n" },
    { "pattern.nhdr", nrrd10 + "data file: d%s%n.raw 1 2 1\n" },
    // vtkNrrdReader looped forever on a last header line without a line break.
    { "no_final_newline.nhdr", nrrd10 + "encoding: raw\ndata file: data40.raw" },
    // VTK XML image data (.vti)
    { "good.vti",
      Vti("0 1 0 1 0 1", "1 1 1",
        "<DataArray type=\"Float32\" Name=\"s\" format=\"ascii\">1 2 3 4 5 6 7 8</DataArray>") },
    { "not_xml.vti", "this is not XML\n" },
    { "truncated.vti",
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" version=\"0.1\">\n<ImageData" },
    { "huge_extent.vti",
      Vti("0 99999 0 99999 0 99999", "1 1 1",
        "<DataArray type=\"Float64\" Name=\"s\" format=\"ascii\">1 2 3</DataArray>") },
    { "big_extent.vti",
      Vti("0 1023 0 1023 0 2047", "1 1 1",
        "<DataArray type=\"Float64\" Name=\"s\" format=\"ascii\">1 2 3</DataArray>") },
    { "zero_spacing.vti",
      Vti("0 1 0 1 0 1", "0 0 0",
        "<DataArray type=\"Float32\" Name=\"s\" format=\"ascii\">1 2 3 4 5 6 7 8</DataArray>") },
    { "negative_components.vti",
      Vti("0 1 0 1 0 1", "1 1 1",
        "<DataArray type=\"Float32\" Name=\"s\" NumberOfComponents=\"-3\" "
        "format=\"ascii\">1</DataArray>") },
    // Anything else
    { "unknown.xyz", "abc" },
    { "folder.mhd/", "" },
    // A raw file with a datasets.json sidecar holding a 1 MiB string (crashed std::regex).
    { "sidecar/scan_4x4x4_uint8.raw", v64 },
    { "sidecar/datasets.json",
      "{\"datasets\": [{\"file\": \"" + std::string(1 << 20, 'a') +
        "\"}, {\"file\": \"scan_4x4x4_uint8.raw\", \"spacing\": [1, 2, 3]}]}" },
  };
  return inputs;
}

bool Write(const fs::path& path, const std::string& bytes)
{
  fs::create_directories(path.parent_path());
  std::ofstream stream(path, std::ios::binary | std::ios::trunc);
  stream.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  return static_cast<bool>(stream);
}

// Seeds for Testing/Fuzz: FuzzHeader takes [format byte][file bytes] (format: 0 .mhd, 1 .mha,
// 2 .nrrd, 3 .nhdr, 4 .vti); FuzzRawVolume takes [flags][dims x3][payload] (see FuzzRawVolume.cxx).
bool WriteSeeds(const fs::path& folder)
{
  const std::vector<std::string> formats = { ".mhd", ".mha", ".nrrd", ".nhdr", ".vti" };
  bool ok = true;
  int count = 0;
  for (const Input& input : Inputs())
  {
    for (std::size_t format = 0; format < formats.size(); ++format)
    {
      const std::string& extension = formats[format];
      const std::string& name = input.name;
      if (name.size() > extension.size() &&
        name.compare(name.size() - extension.size(), extension.size(), extension) == 0)
      {
        ok = Write(folder / "header" / ("seed" + std::to_string(count++)),
               std::string(1, static_cast<char>(format)) + input.bytes) &&
          ok;
      }
    }
  }
  // Flags: bit 0 gzip, bits 1-3 type (0 uint8 ... 6 float64), bit 4 datasets.json, bit 5 dims as
  // flags; dims code 3 is 4 samples (codes below 200 give code % 16 + 1).
  const std::string v64 = Noise(64, 1), gz64 = Deflate(v64);
  const std::string json = "{\"datasets\": [{\"file\": \"v.raw\", \"dims\": [4, 4, 4], "
                           "\"type\": \"uint8\", \"spacing\": [1, 2, 3]}]}";
  const std::string jsonGz = "{\"file\": \"v.raw.gz\", \"dims\": [4, 4, 4], \"type\": \"uint8\"}";
  const std::vector<std::string> raw = { std::string("\x00\x03\x03\x03", 4) + v64,
    std::string("\x01\x03\x03\x03", 4) + gz64, std::string("\x21\x03\x03\x03", 4) + gz64,
    std::string("\x01\x03\x03\x03", 4) + Flip(gz64, 8),
    std::string("\x01\x03\x03\x03", 4) + gz64 + "junk",
    std::string("\x01\x03\x03\x03", 4) + gz64.substr(0, 30),
    std::string("\x0d\xfa\xfa\xfa", 4) + Deflate(std::string(4096, '\0')),
    std::string("\x06\x01\x01\x07", 4) + Noise(2 * 4 * 4 * 4 * 8, 7),
    std::string("\x10\x03\x03\x03", 4) + std::string(1, static_cast<char>(json.size())) + json +
      v64,
    std::string("\x11\x03\x03\x03", 4) + std::string(1, static_cast<char>(jsonGz.size())) + jsonGz +
      gz64 };
  for (std::size_t i = 0; i < raw.size(); ++i)
  {
    ok = Write(folder / "raw" / ("seed" + std::to_string(i)), raw[i]) && ok;
  }
  return ok;
}

} // namespace

int main(int argc, char* argv[])
{
  const bool seeds = argc == 3 && std::string(argv[1]) == "--fuzz-seeds";
  if (argc != 2 && !seeds)
  {
    std::cerr << "usage: MakeBadInputs DIR | MakeBadInputs --fuzz-seeds DIR\n";
    return 2;
  }
  const fs::path folder = argv[argc - 1];
  if (seeds)
  {
    return WriteSeeds(folder) ? 0 : 1;
  }
  bool ok = true;
  for (const Input& input : Inputs())
  {
    if (input.name.back() == '/')
    {
      fs::create_directories(folder / input.name);
      continue;
    }
    ok = Write(folder / input.name, input.bytes) && ok;
  }
  if (!ok)
  {
    std::cerr << "MakeBadInputs: cannot write under '" << folder.string() << "'\n";
  }
  return ok ? 0 : 1;
}
