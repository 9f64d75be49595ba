// Regression image: the shear-warp mapper in four viewports of one window, each with a parallel
// camera: composite unshaded, composite shaded (lookup-table shading), MIP and MinIP (also
// checks that each image lands in its own viewport).
#include "AccelVolumeTestUtilities.h"
#include "vtkAccelVolumeShearWarpMapper.h"
#include "vtkRegressionTestImage.h"

namespace
{
void AddViewport(vtkRenderWindow* window, vtkImageData* image, int blend, bool shade, int column,
  int row)
{
  vtkNew<vtkAccelVolumeShearWarpMapper> mapper;
  mapper->SetInputData(image);
  mapper->SetBlendMode(blend);
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
  renderer->SetViewport(column / 2.0, row / 2.0, (column + 1) / 2.0, (row + 1) / 2.0);
  renderer->SetBackground(0.1, 0.1, 0.2);
  renderer->AddVolume(volume);
  window->AddRenderer(renderer);
  renderer->ResetCamera();
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetParallelProjection(1);
  camera->Azimuth(30);
  camera->Elevation(20);
  camera->OrthogonalizeViewUp();
  renderer->ResetCamera();
}
}

int TestAccelVolumeShearWarpModes(int argc, char* argv[])
{
  auto vessels = accelvolume_test::MakePhantom("vessels", 64, 56, 48, 1.0, 1.0, 1.25);
  auto blobs = accelvolume_test::MakePhantom("blobs", 64, 56, 48, 1.0, 1.0, 1.25);
  vtkNew<vtkRenderWindow> window;
  window->SetSize(400, 400);
  window->SetMultiSamples(0);
  AddViewport(window, blobs, vtkVolumeMapper::COMPOSITE_BLEND, false, 0, 1);
  AddViewport(window, blobs, vtkVolumeMapper::COMPOSITE_BLEND, true, 1, 1);
  AddViewport(window, vessels, vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND, false, 0, 0);
  AddViewport(window, vessels, vtkVolumeMapper::MINIMUM_INTENSITY_BLEND, false, 1, 0);
  window->Render();
  const int result = vtkRegressionTestImage(window);
  return result == vtkRegressionTester::FAILED ? EXIT_FAILURE : EXIT_SUCCESS;
}
