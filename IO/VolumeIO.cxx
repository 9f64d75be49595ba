// VolumeIO: CLI volume loading that checks headers first, so bad input errors instead of crashing.
#include "VolumeIO.h"

#include "VolumeHeaderChecks.h"

#include <vtkDataArray.h>
#include <vtkDataCompressor.h>
#include <vtkFloatArray.h>
#include <vtkLogger.h>
#include <vtkMatrix3x3.h>
#include <vtkMetaImageReader.h>
#include <vtkNew.h>
#include <vtkNrrdReader.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>
#include <vtkPointData.h>
#include <vtkType.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLDataParser.h>
#include <vtkXMLImageDataReader.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <regex>
#include <sstream>
#include <type_traits>
#include <vector>

namespace accelvolume::cli
{
using namespace accelvolume::cli::detail;

namespace
{
namespace fs = std::filesystem;

// Routes VTK's error text into a string while loading, so the CLI can print one clean line.
class CaptureWindow : public vtkOutputWindow
{
public:
  static CaptureWindow* New();
  vtkTypeMacro(CaptureWindow, vtkOutputWindow);
  void DisplayText(const char*) override {}
  void DisplayWarningText(const char*) override {}
  void DisplayGenericWarningText(const char*) override {}
  void DisplayDebugText(const char*) override {}
  void DisplayErrorText(const char* text) override
  {
    if (!this->FirstError.empty() || !text)
    {
      return;
    }
    // VTK formats "ERROR: In file, line N\nClass (0x...): message" and messages may span lines;
    // keep the message, its lines joined by spaces.
    std::string message = Trim(text);
    if (message.compare(0, 10, "ERROR: In ") == 0)
    {
      message = message.substr(std::min(message.find('\n'), message.size()));
    }
    message = Trim(message);
    const auto object = message.find(" (0x"), prefix = message.find("): ");
    if (object != std::string::npos && object == message.find(' ') && prefix > object &&
      prefix != std::string::npos)
    {
      message = message.substr(prefix + 3);
    }
    std::replace_if(
      message.begin(), message.end(), [](char c) { return std::iscntrl(c & 0xff); }, ' ');
    this->FirstError = Trim(message);
  }
  std::string FirstError;
};
vtkStandardNewMacro(CaptureWindow);

// VTK also logs errors to stderr through vtkLogger and MetaIO prints straight to std::cerr, so
// both are silenced for the scope's lifetime. vtkLogger has no getter for the stderr level; the
// overall cutoff, capped at the INFO default, is the closest stand-in to restore.
class MessageCapture
{
public:
  MessageCapture()
    : Previous(vtkOutputWindow::GetInstance())
    , PreviousBuffer(std::cerr.rdbuf(this->Discarded.rdbuf()))
    , PreviousVerbosity(std::min(vtkLogger::GetCurrentVerbosityCutoff(), vtkLogger::VERBOSITY_INFO))
  {
    vtkOutputWindow::SetInstance(this->Window);
    vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  }
  ~MessageCapture()
  {
    vtkLogger::SetStderrVerbosity(this->PreviousVerbosity);
    vtkOutputWindow::SetInstance(this->Previous);
    std::cerr.rdbuf(this->PreviousBuffer);
  }
  std::string FirstError() const { return this->Window->FirstError; }

private:
  vtkNew<CaptureWindow> Window;
  vtkSmartPointer<vtkOutputWindow> Previous;
  std::ostringstream Discarded;
  std::streambuf* PreviousBuffer;
  vtkLogger::Verbosity PreviousVerbosity;
};

// What datasets.json, the file name or the flags say about a raw file.
struct RawLayout
{
  bool haveDims = false;
  Dimensions dims = { 0, 0, 0 };
  OptionalScalarType kind = std::nullopt;
  bool haveSpacing = false;
  double spacing[3] = { 1, 1, 1 };
};

// One JSON object of datasets.json, as far as the raw loader cares.
struct DatasetEntry
{
  std::string file, type;
  std::vector<double> dims, spacing;
  bool haveDims = false, haveSpacing = false;
};

// Reads datasets.json as a stream of events (nlohmann's SAX interface): no document tree, and
// an explicit stack of the open objects and arrays, so no sidecar can exhaust the call stack
// or memory. Stops at the innermost object whose "file" is the raw file's name.
class DatasetsJsonReader final : public nlohmann::json_sax<nlohmann::json>
{
public:
  explicit DatasetsJsonReader(std::string fileName)
    : FileName(std::move(fileName))
  {
  }
  bool Found = false;
  DatasetEntry Entry;

  bool null() override { return this->Scalar(); }
  bool boolean(bool) override { return this->Scalar(); }
  bool number_integer(number_integer_t value) override { return this->Number(double(value)); }
  bool number_unsigned(number_unsigned_t value) override { return this->Number(double(value)); }
  bool number_float(number_float_t value, const string_t&) override { return this->Number(value); }
  bool binary(binary_t&) override { return this->Scalar(); }
  bool string(string_t& value) override
  {
    Frame* object = this->OpenObject();
    if (object && (this->Key == "file" || this->Key == "type"))
    {
      (this->Key == "file" ? object->entry.file : object->entry.type) = value;
    }
    return this->Scalar();
  }
  bool key(string_t& value) override
  {
    this->Key = value;
    return true;
  }
  bool start_object(std::size_t) override
  {
    if (++this->Objects > MaxObjects || this->Stack.size() >= MaxDepth)
    {
      return false; // nested deeper than any dataset list: not ours
    }
    this->Invalidate();
    this->Stack.push_back(Frame{});
    return true;
  }
  bool end_object() override
  {
    --this->Objects;
    const DatasetEntry entry = this->Stack.back().entry;
    this->Stack.pop_back();
    this->Key.clear();
    if (entry.file == this->FileName)
    {
      this->Found = true;
      this->Entry = entry;
      return false; // the innermost object naming the file: done
    }
    return true;
  }
  bool start_array(std::size_t) override
  {
    if (this->Stack.size() >= MaxDepth)
    {
      return false; // nested deeper than any dataset list: not ours
    }
    Frame* object = this->OpenObject();
    this->Invalidate();
    Frame array;
    array.array = true;
    array.collect = object && (this->Key == "dims" || this->Key == "spacing");
    array.target = this->Key;
    this->Stack.push_back(array);
    return true;
  }
  bool end_array() override
  {
    const Frame array = this->Stack.back();
    this->Stack.pop_back();
    Frame* object = this->OpenObject();
    if (array.collect && object)
    {
      DatasetEntry& entry = object->entry;
      (array.target == "dims" ? entry.dims : entry.spacing) = array.values;
      (array.target == "dims" ? entry.haveDims : entry.haveSpacing) = true;
    }
    this->Key.clear();
    return true;
  }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override
  {
    return false; // optional metadata: what was read before the error stands
  }

private:
  static constexpr int MaxObjects = 64;
  static constexpr std::size_t MaxDepth = 256;
  struct Frame
  {
    bool array = false;
    bool collect = false; // a flat array of numbers under "dims" or "spacing"
    std::string target;
    std::vector<double> values;
    DatasetEntry entry; // objects only
  };

  Frame* OpenObject()
  {
    return !this->Stack.empty() && !this->Stack.back().array ? &this->Stack.back() : nullptr;
  }
  // A value that is not a number (or a nested container) spoils the array being collected.
  void Invalidate()
  {
    if (!this->Stack.empty() && this->Stack.back().array)
    {
      this->Stack.back().collect = false;
    }
  }
  bool Scalar()
  {
    this->Invalidate();
    if (this->OpenObject())
    {
      this->Key.clear();
    }
    return true;
  }
  bool Number(double value)
  {
    if (!this->Stack.empty() && this->Stack.back().array)
    {
      Frame& array = this->Stack.back();
      array.collect = array.collect && std::isfinite(value);
      array.values.push_back(value);
      return true;
    }
    return this->Scalar();
  }

  std::string FileName;
  std::string Key;
  std::vector<Frame> Stack;
  int Objects = 0;
};

// datasets.json is optional metadata: the innermost object holding "file": <the raw file's name>
// supplies "dims", "type" and "spacing"; anything unreadable is ignored.
void ReadDatasetsJson(const fs::path& rawPath, RawLayout& layout)
{
  const fs::path jsonPath = rawPath.parent_path() / "datasets.json";
  std::error_code code;
  if (!fs::is_regular_file(jsonPath, code) || FileSize(jsonPath) > (std::int64_t(16) << 20))
  {
    return; // not there, a FIFO (which would block) or implausibly large for metadata
  }
  std::ifstream stream(jsonPath, std::ios::binary);
  const std::string text(
    (std::istreambuf_iterator<char>(stream)), std::istreambuf_iterator<char>());
  DatasetsJsonReader reader(rawPath.filename().string());
  try
  {
    nlohmann::json::sax_parse(text, &reader);
  }
  catch (const nlohmann::json::exception&)
  {
    return; // e.g. a number too large for a double: unreadable, ignored
  }
  if (!reader.Found)
  {
    return;
  }
  const DatasetEntry& entry = reader.Entry;
  layout.haveSpacing = entry.haveSpacing && entry.spacing.size() == 3 &&
    std::all_of(entry.spacing.begin(), entry.spacing.end(), [](double v) { return v > 0; });
  std::copy(
    entry.spacing.begin(), entry.spacing.begin() + (layout.haveSpacing ? 3 : 0), layout.spacing);
  layout.haveDims = entry.haveDims && entry.dims.size() == 3;
  for (std::size_t axis = 0; axis < 3 && layout.haveDims; ++axis)
  {
    // Out-of-range values become 0 or 1e12, which CheckSize refuses with their text.
    layout.dims[axis] = static_cast<std::int64_t>(std::clamp(entry.dims[axis], 0.0, 1e12));
  }
  layout.kind = ParseScalarType(entry.type);
}

void ParseRawName(const std::string& name, RawLayout& layout)
{
  static const std::regex pattern(
    R"(.*_([0-9]{1,12})x([0-9]{1,12})x([0-9]{1,12})_([A-Za-z0-9]+)\.raw(\.gz)?)",
    std::regex::icase);
  std::smatch match;
  if (!std::regex_match(name, match, pattern))
  {
    return;
  }
  layout.haveDims = true;
  for (int axis = 0; axis < 3; ++axis)
  {
    layout.dims[axis] = std::stoll(match[axis + 1].str());
  }
  layout.kind = ParseScalarType(match[4].str());
}

vtkSmartPointer<vtkImageData> LoadRaw(const VolumeRequest& request, std::string& error)
{
  const fs::path path(request.inputPath);
  const bool compressed = EndsWith(Lower(path.filename().string()), ".gz");
  RawLayout layout;
  ReadDatasetsJson(path, layout);
  ParseRawName(path.filename().string(), layout);
  if (request.haveDims)
  {
    layout.haveDims = true;
    std::copy(request.dims, request.dims + 3, layout.dims);
  }
  layout.kind = request.kind != std::nullopt ? request.kind : layout.kind;
  const KindInfo* kind = FindKind(layout.kind);
  if (!layout.haveDims || !kind)
  {
    error = "raw volume '" + request.inputPath + "' needs " +
      (layout.haveDims ? ""
          : kind       ? "--dims"
                       : "--dims and ") +
      (kind ? "" : "--type") + " (or a name like NAME_256x256x113_uint16.raw)";
    return nullptr;
  }
  std::int64_t bytes = 0;
  if (!CheckSize(layout.dims, *kind, bytes, error))
  {
    return nullptr;
  }
  const std::string needs =
    DimensionsText(layout.dims) + " " + kind->name + " needs " + std::to_string(bytes) + " bytes";
  const std::int64_t fileSize = FileSize(path);
  if (!compressed && fileSize != bytes)
  {
    error = "size mismatch: '" + request.inputPath + "' has " + std::to_string(fileSize) +
      " bytes but " + needs;
    return nullptr;
  }
  std::ifstream stream(path, std::ios::binary);
  unsigned char magic[2] = { 0, 0 };
  if (compressed &&
    (!stream.read(reinterpret_cast<char*>(magic), 2) || magic[0] != 0x1f || magic[1] != 0x8b))
  {
    error = "'" + request.inputPath + "' is not gzip data (bad magic bytes)";
    return nullptr;
  }
  if (compressed && bytes / MaximumDeflateRatio > fileSize)
  {
    // Refused before allocating: a tiny file must not make the CLI reserve gigabytes.
    error = "size mismatch: '" + request.inputPath + "' has only " + std::to_string(fileSize) +
      " compressed bytes, too few for " + DimensionsText(layout.dims) + " " + kind->name + " (" +
      std::to_string(bytes) + " bytes; gzip expands at most 1032:1)";
    return nullptr;
  }
  // malloc reports failure as nullptr; VTK's own allocation would print its error to stderr.
  void* memory = std::malloc(static_cast<std::size_t>(bytes));
  if (!memory)
  {
    error = "not enough memory for " + DimensionsText(layout.dims) + " " + kind->name + " (" +
      std::to_string(bytes) + " bytes)";
    return nullptr;
  }
  vtkSmartPointer<vtkDataArray> scalars =
    vtkSmartPointer<vtkDataArray>::Take(vtkDataArray::CreateDataArray(kind->vtkType));
  scalars->SetNumberOfComponents(1);
  scalars->SetVoidArray(memory, bytes / kind->size, 0, vtkAbstractArray::VTK_DATA_ARRAY_FREE);
  scalars->SetName("scalars");
  char* data = static_cast<char*>(memory);
  if (compressed ? !InflateFile(request.inputPath, 0, -1, Wrapper::Gzip, data, bytes, needs, error)
                 : !stream.read(data, bytes))
  {
    error = error.empty() ? "cannot read '" + request.inputPath + "'" : error;
    return nullptr;
  }
  // Raw data is little-endian by convention; swap on the rare big-endian host.
  const std::uint16_t probe = 1;
  if (kind->size > 1 && *reinterpret_cast<const unsigned char*>(&probe) == 0)
  {
    for (std::int64_t offset = 0; offset < bytes; offset += kind->size)
    {
      std::reverse(data + offset, data + offset + kind->size);
    }
  }
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(static_cast<int>(layout.dims[0]), static_cast<int>(layout.dims[1]),
    static_cast<int>(layout.dims[2]));
  image->GetPointData()->SetScalars(scalars);
  if (layout.haveSpacing)
  {
    image->SetSpacing(layout.spacing);
  }
  return image;
}

// Bytes one value of a VTK XML DataArray type takes; 0 for types VTK itself will refuse.
int XMLTypeSize(const char* type)
{
  const std::string name = type ? type : "";
  return name == "Int8" || name == "UInt8" || name == "Char"   ? 1
    : name == "Int16" || name == "UInt16"                      ? 2
    : name == "Int32" || name == "UInt32" || name == "Float32" ? 4
    : name == "Int64" || name == "UInt64" || name == "Float64" ? 8
                                                               : 0;
}

// Sizes a .vti from its parsed XML before vtkXMLImageDataReader allocates anything: the whole
// extent, and the bytes of every data array (piece voxels times components times type size)
// against the limits and against what the file can hold: deflate expands at most 1032:1 (LZ4
// less); LZMA's adaptive coder can reach about 7000:1 on constant data, so it is allowed 65536:1.
bool CheckXMLImage(vtkXMLImageDataReader* reader, const std::string& path, std::string& error)
{
  vtkXMLDataParser* parser = reader->GetXMLParser();
  vtkXMLDataElement* root = parser ? parser->GetRootElement() : nullptr;
  vtkXMLDataElement* image = root ? root->FindNestedElementWithName("ImageData") : nullptr;
  int whole[6];
  if (!image || image->GetVectorAttribute("WholeExtent", 6, whole) != 6)
  {
    error = "cannot read '" + path + "': no ImageData element with a WholeExtent";
    return false;
  }
  auto voxelsOf = [](const int extent[6], Dimensions dims)
  {
    for (int axis = 0; axis < 3; ++axis)
    {
      dims[axis] = std::int64_t(extent[2 * axis + 1]) - extent[2 * axis] + 1;
    }
  };
  Dimensions dims;
  voxelsOf(whole, dims);
  std::int64_t bytes = 0, total = 0;
  const KindInfo& oneByte = Kinds[0];
  if (!CheckSize(dims, oneByte, bytes, error))
  {
    error = "'" + path + "' WholeExtent: " + error;
    return false;
  }
  // Adds the bytes of array with `tuples` tuples; false (error set) when past the limits.
  auto addArray = [&](vtkXMLDataElement* array, std::int64_t tuples)
  {
    const char* componentText = array->GetAttribute("NumberOfComponents");
    std::int64_t components = 1;
    if (componentText &&
      (!ParseCount(componentText, components) || components < 1 || components > 4096))
    {
      error = "cannot read '" + path + "': NumberOfComponents '" + componentText +
        "' is not between 1 and 4096";
      return false;
    }
    total += tuples * components * XMLTypeSize(array->GetAttribute("type"));
    error = total > MaximumBytes
      ? "refusing '" + path + "': its data arrays need more than the 16 GiB limit"
      : "";
    return error.empty();
  };
  for (int p = 0; p < image->GetNumberOfNestedElements(); ++p)
  {
    // Piece > PointData/CellData > DataArray (one tuple per voxel or fewer), FieldData > DataArray.
    vtkXMLDataElement* element = image->GetNestedElement(p);
    const std::string name = element->GetName() ? element->GetName() : "";
    // vtkXMLImageDataReader allocates every piece array over the whole extent it outputs,
    // whatever the piece's own Extent says (a fuzzed 8-value piece in a 2x222222222x2 extent
    // made it allocate 3.5 GB), so each array is sized by the whole extent.
    const std::int64_t voxels = dims[0] * dims[1] * dims[2];
    for (int a = 0; a < element->GetNumberOfNestedElements(); ++a)
    {
      vtkXMLDataElement* child = element->GetNestedElement(a);
      const char* tupleText = child->GetAttribute("NumberOfTuples");
      std::int64_t tuples = 0;
      if (name == "FieldData" &&
        (!tupleText || !ParseCount(tupleText, tuples) || tuples > MaximumVoxels))
      {
        error = "cannot read '" + path + "': FieldData NumberOfTuples '" +
          (tupleText ? tupleText : "") + "' is not between 0 and 2^31";
        return false;
      }
      for (int d = 0; name == "Piece" && d < child->GetNumberOfNestedElements(); ++d)
      {
        if (!addArray(child->GetNestedElement(d), voxels))
        {
          return false;
        }
      }
      if (name == "FieldData" && !addArray(child, tuples))
      {
        return false;
      }
    }
  }
  const bool lzma =
    parser->GetCompressor() && parser->GetCompressor()->IsA("vtkLZMADataCompressor");
  if (total / (lzma ? 65536 : MaximumDeflateRatio) > FileSize(path))
  {
    error = "size mismatch: '" + path + "' has " + std::to_string(FileSize(path)) +
      " bytes, too few for its " + DimensionsText(dims) + " extent (" + std::to_string(total) +
      " bytes of data arrays)";
    return false;
  }
  return true;
}

// Runs a VTK reader with its messages captured. MetaImage and NRRD files passed CheckHeader, so
// the result must match what their header said; .vti files are sized by CheckXMLImage first.
template <typename Reader>
vtkSmartPointer<vtkImageData> RunReader(
  const std::string& path, const HeaderSummary* summary, std::string& error)
{
  MessageCapture capture;
  vtkNew<Reader> reader;
  reader->SetFileName(path.c_str());
  reader->UpdateInformation();
  if (capture.FirstError().empty())
  {
    if constexpr (std::is_same_v<Reader, vtkXMLImageDataReader>)
    {
      if (!CheckXMLImage(reader, path, error))
      {
        return nullptr;
      }
    }
    reader->Update();
  }
  if (!capture.FirstError().empty())
  {
    error = "cannot read '" + path + "': " + capture.FirstError();
    return nullptr;
  }
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->ShallowCopy(reader->GetOutput());
  int dims[3];
  image->GetDimensions(dims);
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  if (summary && scalars &&
    (dims[0] != summary->dims[0] || dims[1] != summary->dims[1] || dims[2] != summary->dims[2] ||
      (scalars->GetDataType() == VTK_CHAR ? VTK_SIGNED_CHAR : scalars->GetDataType()) !=
        summary->kind->vtkType))
  {
    // A disagreement means the header checks and VTK read the header differently: refuse rather
    // than render a volume nobody checked.
    error = "VTK read '" + path + "' as " + DescribeVolume(image) + " but its header says " +
      DimensionsText(summary->dims) + " " + summary->kind->name;
    return nullptr;
  }
  return image;
}

// The checks every loaded volume must pass before a mapper sees it.
bool ValidateImage(vtkImageData* image, const std::string& path, std::string& error)
{
  int extent[6];
  image->GetExtent(extent);
  if (extent[1] < extent[0] || extent[3] < extent[2] || extent[5] < extent[4])
  {
    error = "'" + path + "' contains no voxels";
    return false;
  }
  vtkPointData* pointData = image->GetPointData();
  if (!pointData->GetScalars() && pointData->GetNumberOfArrays() == 1 && pointData->GetArray(0))
  {
    pointData->SetActiveScalars(pointData->GetArray(0)->GetName());
  }
  vtkDataArray* scalars = pointData->GetScalars();
  if (!scalars)
  {
    error = "'" + path + "' has no point scalars";
    return false;
  }
  if (scalars->GetNumberOfComponents() != 1)
  {
    error = "only single-component volumes are supported for now ('" + path + "' has " +
      std::to_string(scalars->GetNumberOfComponents()) + " components)";
    return false;
  }
  const int type = scalars->GetDataType() == VTK_CHAR ? VTK_SIGNED_CHAR : scalars->GetDataType();
  if (std::none_of(std::begin(Kinds), std::end(Kinds),
        [type](const KindInfo& info) { return info.vtkType == type; }))
  {
    error = std::string("unsupported scalar type '") + scalars->GetDataTypeAsString() + "' in '" +
      path + "' (supported: uint8 int8 uint16 int16 int32 float32 float64)";
    return false;
  }
  if (scalars->GetNumberOfTuples() != image->GetNumberOfPoints())
  {
    error = "'" + path + "' has " + std::to_string(scalars->GetNumberOfTuples()) + " values for " +
      std::to_string(image->GetNumberOfPoints()) + " voxels";
    return false;
  }
  // Zero, negative or non-finite geometry gives the mappers no box to render (or NaN bounds).
  const double* spacing = image->GetSpacing();
  const double* origin = image->GetOrigin();
  const double determinant = image->GetDirectionMatrix()->Determinant();
  for (int axis = 0; axis < 3; ++axis)
  {
    if (!(spacing[axis] > 0 && std::isfinite(spacing[axis]) && std::isfinite(origin[axis])))
    {
      std::ostringstream text;
      text << "'" << path << "' has spacing " << spacing[0] << " " << spacing[1] << " "
           << spacing[2] << " and origin " << origin[0] << " " << origin[1] << " " << origin[2]
           << " (spacing must be positive, both finite)";
      error = text.str();
      return false;
    }
  }
  if (!std::isfinite(determinant) || std::fabs(determinant) < 1e-12)
  {
    error = "'" + path + "' has a singular or non-finite direction matrix";
    return false;
  }
  return true;
}

vtkSmartPointer<vtkImageData> LoadFile(const VolumeRequest& request, std::string& error)
{
  const std::string& path = request.inputPath;
  if (!fs::is_regular_file(path) || !std::ifstream(path, std::ios::binary))
  {
    error =
      "cannot open '" + path + "': " + (fs::exists(path) ? "not a readable file" : "no such file");
    return nullptr;
  }
  const std::string name = Lower(fs::path(path).filename().string());
  const bool nrrd = EndsWith(name, ".nrrd") || EndsWith(name, ".nhdr");
  if (EndsWith(name, ".raw") || EndsWith(name, ".raw.gz"))
  {
    return LoadRaw(request, error);
  }
  if (EndsWith(name, ".mhd") || EndsWith(name, ".mha") || nrrd)
  {
    HeaderSummary summary;
    if (!CheckHeader(path, nrrd, summary, error))
    {
      return nullptr;
    }
    return nrrd ? RunReader<vtkNrrdReader>(path, &summary, error)
                : RunReader<vtkMetaImageReader>(path, &summary, error);
  }
  if (EndsWith(name, ".vti"))
  {
    return RunReader<vtkXMLImageDataReader>(path, nullptr, error);
  }
  error = "unknown file extension for '" + path +
    "' (expected .mhd, .mha, .vti, .nrrd, .nhdr, .raw or .raw.gz)";
  return nullptr;
}

} // namespace

OptionalScalarType ParseScalarType(const std::string& name)
{
  for (const KindInfo& info : Kinds)
  {
    if (Lower(name) == info.name)
    {
      return info.kind;
    }
  }
  return std::nullopt;
}

int ToVTKType(OptionalScalarType kind)
{
  const KindInfo* info = FindKind(kind);
  return info ? info->vtkType : VTK_VOID;
}

const char* ScalarTypeName(OptionalScalarType kind)
{
  const KindInfo* info = FindKind(kind);
  return info ? info->name : "unknown";
}

vtkSmartPointer<vtkImageData> LoadVolume(const VolumeRequest& request, std::string& error)
{
  error.clear();
  if (request.haveSpacing &&
    !std::all_of(request.spacing, request.spacing + 3,
      [](double value) { return std::isfinite(value) && value > 0; }))
  {
    error = "spacing must be three positive numbers";
    return nullptr;
  }
  vtkSmartPointer<vtkImageData> image;
  try
  {
    if (request.inputPath.empty())
    {
      accelvolume::PhantomVolume phantom;
      if (accelvolume::GeneratePhantom(
            request.phantom, request.phantomDims, request.phantomTime, phantom, error))
      {
        image = PhantomToImage(phantom);
      }
    }
    else
    {
      image = LoadFile(request, error);
    }
  }
  catch (const std::exception& exception)
  {
    error = std::string("cannot load volume: ") + exception.what();
    return nullptr;
  }
  if (!image || !ValidateImage(image, request.inputPath, error))
  {
    error = error.empty() ? "cannot load '" + request.inputPath + "'" : error;
    return nullptr;
  }
  if (request.haveSpacing)
  {
    image->SetSpacing(request.spacing);
  }
  return image;
}

vtkSmartPointer<vtkImageData> PhantomToImage(const accelvolume::PhantomVolume& phantom)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(phantom.dims[0], phantom.dims[1], phantom.dims[2]);
  image->SetSpacing(phantom.spacing[0], phantom.spacing[1], phantom.spacing[2]);
  image->SetOrigin(0, 0, 0);
  vtkNew<vtkFloatArray> scalars;
  scalars->SetName("scalars");
  scalars->SetNumberOfTuples(static_cast<vtkIdType>(phantom.values.size()));
  std::copy(phantom.values.begin(), phantom.values.end(), scalars->GetPointer(0));
  image->GetPointData()->SetScalars(scalars);
  return image;
}

std::string DescribeVolume(vtkImageData* image)
{
  if (!image)
  {
    return "(no volume)";
  }
  int dims[3];
  image->GetDimensions(dims);
  std::string text =
    std::to_string(dims[0]) + "x" + std::to_string(dims[1]) + "x" + std::to_string(dims[2]);
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  if (!scalars)
  {
    return text + " (no scalars)";
  }
  const int type = scalars->GetDataType() == VTK_CHAR ? VTK_SIGNED_CHAR : scalars->GetDataType();
  const auto* info = std::find_if(std::begin(Kinds), std::end(Kinds),
    [type](const KindInfo& kind) { return kind.vtkType == type; });
  text += " ";
  text += info != std::end(Kinds) ? info->name : scalars->GetDataTypeAsString();
  const int components = scalars->GetNumberOfComponents();
  return components == 1 ? text : text + " (" + std::to_string(components) + " components)";
}

} // namespace accelvolume::cli
