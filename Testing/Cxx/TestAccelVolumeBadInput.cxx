// Bad input never crashes: each case gets a clear vtkErrorMacro and an unchanged background.
#include "AccelVolumeTestUtilities.h"
#include "vtkAccelVolumeSliceMapper.h"

#include "vtkCharArray.h"
#include "vtkCommand.h"
#include "vtkUnsignedIntArray.h"

#include <cstdlib>
#include <functional>
#include <string>

namespace
{

bool Expect(const char* what, const std::function<void(vtkAccelVolumeSliceMapper*)>& configure,
  const char* expectedText)
{
  vtkNew<vtkAccelVolumeSliceMapper> mapper;
  vtkNew<accelvolume_test::ErrorRecorder> recorder;
  mapper->AddObserver(vtkCommand::ErrorEvent, recorder);
  configure(mapper);
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  accelvolume_test::SetRampProperty(volume->GetProperty(), 0, 1000);
  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(0.2, 0.4, 0.6);
  renderer->AddVolume(volume);
  vtkNew<vtkRenderWindow> window;
  window->SetSize(64, 64);
  window->AddRenderer(renderer);
  window->Render();
  const std::vector<float> pixels = accelvolume_test::ReadPixels(window);
  const bool untouched = std::abs(pixels[3 * (32 * 64 + 32) + 2] - 0.6f) < 0.01f;
  const bool reported = recorder->Messages.find(expectedText) != std::string::npos;
  std::cout << what << ": " << (reported ? "reported" : "NOT reported") << " -> "
            << recorder->Messages;
  return reported && untouched;
}
}

int TestAccelVolumeBadInput(int, char*[])
{
  bool ok = true;
  ok = Expect(
         "no input", [](vtkAccelVolumeSliceMapper*) {}, "No input") &&
    ok;
  ok = Expect(
         "empty image",
         [](vtkAccelVolumeSliceMapper* mapper)
         {
           vtkNew<vtkImageData> empty;
           mapper->SetInputData(empty);
         },
         "Empty input") &&
    ok;
  ok = Expect(
         "no scalars",
         [](vtkAccelVolumeSliceMapper* mapper)
         {
           vtkNew<vtkImageData> image;
           image->SetDimensions(4, 4, 4);
           mapper->SetInputData(image);
         },
         "no point scalars") &&
    ok;
  ok = Expect(
         "three components",
         [](vtkAccelVolumeSliceMapper* mapper)
         {
           vtkNew<vtkImageData> image;
           image->SetDimensions(4, 4, 4);
           image->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
           mapper->SetInputData(image);
         },
         "single-component") &&
    ok;
  ok = Expect(
         "unsigned int scalars",
         [](vtkAccelVolumeSliceMapper* mapper)
         {
           vtkNew<vtkImageData> image;
           image->SetDimensions(4, 4, 4);
           image->AllocateScalars(VTK_UNSIGNED_INT, 1);
           mapper->SetInputData(image);
         },
         "Unsupported scalar type") &&
    ok;
  ok = Expect(
         "isosurface blend (not provided)",
         [](vtkAccelVolumeSliceMapper* mapper)
         {
           mapper->SetInputData(accelvolume_test::MakePhantom("blobs", 8, 8, 8));
           mapper->SetBlendModeToIsoSurface();
         },
         "not supported") &&
    ok;
  ok = Expect(
         "nine clipping planes",
         [](vtkAccelVolumeSliceMapper* mapper)
         {
           mapper->SetInputData(accelvolume_test::MakePhantom("blobs", 8, 8, 8));
           for (int i = 0; i < 9; ++i)
           {
             vtkNew<vtkPlane> plane;
             plane->SetNormal(1, 0, 0);
             mapper->AddClippingPlane(plane);
           }
         },
         "clipping planes") &&
    ok;
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
