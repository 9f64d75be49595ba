// Numeric check: the slice mapper's MIP / MinIP / raysum / average images against the CPU
// reference ray caster (accelvolume::RenderReference), parallel and perspective, with cropping
// and a clipping plane. A wrong baseline cannot hide a wrong renderer here.
#include "AccelVolumeTestUtilities.h"
#include "vtkAccelVolumeSliceMapper.h"

#include <cstdlib>

namespace
{
struct Case
{
  const char* Name;
  int Blend;
  bool Perspective;
  bool Crop;
  bool Clip;
  bool Oriented = false; // origin, direction matrix and a rotated, moved vtkVolume
};

bool RunCase(const Case& c)
{
  using namespace accelvolume_test;
  constexpr int Size = 160;
  const bool projection = c.Blend == vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND ||
    c.Blend == vtkVolumeMapper::MINIMUM_INTENSITY_BLEND;
  auto image = MakePhantom(projection ? "vessels" : "blobs", 48, 40, 36, 1.0, 1.2, 1.5);
  vtkNew<vtkAccelVolumeSliceMapper> mapper;
  mapper->SetInputData(image);
  mapper->SetBlendMode(c.Blend);
  mapper->SetAutoAdjustSampleDistances(0);
  mapper->SetSampleDistance(0.25);
  mapper->SetAdditiveUnitDistance(10.0);
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  if (c.Oriented)
  {
    image->SetOrigin(-7.0, 3.0, 11.0);
    image->SetDirectionMatrix(0.0, -1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0);
    volume->RotateX(25);
    volume->RotateZ(-40);
    volume->SetPosition(4, -2, 9);
  }
  if (c.Blend == vtkVolumeMapper::MINIMUM_INTENSITY_BLEND)
  {
    // The minimum runs through the faint background: map its low values brightly.
    SetMinimumProperty(volume->GetProperty());
  }
  else if (projection)
  {
    SetRampProperty(volume->GetProperty(), 50.0, 900.0, true);
  }
  else
  {
    SetRampProperty(volume->GetProperty(), 0.0, 300.0, false);
  }
  ReferenceSettings settings;
  settings.blendMode = c.Blend;
  settings.stepWorld = 0.05;
  settings.additiveUnit = 10.0;
  if (c.Crop)
  {
    mapper->CroppingOn();
    mapper->SetCroppingRegionPlanes(6.0, 40.0, 5.0, 40.0, 4.0, 45.0);
    mapper->SetCroppingRegionFlagsToSubVolume();
    accelvolume::Box box;
    box.lower = { 6.0, 5.0 / 1.2, 4.0 / 1.5 };
    box.upper = { 40.0, 40.0 / 1.2, 45.0 / 1.5 };
    settings.regions.push_back(box);
  }
  if (c.Clip)
  {
    vtkNew<vtkPlane> plane;
    plane->SetOrigin(24, 24, 27);
    plane->SetNormal(-0.6, 0.3, -0.74);
    mapper->AddClippingPlane(plane);
    // World n.(x - o) >= 0 with x = diag(spacing) p.
    accelvolume::HalfSpace half;
    half.normal = { -0.6 * 1.0, 0.3 * 1.2, -0.74 * 1.5 };
    half.offset = -(-0.6 * 24 + 0.3 * 24 - 0.74 * 27);
    settings.clip.push_back(half);
  }
  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(0, 0, 0);
  renderer->AddVolume(volume);
  vtkNew<vtkRenderWindow> window;
  SetupObliqueView(window, renderer, Size, 35, 25, c.Perspective);
  window->Render();
  const std::vector<float> ours = ReadPixels(window);
  const std::vector<float> reference =
    RenderReferenceImage(image, volume, renderer, Size, Size, settings);
  // Slices at 1/4 voxel vs. a 1/20 voxel reference: differences stay within a few grey levels
  // except on a thin set of pixels at silhouettes and crop edges.
  double brightness = 0;
  for (float v : reference)
  {
    brightness += v;
  }
  brightness /= static_cast<double>(reference.size());
  std::cout << c.Name << ": reference mean brightness " << brightness << "\n";
  // An all-black pair would compare equal: demand content.
  const bool hasContent = brightness > 0.005;
  return Report(c.Name, CompareImages(ours, reference, 8.0 / 255.0), 2.0 / 255.0, 0.02) &&
    hasContent;
}
}

int TestAccelVolumeSliceMapperReference(int, char*[])
{
  const Case cases[] = {
    { "MIP parallel", vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND, false, false, false },
    { "MIP perspective crop clip", vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND, true, true, true },
    { "MinIP parallel crop", vtkVolumeMapper::MINIMUM_INTENSITY_BLEND, false, true, false },
    { "MinIP perspective clip", vtkVolumeMapper::MINIMUM_INTENSITY_BLEND, true, false, true },
    { "raysum parallel", vtkVolumeMapper::ADDITIVE_BLEND, false, false, false },
    { "raysum perspective crop clip", vtkVolumeMapper::ADDITIVE_BLEND, true, true, true },
    { "average parallel crop", vtkVolumeMapper::AVERAGE_INTENSITY_BLEND, false, true, false },
    { "average perspective", vtkVolumeMapper::AVERAGE_INTENSITY_BLEND, true, false, false },
    { "MIP oriented volume", vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND, true, false, false, true },
    { "raysum oriented volume", vtkVolumeMapper::ADDITIVE_BLEND, false, false, false, true },
  };
  bool ok = true;
  for (const Case& c : cases)
  {
    ok = RunCase(c) && ok;
  }
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
