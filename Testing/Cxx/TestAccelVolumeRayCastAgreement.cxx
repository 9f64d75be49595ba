// Numeric checks of the CPU ray cast mapper's pictures: against the CPU reference oracle
// (MIP, MinIP, raysum, average; perspective, cropping, a clipping plane), against the slice
// mapper on the same scene (every blend mode, shaded composite included) and against VTK's
// vtkFixedPointVolumeRayCastMapper (composite, MIP).
#include "AccelVolumeTestScene.h"
#include "vtkFixedPointVolumeRayCastMapper.h"

#include <cstdlib>

namespace
{
using namespace accelvolume_test;
constexpr int Size = 200;

struct Case
{
  const char* Name;
  int Blend;
  const char* Phantom;
  bool Perspective;
  bool Crop;
  bool Shade;
};

vtkSmartPointer<vtkVolume> MakeVolume(vtkVolumeMapper* mapper, vtkImageData* image, const Case& c)
{
  mapper->SetInputData(image);
  mapper->SetBlendMode(c.Blend);
  mapper->SetCropping(c.Crop);
  mapper->SetCroppingRegionPlanes(4, 44, 3, 36, 5, 42);
  mapper->SetCroppingRegionFlagsToSubVolume();
  auto volume = vtkSmartPointer<vtkVolume>::New();
  volume->SetMapper(mapper);
  if (c.Blend == vtkVolumeMapper::MINIMUM_INTENSITY_BLEND)
  {
    SetMinimumProperty(volume->GetProperty());
  }
  else
  {
    SetRampProperty(volume->GetProperty(), 40.0, 900.0, true);
  }
  volume->GetProperty()->SetShade(c.Shade);
  volume->GetProperty()->SetScalarOpacityUnitDistance(2.0);
  return volume;
}

std::vector<float> RenderWith(vtkVolumeMapper* mapper, vtkImageData* image, const Case& c,
  std::vector<float>* reference = nullptr, const ReferenceSettings* settings = nullptr)
{
  auto volume = MakeVolume(mapper, image, c);
  vtkNew<vtkRenderer> renderer;
  renderer->AddVolume(volume);
  vtkNew<vtkRenderWindow> window;
  SetupObliqueView(window, renderer, Size, 40, -20, c.Perspective);
  window->Render();
  if (reference)
  {
    *reference = RenderReferenceImage(image, volume, renderer, Size, Size, *settings);
  }
  return ReadPixels(window);
}

vtkSmartPointer<vtkAccelVolumeRayCastMapper> RayCaster(double sampleDistance)
{
  auto mapper = vtkSmartPointer<vtkAccelVolumeRayCastMapper>::New();
  mapper->SetAutoAdjustSampleDistances(0);
  mapper->SetSampleDistance(sampleDistance);
  return mapper;
}

bool AgainstReference()
{
  bool ok = true;
  const Case cases[] = {
    { "MIP persp crop", vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND, "vessels", true, true, false },
    { "MIP parallel", vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND, "vessels", false, false, false },
    { "MinIP persp", vtkVolumeMapper::MINIMUM_INTENSITY_BLEND, "vessels", true, false, false },
    { "raysum parallel", vtkVolumeMapper::ADDITIVE_BLEND, "blobs", false, false, false },
    { "average persp crop", vtkVolumeMapper::AVERAGE_INTENSITY_BLEND, "blobs", true, true, false },
  };
  for (const Case& c : cases)
  {
    auto image = MakePhantom(c.Phantom, 48, 40, 36, 1.0, 1.0, 1.25);
    ReferenceSettings settings;
    settings.blendMode = c.Blend;
    settings.stepWorld = 0.05;
    if (c.Crop)
    {
      settings.regions.push_back({ { 4, 3, 4 }, { 44, 36, 42 / 1.25 } });
    }
    settings.additiveUnit = 2.0; // the raysum unit: the property's ScalarOpacityUnitDistance
    std::vector<float> reference;
    auto mapper = RayCaster(0.1);
    const std::vector<float> ours = RenderWith(mapper, image, c, &reference, &settings);
    DumpImage(std::string("raycast_ref_") + c.Name, ours, Size, Size);
    ok = Report((std::string("ray cast vs CPU reference, ") + c.Name).c_str(),
           CompareImages(ours, reference, 8.0 / 255.0), 2.0 / 255.0, 0.02) &&
      ok;
  }
  return ok;
}

bool AgainstOtherMappers()
{
  bool ok = true;
  const Case cases[] = {
    { "MIP persp crop", vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND, "vessels", true, true, false },
    { "MinIP", vtkVolumeMapper::MINIMUM_INTENSITY_BLEND, "vessels", false, false, false },
    { "raysum persp", vtkVolumeMapper::ADDITIVE_BLEND, "blobs", true, false, false },
    { "average", vtkVolumeMapper::AVERAGE_INTENSITY_BLEND, "blobs", false, true, false },
    { "composite persp crop", vtkVolumeMapper::COMPOSITE_BLEND, "blobs", true, true, false },
    { "composite shaded", vtkVolumeMapper::COMPOSITE_BLEND, "blobs", true, false, true },
    { "composite parallel", vtkVolumeMapper::COMPOSITE_BLEND, "vessels", false, false, false },
  };
  for (const Case& c : cases)
  {
    auto image = MakePhantom(c.Phantom, 48, 40, 36, 1.0, 1.0, 1.25);
    auto ours = RayCaster(0.25);
    const std::vector<float> ourImage = RenderWith(ours, image, c);
    vtkNew<vtkAccelVolumeSliceMapper> slice;
    slice->SetAutoAdjustSampleDistances(0);
    slice->SetSampleDistance(0.25);
    const std::vector<float> sliceImage = RenderWith(slice, image, c);
    DumpImage(std::string("raycast_vs_slice_") + c.Name, ourImage, Size, Size);
    DumpImage(std::string("slice_vs_raycast_") + c.Name, sliceImage, Size, Size);
    // Different sample positions (rays vs eye-depth planes) leave small differences on thin
    // features and silhouettes; the bulk must agree within a few grey levels.
    ok = Report((std::string("ray cast vs slice mapper, ") + c.Name).c_str(),
           CompareImages(ourImage, sliceImage, 16.0 / 255.0), 3.0 / 255.0, 0.03) &&
      ok;
    if (c.Blend == vtkVolumeMapper::COMPOSITE_BLEND ||
      c.Blend == vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND)
    {
      vtkNew<vtkFixedPointVolumeRayCastMapper> fixed;
      fixed->SetAutoAdjustSampleDistances(0);
      fixed->SetSampleDistance(0.25);
      fixed->SetInteractiveSampleDistance(0.25);
      fixed->SetImageSampleDistance(1.0);
      const std::vector<float> fixedImage = RenderWith(fixed, image, c);
      DumpImage(std::string("fixed_vs_raycast_") + c.Name, fixedImage, Size, Size);
      // VTK's fixed-point mapper quantises scalars, opacities and shading into tables and
      // samples from the box entry in its own way: a looser bound.
      ok = Report((std::string("ray cast vs vtkFixedPointVolumeRayCastMapper, ") + c.Name).c_str(),
             CompareImages(ourImage, fixedImage, 24.0 / 255.0), 6.0 / 255.0, 0.06) &&
        ok;
    }
  }
  return ok;
}
}

int TestAccelVolumeRayCastAgreement(int, char*[])
{
  const bool reference = AgainstReference();
  const bool mappers = AgainstOtherMappers();
  return reference && mappers ? EXIT_SUCCESS : EXIT_FAILURE;
}
