// Image and interactive sample distances of the CPU ray cast mapper, like VTK's CPU mapper:
// ImageSampleDistance 2 casts a quarter of the rays and still covers the viewport with nearly
// the same picture; an interactive frame (allocated time < 1 s, auto-adjust on) uses
// InteractiveSampleDistance and an image sample distance within the allowed range; still frames
// keep SampleDistance and ImageSampleDistance.
#include "AccelVolumeTestScene.h"

#include <cstdlib>

int TestAccelVolumeRayCastSampleDistances(int, char*[])
{
  using namespace accelvolume_test;
  bool ok = true;
  RayCastScene scene("blobs", vtkVolumeMapper::COMPOSITE_BLEND);
  vtkAccelVolumeRayCastMapper* mapper = scene.Mapper;
  mapper->SetAutoAdjustSampleDistances(0);
  mapper->SetSampleDistance(0.5);
  scene.Window->Render();
  const std::vector<float> full = ReadPixels(scene.Window);
  const vtkTypeInt64 fullRays = mapper->GetLastNumberOfRays();

  mapper->SetImageSampleDistance(2.0);
  scene.Window->Render();
  const std::vector<float> half = ReadPixels(scene.Window);
  const vtkTypeInt64 halfRays = mapper->GetLastNumberOfRays();
  std::cout << "rays at image sample distance 1: " << fullRays << ", at 2: " << halfRays << "\n";
  if (!(halfRays * 3 < fullRays && halfRays * 5 > fullRays))
  {
    std::cout << "image sample distance 2 should cast about a quarter of the rays  FAILED\n";
    ok = false;
  }
  // Bilinear magnification blurs edges; the bulk must stay.
  ok = Report("image sample distance 2 vs 1", CompareImages(half, full, 24.0 / 255.0), 3.0 / 255.0,
         0.05) &&
    ok;

  // Interactive frame: the renderer allots a tenth of a second.
  mapper->SetImageSampleDistance(1.0);
  mapper->SetAutoAdjustSampleDistances(1);
  mapper->SetInteractiveSampleDistance(2.0);
  mapper->SetMaximumImageSampleDistance(4.0);
  scene.Window->SetDesiredUpdateRate(10.0);
  scene.Window->Render();
  std::cout << "interactive frame: sample distance " << mapper->GetLastSampleDistance()
            << ", image sample distance " << mapper->GetLastImageSampleDistance() << "\n";
  if (mapper->GetLastSampleDistance() != 2.0 || mapper->GetLastImageSampleDistance() < 1.0 ||
    mapper->GetLastImageSampleDistance() > 4.0)
  {
    std::cout << "interactive sample distances not applied  FAILED\n";
    ok = false;
  }
  // Still frame again: the still settings come back.
  scene.Window->SetDesiredUpdateRate(0.0001);
  scene.Window->Render();
  if (mapper->GetLastSampleDistance() != 0.5 || mapper->GetLastImageSampleDistance() != 1.0)
  {
    std::cout << "still frame did not restore the sample distances  FAILED\n";
    ok = false;
  }
  else
  {
    ok = Report("still frame after an interactive one",
           CompareImages(ReadPixels(scene.Window), full, 1.0 / 255.0), 0.0, 0.0) &&
      ok;
  }
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
