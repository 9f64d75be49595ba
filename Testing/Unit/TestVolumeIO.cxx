// TestVolumeIO: unit tests for the CLI's volume loading (every format, name patterns, errors).
#include "VolumeIO.h"

#include <vtkDataArray.h>
#include <vtkFloatArray.h>
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
    const ScalarKind kind = ParseScalarKind(entry.first);
    EXPECT_NE(kind, ScalarKind::Unknown);
    EXPECT_EQ(ToVTKType(kind), entry.second);
    EXPECT_EQ(ScalarKindName(kind), entry.first);
  }
  EXPECT_EQ(ParseScalarKind("UInt16"), ScalarKind::UInt16);
  EXPECT_EQ(ParseScalarKind("uint64"), ScalarKind::Unknown);
  EXPECT_EQ(ParseScalarKind(""), ScalarKind::Unknown);
  EXPECT_EQ(ToVTKType(ScalarKind::Unknown), VTK_VOID);
  EXPECT_STREQ(ScalarKindName(ScalarKind::Unknown), "unknown");
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
  request.kind = ScalarKind::UInt16;
  std::string error;
  ExpectSameVoxels(image, LoadVolume(request, error));

  // Name dims with a flag type: 4x4x4 uint16 needs 128 bytes, the file has 64.
  request.haveDims = false;
  ExpectError(request, { "size mismatch", "64", "128" });
  request.kind = ScalarKind::Unknown;
  std::string plain = this->WriteFile("plain.raw", Bytes(image));
  ExpectError(plain, { "--dims and --type" });
  request.inputPath = plain;
  request.kind = ScalarKind::UInt16;
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
    { "truncated or corrupt gzip" });
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
  request.kind = ScalarKind::Float64;
  ExpectError(request, { "refusing", "100000x100000x100000" });
  // 2^31 voxels of float64 is exactly 16 GiB; int32 at 2^31 + voxels would also be refused above.
  request.dims[0] = 2048;
  request.dims[1] = 1024;
  request.dims[2] = 1025;
  request.kind = ScalarKind::UInt8;
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
    { "one size per axis" });
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
