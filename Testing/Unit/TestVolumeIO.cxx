// TestVolumeIO: unit tests for the CLI's volume loading (every format, name patterns, errors).
#include "VolumeIO.h"

#include <vtkDataArray.h>
#include <vtkFloatArray.h>
#include <vtkMatrix3x3.h>
#include <vtkMetaImageWriter.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkType.h>
#include <vtkXMLImageDataWriter.h>

#include <gtest/gtest.h>
#include <zlib.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sys/resource.h>
#include <unistd.h>

namespace
{
namespace fs = std::filesystem;
using namespace accelvolume::cli;

// A small volume whose values identify each voxel and fit every scalar type.
vtkSmartPointer<vtkImageData> MakeImage(int x, int y, int z, int vtkType, int components = 1)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(x, y, z);
  image->SetSpacing(0.5, 1.0, 2.0);
  image->AllocateScalars(vtkType, components);
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  for (vtkIdType index = 0; index < scalars->GetNumberOfValues(); ++index)
  {
    scalars->SetVariantValue(index, vtkVariant((index * 7) % 120));
  }
  return image;
}

void ExpectSameVoxels(vtkImageData* expected, vtkImageData* actual, bool compareSpacing = true)
{
  ASSERT_NE(actual, nullptr);
  int a[3], b[3];
  expected->GetDimensions(a);
  actual->GetDimensions(b);
  EXPECT_EQ(std::vector<int>(a, a + 3), std::vector<int>(b, b + 3));
  vtkDataArray* e = expected->GetPointData()->GetScalars();
  vtkDataArray* v = actual->GetPointData()->GetScalars();
  ASSERT_NE(v, nullptr);
  EXPECT_EQ(DescribeVolume(expected), DescribeVolume(actual));
  ASSERT_EQ(e->GetNumberOfValues(), v->GetNumberOfValues());
  for (vtkIdType index = 0; index < e->GetNumberOfValues(); ++index)
  {
    ASSERT_EQ(e->GetVariantValue(index).ToDouble(), v->GetVariantValue(index).ToDouble()) << index;
  }
  if (compareSpacing)
  {
    for (int axis = 0; axis < 3; ++axis)
    {
      EXPECT_DOUBLE_EQ(expected->GetSpacing()[axis], actual->GetSpacing()[axis]);
    }
  }
}

class VolumeIO : public ::testing::Test
{
protected:
  void SetUp() override
  {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    this->Directory =
      fs::temp_directory_path() / ("accelvolume_" + std::to_string(getpid()) + "_" + info->name());
    fs::remove_all(this->Directory);
    fs::create_directories(this->Directory);
  }
  void TearDown() override { fs::remove_all(this->Directory); }

  std::string Path(const std::string& name) const { return (this->Directory / name).string(); }

  std::string WriteFile(const std::string& name, const std::string& bytes) const
  {
    std::ofstream(this->Path(name), std::ios::binary) << bytes;
    return this->Path(name);
  }

  static std::string Bytes(vtkImageData* image)
  {
    vtkDataArray* scalars = image->GetPointData()->GetScalars();
    const auto size = scalars->GetNumberOfValues() * scalars->GetDataTypeSize();
    return std::string(static_cast<const char*>(scalars->GetVoidPointer(0)), size);
  }

  std::string WriteGzip(const std::string& name, const std::string& bytes) const
  {
    gzFile file = gzopen(this->Path(name).c_str(), "wb");
    EXPECT_EQ(gzwrite(file, bytes.data(), static_cast<unsigned>(bytes.size())),
      static_cast<int>(bytes.size()));
    gzclose(file);
    return this->Path(name);
  }

  static std::string ReadBytes(const std::string& path)
  {
    std::ifstream stream(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(stream), {});
  }

  // gzip (windowBits 15 + 16) or zlib (15) compressed bytes.
  static std::string Deflate(const std::string& bytes, bool gzip = true)
  {
    z_stream zlib{};
    EXPECT_EQ(deflateInit2(&zlib, 9, Z_DEFLATED, gzip ? 31 : 15, 8, Z_DEFAULT_STRATEGY), Z_OK);
    std::string out(deflateBound(&zlib, bytes.size()), '\0');
    zlib.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data()));
    zlib.avail_in = static_cast<uInt>(bytes.size());
    zlib.next_out = reinterpret_cast<Bytef*>(&out[0]);
    zlib.avail_out = static_cast<uInt>(out.size());
    EXPECT_EQ(deflate(&zlib, Z_FINISH), Z_STREAM_END);
    out.resize(zlib.total_out);
    deflateEnd(&zlib);
    return out;
  }

  static vtkSmartPointer<vtkImageData> Load(const std::string& path, std::string& error)
  {
    VolumeRequest request;
    request.inputPath = path;
    return LoadVolume(request, error);
  }

  // Loading must fail with a one-line message containing every given fragment.
  static void ExpectError(const VolumeRequest& request, const std::vector<std::string>& fragments)
  {
    std::string error;
    EXPECT_EQ(LoadVolume(request, error), nullptr) << request.inputPath;
    EXPECT_EQ(error.find('\n'), std::string::npos) << error;
    for (const std::string& fragment : fragments)
    {
      EXPECT_NE(error.find(fragment), std::string::npos)
        << "'" << fragment << "' not in: " << error;
    }
  }
  static void ExpectError(const std::string& path, const std::vector<std::string>& fragments)
  {
    VolumeRequest request;
    request.inputPath = path;
    ExpectError(request, fragments);
  }

  fs::path Directory;
};

TEST(ScalarKinds, NamesRoundTrip)
{
  const std::vector<std::pair<std::string, int>> expected = { { "uint8", VTK_UNSIGNED_CHAR },
    { "int8", VTK_SIGNED_CHAR }, { "uint16", VTK_UNSIGNED_SHORT }, { "int16", VTK_SHORT },
    { "int32", VTK_INT }, { "float32", VTK_FLOAT }, { "float64", VTK_DOUBLE } };
  for (const auto& entry : expected)
  {
    const OptionalScalarType kind = ParseScalarType(entry.first);
    EXPECT_NE(kind, std::nullopt);
    EXPECT_EQ(ToVTKType(kind), entry.second);
    EXPECT_EQ(ScalarTypeName(kind), entry.first);
  }
  EXPECT_EQ(ParseScalarType("UInt16"), ScalarType::UInt16);
  EXPECT_EQ(ParseScalarType("uint64"), std::nullopt);
  EXPECT_EQ(ParseScalarType(""), std::nullopt);
  EXPECT_EQ(ToVTKType(std::nullopt), VTK_VOID);
  EXPECT_STREQ(ScalarTypeName(std::nullopt), "unknown");
}

TEST_F(VolumeIO, PhantomIsTheDefault)
{
  std::string error;
  VolumeRequest request;
  request.phantomDims[0] = 16;
  request.phantomDims[1] = 12;
  request.phantomDims[2] = 8;
  auto image = LoadVolume(request, error);
  ASSERT_NE(image, nullptr) << error;
  EXPECT_EQ(DescribeVolume(image), "16x12x8 float32");
  EXPECT_STREQ(image->GetPointData()->GetScalars()->GetName(), "scalars");
  EXPECT_EQ(image->GetOrigin()[0], 0.0);

  accelvolume::PhantomVolume phantom;
  ASSERT_TRUE(accelvolume::GeneratePhantom("vessels", request.phantomDims, 0, phantom, error));
  auto* values = vtkFloatArray::SafeDownCast(image->GetPointData()->GetScalars());
  ASSERT_NE(values, nullptr);
  EXPECT_TRUE(std::equal(phantom.values.begin(), phantom.values.end(), values->GetPointer(0)));

  request.phantom = "box";
  request.haveSpacing = true;
  request.spacing[2] = 3;
  image = LoadVolume(request, error);
  ASSERT_NE(image, nullptr) << error;
  EXPECT_EQ(image->GetSpacing()[2], 3.0);
  request.phantom = "teapot";
  ExpectError(request, { "unknown phantom 'teapot'" });
}

TEST_F(VolumeIO, MetaImageRoundTrips)
{
  for (const std::string name : { "volume.mhd", "volume.mha" })
  {
    auto image = MakeImage(5, 4, 3, VTK_UNSIGNED_SHORT);
    vtkNew<vtkMetaImageWriter> writer;
    writer->SetInputData(image);
    writer->SetFileName(this->Path(name).c_str());
    writer->SetCompression(name == "volume.mha");
    writer->Write();
    std::string error;
    ExpectSameVoxels(image, Load(this->Path(name), error));
    EXPECT_EQ(error, "");
  }
}

TEST_F(VolumeIO, XMLImageDataRoundTrips)
{
  for (int type : { VTK_FLOAT, VTK_SIGNED_CHAR, VTK_DOUBLE })
  {
    auto image = MakeImage(3, 5, 7, type);
    vtkNew<vtkXMLImageDataWriter> writer;
    writer->SetInputData(image);
    writer->SetFileName(this->Path("volume.vti").c_str());
    writer->Write();
    std::string error;
    ExpectSameVoxels(image, Load(this->Path("volume.vti"), error));
  }
}

TEST_F(VolumeIO, NrrdRoundTrips)
{
  auto image = MakeImage(12, 3, 2, VTK_SHORT);
  const std::string header = "type: short\ndimension: 3\nsizes: 12 3 2\nspacings: 0.5 1 2\n"
                             "endian: little\nencoding: raw\n";
  this->WriteFile("data.raw", Bytes(image));
  std::string error;
  ExpectSameVoxels(image,
    Load(this->WriteFile("volume.nhdr", "NRRD0004\n" + header + "data file: data.raw\n"), error));
  EXPECT_EQ(error, "");
  ExpectSameVoxels(image,
    Load(this->WriteFile("volume.nrrd", "NRRD0004\n# comment\n" + header + "\n" + Bytes(image)),
      error));
  EXPECT_EQ(error, "");
}

TEST_F(VolumeIO, RawAndGzipRoundTripWithDimsAndTypeFromName)
{
  for (int type : { VTK_UNSIGNED_CHAR, VTK_SIGNED_CHAR, VTK_UNSIGNED_SHORT, VTK_SHORT, VTK_INT,
         VTK_FLOAT, VTK_DOUBLE })
  {
    auto image = MakeImage(6, 5, 3, type);
    image->SetSpacing(1, 1, 1);
    const std::string stem = std::string("scan_6x5x3_") + DescribeVolume(image).substr(6);
    std::string error;
    ExpectSameVoxels(image, Load(this->WriteFile(stem + ".raw", Bytes(image)), error));
    ExpectSameVoxels(image, Load(this->WriteGzip(stem + ".raw.gz", Bytes(image)), error));
    EXPECT_EQ(error, "");
  }
}

TEST_F(VolumeIO, ExplicitFlagsWinOverName)
{
  auto image = MakeImage(2, 4, 4, VTK_UNSIGNED_SHORT);
  image->SetSpacing(1, 1, 1);
  VolumeRequest request;
  request.inputPath = this->WriteFile("wrong_4x4x4_uint8.raw", Bytes(image));
  request.haveDims = true;
  request.dims[0] = 2;
  request.dims[1] = 4;
  request.dims[2] = 4;
  request.kind = ScalarType::UInt16;
  std::string error;
  ExpectSameVoxels(image, LoadVolume(request, error));

  // Name dims with a flag type: 4x4x4 uint16 needs 128 bytes, the file has 64.
  request.haveDims = false;
  ExpectError(request, { "size mismatch", "64", "128" });
  request.kind = std::nullopt;
  std::string plain = this->WriteFile("plain.raw", Bytes(image));
  ExpectError(plain, { "--dims and --type" });
  request.inputPath = plain;
  request.kind = ScalarType::UInt16;
  ExpectError(request, { "--dims", "NAME_256x256x113_uint16.raw" });
}

TEST_F(VolumeIO, DatasetsJsonGivesSpacingUnlessFlagged)
{
  auto image = MakeImage(3, 3, 3, VTK_UNSIGNED_CHAR);
  this->WriteGzip("ct_3x3x3_uint8.raw.gz", Bytes(image));
  this->WriteFile("datasets.json",
    R"({"description": "x", "datasets": [ {"file": "other_1x1x1_uint8.raw", "spacing": [9, 9, 9]},
       {"name": "ct", "file": "ct_3x3x3_uint8.raw.gz", "gz": true, "spacing": [0.5, 1.0, 2.0],
        "min": -1.5e2, "ok": null, "note": "quote \" and \u00e9"}]})");
  std::string error;
  ExpectSameVoxels(image, Load(this->Path("ct_3x3x3_uint8.raw.gz"), error));

  VolumeRequest request;
  request.inputPath = this->Path("ct_3x3x3_uint8.raw.gz");
  request.haveSpacing = true;
  request.spacing[0] = 4;
  auto loaded = LoadVolume(request, error);
  ASSERT_NE(loaded, nullptr) << error;
  EXPECT_EQ(loaded->GetSpacing()[0], 4.0);
  EXPECT_EQ(loaded->GetSpacing()[2], 1.0);

  // A broken sidecar is optional metadata: it is ignored, not fatal.
  this->WriteFile("datasets.json", "{ \"datasets\": [ {");
  loaded = Load(this->Path("ct_3x3x3_uint8.raw.gz"), error);
  ASSERT_NE(loaded, nullptr) << error;
  EXPECT_EQ(loaded->GetSpacing()[2], 1.0);
}

TEST_F(VolumeIO, FileErrorsAreReported)
{
  ExpectError(this->Path("missing_4x4x4_uint8.raw"), { "cannot open", "missing_4x4x4_uint8.raw" });
  ExpectError(this->WriteFile("volume.xyz", "abc"), { "unknown file extension", ".raw.gz" });
  ExpectError(this->WriteFile("short_4x4x4_uint8.raw", std::string(60, 'a')),
    { "size mismatch", "60", "64" });
  ExpectError(this->WriteGzip("small_4x4x4_uint8.raw.gz", std::string(60, 'a')),
    { "size mismatch", "60", "64" });
  ExpectError(this->WriteGzip("big_4x4x4_uint8.raw.gz", std::string(65, 'a')),
    { "size mismatch", "more than 64" });
  ExpectError(this->WriteFile("plain_4x4x4_uint8.raw.gz", std::string(64, 'a')), { "not gzip" });
  ExpectError(this->WriteFile("zero_0x4x4_uint8.raw", ""), { "at least 1" });

  std::string noise(40000, '\0');
  for (std::size_t i = 0; i < noise.size(); ++i)
  {
    noise[i] = static_cast<char>((i * 2654435761u) >> 13);
  }
  std::string compressed;
  {
    std::ifstream stream(this->WriteGzip("good_40000x1x1_uint8.raw.gz", noise), std::ios::binary);
    compressed.assign(std::istreambuf_iterator<char>(stream), {});
  }
  ExpectError(
    this->WriteFile("cut_40000x1x1_uint8.raw.gz", compressed.substr(0, compressed.size() / 2)),
    { "truncated gzip data", "the stream ends after" });
  std::string corrupt = compressed;
  for (std::size_t i = compressed.size() / 3; i < compressed.size() / 3 + 64; ++i)
  {
    corrupt[i] = static_cast<char>(~corrupt[i]);
  }
  ExpectError(this->WriteFile("bad_40000x1x1_uint8.raw.gz", corrupt), { "corrupt gzip" });
}

TEST_F(VolumeIO, AbsurdSizesAreRefusedWithoutAllocating)
{
  const auto start = std::chrono::steady_clock::now();
  ExpectError(this->WriteFile("huge_100000x100000x100000_uint8.raw", "x"), { "2^31" });
  ExpectError(this->WriteGzip("huge_100000x100000x100000_float64.raw.gz", "x"), { "2^31" });
  VolumeRequest request;
  request.inputPath = this->WriteFile("flags.raw", "x");
  request.haveDims = true;
  request.dims[0] = request.dims[1] = request.dims[2] = 100000;
  request.kind = ScalarType::Float64;
  ExpectError(request, { "refusing", "100000x100000x100000" });
  // 2^31 voxels of float64 is exactly 16 GiB; int32 at 2^31 + voxels would also be refused above.
  request.dims[0] = 2048;
  request.dims[1] = 1024;
  request.dims[2] = 1025;
  request.kind = ScalarType::UInt8;
  ExpectError(request, { "2^31" });
  ExpectError(this->WriteFile("huge.mhd",
                "NDims = 3\nDimSize = 100000 100000 100000\nElementType = MET_UCHAR\n"
                "ElementDataFile = LOCAL\n"),
    { "2^31" });
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(2));
}

TEST_F(VolumeIO, MalformedHeadersGiveErrors)
{
  std::string garbage(3000, '\0');
  for (std::size_t i = 0; i < garbage.size(); ++i)
  {
    garbage[i] = static_cast<char>(i * 131 + 7);
  }
  ExpectError(this->WriteFile("garbage.mhd", garbage), { "malformed MetaImage header" });
  ExpectError(this->WriteFile("words.mhd", "hello world\n"), { "malformed MetaImage header" });
  ExpectError(this->WriteFile("nodata.mhd", "NDims = 3\nDimSize = 2 2 2\n"), { "ElementDataFile" });
  ExpectError(this->WriteFile("dims.mhd",
                "NDims = 3\nDimSize = 2 2\nElementType = MET_UCHAR\nElementDataFile = LOCAL\n"),
    { "DimSize must be 3 positive integer(s), one per axis" });
  ExpectError(this->WriteFile("type.mhd",
                "NDims = 3\nDimSize = 2 2 2\nElementType = MET_ULONG\nElementDataFile = a.raw\n"),
    { "unsupported scalar type", "MET_ULONG" });
  ExpectError(
    this->WriteFile("lost.mhd",
      "NDims = 3\nDimSize = 2 2 2\nElementType = MET_UCHAR\nElementDataFile = lost.raw\n"),
    { "lost.raw", "does not exist" });
  ExpectError(this->WriteFile("short.mha",
                "NDims = 3\nDimSize = 2 2 2\nElementType = MET_SHORT\nElementDataFile = LOCAL\nab"),
    { "size mismatch", "2 data bytes", "16 bytes" });
  ExpectError(this->WriteFile("rgb.mhd",
                "NDims = 3\nDimSize = 2 2 2\nElementType = MET_UCHAR\n"
                "ElementNumberOfChannels = 3\nElementDataFile = LOCAL\n"),
    { "only single-component volumes are supported for now" });
  ExpectError(this->WriteFile("garbage.nrrd", garbage), { "NRRD magic" });
  ExpectError(this->WriteFile("detached.nhdr",
                "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 20 2 2\nencoding: raw\n"),
    { "data file" });
  ExpectError(this->WriteFile("hex.nrrd",
                "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 20 2 2\nencoding: hex\n\n00"),
    { "unsupported NRRD encoding 'hex'" });
  ExpectError(this->WriteFile("short.nrrd",
                "NRRD0004\ntype: float\ndimension: 3\nsizes: 10 2 2\nencoding: raw\n\n1234"),
    { "size mismatch", "4 data bytes", "160 bytes" });
  ExpectError(this->WriteFile("narrow.nrrd",
                "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 3 20 20\nencoding: raw\n\n"),
    { "single-component", "9 or fewer" });
  ExpectError(this->WriteFile("order.nrrd",
                "NRRD0004\ntype: uchar\nsizes: 20 20 20\ndimension: 3\nencoding: raw\n\n"),
    { "'sizes' before 'dimension'" });
  ExpectError(this->WriteFile("skip.nrrd",
                "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 20 2 2\n"
                "encoding: raw\nbyte skip: 4\n\n"),
    { "byte skip" });
  ExpectError(
    this->WriteFile("broken.vti", "<VTKFile type=\"ImageData\"><ImageData"), { "broken.vti" });
}

TEST_F(VolumeIO, UnsupportedVTIContentIsRefused)
{
  vtkNew<vtkXMLImageDataWriter> writer;
  writer->SetFileName(this->Path("rgb.vti").c_str());
  writer->SetInputData(MakeImage(2, 2, 2, VTK_UNSIGNED_CHAR, 3));
  writer->Write();
  ExpectError(this->Path("rgb.vti"), { "only single-component volumes are supported for now" });
  writer->SetFileName(this->Path("uint.vti").c_str());
  writer->SetInputData(MakeImage(2, 2, 2, VTK_UNSIGNED_INT));
  writer->Write();
  ExpectError(this->Path("uint.vti"), { "unsupported scalar type", "unsigned int" });
}

// Loads path in a child process whose address space is capped at its current size + 1 GiB, so
// any attempt to allocate a huge volume fails; the refusal must come first, with its message.
void ExpectRefusedWithinOneGiB(const std::string& path, const std::string& fragment)
{
  EXPECT_EXIT(
    {
      std::ifstream status("/proc/self/status");
      std::string line;
      long long kilobytes = 0;
      while (std::getline(status, line))
      {
        kilobytes = line.compare(0, 7, "VmSize:") == 0 ? std::stoll(line.substr(7)) : kilobytes;
      }
      rlimit limit;
      limit.rlim_cur = limit.rlim_max = static_cast<rlim_t>(kilobytes * 1024 + (1LL << 30));
      setrlimit(RLIMIT_AS, &limit);
      VolumeRequest request;
      request.inputPath = path;
      std::string error;
      const bool loaded = LoadVolume(request, error) != nullptr;
      std::fprintf(stderr, "%s\n", error.c_str());
      std::exit(!loaded && error.find(fragment) != std::string::npos ? 0 : 1);
    },
    ::testing::ExitedWithCode(0), "")
    << path << " must be refused with '" << fragment << "'";
}

TEST_F(VolumeIO, GzipStreamsAreCheckedExactly)
{
  std::string volume(64, '\0');
  for (std::size_t i = 0; i < volume.size(); ++i)
  {
    volume[i] = static_cast<char>(i * 3);
  }
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(4, 4, 4);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 1);
  std::copy(volume.begin(), volume.end(), static_cast<char*>(image->GetScalarPointer()));
  // Concatenated members are one valid gzip stream (gzip -c a b > c).
  std::string error;
  ExpectSameVoxels(image,
    Load(this->WriteFile(
           "two_4x4x4_uint8.raw.gz", Deflate(volume.substr(0, 20)) + Deflate(volume.substr(20))),
      error),
    false);
  EXPECT_EQ(error, "");
  const std::string good = Deflate(volume);
  ExpectError(this->WriteFile("tail_4x4x4_uint8.raw.gz", good + "garbage"),
    { "trailing bytes after the gzip stream" });
  std::string crc = good, length = good;
  crc[crc.size() - 8] = static_cast<char>(~crc[crc.size() - 8]);
  length[length.size() - 1] = static_cast<char>(~length[length.size() - 1]);
  ExpectError(this->WriteFile("crc_4x4x4_uint8.raw.gz", crc),
    { "corrupt gzip data", "after 64 of 64 bytes", "incorrect data check" });
  ExpectError(
    this->WriteFile("length_4x4x4_uint8.raw.gz", length), { "corrupt gzip", "incorrect length" });
  ExpectError(this->WriteFile("header_4x4x4_uint8.raw.gz", good.substr(0, 4)),
    { "truncated gzip data", "after 0 of 64 bytes" });
  ExpectError(this->WriteFile("cut_4x4x4_uint8.raw.gz", good.substr(0, good.size() - 4)),
    { "truncated gzip data" });
}

TEST_F(VolumeIO, HugeClaimsAreRefusedBeforeAllocating)
{
  const std::string zeros = Deflate(std::string(4096, '\0'));
  ExpectRefusedWithinOneGiB(this->WriteFile("bomb_1024x1024x2048_float64.raw.gz", zeros),
    "too few for 1024x1024x2048 float64");
  const std::string zlibZeros = Deflate(std::string(4096, '\0'), false);
  ExpectRefusedWithinOneGiB(
    this->WriteFile("bomb.mha",
      "NDims = 3\nDimSize = 1024 1024 2048\nElementType = MET_DOUBLE\n"
      "CompressedData = True\nCompressedDataSize = " +
        std::to_string(zlibZeros.size()) + "\nElementDataFile = LOCAL\n" + zlibZeros),
    "1032:1");
  ExpectRefusedWithinOneGiB(this->WriteFile("bomb.nrrd",
                              "NRRD0004\ntype: double\ndimension: 3\nsizes: 1024 1024 2048\n"
                              "encoding: gzip\n\n" +
                                zeros),
    "1032:1");
  ExpectRefusedWithinOneGiB(
    this->WriteFile("bomb.vti",
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" version=\"0.1\">\n"
      "<ImageData WholeExtent=\"0 1023 0 1023 0 2047\" Origin=\"0 0 0\" Spacing=\"1 1 1\">\n"
      "<Piece Extent=\"0 1023 0 1023 0 2047\"><PointData Scalars=\"s\">\n"
      "<DataArray type=\"Float64\" Name=\"s\" format=\"ascii\">1 2 3</DataArray>\n"
      "</PointData></Piece></ImageData></VTKFile>\n"),
    "too few for its 1024x1024x2048 extent");
  ExpectRefusedWithinOneGiB(
    this->WriteFile("huge.vti",
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" version=\"0.1\">\n"
      "<ImageData WholeExtent=\"0 99999 0 99999 0 99999\" Origin=\"0 0 0\" Spacing=\"1 1 1\">\n"
      "</ImageData></VTKFile>\n"),
    "more than 2^31 voxels");
  ExpectRefusedWithinOneGiB(
    this->WriteFile("huge_3000000x3000000x3000000_uint8.raw.gz", zeros), "more than 2^31 voxels");
}

TEST_F(VolumeIO, CompressedMetaImageDataIsVerified)
{
  auto image = MakeImage(20, 20, 20, VTK_UNSIGNED_CHAR);
  // A compressed .mha whose CompressedDataSize is that of `stored` unless `size` is given.
  auto mha = [](const std::string& stored, const std::string& size = "")
  {
    return "NDims = 3\nDimSize = 20 20 20\nElementSpacing = 0.5 1 2\nElementType = MET_UCHAR\n"
           "CompressedData = True\nCompressedDataSize = " +
      (size.empty() ? std::to_string(stored.size()) : size) + "\nElementDataFile = LOCAL\n" +
      stored;
  };
  const std::string data = Deflate(Bytes(image), false);
  std::string error;
  ExpectSameVoxels(image, Load(this->WriteFile("good.mha", mha(data)), error));
  EXPECT_EQ(error, "");
  ExpectError(this->WriteFile("garbage.mha", mha(std::string(100, 'x'))),
    { "corrupt compressed data", "after 0 of 8000 bytes" });
  ExpectError(this->WriteFile("short.mha", mha(Deflate(Bytes(image).substr(0, 100), false))),
    { "size mismatch", "decompresses to 100 bytes", "8000 bytes" });
  ExpectError(this->WriteFile("cut.mha", mha(data, std::to_string(data.size() / 2))),
    { "truncated compressed data" });
  ExpectError(this->WriteFile("size.mha", mha(data, "99999999")),
    { "CompressedData needs a CompressedDataSize", "got '99999999'" });
  // MetaIO reads compressed data without a CompressedDataSize wrongly (all zeros here).
  std::string unsized = mha(data);
  unsized.erase(unsized.find("CompressedDataSize"),
    unsized.find("ElementDataFile") - unsized.find("CompressedDataSize"));
  ExpectError(this->WriteFile("unsized.mha", unsized), { "needs a CompressedDataSize" });
  ExpectError(this->WriteFile("tail.mha", mha(data + "tail")),
    { "trailing bytes after the compressed stream" });
}

TEST_F(VolumeIO, MetaImageFieldsAreStrict)
{
  const std::string rest = "ElementType = MET_UCHAR\nElementDataFile = data.raw\n";
  this->WriteFile("data.raw", std::string(8, 'd'));
  const std::vector<std::pair<std::string, std::string>> cases = {
    { "NDims = 3\nNDims = 3\nDimSize = 2 2 2\n", "'NDims' appears twice" },
    { "NDims = three\nDimSize = 2 2 2\n", "NDims must be 1, 2 or 3, got 'three'" },
    { "NDims = 3\nDimSize = 2 two 2\n", "DimSize must be 3 positive integer(s)" },
    { "NDims = 3\nDimSize = 99999999999999999999 1 1\n", "DimSize must be 3 positive" },
    { "NDims = 3\nDimSize = 2 2 2\nElementNumberOfChannels = -3\n",
      "ElementNumberOfChannels must be a positive integer, got '-3'" },
    { "NDims = 3\nDimSize = 2 2 2\nBinaryData = False\n", "BinaryData = False" },
    { "NDims = 3\nDimSize = 2 2 2\nBinaryData = 0\n", "BinaryData = False" },
    // MetaIO takes any value starting with T, t or 1 as true (this one hung it before).
    { "NDims = 3\nDimSize = 2 2 2\nCompressedData = TrDataArrayue\n",
      "CompressedData needs a CompressedDataSize" },
    // MetaIO matches field names exactly: "ndims" is not NDims.
    { "ndims = 3\nDimSize = 2 2 2\n", "NDims must be 1, 2 or 3, got ''" },
    { "NDims = 3\nDimSize = 2 2 2\nHeaderSize = x\n", "HeaderSize must be -1 or a byte count" },
    { "NDims = 3\nDimSize = 2 2 2\nElementSpacing = 0 0 0\n", "spacing must be positive" },
  };
  for (const auto& entry : cases)
  {
    ExpectError(this->WriteFile("case.mhd", entry.first + rest), { entry.second });
  }
  ExpectError(this->WriteFile("list.mhd",
                "NDims = 3\nDimSize = 2 2 2\nElementType = MET_UCHAR\nElementDataFile = LIST\n"
                "data.raw\n"),
    { "multi-file data" });
  fs::create_directories(this->Path("folder.raw"));
  ExpectError(this->WriteFile("folder.mhd",
                "NDims = 3\nDimSize = 2 2 2\nElementType = MET_UCHAR\nElementDataFile = "
                "folder.raw\n"),
    { "folder.raw", "is not a regular file" });
}

TEST_F(VolumeIO, NrrdHeadersAreReadAsVTKReadsThem)
{
  auto image = MakeImage(10, 3, 2, VTK_SHORT);
  const std::string header = "NRRD0004\ntype: short\ndimension: 3\nsizes: 10 3 2\n";
  std::string text;
  for (vtkIdType i = 0; i < image->GetNumberOfPoints(); ++i)
  {
    text +=
      std::to_string(static_cast<int>(image->GetPointData()->GetScalars()->GetComponent(i, 0)));
    text += i % 2 ? "\n" : " ";
  }
  std::string error;
  ExpectSameVoxels(image,
    Load(
      this->WriteFile("gzip.nrrd", header + "encoding: gzip\n\n" + Deflate(Bytes(image))), error),
    false);
  ExpectSameVoxels(image,
    Load(this->WriteFile("crlf.nrrd",
           "NRRD0004\r\ntype: short\r\ndimension: 3\r\nsizes: 10 3 2\r\n\r\n" + Bytes(image)),
      error),
    false);
  this->WriteFile("values.txt", text);
  ExpectSameVoxels(image,
    Load(this->WriteFile("ascii.nhdr", header + "encoding: ascii\ndata file: values.txt\n"), error),
    false);
  EXPECT_EQ(error, "");
  // vtkNrrdReader takes a first axis of one sample as the (single) component.
  auto flat = MakeImage(10, 3, 2, VTK_UNSIGNED_CHAR);
  ExpectSameVoxels(flat,
    Load(this->WriteFile(
           "one.nrrd", "NRRD0004\ntype: uchar\ndimension: 4\nsizes: 1 10 3 2\n\n" + Bytes(flat)),
      error),
    false);

  const std::vector<std::pair<std::string, std::string>> cases = {
    { "encoding: gzip\n\n" + Deflate(Bytes(image)).substr(0, 30), "truncated gzip data" },
    { "encoding: ascii\n\n" + text, "ASCII data in the header's own file" },
    { "encoding: ascii\ndata file: values.txt\nendian: big\nspacings: 1 1 nan\n",
      "axis 2 has spacing nan" },
    { "spacings: 0 1 1\n\n", "spacings must be positive numbers" },
    { "space directions: (1,0,0) (0,0,0) (0,0,1)\n\n", "axis 1 has spacing 0" },
    { "space origin: (nan,0,0)\n\n", "origin nan" },
    { "data file: \n", "empty 'data file'" },
    { "data file: d%03d.raw 1 4 1\n", "multi-file data" },
    { "data file: values.txt\ndata file: values.txt\n", "multi-file data" },
    { "encoding: ascii\ndata file: bad.txt\n", "bad ASCII value 'x' (value 3)" },
    { "encoding: ascii\ndata file: few.txt\n", "has 3 ASCII values but 60 are needed" },
    { "line skip: 1\n\n", "line skip" },
    { "endian: middle\n\n", "unknown NRRD endian 'middle'" },
    { "space: right-anterior-superior-time\n\n", "with time is not supported" },
  };
  this->WriteFile("bad.txt", "1 2 x 4");
  this->WriteFile("few.txt", "1 2 3");
  for (const auto& entry : cases)
  {
    ExpectError(this->WriteFile("case.nrrd", header + entry.first), { entry.second });
  }
  ExpectError(this->WriteFile("line.nrrd",
                "NRRD0004\ntype: uchar\ndimension: 1\nsizes: 40\n\n" + std::string(40, 'x')),
    { "need 2 or 3 spatial axes, got 1" });
  ExpectError(this->WriteFile("space.nrrd",
                "NRRD0004\ntype: uchar\ndimension: 4\nspace dimension: 3\nsizes: 1 10 3 2\n\n"),
    { "'sizes' has 4 values but 'space dimension' before it set 3 axes" });
  ExpectError(this->WriteFile("rgb.nrrd",
                "NRRD0004\ntype: uchar\ndimension: 4\nsizes: 3 10 3 2\n"
                "space directions: none (1,0,0) (0,1,0) (0,0,1)\n\n"),
    { "has 3 components" });
  // vtkNrrdReader never returns from a header whose last line has no line break.
  ExpectError(this->WriteFile("unterminated.nhdr", header + "data file: values.txt"),
    { "its last header line has no line break" });
  ExpectError(this->WriteFile("byte.nhdr",
                "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 10 3 2\nencoding: ascii\n"
                "data file: values.txt\n"),
    { "ASCII data of 8-bit type" });
}

TEST_F(VolumeIO, ImageGeometryMustBeUsable)
{
  const std::string vti =
    "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" version=\"0.1\">\n"
    "<ImageData WholeExtent=\"0 1 0 1 0 1\" Origin=\"0 0 0\" Spacing=\"SPACING\" "
    "Direction=\"DIRECTION\">\n<Piece Extent=\"0 1 0 1 0 1\"><PointData Scalars=\"s\">\n"
    "<DataArray type=\"Float32\" Name=\"s\" format=\"ascii\">1 2 3 4 5 6 7 8</DataArray>\n"
    "</PointData></Piece></ImageData></VTKFile>\n";
  auto make = [&vti](const std::string& spacing, const std::string& direction)
  {
    std::string text = vti;
    text.replace(text.find("SPACING"), 7, spacing);
    text.replace(text.find("DIRECTION"), 9, direction);
    return text;
  };
  std::string error;
  auto image = Load(this->WriteFile("good.vti", make("1 2 3", "0 1 0 1 0 0 0 0 1")), error);
  ASSERT_NE(image, nullptr) << error;
  EXPECT_EQ(image->GetDirectionMatrix()->GetElement(0, 1), 1.0);
  ExpectError(this->WriteFile("zero.vti", make("0 0 0", "1 0 0 0 1 0 0 0 1")),
    { "has spacing 0 0 0", "spacing must be positive" });
  ExpectError(this->WriteFile("negative.vti", make("1 -1 1", "1 0 0 0 1 0 0 0 1")),
    { "spacing must be positive" });
  ExpectError(this->WriteFile("flat.vti", make("1 1 1", "1 0 0 1 0 0 0 0 1")),
    { "singular or non-finite direction matrix" });
  ExpectError(this->WriteFile("components.vti",
                "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" version=\"0.1\">\n"
                "<ImageData WholeExtent=\"0 1 0 1 0 1\" Origin=\"0 0 0\" Spacing=\"1 1 1\">\n"
                "<Piece Extent=\"0 1 0 1 0 1\"><PointData>\n<DataArray type=\"Float32\" "
                "Name=\"s\" NumberOfComponents=\"-3\" format=\"ascii\">1</DataArray>\n"
                "</PointData></Piece></ImageData></VTKFile>\n"),
    { "NumberOfComponents '-3' is not between 1 and 4096" });
  ExpectError(this->WriteFile("text.vti", "not XML at all\n"), { "cannot read", "text.vti" });
}

TEST_F(VolumeIO, DatasetsJsonCannotCrashTheLoader)
{
  auto image = MakeImage(4, 4, 4, VTK_UNSIGNED_CHAR);
  image->SetSpacing(1, 1, 1);
  this->WriteFile("scan_4x4x4_uint8.raw", Bytes(image));
  // std::regex recursed per character here and overflowed the stack on long strings.
  const std::vector<std::string> sidecars = { "{\"datasets\": [{\"file\": \"" +
      std::string(1 << 20, 'a') + "\"}]}",
    std::string(1 << 20, '{'), std::string(1 << 20, '['), "{\"file\": \"scan_4x4x4_uint8.raw\"",
    "{\"file\": \"scan_4x4x4_uint8.raw\", \"spacing\": [1e999, 1, 1], \"dims\": [[4], 4, 4]}" };
  for (const std::string& sidecar : sidecars)
  {
    this->WriteFile("datasets.json", sidecar);
    std::string error;
    ExpectSameVoxels(image, Load(this->Path("scan_4x4x4_uint8.raw"), error));
  }
  this->WriteFile("plain.raw", Bytes(image));
  this->WriteFile("datasets.json",
    "{\"datasets\": [{\"file\": \"plain.raw\", \"dims\": [4, 4, 4], \"type\": \"uint8\", "
    "\"spacing\": [0.5, 1, 2], \"note\": \"a } and a \\\" inside\"}]}");
  std::string error;
  auto loaded = Load(this->Path("plain.raw"), error);
  ASSERT_NE(loaded, nullptr) << error;
  EXPECT_EQ(loaded->GetSpacing()[0], 0.5);
  this->WriteFile(
    "datasets.json", "{\"file\": \"plain.raw\", \"dims\": [-4, 4, 4], \"type\": \"uint8\"}");
  ExpectError(this->Path("plain.raw"), { "dimensions must be at least 1, got 0x4x4" });
}

TEST(SharedData, LoadsHeadByNamePattern)
{
  const std::string path = "/work/shared/data/headsq_quarter_64x64x93_int16.raw.gz";
  if (!fs::exists(path))
  {
    GTEST_SKIP() << path << " is not available";
  }
  VolumeRequest request;
  request.inputPath = path;
  std::string error;
  auto image = LoadVolume(request, error);
  ASSERT_NE(image, nullptr) << error;
  EXPECT_EQ(DescribeVolume(image), "64x64x93 int16");
  double range[2];
  image->GetPointData()->GetScalars()->GetRange(range);
  EXPECT_LT(range[0], range[1]);
  if (fs::exists(fs::path(path).parent_path() / "datasets.json"))
  {
    EXPECT_DOUBLE_EQ(image->GetSpacing()[0], 3.2);
    EXPECT_DOUBLE_EQ(image->GetSpacing()[2], 1.5);
  }
}

} // namespace
