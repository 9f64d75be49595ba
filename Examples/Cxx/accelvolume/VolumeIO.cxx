// VolumeIO: CLI volume loading that checks headers first, so bad input errors instead of crashing.
#include "VolumeIO.h"

#include "VolumeHeaderChecks.h"

#include <vtkDataArray.h>
#include <vtkFloatArray.h>
#include <vtkLogger.h>
#include <vtkMetaImageReader.h>
#include <vtkNew.h>
#include <vtkNrrdReader.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>
#include <vtkPointData.h>
#include <vtkType.h>
#include <vtkXMLImageDataReader.h>

#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <regex>
#include <sstream>
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
    // VTK formats "ERROR: In file, line N\nClass (0x...): message"; keep only the message.
    std::string message = Trim(text);
    message = message.substr(message.find_last_of('\n') + 1);
    const auto prefix = message.find("): ");
    this->FirstError = Trim(prefix == std::string::npos ? message : message.substr(prefix + 3));
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
  ScalarKind kind = ScalarKind::Unknown;
  bool haveSpacing = false;
  double spacing[3] = { 1, 1, 1 };
};

// datasets.json lists flat objects, so the object holding a "file" entry is found by scanning
// to the surrounding braces; that avoids a JSON dependency for three fields.
void ReadDatasetsJson(const fs::path& rawPath, RawLayout& layout)
{
  std::ifstream stream(rawPath.parent_path() / "datasets.json", std::ios::binary);
  const std::string text(
    (std::istreambuf_iterator<char>(stream)), std::istreambuf_iterator<char>());
  static const std::regex fileEntry(R"re("file"\s*:\s*"([^"]*)")re");
  for (std::sregex_iterator match(text.begin(), text.end(), fileEntry), end; match != end; ++match)
  {
    const auto first = text.rfind('{', match->position());
    const auto last = text.find('}', match->position());
    if ((*match)[1] != rawPath.filename().string() || first == std::string::npos ||
      last == std::string::npos)
    {
      continue;
    }
    const std::string entry = text.substr(first, last - first);
    auto numbers = [&entry](const std::string& key)
    {
      std::smatch found;
      std::vector<double> values;
      if (std::regex_search(entry, found, std::regex("\"" + key + R"("\s*:\s*\[([^\]]*)\])")))
      {
        std::istringstream list(std::regex_replace(found[1].str(), std::regex(","), " "));
        for (double value; list >> value;)
        {
          values.push_back(value);
        }
      }
      return values;
    };
    const std::vector<double> spacing = numbers("spacing"), dims = numbers("dims");
    layout.haveSpacing = spacing.size() == 3 &&
      std::all_of(
        spacing.begin(), spacing.end(), [](double v) { return std::isfinite(v) && v > 0; });
    std::copy(spacing.begin(), spacing.begin() + (layout.haveSpacing ? 3 : 0), layout.spacing);
    layout.haveDims = dims.size() == 3;
    for (std::size_t axis = 0; axis < dims.size() && layout.haveDims; ++axis)
    {
      layout.dims[axis] = static_cast<std::int64_t>(std::min(dims[axis], 1e12));
    }
    std::smatch type;
    if (std::regex_search(entry, type, std::regex(R"re("type"\s*:\s*"([^"]*)")re")))
    {
      layout.kind = ParseScalarKind(type[1].str());
    }
    return;
  }
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
  layout.kind = ParseScalarKind(match[4].str());
}

// Gzip data streams straight into the scalar array, so only the volume itself is ever in memory.
bool ReadGzip(const std::string& path, char* data, std::int64_t bytes, std::string& error)
{
  gzFile file = gzopen(path.c_str(), "rb");
  if (!file)
  {
    error = "cannot open '" + path + "'";
    return false;
  }
  gzbuffer(file, 1 << 20);
  std::int64_t done = 0;
  while (done < bytes)
  {
    const unsigned chunk = static_cast<unsigned>(std::min<std::int64_t>(bytes - done, 1 << 26));
    const int count = gzread(file, data + done, chunk);
    if (count <= 0)
    {
      break;
    }
    done += count;
  }
  char extra = 0;
  const bool more = done == bytes && gzread(file, &extra, 1) > 0;
  int code = Z_OK;
  const std::string zlibMessage = gzerror(file, &code);
  gzclose(file);
  if (code != Z_OK && code != Z_STREAM_END)
  {
    error = "truncated or corrupt gzip data in '" + path + "' after " + std::to_string(done) +
      " of " + std::to_string(bytes) + " bytes (zlib: " + zlibMessage + ")";
    return false;
  }
  if (done != bytes || more)
  {
    error = "size mismatch: '" + path + "' decompresses to " +
      (more ? "more than " + std::to_string(bytes) : std::to_string(done)) + " bytes but " +
      std::to_string(bytes) + " bytes are needed";
    return false;
  }
  return true;
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
  layout.kind = request.kind != ScalarKind::Unknown ? request.kind : layout.kind;
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
  const std::string expected =
    DimensionsText(layout.dims) + " " + kind->name + " needs " + std::to_string(bytes) + " bytes";
  const std::int64_t fileSize = FileSize(path);
  if (!compressed && fileSize != bytes)
  {
    error = "size mismatch: '" + request.inputPath + "' has " + std::to_string(fileSize) +
      " bytes but " + expected;
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
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(static_cast<int>(layout.dims[0]), static_cast<int>(layout.dims[1]),
    static_cast<int>(layout.dims[2]));
  image->AllocateScalars(kind->vtkType, 1);
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  if (!scalars || scalars->GetNumberOfValues() != bytes / kind->size)
  {
    error = "not enough memory for " + expected;
    return nullptr;
  }
  scalars->SetName("scalars");
  char* data = static_cast<char*>(scalars->GetVoidPointer(0));
  if (compressed ? !ReadGzip(request.inputPath, data, bytes, error) : !stream.read(data, bytes))
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
  if (layout.haveSpacing)
  {
    image->SetSpacing(layout.spacing);
  }
  return image;
}

template <typename Reader>
vtkSmartPointer<vtkImageData> RunReader(const std::string& path, std::string& error)
{
  MessageCapture capture;
  vtkNew<Reader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->ShallowCopy(reader->GetOutput());
  if (!capture.FirstError().empty())
  {
    error = "cannot read '" + path + "': " + capture.FirstError();
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
    if (!CheckHeader(path, nrrd, error))
    {
      return nullptr;
    }
    return nrrd ? RunReader<vtkNrrdReader>(path, error)
                : RunReader<vtkMetaImageReader>(path, error);
  }
  if (EndsWith(name, ".vti"))
  {
    return RunReader<vtkXMLImageDataReader>(path, error);
  }
  error = "unknown file extension for '" + path +
    "' (expected .mhd, .mha, .vti, .nrrd, .nhdr, .raw or .raw.gz)";
  return nullptr;
}

} // namespace

ScalarKind ParseScalarKind(const std::string& name)
{
  for (const KindInfo& info : Kinds)
  {
    if (Lower(name) == info.name)
    {
      return info.kind;
    }
  }
  return ScalarKind::Unknown;
}

int ToVTKType(ScalarKind kind)
{
  const KindInfo* info = FindKind(kind);
  return info ? info->vtkType : VTK_VOID;
}

const char* ScalarKindName(ScalarKind kind)
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
