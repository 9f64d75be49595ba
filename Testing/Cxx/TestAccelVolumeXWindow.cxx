// The plain X window (ACCELVOLUME_GL=x, e.g. under Xvfb) keeps working with the module loaded:
// vtkRenderWindow::New() gives VTK's X window and the slice mapper's MIP matches the CPU
// reference there too. Skipped (exit 125) without a display or when a headless backend is chosen.
#include "AccelVolumeTestUtilities.h"
#include "vtkAccelVolumeHeadlessRenderWindow.h"
#include "vtkAccelVolumeRayCastMapper.h"
#include "vtkAccelVolumeSliceMapper.h"

#include <cstdlib>
#include <cstring>

namespace
{
// VTK's TestRemoveVolumeNonCurrentContext: two X windows, each with its own mapper; the second
// window's volume is removed (its mapper's objects released) while the first window's context
// is current. Releasing in the wrong context deleted the first window's objects of the same
// names, and its next frame was blank.
template <typename MapperType>
bool TwoWindows(vtkImageData* image, const char* name)
{
  using namespace accelvolume_test;
  vtkNew<MapperType> mappers[2];
  vtkNew<vtkVolume> volumes[2];
  vtkNew<vtkRenderer> renderers[2];
  vtkNew<vtkRenderWindow> windows[2];
  for (int w = 0; w < 2; ++w)
  {
    mappers[w]->SetInputData(image);
    mappers[w]->SetAutoAdjustSampleDistances(0);
    volumes[w]->SetMapper(mappers[w]);
    SetRampProperty(volumes[w]->GetProperty(), 50.0, 900.0, true);
    renderers[w]->AddVolume(volumes[w]);
    SetupObliqueView(windows[w], renderers[w], 100, 25, 15, true);
    windows[w]->Render();
  }
  const std::vector<float> before = ReadPixels(windows[0]);
  windows[0]->MakeCurrent();
  renderers[1]->RemoveAllViewProps();
  windows[0]->Render();
  windows[1]->Render();
  const std::vector<float> after = ReadPixels(windows[0]);
  return Report(
    (std::string(name) + ": first window after the second's volume was removed").c_str(),
    CompareImages(after, before, 1.0 / 255.0), 0.5 / 255.0, 0.001);
}
}

int TestAccelVolumeXWindow(int, char*[])
{
  const char* display = std::getenv("DISPLAY");
  const char* requested = std::getenv("ACCELVOLUME_GL");
  if (!display || !*display || !requested || std::strcmp(requested, "x") != 0)
  {
    std::cout << "needs ACCELVOLUME_GL=x and a DISPLAY: skipped\n";
    return 125;
  }
  using namespace accelvolume_test;
  constexpr int Size = 120;
  auto image = MakePhantom("vessels", 40, 36, 32);
  vtkNew<vtkAccelVolumeSliceMapper> mapper;
  mapper->SetInputData(image);
  mapper->SetBlendModeToMaximumIntensity();
  mapper->SetAutoAdjustSampleDistances(0);
  mapper->SetSampleDistance(0.25);
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  SetRampProperty(volume->GetProperty(), 50.0, 900.0, true);
  vtkNew<vtkRenderer> renderer;
  renderer->AddVolume(volume);
  vtkNew<vtkRenderWindow> window;
  if (vtkAccelVolumeHeadlessRenderWindow::SafeDownCast(window))
  {
    std::cerr << "ACCELVOLUME_GL=x but vtkRenderWindow::New() returned the headless window\n";
    return EXIT_FAILURE;
  }
  std::cout << "window class: " << window->GetClassName() << "\n";
  SetupObliqueView(window, renderer, Size, 25, 15, true);
  window->Render();
  const std::vector<float> ours = ReadPixels(window);
  ReferenceSettings settings;
  const std::vector<float> reference =
    RenderReferenceImage(image, volume, renderer, Size, Size, settings);
  bool ok =
    Report("MIP in the X window", CompareImages(ours, reference, 8.0 / 255.0), 2.0 / 255.0, 0.02);
  ok = TwoWindows<vtkAccelVolumeSliceMapper>(image, "slice") && ok;
  ok = TwoWindows<vtkAccelVolumeRayCastMapper>(image, "ray cast") && ok;
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
