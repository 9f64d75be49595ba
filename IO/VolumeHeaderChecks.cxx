// VolumeHeaderChecks: validates MetaImage and NRRD headers against their data files, and checks
// compressed and ASCII data without allocating the volume.
#include "VolumeHeaderChecks.h"

#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>
#include <vector>

namespace accelvolume::cli::detail
{
namespace fs = std::filesystem;

const KindInfo* FindKind(OptionalScalarType kind)
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
  const auto first = text.find_first_not_of(" \t\r\n\v\f");
  const auto last = text.find_last_not_of(" \t\r\n\v\f");
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
  if (dims[0] < 1 || dims[1] < 1 || dims[2] < 1)
  {
    error = "dimensions must be at least 1, got " + DimensionsText(dims);
    return false;
  }
  std::int64_t voxels = 1;
  for (int axis = 0; axis < 3; ++axis)
  {
    // Dividing first keeps the product from overflowing for absurd inputs.
    if (dims[axis] > MaximumVoxels / voxels)
    {
      error = "refusing " + DimensionsText(dims) + ": more than 2^31 voxels";
      return false;
    }
    voxels *= dims[axis];
  }
  bytes = voxels * kind.size;
  if (bytes > MaximumBytes)
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

bool ParseCount(const std::string& text, std::int64_t& value)
{
  if (text.empty() || text.size() > 12 || text.find_first_not_of("0123456789") != std::string::npos)
  {
    return false;
  }
  value = std::stoll(text);
  return true;
}

bool InflateFile(const std::string& path, std::int64_t offset, std::int64_t length, Wrapper wrapper,
  char* output, std::int64_t expected, const std::string& needs, std::string& error)
{
  std::ifstream stream(path, std::ios::binary);
  if (!stream || offset < 0 || !stream.seekg(offset))
  {
    error = "cannot read '" + path + "'";
    return false;
  }
  z_stream zlib{};
  // 15 + 16: gzip only; 15 + 32: zlib or gzip, detected from the header (as MetaIO does).
  if (inflateInit2(&zlib, wrapper == Wrapper::Gzip ? 15 + 16 : 15 + 32) != Z_OK)
  {
    error = "cannot initialize zlib";
    return false;
  }
  const std::string format = wrapper == Wrapper::Gzip ? "gzip" : "compressed";
  std::vector<unsigned char> input(1 << 20);
  std::vector<unsigned char> scratch(1 << 16);
  std::int64_t left = length < 0 ? INT64_MAX : length; // compressed bytes not read yet
  std::int64_t produced = 0;
  bool streamEnded = false, trailing = false;
  std::string failure;
  while (failure.empty())
  {
    if (zlib.avail_in == 0 && left > 0 && stream)
    {
      stream.read(reinterpret_cast<char*>(input.data()),
        static_cast<std::streamsize>(std::min<std::int64_t>(left, input.size())));
      left -= stream.gcount();
      zlib.next_in = input.data();
      zlib.avail_in = static_cast<uInt>(stream.gcount());
    }
    if (streamEnded)
    {
      if (zlib.avail_in == 0)
      {
        break; // the data ends with the last member, as it should
      }
      // Concatenated gzip members are one valid stream (gzip -c a b); anything else is garbage.
      trailing = zlib.next_in[0] != 0x1f || inflateReset(&zlib) != Z_OK;
      if (trailing)
      {
        break;
      }
      streamEnded = false;
    }
    // Straight into the volume while it has room; past that into scratch, only to notice excess.
    const bool direct = output && produced < expected;
    const auto room = static_cast<uInt>(
      direct ? std::min<std::int64_t>(expected - produced, 1 << 30) : std::int64_t(scratch.size()));
    zlib.next_out = direct ? reinterpret_cast<Bytef*>(output + produced) : scratch.data();
    zlib.avail_out = room;
    const int code = inflate(&zlib, Z_NO_FLUSH);
    produced += room - zlib.avail_out;
    if (produced > expected)
    {
      failure = "size mismatch: '" + path + "' decompresses to more than " +
        std::to_string(expected) + " bytes but " + needs;
    }
    else if (code == Z_STREAM_END)
    {
      streamEnded = true;
    }
    else if (code == Z_BUF_ERROR && zlib.avail_in == 0)
    {
      // No progress without more input, and there is none: the stream was cut short.
      failure = "truncated " + format + " data in '" + path + "': the stream ends after " +
        std::to_string(produced) + " of " + std::to_string(expected) + " bytes";
    }
    else if (code != Z_OK)
    {
      failure = "corrupt " + format + " data in '" + path + "' after " + std::to_string(produced) +
        " of " + std::to_string(expected) +
        " bytes (zlib: " + (zlib.msg ? zlib.msg : "error " + std::to_string(code)) + ")";
    }
  }
  inflateEnd(&zlib);
  if (failure.empty() && produced != expected)
  {
    failure = "size mismatch: '" + path + "' decompresses to " + std::to_string(produced) +
      " bytes but " + needs;
  }
  if (failure.empty() && trailing)
  {
    failure = "trailing bytes after the " + format + " stream in '" + path + "'";
  }
  error = failure;
  return failure.empty();
}

namespace
{

constexpr std::size_t MetaImageHeaderLimit = std::size_t(4) << 20;
// vtkNrrdReader reads at most 4 MiB - 1 bytes of header.
constexpr std::size_t NrrdHeaderLimit = (std::size_t(4) << 20) - 1;

std::string ReadPrefix(const std::string& path, std::size_t limit)
{
  std::ifstream stream(path, std::ios::binary);
  std::string buffer(
    std::min<std::int64_t>(std::max<std::int64_t>(FileSize(path), 0), limit), '\0');
  stream.read(&buffer[0], static_cast<std::streamsize>(buffer.size()));
  buffer.resize(static_cast<std::size_t>(std::max<std::streamsize>(stream.gcount(), 0)));
  return buffer;
}

std::vector<std::string> SplitWords(const std::string& text)
{
  std::istringstream stream(text);
  std::vector<std::string> words;
  for (std::string word; stream >> word;)
  {
    words.push_back(word);
  }
  return words;
}

bool Printable(const std::string& line)
{
  return std::all_of(
    line.begin(), line.end(), [](unsigned char c) { return std::isprint(c) || std::isspace(c); });
}

std::string Needs(const Dimensions dims, const KindInfo& kind, std::int64_t bytes)
{
  return DimensionsText(dims) + " " + kind.name + " needs " + std::to_string(bytes) + " bytes";
}

// Whether `in >> value` reads all of token, as vtkNrrdReader reads ASCII values.
template <typename T>
bool ReadsAs(std::istringstream& in, const std::string& token)
{
  T value;
  in.clear();
  in.str(token);
  in >> value;
  return !in.fail() && in.peek() == std::char_traits<char>::eof();
}

bool AsciiValueFits(std::istringstream& in, const std::string& token, const KindInfo& kind)
{
  switch (kind.vtkType)
  {
    case VTK_SHORT:
      return ReadsAs<short>(in, token);
    case VTK_UNSIGNED_SHORT:
      return ReadsAs<unsigned short>(in, token);
    case VTK_INT:
      return ReadsAs<int>(in, token);
    case VTK_FLOAT:
      return ReadsAs<float>(in, token);
    default:
      return ReadsAs<double>(in, token);
  }
}

// The first `count` whitespace-separated tokens of path must be numbers of the kind.
bool CheckAsciiValues(
  const fs::path& path, std::int64_t count, const KindInfo& kind, std::string& error)
{
  std::ifstream stream(path, std::ios::binary);
  std::istringstream parser;
  std::int64_t found = 0;
  // setw bounds each token, so a file without white space is not read into memory whole.
  for (std::string token; found < count && stream >> std::setw(65) >> token; ++found)
  {
    if (token.size() > 64 || !AsciiValueFits(parser, token, kind))
    {
      error = "bad ASCII value '" + token.substr(0, 40) + "' (value " + std::to_string(found + 1) +
        ") in '" + path.string() + "' for type " + kind.name;
      return false;
    }
  }
  if (found < count)
  {
    error = "size mismatch: '" + path.string() + "' has " + std::to_string(found) +
      " ASCII values but " + std::to_string(count) + " are needed";
    return false;
  }
  return true;
}

// Checks the stored data (raw, gzip or ASCII) of a header that passed its own checks.
bool CheckData(const fs::path& dataPath, std::int64_t offset, std::int64_t length,
  const std::string& encoding, const Dimensions dims, const KindInfo& kind, std::int64_t bytes,
  std::string& error)
{
  const std::int64_t stored =
    std::max<std::int64_t>(length >= 0 ? length : FileSize(dataPath) - offset, 0);
  if (encoding == "ascii")
  {
    return CheckAsciiValues(dataPath, bytes / kind.size, kind, error);
  }
  if (encoding == "raw")
  {
    if (stored < bytes)
    {
      error = "size mismatch: '" + dataPath.string() + "' has " + std::to_string(stored) +
        " data bytes but " + Needs(dims, kind, bytes);
    }
    return stored >= bytes;
  }
  if (bytes / MaximumDeflateRatio > stored)
  {
    error = "size mismatch: '" + dataPath.string() + "' has only " + std::to_string(stored) +
      " compressed bytes, too few for " + DimensionsText(dims) + " " + kind.name + " (" +
      std::to_string(bytes) + " bytes; deflate expands at most 1032:1)";
    return false;
  }
  return InflateFile(dataPath.string(), offset, length,
    encoding == "gzip" ? Wrapper::Gzip : Wrapper::ZlibOrGzip, nullptr, bytes,
    Needs(dims, kind, bytes), error);
}

// Resolves a header's data file name against the header's folder; it must be a regular file.
bool FindDataFile(
  const std::string& header, const std::string& name, fs::path& dataPath, std::string& error)
{
  dataPath = fs::path(name).is_absolute() ? fs::path(name) : fs::path(header).parent_path() / name;
  std::error_code code;
  if (!fs::is_regular_file(dataPath, code))
  {
    error = "data file '" + dataPath.string() + "' named in '" + header + "' " +
      (fs::exists(dataPath, code) ? "is not a regular file" : "does not exist");
    return false;
  }
  return true;
}

bool CheckMetaImage(const std::string& path, HeaderSummary& summary, std::string& error)
{
  const std::string buffer = ReadPrefix(path, MetaImageHeaderLimit);
  const std::string where = "MetaImage header in '" + path + "'";
  // Keys as written: MetaIO matches its field names exactly, so "dimsize" is no DimSize to it.
  std::map<std::string, std::string> fields, lowerKeys;
  std::int64_t dataOffset = -1;
  std::size_t position = 0;
  for (int lineNumber = 1; position < buffer.size() && dataOffset < 0; ++lineNumber)
  {
    const std::size_t end = buffer.find('\n', position);
    const std::string line = Trim(buffer.substr(position, end - position));
    position = end == std::string::npos ? buffer.size() : end + 1;
    if (line.empty() || line[0] == '#')
    {
      continue;
    }
    const auto separator = line.find('=');
    if (separator == std::string::npos || !Printable(line))
    {
      error = "malformed " + where + " at line " + std::to_string(lineNumber) +
        " (expected 'Key = Value')";
      return false;
    }
    const std::string key = Trim(line.substr(0, separator));
    // MetaIO and this check could each take a different copy of a repeated key.
    if (!lowerKeys.emplace(Lower(key), key).second)
    {
      error = "malformed " + where + ": '" + key + "' appears twice";
      return false;
    }
    // MetaIO stops at ElementDataFile; LOCAL data starts on the next line.
    fields[key] = Trim(line.substr(separator + 1));
    dataOffset = key == "ElementDataFile" ? static_cast<std::int64_t>(position) : -1;
  }
  if (dataOffset < 0)
  {
    error = "malformed " + where + ": no ElementDataFile" +
      (buffer.size() == MetaImageHeaderLimit ? " in its first 4 MiB" : "");
    return false;
  }
  auto field = [&](const std::string& key) { return fields.count(key) ? fields[key] : ""; };
  std::int64_t dimension = 0, channels = 1;
  if (!ParseCount(field("NDims"), dimension) || dimension < 1 || dimension > 3)
  {
    error = "malformed " + where + ": NDims must be 1, 2 or 3, got '" + field("NDims") + "'";
    return false;
  }
  if (fields.count("ElementNumberOfChannels") &&
    (!ParseCount(field("ElementNumberOfChannels"), channels) || channels < 1))
  {
    error = "malformed " + where + ": ElementNumberOfChannels must be a positive integer, got '" +
      field("ElementNumberOfChannels") + "'";
    return false;
  }
  if (channels > 1)
  {
    error = "only single-component volumes are supported for now ('" + path + "' has " +
      std::to_string(channels) + " components)";
    return false;
  }
  const std::vector<std::string> sizes = SplitWords(field("DimSize"));
  Dimensions dims = { 1, 1, 1 };
  for (std::size_t axis = 0; axis < sizes.size() && axis < 3; ++axis)
  {
    dims[axis] = ParseCount(sizes[axis], dims[axis]) ? dims[axis] : 0;
  }
  if (static_cast<std::int64_t>(sizes.size()) != dimension || dims[0] < 1 || dims[1] < 1 ||
    dims[2] < 1)
  {
    error = "malformed " + where + ": DimSize must be " + std::to_string(dimension) +
      " positive integer(s), one per axis, got '" + field("DimSize") + "'";
    return false;
  }
  static const std::map<std::string, OptionalScalarType> types = { { "MET_UCHAR", ScalarType::UInt8 },
    { "MET_CHAR", ScalarType::Int8 }, { "MET_USHORT", ScalarType::UInt16 },
    { "MET_SHORT", ScalarType::Int16 }, { "MET_INT", ScalarType::Int32 },
    { "MET_FLOAT", ScalarType::Float32 }, { "MET_DOUBLE", ScalarType::Float64 } };
  const auto type = types.find(field("ElementType"));
  if (type == types.end())
  {
    error = "unsupported scalar type '" + field("ElementType") + "' in " + where +
      " (supported: MET_UCHAR MET_CHAR MET_USHORT MET_SHORT MET_INT MET_FLOAT MET_DOUBLE)";
    return false;
  }
  summary.kind = FindKind(type->second);
  std::int64_t bytes = 0;
  if (!CheckSize(dims, *summary.kind, bytes, error))
  {
    return false;
  }
  std::copy(dims, dims + 3, summary.dims);
  // MetaIO reads a boolean as true when its value starts with T, t or 1.
  auto isTrue = [&](const std::string& key) { return std::string("Tt1").find(field(key)[0]) < 3; };
  if (fields.count("BinaryData") && !isTrue("BinaryData"))
  {
    error = "ASCII MetaImage data (BinaryData = False) is not supported ('" + path + "')";
    return false;
  }
  const std::string dataFile = field("ElementDataFile");
  if (dataFile.compare(0, 4, "LIST") == 0 || dataFile.find_first_of("% \t") != std::string::npos)
  {
    error = "multi-file data in '" + path + "' is not supported";
    return false;
  }
  fs::path dataPath = path;
  if (dataFile != "LOCAL")
  {
    dataOffset = 0;
    if (!FindDataFile(path, dataFile, dataPath, error))
    {
      return false;
    }
  }
  const bool compressed = fields.count("CompressedData") && isTrue("CompressedData");
  std::int64_t skip = 0, length = -1;
  if (fields.count("HeaderSize") && field("HeaderSize") != "-1" &&
    !ParseCount(field("HeaderSize"), skip))
  {
    error = "malformed " + where + ": HeaderSize must be -1 or a byte count, got '" +
      field("HeaderSize") + "'";
    return false;
  }
  const std::int64_t available = FileSize(dataPath) - dataOffset - (compressed ? 0 : skip);
  // MetaIO (VTK 9.1) silently reads compressed data without a CompressedDataSize wrongly.
  if (compressed &&
    (!ParseCount(field("CompressedDataSize"), length) || length < 1 || length > available))
  {
    error = "malformed " + where + ": CompressedData needs a CompressedDataSize between 1 and " +
      "the " + std::to_string(std::max<std::int64_t>(available, 0)) + " bytes stored, got '" +
      field("CompressedDataSize") + "'";
    return false;
  }
  return CheckData(dataPath, dataOffset + (compressed ? 0 : skip),
    compressed ? length : std::max<std::int64_t>(available, 0), compressed ? "zlib" : "raw", dims,
    *summary.kind, bytes, error);
}

// vtkNrrdReader's reading of "(x,y,z)": the numbers between the parentheses; none otherwise.
std::vector<double> ParseNrrdVector(const std::string& text)
{
  const std::string trimmed = Trim(text);
  std::vector<double> values;
  if (trimmed.size() < 2 || trimmed.front() != '(' || trimmed.back() != ')')
  {
    return values;
  }
  std::stringstream list(trimmed.substr(1, trimmed.size() - 2));
  for (std::string value; std::getline(list, value, ',');)
  {
    values.push_back(std::atof(value.c_str()));
  }
  return values;
}

// vtkNrrdReader's names of the types supported here; Unknown for any other name.
OptionalScalarType NrrdKind(const std::string& type)
{
  static const std::map<std::string, OptionalScalarType> kinds = { { "signed char", ScalarType::Int8 },
    { "int8", ScalarType::Int8 }, { "int8_t", ScalarType::Int8 }, { "uchar", ScalarType::UInt8 },
    { "unsigned char", ScalarType::UInt8 }, { "uint8", ScalarType::UInt8 },
    { "uint8_t", ScalarType::UInt8 }, { "short", ScalarType::Int16 },
    { "short int", ScalarType::Int16 }, { "signed short", ScalarType::Int16 },
    { "signed short int", ScalarType::Int16 }, { "int16", ScalarType::Int16 },
    { "int16_t", ScalarType::Int16 }, { "ushort", ScalarType::UInt16 },
    { "unsigned short", ScalarType::UInt16 }, { "unsigned short int", ScalarType::UInt16 },
    { "uint16", ScalarType::UInt16 }, { "uint16_t", ScalarType::UInt16 },
    { "int", ScalarType::Int32 }, { "signed int", ScalarType::Int32 },
    { "int32", ScalarType::Int32 }, { "int32_t", ScalarType::Int32 },
    { "float", ScalarType::Float32 }, { "double", ScalarType::Float64 } };
  const auto found = kinds.find(type);
  return found != kinds.end() ? found->second : std::nullopt;
}

// What vtkNrrdReader's header parse leaves behind, field by field.
struct NrrdFields
{
  long long dimension = 0;
  std::string dimensionField; // the field that set dimension last
  std::vector<std::int64_t> sizes;
  std::vector<double> spacings;
  std::vector<double> origin;
  std::string type, encoding = "raw";
  std::vector<std::string> dataFiles;
};

bool ParseNrrdLine(const std::string& field, const std::string& value, NrrdFields& nrrd,
  const std::string& where, std::string& error)
{
  const std::vector<std::string> words = SplitWords(value);
  char* end = nullptr;
  if (field == "dimension" || field == "space dimension" || field == "space")
  {
    nrrd.dimensionField = field;
  }
  if (field == "dimension" || field == "space dimension")
  {
    nrrd.dimension = std::strtoll(value.c_str(), &end, 10);
    if (value.empty() || *end || nrrd.dimension < 1 || nrrd.dimension > 4)
    {
      error = "malformed " + where + ": " + field + " must be 1 to 4, got '" + value + "'";
    }
  }
  else if (field == "space")
  {
    nrrd.dimension = 3; // every NRRD space is 3D (or 3D and time)
    error = value.find("time") == std::string::npos
      ? ""
      : "NRRD space '" + value + "' with time is not supported (" + where + ")";
  }
  else if (field == "sizes" || field == "spacings")
  {
    // vtkNrrdReader sizes its axis list from the 'dimension' seen so far and indexes it blindly.
    if (nrrd.dimension < 1 || words.size() != static_cast<std::size_t>(nrrd.dimension))
    {
      error = "malformed " + where + ": '" + field + "' " +
        (nrrd.dimension < 1 ? std::string("before 'dimension'")
                            : "has " + std::to_string(words.size()) + " values but '" +
              nrrd.dimensionField + "' before it set " + std::to_string(nrrd.dimension) + " axes");
      return false;
    }
    std::vector<std::int64_t> sizes(words.size());
    std::vector<double> spacings(words.size());
    for (std::size_t axis = 0; axis < words.size(); ++axis)
    {
      // NRRD marks non-spatial axes with nan spacing; any other spacing must be positive.
      spacings[axis] = std::strtod(words[axis].c_str(), &end);
      if (field == "sizes" ? !ParseCount(words[axis], sizes[axis]) || !sizes[axis]
                           : *end || !(spacings[axis] > 0 || std::isnan(spacings[axis])))
      {
        error = "malformed " + where + ": " + field + " must be positive " +
          (field == "sizes" ? "integers" : "numbers") + ", got '" + value + "'";
        return false;
      }
    }
    if (field == "sizes")
    {
      nrrd.sizes = sizes;
    }
    else
    {
      nrrd.spacings = spacings;
    }
  }
  else if (field == "space directions")
  {
    nrrd.spacings.clear();
    for (const std::string& word : words)
    {
      double squared = 0;
      for (const double component : ParseNrrdVector(word == "none" ? "" : word))
      {
        squared += component * component;
      }
      nrrd.spacings.push_back(std::sqrt(squared));
    }
  }
  else if (field == "space origin")
  {
    nrrd.origin = ParseNrrdVector(value);
  }
  else if (field == "type")
  {
    nrrd.type = value;
  }
  else if (field == "encoding")
  {
    const std::string name = Lower(value);
    nrrd.encoding = name == "raw"                          ? "raw"
      : name == "gzip" || name == "gz"                     ? "gzip"
      : name == "ascii" || name == "txt" || name == "text" ? "ascii"
                                                           : "";
    error = nrrd.encoding.empty()
      ? "unsupported NRRD encoding '" + value + "' in " + where + " (supported: raw, gzip, ascii)"
      : "";
  }
  else if (field == "data file" || field == "datafile")
  {
    // vtkNrrdReader reads the first word blindly and formats 4-word patterns with snprintf.
    if (words.empty() || words[0] == "LIST" || words.size() >= 4 || !nrrd.dataFiles.empty())
    {
      error = words.empty() ? "malformed " + where + ": empty 'data file'"
                            : "multi-file data in " + where + " is not supported";
    }
    nrrd.dataFiles.push_back(value);
  }
  else if (field == "endian" && value != "little" && value != "big")
  {
    error = "unknown NRRD endian '" + value + "' in " + where;
  }
  else if (field == "line skip" || field == "lineskip" || field == "byte skip" ||
    field == "byteskip")
  {
    error = std::strtoll(value.c_str(), &end, 10) != 0
      ? "NRRD byte skip and line skip are not supported (" + where + ")"
      : "";
  }
  return error.empty();
}

bool CheckNrrd(const std::string& path, HeaderSummary& summary, std::string& error)
{
  const std::string buffer = ReadPrefix(path, NrrdHeaderLimit);
  const std::string where = "NRRD header in '" + path + "'";
  if (buffer.compare(0, 4, "NRRD") != 0)
  {
    error = "malformed " + where + ": missing NRRD magic";
    return false;
  }
  // Like vtkNrrdReader: the header is the text before the first NUL and ends after the first
  // blank line found from byte 1; attached data follows it (or the whole buffer, if none).
  std::string header = buffer.substr(0, buffer.find('\0'));
  std::int64_t dataOffset = static_cast<std::int64_t>(buffer.size());
  for (std::size_t s = header.find('\n', 1); s != std::string::npos; s = header.find('\n', s + 1))
  {
    const std::size_t blank = header.compare(s, 2, "\n\n") == 0 ? 2
      : header.compare(s, 3, "\n\r\n") == 0                     ? 3
                                                                : 0;
    if (blank)
    {
      dataOffset = static_cast<std::int64_t>(s + blank);
      header.resize(s + blank);
      break;
    }
  }
  if (header.back() != '\n')
  {
    // vtkNrrdReader's line loop never ends on a last line without a line break (getline keeps
    // the old line at end of file).
    error = "malformed " + where + ": its last header line has no line break";
    return false;
  }
  NrrdFields nrrd;
  std::istringstream lines(header);
  std::string line;
  std::getline(lines, line); // the magic
  for (int lineNumber = 2; std::getline(lines, line) && !line.empty(); ++lineNumber)
  {
    const auto separator = line.find(": ");
    if (line[0] == '#' || Trim(line).empty() ||
      (separator == std::string::npos && line.find(":=") != std::string::npos))
    {
      continue; // comments, blank-looking lines ("\r") and key/value pairs
    }
    if (separator == std::string::npos || !Printable(line))
    {
      error = "malformed " + where + " at line " + std::to_string(lineNumber) +
        " (expected 'field: description')";
      return false;
    }
    if (!ParseNrrdLine(
          line.substr(0, separator), Trim(line.substr(separator + 2)), nrrd, where, error))
    {
      return false;
    }
  }
  summary.kind = FindKind(NrrdKind(Trim(nrrd.type)));
  if (nrrd.type.empty() || nrrd.sizes.empty())
  {
    error = "malformed " + where + ": no '" + (nrrd.type.empty() ? "type" : "sizes") + "' field";
    return false;
  }
  // vtkNrrdReader takes a 4th axis, a first axis of at most 9 samples, or a first axis with zero
  // spacing ("none" direction) for vector components.
  std::vector<std::int64_t> sizes = nrrd.sizes;
  std::vector<double> spacings = nrrd.spacings;
  if (sizes.size() > 3 || sizes[0] <= 9 || (!spacings.empty() && spacings[0] == 0))
  {
    if (sizes[0] != 1)
    {
      error = "only single-component volumes are supported for now ('" + path + "' has " +
        std::to_string(sizes[0]) +
        " components; VTK reads a first NRRD axis of 9 or fewer "
        "samples, a 4th axis or a 'none' direction as components)";
      return false;
    }
    sizes.erase(sizes.begin());
    spacings.erase(spacings.begin(), spacings.begin() + (spacings.empty() ? 0 : 1));
  }
  if (sizes.size() < 2 || sizes.size() > 3)
  {
    // VTK's image reader crashes on one-dimensional data.
    error =
      "malformed " + where + ": need 2 or 3 spatial axes, got " + std::to_string(sizes.size());
    return false;
  }
  for (std::size_t axis = 0; axis < 3; ++axis)
  {
    const double spacing = axis < spacings.size() ? spacings[axis] : 1;
    const double origin = axis < nrrd.origin.size() ? nrrd.origin[axis] : 0;
    if (!(spacing > 0 && std::isfinite(spacing)) || !std::isfinite(origin))
    {
      std::ostringstream text;
      text << "malformed " << where << ": axis " << axis << " has spacing " << spacing
           << " and origin " << origin << " (spacing must be positive, both finite)";
      error = text.str();
      return false;
    }
  }
  if (!summary.kind)
  {
    error = "unsupported scalar type '" + nrrd.type + "' in " + where +
      " (supported: int8 uint8 int16 uint16 int32 float double)";
    return false;
  }
  Dimensions dims = { sizes[0], sizes[1], sizes.size() > 2 ? sizes[2] : 1 };
  std::int64_t bytes = 0;
  if (!CheckSize(dims, *summary.kind, bytes, error))
  {
    return false;
  }
  std::copy(dims, dims + 3, summary.dims);
  fs::path dataPath = path;
  if (!nrrd.dataFiles.empty())
  {
    dataOffset = 0;
    if (!FindDataFile(path, nrrd.dataFiles[0], dataPath, error))
    {
      return false;
    }
  }
  else if (EndsWith(Lower(path), ".nhdr"))
  {
    error = "malformed " + where + ": a detached header needs a 'data file' field";
    return false;
  }
  if (nrrd.encoding == "ascii" && (nrrd.dataFiles.empty() || summary.kind->size == 1))
  {
    // vtkNrrdReader 9.1 reads ASCII data from the start of the named file (the header, for
    // attached data) and 8-bit ASCII values as single characters: both give wrong voxels.
    error = "NRRD ASCII data " +
      std::string(nrrd.dataFiles.empty() ? "in the header's own file" : "of 8-bit type") +
      " is not supported ('" + path + "'; use raw or gzip encoding)";
    return false;
  }
  return CheckData(dataPath, dataOffset, -1, nrrd.encoding, dims, *summary.kind, bytes, error);
}

} // namespace

bool CheckHeader(const std::string& path, bool nrrd, HeaderSummary& summary, std::string& error)
{
  return nrrd ? CheckNrrd(path, summary, error) : CheckMetaImage(path, summary, error);
}

} // namespace accelvolume::cli::detail
