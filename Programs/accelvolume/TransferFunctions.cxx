// TransferFunctions: --tf presets, the JSON transfer-function schema and the volume property.
#include "TransferFunctions.h"

#include <nlohmann/json.hpp>

#include <vtkColorTransferFunction.h>
#include <vtkNew.h>
#include <vtkPiecewiseFunction.h>
#include <vtkVolumeProperty.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <regex>
#include <set>
#include <sstream>

namespace accelvolume::cli
{
namespace
{

// Lighting unless the file gives it: VTK's own defaults (ambient 0, diffuse 1, specular 0) look
// flat once shading is on; these match common volume-rendering presets.
constexpr double DefaultAmbient = 0.2;
constexpr double DefaultDiffuse = 0.7;
constexpr double DefaultSpecular = 0.3;
constexpr double DefaultSpecularPower = 10;

// A transfer-function file is a few kilobytes; the cap keeps a wrong path (a volume, say) from
// being read whole into memory.
constexpr std::uintmax_t MaxFileBytes = 16u << 20;

using Json = nlohmann::json;

// "a number", "an array", ...: the kind a schema error names.
const char* KindName(const Json& value)
{
  switch (value.type())
  {
    case Json::value_t::null:
      return "null";
    case Json::value_t::boolean:
      return "a boolean";
    case Json::value_t::number_integer:
    case Json::value_t::number_unsigned:
    case Json::value_t::number_float:
      return "a number";
    case Json::value_t::string:
      return "a string";
    case Json::value_t::array:
      return "an array";
    case Json::value_t::object:
      return "an object";
    default:
      return "unknown";
  }
}

// nlohmann's parse error as one line "line L, column C: expected ..., got ...". In an array or
// object after a value both the closing bracket and a comma may follow, which the library's
// message names only as the bracket.
std::string DescribeParseError(const Json::parse_error& error)
{
  static const std::regex pattern(
    R"(parse error at line ([0-9]+), column ([0-9]+): syntax error while parsing ([a-z ]+?)(?: value)? - (.*))");
  std::smatch match;
  const std::string what = error.what();
  if (!std::regex_search(what, match, pattern))
  {
    return what;
  }
  std::string detail = match[4].str();
  static const std::regex unexpected(R"(^(.*); expected (.*)$)");
  std::smatch parts;
  if (std::regex_match(detail, parts, unexpected))
  {
    std::string expected = parts[2].str();
    if (expected == "']'" || expected == "'}'")
    {
      expected += " or ','";
    }
    detail = "expected " + expected + ", " + parts[1].str();
  }
  return "line " + match[1].str() + ", column " + match[2].str() + ": " + detail;
}

// Parses a whole transfer-function file; a key repeated in one object is refused, since it is
// almost certainly a mistake (the library would keep the last silently).
Json ParseDocument(const std::string& text)
{
  std::vector<std::set<std::string>> keys;
  const Json::parser_callback_t refuseDuplicates =
    [&keys](int, Json::parse_event_t event, Json& parsed)
  {
    if (event == Json::parse_event_t::object_start)
    {
      keys.emplace_back();
    }
    else if (event == Json::parse_event_t::object_end && !keys.empty())
    {
      keys.pop_back();
    }
    else if (event == Json::parse_event_t::key && !keys.empty() &&
      !keys.back().insert(parsed.get<std::string>()).second)
    {
      throw std::invalid_argument("duplicate key '" + parsed.get<std::string>() + "'");
    }
    return true;
  };
  return Json::parse(text, refuseDuplicates);
}

class SchemaReader
{
public:
  explicit SchemaReader(const std::string& path)
    : Path(path)
  {
  }

  [[noreturn]] void Fail(const std::string& message) const
  {
    throw CliError(ExitRuntime, "--tf '" + this->Path + "': " + message);
  }

  double Number(const Json& value, const std::string& name, double low, double high) const
  {
    if (!value.is_number())
    {
      this->Fail(name + " must be a number, got " + KindName(value));
    }
    const double number = value.get<double>();
    if (number < low || number > high)
    {
      std::ostringstream message;
      message << name << " must lie in [" << low << ", " << high << "], got " << number;
      this->Fail(message.str());
    }
    return number;
  }

  // [[x, v...], ...] with N numbers per point, x strictly increasing, values in [0, 1].
  template <std::size_t N>
  std::vector<std::array<double, N>> Points(const Json& value, const std::string& key) const
  {
    const char* shape = N == 2 ? "[x, value]" : "[x, r, g, b]";
    if (!value.is_array() || value.empty())
    {
      this->Fail(key + " must be a non-empty array of " + shape + " points");
    }
    std::vector<std::array<double, N>> points;
    for (std::size_t i = 0; i < value.size(); ++i)
    {
      const Json& item = value[i];
      const std::string name = key + "[" + std::to_string(i) + "]";
      if (!item.is_array() || item.size() != N)
      {
        this->Fail(name + " must be " + shape + " (" + std::to_string(N) + " numbers)");
      }
      std::array<double, N> point;
      for (std::size_t j = 0; j < N; ++j)
      {
        const double limit = j == 0 ? std::numeric_limits<double>::max() : 1.0;
        point[j] = this->Number(
          item[j], name + "[" + std::to_string(j) + "]", j == 0 ? -limit : 0.0, limit);
      }
      // VTK's functions keep one value per x, so a repeated x would silently drop a point.
      if (!points.empty() && !(point[0] > points.back()[0]))
      {
        std::ostringstream message;
        message << key << " x values must increase (unsorted x: " << point[0] << " after "
                << points.back()[0] << ")";
        this->Fail(message.str());
      }
      points.push_back(point);
    }
    return points;
  }

  TransferFunctionSpec Read(const Json& root) const
  {
    if (!root.is_object())
    {
      this->Fail(std::string("expected an object, got ") + KindName(root));
    }
    // Unknown keys are refused so that a misspelt optional key (say "specularpower") is not
    // silently ignored; name and description are free-form labels.
    static const std::set<std::string> known = { "scalarOpacity", "color", "gradientOpacity",
      "shade", "ambient", "diffuse", "specular", "specularPower", "name", "description" };
    for (const auto& member : root.items())
    {
      if (!known.count(member.key()))
      {
        this->Fail("unknown key '" + member.key() +
            "' (expected scalarOpacity, color, gradientOpacity, shade, ambient, diffuse, "
            "specular, specularPower, name, description)");
      }
    }
    for (const char* required : { "scalarOpacity", "color" })
    {
      if (!root.contains(required))
      {
        this->Fail(std::string("missing required key '") + required + "'");
      }
    }
    TransferFunctionSpec spec;
    spec.source = this->Path;
    spec.scalarOpacity = this->Points<2>(root.at("scalarOpacity"), "scalarOpacity");
    spec.color = this->Points<4>(root.at("color"), "color");
    const auto member = [&](const char* key) -> const Json*
    {
      const auto found = root.find(key);
      return found == root.end() ? nullptr : &*found;
    };
    if (const Json* gradient = member("gradientOpacity"))
    {
      spec.gradientOpacity = this->Points<2>(*gradient, "gradientOpacity");
    }
    if (const Json* shade = member("shade"))
    {
      if (!shade->is_boolean())
      {
        this->Fail(std::string("shade must be true or false, got ") + KindName(*shade));
      }
      spec.shade = shade->get<bool>();
    }
    const std::pair<const char*, std::optional<double>*> coefficients[] = {
      { "ambient", &spec.ambient }, { "diffuse", &spec.diffuse }, { "specular", &spec.specular }
    };
    for (const auto& coefficient : coefficients)
    {
      if (const Json* value = member(coefficient.first))
      {
        *coefficient.second = this->Number(*value, coefficient.first, 0, 1);
      }
    }
    if (const Json* power = member("specularPower"))
    {
      // vtkVolumeProperty clamps the power to [0, 128]; say so instead of clamping silently.
      spec.specularPower = this->Number(*power, "specularPower", 0, 128);
    }
    return spec;
  }

private:
  std::string Path;
};

TransferFunctionSpec ReadFile(const std::string& path)
{
  namespace fs = std::filesystem;
  std::error_code code;
  if (!fs::exists(path, code))
  {
    throw CliError(
      ExitRuntime, "--tf '" + path + "' is neither a preset (tf1|tf2) nor an existing file");
  }
  if (fs::is_directory(path, code))
  {
    throw CliError(ExitRuntime, "--tf '" + path + "' is a directory, not a JSON file");
  }
  const std::uintmax_t bytes = fs::file_size(path, code);
  if (!code && bytes > MaxFileBytes)
  {
    throw CliError(ExitRuntime, "--tf '" + path + "' is too large for a transfer-function file");
  }
  std::ifstream stream(path, std::ios::binary);
  std::ostringstream text;
  text << stream.rdbuf();
  if (!stream)
  {
    throw CliError(ExitRuntime, "cannot read --tf '" + path + "'");
  }
  Json root;
  try
  {
    root = ParseDocument(text.str());
  }
  catch (const Json::parse_error& error)
  {
    throw CliError(
      ExitRuntime, "--tf '" + path + "': malformed JSON: " + DescribeParseError(error));
  }
  catch (const Json::exception& error) // e.g. a number too large for a double
  {
    // The library's what() starts with "[json.exception.<kind>.<id>] ".
    const std::string what = error.what();
    const std::size_t start = what.rfind("] ", what.find(' ') + 1);
    throw CliError(ExitRuntime,
      "--tf '" + path + "': malformed JSON: " + (start == std::string::npos ? what : what.substr(start + 2)));
  }
  catch (const std::invalid_argument& error) // a repeated key
  {
    throw CliError(ExitRuntime, "--tf '" + path + "': malformed JSON: " + error.what());
  }
  return SchemaReader(path).Read(root);
}

// The presets in data units over window [lo, hi].
void BuildPreset(const std::string& name, const double window[2], TransferFunctionSpec& spec)
{
  const double lo = window[0], width = window[1] - window[0];
  const auto at = [&](double fraction) { return lo + fraction * width; };
  if (name == "tf1")
  {
    // Semi-transparent: low values (background, noise) vanish, the rest accumulates softly, hot
    // colours so that denser material reads brighter.
    spec.scalarOpacity = { { lo, 0 }, { at(0.1), 0 }, { window[1], 0.35 } };
    spec.color = { { lo, 0.3, 0.0, 0.0 }, { at(0.1), 0.35, 0.02, 0.0 }, { at(0.55), 1.0, 0.5, 0.0 },
      { window[1], 1.0, 1.0, 1.0 } };
  }
  else
  {
    // Opaque surfaces: a 2 %-wide step at 30 % of the range turns the first material above it
    // into a surface; bone colour, slightly darker at the threshold so edges read.
    const double threshold = at(0.3);
    spec.scalarOpacity = { { lo, 0 }, { threshold, 0 }, { at(0.32), 1 }, { window[1], 1 } };
    spec.color = { { lo, 0.6, 0.5, 0.4 }, { threshold, 0.7, 0.62, 0.52 },
      { at(0.4), 0.9, 0.85, 0.75 }, { window[1], 0.9, 0.85, 0.75 } };
  }
}

} // namespace

TransferFunctionSpec LoadTransferFunction(const Options& options)
{
  TransferFunctionSpec spec;
  const std::string& name = options.transferFunction;
  if (name.empty())
  {
    return spec;
  }
  // Presets win over a file of the same name; ./tf1 names such a file.
  if (name == "tf1" || name == "tf2")
  {
    spec.source = name;
    spec.preset = true;
    return spec;
  }
  return ReadFile(name);
}

AppliedTransferFunction ApplyTransferFunction(const TransferFunctionSpec& spec,
  const Options& options, const double window[2], vtkVolumeProperty* property)
{
  TransferFunctionSpec points = spec;
  if (spec.preset)
  {
    BuildPreset(spec.source, window, points);
  }
  else if (spec.source.empty())
  {
    // The default: black..white over the window, opacity 0..1 (MinIP: opaque everywhere, since
    // it keeps the lowest value and transparent low values would show nothing).
    points.scalarOpacity = { { window[0], options.blend == BlendKind::MinIP ? 1.0 : 0.0 },
      { window[1], 1.0 } };
    points.color = { { window[0], 0, 0, 0 }, { window[1], 1, 1, 1 } };
  }
  vtkNew<vtkColorTransferFunction> colour;
  for (const auto& point : points.color)
  {
    colour->AddRGBPoint(point[0], point[1], point[2], point[3]);
  }
  vtkNew<vtkPiecewiseFunction> opacity;
  for (const auto& point : points.scalarOpacity)
  {
    opacity->AddPoint(point[0], point[1]);
  }
  property->SetColor(colour);
  property->SetScalarOpacity(opacity);
  property->SetInterpolationTypeToLinear();

  AppliedTransferFunction applied;
  if (options.haveGradientOpacity)
  {
    points.gradientOpacity = { { options.gradientOpacity[0], options.gradientOpacity[1] },
      { options.gradientOpacity[2], options.gradientOpacity[3] } };
  }
  if (!points.gradientOpacity.empty())
  {
    vtkNew<vtkPiecewiseFunction> gradient;
    for (const auto& point : points.gradientOpacity)
    {
      gradient->AddPoint(point[0], point[1]);
    }
    property->SetGradientOpacity(gradient);
    property->DisableGradientOpacityOff();
    applied.gradientOpacity = points.gradientOpacity;
  }

  applied.shade = options.haveShade ? options.shade : points.shade.value_or(false);
  applied.ambient = points.ambient.value_or(DefaultAmbient);
  applied.diffuse = points.diffuse.value_or(DefaultDiffuse);
  applied.specular = points.specular.value_or(DefaultSpecular);
  applied.specularPower = points.specularPower.value_or(DefaultSpecularPower);
  property->SetShade(applied.shade ? 1 : 0);
  property->SetAmbient(applied.ambient);
  property->SetDiffuse(applied.diffuse);
  property->SetSpecular(applied.specular);
  property->SetSpecularPower(applied.specularPower);
  return applied;
}

} // namespace accelvolume::cli
