// Regression image: the CPU ray cast mapper in six viewports of one window: MIP, MinIP, raysum,
// average, shaded composite, and a cropped perspective composite (also checks that the image
// lands in its own viewport).
#include "AccelVolumeTestUtilities.h"
#include "vtkAccelVolumeRayCastMapper.h"
#include "vtkRegressionTestImage.h"

namespace
{
void AddViewport(vtkRenderWindow* window, vtkImageData* image, int blend, bool shade, bool crop,
  bool perspective, int column, int row)
{
  vtkNew<vtkAccelVolumeRayCastMapper> mapper;
  mapper->SetInputData(image);
  mapper->SetBlendMode(blend);
  mapper->SetAutoAdjustSampleDistances(0);
  mapper->SetSampleDistance(0.5);
  if (crop)
  {
    mapper->SetCropping(1);
    mapper->SetCroppingRegionPlanes(10, 50, 8, 40, 6, 36);
    mapper->SetCroppingRegionFlagsToFence();
  }
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  if (blend == vtkVolumeMapper::MINIMUM_INTENSITY_BLEND)
  {
    accelvolume_test::SetMinimumProperty(volume->GetProperty());
  }
  else
  {
    accelvolume_test::SetRampProperty(volume->GetProperty(), 40.0, 900.0, true);
  }
  volume->GetProperty()->SetShade(shade);
  vtkNew<vtkRenderer> renderer;
  renderer->SetViewport(column / 3.0, row / 2.0, (column + 1) / 3.0, (row + 1) / 2.0);
  renderer->SetBackground(0.1, 0.1, 0.2);
  renderer->AddVolume(volume);
  window->AddRenderer(renderer);
  renderer->ResetCamera();
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetParallelProjection(perspective ? 0 : 1);
  camera->Azimuth(30);
  camera->Elevation(20);
  camera->OrthogonalizeViewUp();
  renderer->ResetCamera();
}
}

int TestAccelVolumeRayCastModes(int argc, char* argv[])
{
  auto vessels = accelvolume_test::MakePhantom("vessels", 64, 56, 48, 1.0, 1.0, 1.25);
  auto blobs = accelvolume_test::MakePhantom("blobs", 64, 56, 48, 1.0, 1.0, 1.25);
  vtkNew<vtkRenderWindow> window;
  window->SetSize(450, 300);
  window->SetMultiSamples(0);
  AddViewport(window, vessels, vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND, false, false, true, 0, 1);
  AddViewport(window, vessels, vtkVolumeMapper::MINIMUM_INTENSITY_BLEND, false, false, false, 1, 1);
  AddViewport(window, blobs, vtkVolumeMapper::ADDITIVE_BLEND, false, false, false, 2, 1);
  AddViewport(window, blobs, vtkVolumeMapper::AVERAGE_INTENSITY_BLEND, false, false, true, 0, 0);
  AddViewport(window, blobs, vtkVolumeMapper::COMPOSITE_BLEND, true, false, true, 1, 0);
  AddViewport(window, vessels, vtkVolumeMapper::COMPOSITE_BLEND, false, true, true, 2, 0);
  window->Render();
  const int result = vtkRegressionTestImage(window);
  return result == vtkRegressionTester::FAILED ? EXIT_FAILURE : EXIT_SUCCESS;
}
