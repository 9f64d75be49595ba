// VolumeHeaderChecks: validates MetaImage and NRRD headers against their data files.
#include "VolumeHeaderChecks.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

namespace accelvolume::cli::detail
{
namespace fs = std::filesystem;

const KindInfo* FindKind(ScalarKind kind)
{
  for (const KindInfo& info : Kinds)
  {
    if (info.kind == kind)
    {
      return &info;
    }
  }
  return nullptr;
}

std::string Lower(std::string text)
{
  for (char& c : text)
  {
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  return text;
}

std::string Trim(const std::string& text)
{
  const auto first = text.find_first_not_of(" \t\r\n");
  const auto last = text.find_last_not_of(" \t\r\n");
  return first == std::string::npos ? std::string() : text.substr(first, last - first + 1);
}

bool EndsWith(const std::string& text, const std::string& suffix)
{
  return text.size() >= suffix.size() &&
    text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::string DimensionsText(const Dimensions dims)
{
  return std::to_string(dims[0]) + "x" + std::to_string(dims[1]) + "x" + std::to_string(dims[2]);
}

bool CheckSize(const Dimensions dims, const KindInfo& kind, std::int64_t& bytes, std::string& error)
{
  const std::int64_t maximumVoxels = std::int64_t(1) << 31;
  if (dims[0] < 1 || dims[1] < 1 || dims[2] < 1)
  {
    error = "dimensions must be at least 1, got " + DimensionsText(dims);
    return false;
  }
  std::int64_t voxels = 1;
  for (int axis = 0; axis < 3; ++axis)
  {
    // Dividing first keeps the product from overflowing for absurd inputs.
    if (dims[axis] > maximumVoxels / voxels)
    {
      error = "refusing " + DimensionsText(dims) + ": more than 2^31 voxels";
      return false;
    }
    voxels *= dims[axis];
  }
  bytes = voxels * kind.size;
  if (bytes > (std::int64_t(16) << 30))
  {
    error = "refusing " + DimensionsText(dims) + " " + kind.name + ": " + std::to_string(bytes) +
      " bytes exceeds the 16 GiB limit";
    return false;
  }
  return true;
}

std::int64_t FileSize(const fs::path& path)
{
  std::error_code code;
  const auto size = fs::file_size(path, code);
  return code ? -1 : static_cast<std::int64_t>(size);
}

namespace
{

// Reads "key = value" (MetaImage) or "key: value" (NRRD) lines from the start of a header.
// Returns false for text that is not a header; dataOffset is where the header ends.
bool ReadHeader(const std::string& path, bool nrrd, std::map<std::string, std::string>& fields,
  std::int64_t& dataOffset, std::string& error)
{
  std::ifstream stream(path, std::ios::binary);
  std::string buffer(1 << 16, '\0');
  stream.read(&buffer[0], static_cast<std::streamsize>(buffer.size()));
  buffer.resize(static_cast<std::size_t>(stream.gcount()));
  const std::string kind = nrrd ? "NRRD" : "MetaImage";
  if (nrrd && buffer.compare(0, 4, "NRRD") != 0)
  {
    error = "malformed NRRD header in '" + path + "': missing NRRD magic";
    return false;
  }
  // The NRRD magic line is skipped; without a newline the header is empty and checks fail below.
  std::size_t position = nrrd ? std::min(buffer.find('\n'), buffer.size() - 1) + 1 : 0;
  for (int lineNumber = nrrd ? 2 : 1; position < buffer.size(); ++lineNumber)
  {
    const std::size_t end = buffer.find('\n', position);
    const std::string line = Trim(buffer.substr(position, end - position));
    position = end == std::string::npos ? buffer.size() : end + 1;
    dataOffset = static_cast<std::int64_t>(position);
    if (nrrd && line.empty())
    {
      return true; // A blank line ends an attached NRRD header.
    }
    if (line.empty() || line[0] == '#' || (nrrd && line.find(":=") != std::string::npos))
    {
      continue;
    }
    const auto separator = line.find(nrrd ? ":" : "=");
    const bool printable = std::all_of(line.begin(), line.end(),
      [](char c) { return std::isprint(static_cast<unsigned char>(c)) || c == '\t'; });
    if (separator == std::string::npos || !printable)
    {
      error = "malformed " + kind + " header in '" + path + "' at line " +
        std::to_string(lineNumber) + " (expected " + (nrrd ? "'key: value'" : "'Key = Value'") +
        ")";
      return false;
    }
    const std::string key = Lower(Trim(line.substr(0, separator)));
    if (nrrd && key == "sizes" && !fields.count("dimension"))
    {
      // vtkNrrdReader sizes its axis list from an earlier "dimension" and indexes it blindly.
      error = "malformed NRRD header in '" + path + "': 'sizes' before 'dimension'";
      return false;
    }
    fields[key] = Trim(line.substr(separator + 1));
    if (!nrrd && key == "elementdatafile")
    {
      return true;
    }
  }
  if (!nrrd && !fields.count("elementdatafile"))
  {
    error = "malformed MetaImage header in '" + path + "': no ElementDataFile";
    return false;
  }
  dataOffset = static_cast<std::int64_t>(buffer.size());
  return true;
}

// MetaImage ElementType and NRRD type spellings (NRRD's "_t" suffix is stripped first).
ScalarKind HeaderKind(std::string type)
{
  type = Lower(type);
  type = EndsWith(type, "_t") ? type.substr(0, type.size() - 2) : type;
  static const std::map<std::string, ScalarKind> kinds = { { "met_uchar", ScalarKind::UInt8 },
    { "met_char", ScalarKind::Int8 }, { "met_ushort", ScalarKind::UInt16 },
    { "met_short", ScalarKind::Int16 }, { "met_int", ScalarKind::Int32 },
    { "met_float", ScalarKind::Float32 }, { "met_double", ScalarKind::Float64 },
    { "uchar", ScalarKind::UInt8 }, { "unsigned char", ScalarKind::UInt8 },
    { "signed char", ScalarKind::Int8 }, { "short", ScalarKind::Int16 },
    { "short int", ScalarKind::Int16 }, { "signed short", ScalarKind::Int16 },
    { "signed short int", ScalarKind::Int16 }, { "ushort", ScalarKind::UInt16 },
    { "unsigned short", ScalarKind::UInt16 }, { "unsigned short int", ScalarKind::UInt16 },
    { "int", ScalarKind::Int32 }, { "signed int", ScalarKind::Int32 },
    { "float", ScalarKind::Float32 }, { "double", ScalarKind::Float64 } };
  const auto found = kinds.find(type);
  return found != kinds.end()    ? found->second
    : type.compare(0, 4, "met_") ? ParseScalarKind(type)
                                 : ScalarKind::Unknown;
}

} // namespace

bool CheckHeader(const std::string& path, bool nrrd, std::string& error)
{
  std::map<std::string, std::string> fields;
  std::int64_t offset = 0;
  if (!ReadHeader(path, nrrd, fields, offset, error))
  {
    return false;
  }
  const std::string where = std::string(nrrd ? "NRRD" : "MetaImage") + " header in '" + path + "'";
  auto field = [&](const std::string& key) { return fields.count(key) ? fields[key] : ""; };
  const int dimension = std::atoi(field(nrrd ? "dimension" : "ndims").c_str());
  std::vector<std::int64_t> sizes;
  std::istringstream sizeStream(field(nrrd ? "sizes" : "dimsize"));
  for (std::string token; sizeStream >> token;)
  {
    sizes.push_back(token.find_first_not_of("0123456789") == std::string::npos && token.size() < 13
        ? std::stoll(token)
        : -1);
  }
  // vtkNrrdReader reads a 4th axis, or a first axis of at most 9 samples, as vector components.
  const bool nrrdComponents = nrrd && !sizes.empty() && (dimension > 3 || sizes[0] <= 9);
  const int channels = nrrdComponents ? static_cast<int>(std::max<std::int64_t>(sizes[0], 1))
    : nrrd                            ? 1
                                      : std::atoi(field("elementnumberofchannels").c_str());
  if (channels > 1 || nrrdComponents)
  {
    error = "only single-component volumes are supported for now ('" + path + "' has " +
      std::to_string(channels) + " components" +
      (nrrd ? "; VTK reads a first NRRD axis of 9 or fewer samples as components)" : ")");
    return false;
  }
  if (dimension < 1 || dimension > 3 || static_cast<int>(sizes.size()) != dimension)
  {
    error = "malformed " + where + ": need a 1 to 3 dimensional volume with one size per axis";
    return false;
  }
  Dimensions dims = { 1, 1, 1 };
  std::copy(sizes.begin(), sizes.end(), dims);
  const std::string typeName = field(nrrd ? "type" : "elementtype");
  const KindInfo* kind = FindKind(HeaderKind(typeName));
  if (!kind)
  {
    error = "unsupported scalar type '" + typeName + "' in " + where;
    return false;
  }
  std::int64_t bytes = 0;
  if (!CheckSize(dims, *kind, bytes, error))
  {
    return false;
  }
  const std::string encoding = Lower(field("encoding"));
  std::string dataFile =
    field(nrrd ? (fields.count("datafile") ? "datafile" : "data file") : "elementdatafile");
  bool raw = !nrrd || encoding == "raw";
  if (nrrd && !raw && encoding != "ascii" && encoding != "text" && encoding != "txt" &&
    encoding != "gzip" && encoding != "gz")
  {
    error = "unsupported NRRD encoding '" + encoding + "' in '" + path + "'";
    return false;
  }
  if (!nrrd && (Lower(field("compresseddata")) == "true" || dataFile == "LIST"))
  {
    raw = false; // Compressed or listed data can only be checked by MetaIO itself.
  }
  if (dataFile.find('%') != std::string::npos || dataFile.find(' ') != std::string::npos ||
    (nrrd && dataFile == "LIST"))
  {
    error = "multi-file data in '" + path + "' is not supported";
    return false;
  }
  fs::path dataPath = path;
  if (!dataFile.empty() && dataFile != "LOCAL" && dataFile != "LIST")
  {
    dataPath = fs::path(dataFile).is_absolute() ? fs::path(dataFile)
                                                : fs::path(path).parent_path() / dataFile;
    offset = 0;
    if (!fs::is_regular_file(dataPath))
    {
      error = "data file '" + dataPath.string() + "' named in '" + path + "' does not exist";
      return false;
    }
  }
  else if (nrrd && EndsWith(Lower(path), ".nhdr"))
  {
    error = "malformed " + where + ": a detached header needs a 'data file' field";
    return false;
  }
  if (nrrd &&
    (std::atoll(field("byte skip").c_str()) || std::atoll(field("line skip").c_str()) ||
      std::atoll(field("byteskip").c_str()) || std::atoll(field("lineskip").c_str())))
  {
    error = "NRRD byte skip and line skip are not supported ('" + path + "')";
    return false;
  }
  const std::int64_t skip = nrrd ? 0 : std::atoll(field("headersize").c_str());
  const std::int64_t available = FileSize(dataPath) - offset - std::max<std::int64_t>(skip, 0);
  if (raw && available < bytes)
  {
    error = "size mismatch: '" + dataPath.string() + "' has " + std::to_string(available) +
      " data bytes but " + DimensionsText(dims) + " " + kind->name + " needs " +
      std::to_string(bytes) + " bytes";
    return false;
  }
  return true;
}

} // namespace accelvolume::cli::detail
