// TransferFunctions: the --tf presets (tf1, tf2), JSON transfer-function files and lighting.
#ifndef accelvolume_cli_TransferFunctions_h
#define accelvolume_cli_TransferFunctions_h

#include "Options.h"

#include <array>
#include <optional>
#include <string>
#include <vector>

class vtkVolumeProperty;

namespace accelvolume::cli
{

// What --tf names, read before any VTK object exists so that a bad file fails fast.
struct TransferFunctionSpec
{
  // "" (no --tf: the grey window ramp), "tf1", "tf2" or the JSON file's path as given.
  std::string source;
  bool preset = false; // tf1/tf2: the points are built from the window at render time
  // Points in data units (files only): [x, opacity], [x, r, g, b], [gradient magnitude, opacity].
  std::vector<std::array<double, 2>> scalarOpacity;
  std::vector<std::array<double, 4>> color;
  std::vector<std::array<double, 2>> gradientOpacity;
  std::optional<bool> shade;
  std::optional<double> ambient, diffuse, specular, specularPower;
};

// Resolves options.transferFunction: a preset name, else a JSON file (see --help for the keys).
// Throws CliError(ExitRuntime, ...) for a missing/unreadable file, malformed JSON, missing
// scalarOpacity or color, non-numeric or out-of-range entries and x values that do not increase.
TransferFunctionSpec LoadTransferFunction(const Options& options);

// What ApplyTransferFunction set, for --stats.
struct AppliedTransferFunction
{
  bool shade = false;
  double ambient = 0, diffuse = 0, specular = 0, specularPower = 0;
  std::vector<std::array<double, 2>> gradientOpacity; // empty: none set
};

// Fills property's colour, scalar opacity, optional gradient opacity, shading and lighting.
// window is [lo, hi]: the --window values or the data range; the presets and the default ramp are
// laid out over it. Command-line --shade and --gradient-opacity override the file's.
AppliedTransferFunction ApplyTransferFunction(const TransferFunctionSpec& spec,
  const Options& options, const double window[2], vtkVolumeProperty* property);

} // namespace accelvolume::cli

#endif
