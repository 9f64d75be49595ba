// SliceMIP: maximum intensity projection with vtkAccelVolumeSliceMapper (view-aligned slices
// on the GPU), cropped to a sub-volume, with the cut faces re-rendered (Kye et al. 2007) so the
// oblique crop planes show no slice aliasing even with few slices.
//
//   SliceMIP [output.png] [--check]
#include "ExampleCommon.h"

#include <vtkAccelVolumeSliceMapper.h>
#include <vtkCamera.h>
#include <vtkColorTransferFunction.h>
#include <vtkNew.h>
#include <vtkPiecewiseFunction.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkVolume.h>
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

  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  volume->SetProperty(property);

  vtkNew<vtkRenderer> renderer;
  renderer->AddVolume(volume);
  renderer->SetBackground(0.1, 0.1, 0.2);
  renderer->ResetCamera();
  renderer->GetActiveCamera()->Azimuth(30); // oblique, so the crop faces are not axis aligned
  renderer->GetActiveCamera()->Elevation(20);
  renderer->GetActiveCamera()->Zoom(1.5); // the bounding sphere leaves a wide margin
  renderer->ResetCameraClippingRange();

  // The module's object factory makes this a headless EGL / OSMesa window when there is no
  // DISPLAY or ACCELVOLUME_GL=egl|osmesa is set.
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(0); // no MSAA: volume mappers draw into their own targets
  window->SetSize(256, 256);
  window->AddRenderer(renderer);

  example::ErrorWatch errors;
  errors.Watch(mapper);
  errors.Watch(window);
  window->Render();
  if (errors.GetErrors() > 0)
  {
    std::fprintf(stderr, "SliceMIP: rendering failed\n");
    return 1;
  }
  if (example::WritePNG(window, renderer, options.Output, options.Check) != 0)
  {
    return 1;
  }
  std::printf("SliceMIP: MIP of a 64^3 volume cropped to a sub-volume, %d slices, %d cut faces "
              "re-rendered, %.1f ms -> %s\n",
    mapper->GetLastNumberOfSlices(), mapper->GetLastNumberOfBoundaryFaces(),
    1000.0 * mapper->GetLastRenderTime(), options.Output.c_str());
  return 0;
}
