// ReadRealVolume: renders a real scan instead of the procedural volume: a gzip-compressed raw
// file named NAME_XxYxZ_uint8.raw.gz (or _uint16, little endian), as in ../shared/data, read
// with zlib into a vtkImageData and shown as a MIP with the slice mapper. Without the file it
// exits with code 125, which ctest reports as skipped.
//
//   ReadRealVolume [output.png] [--check] [--input FILE.raw.gz]
#include "ExampleCommon.h"

#include <vtkAccelVolumeSliceMapper.h>
#include <vtkColorTransferFunction.h>
#include <vtkNew.h>
#include <vtkPiecewiseFunction.h>
#include <vtkVolumeProperty.h>

#include <zlib.h>

#include <cstdio>
#include <regex>

int main(int argc, char* argv[])
{
  example::Options options = example::ParseArguments(argc, argv, "ReadRealVolume");
  if (options.Input.empty())
  {
    options.Input = ACCELVOLUME_EXAMPLE_DATA "/HeadMRVolume_48x62x42_uint8.raw.gz";
  }
  // The raw file has no header: dimensions and type come from its name.
  std::smatch match;
  const std::regex pattern("_([0-9]+)x([0-9]+)x([0-9]+)_(uint8|uint16)\\.raw\\.gz$");
  if (!std::regex_search(options.Input, match, pattern))
  {
    std::fprintf(stderr, "ReadRealVolume: %s is not named NAME_XxYxZ_uint8|uint16.raw.gz\n",
      options.Input.c_str());
    return 1;
  }
  gzFile file = gzopen(options.Input.c_str(), "rb");
  if (!file)
  {
    std::printf("ReadRealVolume: %s not found, skipped\n", options.Input.c_str());
    return 125; // ctest SKIP_RETURN_CODE: the data folder is optional
  }
  vtkNew<vtkImageData> image;
  image->SetDimensions(std::stoi(match[1]), std::stoi(match[2]), std::stoi(match[3]));
  image->AllocateScalars(match[4] == "uint8" ? VTK_UNSIGNED_CHAR : VTK_UNSIGNED_SHORT, 1);
  const vtkIdType bytes = image->GetNumberOfPoints() * image->GetScalarSize();
  const int read = gzread(file, image->GetScalarPointer(), static_cast<unsigned>(bytes));
  gzclose(file);
  if (read != bytes) // x fastest, then y, then z: VTK's own order, so no reshuffling
  {
    std::fprintf(stderr, "ReadRealVolume: %s holds %d bytes, expected %lld\n",
      options.Input.c_str(), read, static_cast<long long>(bytes));
    return 1;
  }
  double range[2];
  image->GetScalarRange(range);

  vtkNew<vtkAccelVolumeSliceMapper> mapper;
  mapper->SetInputData(image);
  mapper->SetBlendModeToMaximumIntensity();
  // MIP: a grey ramp over the data range (the mapper maps the functions in data values).
  vtkNew<vtkColorTransferFunction> color;
  color->AddRGBPoint(range[0], 0.0, 0.0, 0.0);
  color->AddRGBPoint(range[1], 1.0, 1.0, 1.0);
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(range[0], 1.0);
  opacity->AddPoint(range[1], 1.0);
  vtkNew<vtkVolumeProperty> property;
  property->SetColor(color);
  property->SetScalarOpacity(opacity);
  property->SetInterpolationTypeToLinear();

  example::Scene scene(mapper, property);
  scene.Frame(0, -90, 1.3);
  if (!scene.Render("ReadRealVolume"))
  {
    return 1;
  }
  if (scene.Write(options) != 0)
  {
    return 1;
  }
  int dims[3];
  image->GetDimensions(dims);
  std::printf("ReadRealVolume: MIP of %s (%dx%dx%d, values %g..%g), %.1f ms -> %s\n",
    options.Input.c_str(), dims[0], dims[1], dims[2], range[0], range[1],
    1000.0 * mapper->GetLastRenderTime(), options.Output.c_str());
  return 0;
}
