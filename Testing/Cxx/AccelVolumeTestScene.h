// A standard small scene for the one-feature regression image tests.
#ifndef AccelVolumeTestScene_h
#define AccelVolumeTestScene_h

#include "AccelVolumeTestUtilities.h"
#include "vtkAccelVolumeSliceMapper.h"
#include "vtkRegressionTestImage.h"

namespace accelvolume_test
{
struct Scene
{
  vtkSmartPointer<vtkImageData> Image;
  vtkNew<vtkAccelVolumeSliceMapper> Mapper;
  vtkNew<vtkVolume> Volume;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkRenderWindow> Window;

  // 300x300 window, phantom volume, grey (or colour) ramp, oblique view.
  explicit Scene(
    const char* phantom = "vessels", int blend = vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND)
  {
    this->Image = MakePhantom(phantom, 64, 56, 48, 1.0, 1.0, 1.25);
    this->Mapper->SetInputData(this->Image);
    this->Mapper->SetBlendMode(blend);
    this->Volume->SetMapper(this->Mapper);
    SetRampProperty(this->Volume->GetProperty(), 40.0, 900.0, true);
    this->Renderer->SetBackground(0.1, 0.1, 0.2);
    this->Renderer->AddVolume(this->Volume);
    this->Window->SetSize(300, 300);
    this->Window->SetMultiSamples(0);
    this->Window->AddRenderer(this->Renderer);
    this->Renderer->ResetCamera();
    this->Renderer->GetActiveCamera()->Azimuth(30);
    this->Renderer->GetActiveCamera()->Elevation(20);
    this->Renderer->GetActiveCamera()->OrthogonalizeViewUp();
    this->Renderer->ResetCamera();
  }

  // Renders and compares with the baseline; returns a ctest exit code.
  int Regress(int argc, char* argv[])
  {
    this->Window->Render();
    const int result = vtkRegressionTestImage(this->Window);
    return result == vtkRegressionTester::FAILED ? EXIT_FAILURE : EXIT_SUCCESS;
  }
};
}

#endif
