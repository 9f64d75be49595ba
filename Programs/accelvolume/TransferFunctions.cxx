// TransferFunctions: --tf presets, the JSON transfer-function schema and the volume property.
#include "TransferFunctions.h"

#include "JsonReader.h"

#include <vtkColorTransferFunction.h>
#include <vtkNew.h>
#include <vtkPiecewiseFunction.h>
#include <vtkVolumeProperty.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
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

class SchemaReader
{
public:
  explicit SchemaReader(const std::string& path)
    : Path(path)
  {
  }

  [[noreturn]] void Fail(const JsonValue& where, const std::string& message) const
  {
    throw CliError(ExitRuntime, "--tf '" + this->Path + "': " + where.Where() + ": " + message);
  }

  double Number(const JsonValue& value, const std::string& name, double low, double high) const
  {
    if (value.kind != JsonValue::Kind::Number)
    {
      this->Fail(value, name + " must be a number, got " + JsonKindName(value.kind));
    }
    if (value.number < low || value.number > high)
    {
      std::ostringstream message;
      message << name << " must lie in [" << low << ", " << high << "], got " << value.number;
      this->Fail(value, message.str());
    }
    return value.number;
  }

  // [[x, v...], ...] with N numbers per point, x strictly increasing, values in [0, 1].
  template <std::size_t N>
  std::vector<std::array<double, N>> Points(const JsonValue& value, const std::string& key) const
  {
    const char* shape = N == 2 ? "[x, value]" : "[x, r, g, b]";
    if (value.kind != JsonValue::Kind::Array || value.items.empty())
    {
      this->Fail(value, key + " must be a non-empty array of " + shape + " points");
    }
    std::vector<std::array<double, N>> points;
    for (std::size_t i = 0; i < value.items.size(); ++i)
    {
      const JsonValue& item = value.items[i];
      const std::string name = key + "[" + std::to_string(i) + "]";
      if (item.kind != JsonValue::Kind::Array || item.items.size() != N)
      {
        this->Fail(item, name + " must be " + shape + " (" + std::to_string(N) + " numbers)");
      }
      std::array<double, N> point;
      for (std::size_t j = 0; j < N; ++j)
      {
        const double limit = j == 0 ? std::numeric_limits<double>::max() : 1.0;
        point[j] = this->Number(
          item.items[j], name + "[" + std::to_string(j) + "]", j == 0 ? -limit : 0.0, limit);
      }
      // VTK's functions keep one value per x, so a repeated x would silently drop a point.
      if (!points.empty() && !(point[0] > points.back()[0]))
      {
        std::ostringstream message;
        message << key << " x values must increase (unsorted x: " << point[0] << " after "
                << points.back()[0] << ")";
        this->Fail(item, message.str());
      }
      points.push_back(point);
    }
    return points;
  }

  TransferFunctionSpec Read(const JsonValue& root) const
  {
    if (root.kind != JsonValue::Kind::Object)
    {
      this->Fail(root, std::string("expected an object, got ") + JsonKindName(root.kind));
    }
    // Unknown keys are refused so that a misspelt optional key (say "specularpower") is not
    // silently ignored; name and description are free-form labels.
    static const std::set<std::string> known = { "scalarOpacity", "color", "gradientOpacity",
      "shade", "ambient", "diffuse", "specular", "specularPower", "name", "description" };
    for (const auto& member : root.members)
    {
      if (!known.count(member.first))
      {
        this->Fail(member.second,
          "unknown key '" + member.first +
            "' (expected scalarOpacity, color, gradientOpacity, shade, ambient, diffuse, "
            "specular, specularPower, name, description)");
      }
    }
    for (const char* required : { "scalarOpacity", "color" })
    {
      if (!root.members.count(required))
      {
        this->Fail(root, std::string("missing required key '") + required + "'");
      }
    }
    TransferFunctionSpec spec;
    spec.source = this->Path;
    spec.scalarOpacity = this->Points<2>(root.members.at("scalarOpacity"), "scalarOpacity");
    spec.color = this->Points<4>(root.members.at("color"), "color");
    const auto member = [&](const char* key) -> const JsonValue*
    {
      const auto found = root.members.find(key);
      return found == root.members.end() ? nullptr : &found->second;
    };
    if (const JsonValue* gradient = member("gradientOpacity"))
    {
      spec.gradientOpacity = this->Points<2>(*gradient, "gradientOpacity");
    }
    if (const JsonValue* shade = member("shade"))
    {
      if (shade->kind != JsonValue::Kind::Bool)
      {
        this->Fail(
          *shade, std::string("shade must be true or false, got ") + JsonKindName(shade->kind));
      }
      spec.shade = shade->boolean;
    }
    const std::pair<const char*, std::optional<double>*> coefficients[] = {
      { "ambient", &spec.ambient }, { "diffuse", &spec.diffuse }, { "specular", &spec.specular }
    };
    for (const auto& coefficient : coefficients)
    {
      if (const JsonValue* value = member(coefficient.first))
      {
        *coefficient.second = this->Number(*value, coefficient.first, 0, 1);
      }
    }
    if (const JsonValue* power = member("specularPower"))
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
  JsonValue root;
  try
  {
    root = ParseJson(text.str());
  }
  catch (const JsonError& error)
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
