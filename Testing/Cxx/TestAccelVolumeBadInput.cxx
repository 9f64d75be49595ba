// Bad input never crashes: each case gets a clear vtkErrorMacro and an unchanged background,
// for the slice mapper, the CPU ray cast mapper and the shear-warp mapper alike (the shear-warp
// mapper, parallel projection only, also for a perspective camera).
#include "AccelVolumeTestUtilities.h"
#include "vtkAccelVolumeRayCastMapper.h"
#include "vtkAccelVolumeShearWarpMapper.h"
#include "vtkAccelVolumeSliceMapper.h"

#include "vtkCharArray.h"
#include "vtkCommand.h"
#include "vtkUnsignedIntArray.h"

#include <cstdlib>
#include <functional>
#include <string>
#include <type_traits>

namespace
{

// The shear-warp mapper renders parallel projections only: its cases use a parallel camera,
// except the one about the camera.
template <typename MapperType>
bool Expect(const char* what, const std::function<void(vtkVolumeMapper*)>& configure,
  const char* expectedText,
  bool parallel = std::is_same<MapperType, vtkAccelVolumeShearWarpMapper>::value)
{
  vtkNew<MapperType> mapper;
  vtkNew<accelvolume_test::ErrorRecorder> recorder;
  mapper->AddObserver(vtkCommand::ErrorEvent, recorder);
  configure(mapper);
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  accelvolume_test::SetRampProperty(volume->GetProperty(), 0, 1000);
  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(0.2, 0.4, 0.6);
  renderer->AddVolume(volume);
  renderer->GetActiveCamera()->SetParallelProjection(parallel);
  vtkNew<vtkRenderWindow> window;
  window->SetSize(64, 64);
  window->AddRenderer(renderer);
  window->Render();
  const std::vector<float> pixels = accelvolume_test::ReadPixels(window);
  const bool untouched = std::abs(pixels[3 * (32 * 64 + 32) + 2] - 0.6f) < 0.01f;
  const bool reported = recorder->Messages.find(expectedText) != std::string::npos;
  std::cout << mapper->GetClassName() << ", " << what << ": "
            << (reported ? "reported" : "NOT reported") << " -> " << recorder->Messages;
  return reported && untouched;
}
}

template <typename MapperType>
bool ExpectAll()
{
  bool ok = true;
  ok = Expect<MapperType>(
         "no input", [](vtkVolumeMapper*) {}, "No input") &&
    ok;
  ok = Expect<MapperType>(
         "empty image",
         [](vtkVolumeMapper* mapper)
         {
           vtkNew<vtkImageData> empty;
           mapper->SetInputData(empty);
         },
         "Empty input") &&
    ok;
  ok = Expect<MapperType>(
         "no scalars",
         [](vtkVolumeMapper* mapper)
         {
           vtkNew<vtkImageData> image;
           image->SetDimensions(4, 4, 4);
           mapper->SetInputData(image);
         },
         "no point scalars") &&
    ok;
  // The slice mapper renders 2-4 components; five are refused by every mapper.
  ok = Expect<MapperType>(
         "five components",
         [](vtkVolumeMapper* mapper)
         {
           vtkNew<vtkImageData> image;
           image->SetDimensions(4, 4, 4);
           image->AllocateScalars(VTK_UNSIGNED_CHAR, 5);
           mapper->SetInputData(image);
         },
         std::is_same<MapperType, vtkAccelVolumeSliceMapper>::value ? "At most 4 scalar components"
                                                                    : "single-component") &&
    ok;
  ok = Expect<MapperType>(
         "bit scalars",
         [](vtkVolumeMapper* mapper)
         {
           vtkNew<vtkImageData> image;
           image->SetDimensions(4, 4, 4);
           image->AllocateScalars(VTK_BIT, 1);
           mapper->SetInputData(image);
         },
         "Unsupported scalar type") &&
    ok;
  // The slice mapper and the ray caster draw iso-surfaces (TestAccelVolumeVsGPURayCastFeatures).
  ok = !std::is_same<MapperType, vtkAccelVolumeShearWarpMapper>::value ||
    Expect<MapperType>(
      "isosurface blend (not provided)",
      [](vtkVolumeMapper* mapper)
      {
        mapper->SetInputData(accelvolume_test::MakePhantom("blobs", 8, 8, 8));
        mapper->SetBlendModeToIsoSurface();
      },
      "not supported") &&
      ok;
  if (std::is_same<MapperType, vtkAccelVolumeRayCastMapper>::value)
  {
    ok = Expect<MapperType>(
           "slice blend without a slice function",
           [](vtkVolumeMapper* mapper)
           {
             mapper->SetInputData(accelvolume_test::MakePhantom("blobs", 8, 8, 8));
             mapper->SetBlendMode(vtkVolumeMapper::SLICE_BLEND);
           },
           "needs a vtkPlane") &&
      ok;
  }
  if (std::is_same<MapperType, vtkAccelVolumeShearWarpMapper>::value)
  {
    ok = Expect<MapperType>(
           "two components",
           [](vtkVolumeMapper* mapper)
           {
             vtkNew<vtkImageData> image;
             image->SetDimensions(4, 4, 4);
             image->AllocateScalars(VTK_UNSIGNED_CHAR, 2);
             mapper->SetInputData(image);
           },
           "single-component") &&
      ok;
    for (int blend : { vtkVolumeMapper::ADDITIVE_BLEND, vtkVolumeMapper::AVERAGE_INTENSITY_BLEND })
    {
      ok = Expect<MapperType>(
             blend == vtkVolumeMapper::ADDITIVE_BLEND ? "additive blend" : "average blend",
             [blend](vtkVolumeMapper* mapper)
             {
               mapper->SetInputData(accelvolume_test::MakePhantom("blobs", 8, 8, 8));
               mapper->SetBlendMode(blend);
             },
             "not supported by the shear-warp mapper") &&
        ok;
    }
    ok = Expect<MapperType>(
           "perspective camera",
           [](vtkVolumeMapper* mapper)
           { mapper->SetInputData(accelvolume_test::MakePhantom("blobs", 8, 8, 8)); },
           "needs a parallel projection", false) &&
      ok;
  }
  if (std::is_same<MapperType, vtkAccelVolumeSliceMapper>::value)
  {
    ok = Expect<MapperType>(
           "nine clipping planes (slice mapper only: the ray caster takes any number)",
           [](vtkVolumeMapper* mapper)
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
  }
  return ok;
}

int TestAccelVolumeBadInput(int, char*[])
{
  const bool slice = ExpectAll<vtkAccelVolumeSliceMapper>();
  const bool rayCast = ExpectAll<vtkAccelVolumeRayCastMapper>();
  const bool shearWarp = ExpectAll<vtkAccelVolumeShearWarpMapper>();
  return slice && rayCast && shearWarp ? EXIT_SUCCESS : EXIT_FAILURE;
}
