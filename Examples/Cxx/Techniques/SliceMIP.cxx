// SliceMIP: maximum intensity projection with vtkAccelVolumeSliceMapper (view-aligned slices
// on the GPU), cropped to a sub-volume, with the cut faces re-rendered (Hong, Kye and Shin 2007) so the
// oblique crop planes show no slice aliasing even with few slices.
//
//   SliceMIP [output.png] [--check]
#include "ExampleCommon.h"

#include <vtkAccelVolumeSliceMapper.h>
#include <vtkColorTransferFunction.h>
#include <vtkNew.h>
#include <vtkPiecewiseFunction.h>
#include <vtkVolumeProperty.h>

#include <cstdio>

int main(int argc, char* argv[])
{
  const example::Options options = example::ParseArguments(argc, argv, "SliceMIP");
  auto image = example::MakeVolume(64); // spacing 1, origin 0: world = voxel index

  vtkNew<vtkAccelVolumeSliceMapper> mapper;
  mapper->SetInputData(image);
  mapper->SetBlendModeToMaximumIntensity();
  // Keep the middle of the volume: x 10..54, y 6..50, z 12..44 (world coordinates). The crop
  // cuts through the blobs, so the cut faces carry bright values that coarse slices would miss.
  mapper->CroppingOn();
  mapper->SetCroppingRegionPlanes(10, 54, 6, 50, 12, 44);
  mapper->SetCroppingRegionFlagsToSubVolume();
  mapper->BoundaryRerenderingOn(); // the default; set here because it is what this shows
  mapper->SetNumberOfSlices(32);   // deliberately coarse: the faces keep the crop exact

  // MIP: the colour and opacity of the maximum along each ray; a grey ramp, fully opaque.
  vtkNew<vtkColorTransferFunction> color;
  color->AddRGBPoint(0, 0.0, 0.0, 0.0);
  color->AddRGBPoint(255, 1.0, 1.0, 1.0);
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0, 1.0);
  opacity->AddPoint(255, 1.0);
  vtkNew<vtkVolumeProperty> property;
  property->SetColor(color);
  property->SetScalarOpacity(opacity);
  property->SetInterpolationTypeToLinear();

  example::Scene scene(mapper, property);
  scene.Frame(30, 20, 1.5);
  if (!scene.Render("SliceMIP"))
  {
    return 1;
  }
  if (scene.Write(options) != 0)
  {
    return 1;
  }
  std::printf("SliceMIP: MIP of a 64^3 volume cropped to a sub-volume, %d slices, %d cut faces "
              "re-rendered, %.1f ms -> %s\n",
    mapper->GetLastNumberOfSlices(), mapper->GetLastNumberOfBoundaryFaces(),
    1000.0 * mapper->GetLastRenderTime(), options.Output.c_str());
  return 0;
}
