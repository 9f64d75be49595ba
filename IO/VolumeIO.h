// VolumeIO: loads the CLI's input volume from image files, raw dumps or a built-in phantom.
#ifndef accelvolume_cli_VolumeIO_h
#define accelvolume_cli_VolumeIO_h

#include "common/VolumeView.h"
#include "reference/Phantoms.h"

#include <vtkImageData.h>
#include <vtkSmartPointer.h>

#include <optional>
#include <string>

namespace accelvolume::cli
{

// Core's one scalar-type enum; "no type" (not given, or a name no type has) is std::nullopt.
using accelvolume::ScalarType;
using OptionalScalarType = std::optional<ScalarType>;

// Accepts "uint8", "int8", "uint16", "int16", "int32", "float32", "float64" in any letter case;
// anything else gives std::nullopt.
OptionalScalarType ParseScalarType(const std::string& name);
// VTK_UNSIGNED_CHAR, VTK_SIGNED_CHAR, ... VTK_DOUBLE; VTK_VOID for std::nullopt.
int ToVTKType(OptionalScalarType kind);
// The name ParseScalarType accepts; "unknown" for std::nullopt.
const char* ScalarTypeName(OptionalScalarType kind);

struct VolumeRequest
{
  std::string inputPath; // empty -> phantom
  std::string phantom = "vessels";
  int phantomDims[3] = { 128, 128, 128 };
  double phantomTime = 0;
  bool haveDims = false; // raw input only
  int dims[3] = { 0, 0, 0 };
  OptionalScalarType kind = std::nullopt; // raw input only
  bool haveSpacing = false;              // overrides the spacing of every input
  double spacing[3] = { 1, 1, 1 };
};

// Loads .mhd/.mha (vtkMetaImageReader), .vti (vtkXMLImageDataReader), .nrrd/.nhdr (vtkNrrdReader),
// headerless little-endian .raw or gzip-compressed .raw.gz (streamed through zlib), or a phantom
// when inputPath is empty. Raw files named NAME_<X>x<Y>x<Z>_<type>.raw[.gz] supply dims and type
// unless haveDims / kind are set; a datasets.json next to a raw file that lists it by name supplies
// spacing (and dims / type when neither flags nor name do) unless haveSpacing.
// The result has one scalar component of a ScalarType type, active point scalars with one tuple
// per voxel, and a non-empty extent. On failure returns nullptr and sets error to one line without
// a trailing newline; VTK and MetaIO messages are captured rather than printed.
vtkSmartPointer<vtkImageData> LoadVolume(const VolumeRequest& request, std::string& error);

// Float scalars named "scalars", spacing from the phantom, origin 0.
vtkSmartPointer<vtkImageData> PhantomToImage(const accelvolume::PhantomVolume& phantom);

// "256x256x113 uint16"; "(no volume)" for nullptr; multi-component data adds " (3 components)".
std::string DescribeVolume(vtkImageData* image);

} // namespace accelvolume::cli

#endif
