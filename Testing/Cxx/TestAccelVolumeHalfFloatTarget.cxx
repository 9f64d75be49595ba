// The slice mapper's 16-bit float accumulation target (SetHalfFloatTarget) against the default
// 32-bit target on the same scenes: composite (semi-transparent and opaque, shaded, with early
// termination and skipping), MIP (at most one level of 255 apart) and raysum (which keeps the
// 32-bit target: identical). Half floats carry an 11-bit mantissa: each blend rounds to 1/2048
// of the running value.
#include "AccelVolumeTestUtilities.h"
#include "vtkAccelVolumeSliceMapper.h"

#include <vtkNew.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkVolume.h>
#include <vtkVolumeProperty.h>

#include <algorithm>
#include <cstdlib>
#include <iostream>

namespace
{

struct Scene
{
  const char* Name;
  int BlendMode;
  double OpacityScale; // 1 = the ramp; > 1 saturates early (opaque)
  bool Shade;
};

std::vector<float> Render(vtkImageData* image, const Scene& scene, bool half, bool& usedHalf)
{
  vtkNew<vtkAccelVolumeSliceMapper> mapper;
  // A rasterisation feature: compute slices would take the same samples without it.
  mapper->SetSliceCompositing(vtkAccelVolumeSliceMapper::SLICE_COMPOSITING_RASTER);
  mapper->SetInputData(image);
  mapper->SetBlendMode(scene.BlendMode);
  mapper->SetHalfFloatTarget(half);
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  accelvolume_test::SetRampProperty(volume->GetProperty(), 0.15, 1.0, true);
  if (scene.OpacityScale != 1.0)
  {
    vtkPiecewiseFunction* opacity = volume->GetProperty()->GetScalarOpacity();
    opacity->RemoveAllPoints();
    opacity->AddPoint(0.15, 0.0);
    opacity->AddPoint(0.4, std::min(1.0, 0.4 * scene.OpacityScale));
    opacity->AddPoint(1.0, 1.0);
  }
  volume->GetProperty()->SetShade(scene.Shade);
  vtkNew<vtkRenderer> renderer;
  renderer->AddVolume(volume);
  vtkNew<vtkRenderWindow> window;
  accelvolume_test::SetupObliqueView(window, renderer, 192, 35, 25, true);
  window->Render();
  usedHalf = mapper->GetHalfFloatTarget() != 0;
  return accelvolume_test::ReadPixels(window);
}

} // namespace

int TestAccelVolumeHalfFloatTarget(int, char*[])
{
  vtkSmartPointer<vtkImageData> image = accelvolume_test::MakePhantom("vessels", 96, 96, 96);
  if (!image)
  {
    return EXIT_FAILURE;
  }
  const Scene scenes[] = {
    { "composite, semi-transparent, shaded", vtkVolumeMapper::COMPOSITE_BLEND, 1.0, true },
    { "composite, semi-transparent", vtkVolumeMapper::COMPOSITE_BLEND, 0.3, false },
    { "composite, opaque", vtkVolumeMapper::COMPOSITE_BLEND, 8.0, false },
    { "MIP", vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND, 1.0, false },
    { "MinIP", vtkVolumeMapper::MINIMUM_INTENSITY_BLEND, 1.0, false },
    { "raysum (32-bit target kept)", vtkVolumeMapper::ADDITIVE_BLEND, 1.0, false },
  };
  bool ok = true;
  for (const Scene& scene : scenes)
  {
    bool usedFull = true;
    bool usedHalf = false;
    const std::vector<float> full = Render(image, scene, false, usedFull);
    const std::vector<float> half = Render(image, scene, true, usedHalf);
    const double drawn = static_cast<double>(std::count_if(
                           full.begin(), full.end(), [](float v) { return v > 0.05f; })) /
      static_cast<double>(full.size());
    // At most one level of 255 anywhere (none for raysum), mean under a quarter level.
    const bool sum = scene.BlendMode == vtkVolumeMapper::ADDITIVE_BLEND;
    const accelvolume_test::ImageDifference d =
      accelvolume_test::CompareImages(half, full, (sum ? 0.5 : 1.5) / 255.0);
    const std::string what = std::string("half vs 32-bit float target, ") + scene.Name;
    ok = accelvolume_test::Report(what.c_str(), d, 0.25 / 255.0, 0.0) && ok;
    if (drawn < 0.02 || usedFull || !usedHalf)
    {
      std::cout << scene.Name << ": drawn fraction " << drawn << ", half flag " << usedHalf
                << "  FAILED\n";
      ok = false;
    }
  }
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
