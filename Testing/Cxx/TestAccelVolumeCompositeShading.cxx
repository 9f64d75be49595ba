// Composite with Phong shading and gradient opacity: the slice mapper against
// vtkGPUVolumeRayCastMapper on the same scene (same lights, coefficients, transfer functions).
#include "AccelVolumeTestUtilities.h"
#include "vtkAccelVolumeSliceMapper.h"
#include "vtkGPUVolumeRayCastMapper.h"

#include <cstdlib>

namespace
{
std::vector<float> RenderWith(
  vtkVolumeMapper* mapper, vtkImageData* image, bool shade, bool gradientOpacity, bool perspective)
{
  constexpr int Size = 180;
  mapper->SetInputData(image);
  mapper->SetBlendModeToComposite();
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  vtkVolumeProperty* property = volume->GetProperty();
  accelvolume_test::SetRampProperty(property, 150.0, 700.0, true);
  property->SetShade(shade);
  property->SetAmbient(0.2);
  property->SetDiffuse(0.7);
  property->SetSpecular(0.3);
  property->SetSpecularPower(12.0);
  if (gradientOpacity)
  {
    vtkNew<vtkPiecewiseFunction> gradient;
    gradient->AddPoint(0.0, 0.0);
    gradient->AddPoint(60.0, 1.0);
    property->SetGradientOpacity(gradient);
  }
  vtkNew<vtkRenderer> renderer;
  renderer->AddVolume(volume);
  vtkNew<vtkRenderWindow> window;
  accelvolume_test::SetupObliqueView(window, renderer, Size, 30, 25, perspective);
  window->Render();
  return accelvolume_test::ReadPixels(window);
}
}

int TestAccelVolumeCompositeShading(int, char*[])
{
  struct Case
  {
    const char* Name;
    bool Shade;
    bool GradientOpacity;
    bool Perspective;
  };
  const Case cases[] = {
    { "shaded", true, false, true },
    { "gradient-opacity", false, true, false },
    { "shaded-gradient-opacity", true, true, true },
  };
  bool ok = true;
  for (const Case& c : cases)
  {
    auto image = accelvolume_test::MakePhantom("shells", 56, 52, 48);
    vtkNew<vtkGPUVolumeRayCastMapper> vtkMapper;
    vtkMapper->SetAutoAdjustSampleDistances(0);
    vtkMapper->SetSampleDistance(0.5);
    vtkNew<vtkAccelVolumeSliceMapper> ours;
    ours->SetAutoAdjustSampleDistances(0);
    ours->SetSampleDistance(0.5);
    const std::vector<float> reference =
      RenderWith(vtkMapper, image, c.Shade, c.GradientOpacity, c.Perspective);
    const std::vector<float> image2 =
      RenderWith(ours, image, c.Shade, c.GradientOpacity, c.Perspective);
    accelvolume_test::DumpImage(std::string(c.Name) + "_vtk", reference, 180, 180);
    accelvolume_test::DumpImage(std::string(c.Name) + "_ours", image2, 180, 180);
    ok = accelvolume_test::Report(c.Name,
           accelvolume_test::CompareImages(image2, reference, 16.0 / 255.0), 4.0 / 255.0, 0.05) &&
      ok;
  }
  // Jittered sampling: deterministic, close to the plain image on average.
  {
    auto image = accelvolume_test::MakePhantom("shells", 56, 52, 48);
    vtkNew<vtkAccelVolumeSliceMapper> plain;
    vtkNew<vtkAccelVolumeSliceMapper> jittered;
    vtkNew<vtkAccelVolumeSliceMapper> jitteredAgain;
    jittered->JitteringOn();
    jitteredAgain->JitteringOn();
    const std::vector<float> a = RenderWith(plain, image, true, false, true);
    const std::vector<float> b = RenderWith(jittered, image, true, false, true);
    const std::vector<float> c = RenderWith(jitteredAgain, image, true, false, true);
    const accelvolume_test::ImageDifference shift =
      accelvolume_test::CompareImages(b, a, 16.0 / 255.0);
    std::cout << "jittered vs plain: mean " << shift.mean << "\n";
    ok = shift.mean > 0.0 && shift.mean < 4.0 / 255.0 && ok;
    ok = accelvolume_test::CompareImages(b, c, 0.0).maximum == 0.0 && ok;
  }
  // Precomputed 16-bit gradients against central differences on the fly.
  for (bool perspective : { false, true })
  {
    auto image = accelvolume_test::MakePhantom("shells", 56, 52, 48);
    vtkNew<vtkAccelVolumeSliceMapper> onTheFly;
    vtkNew<vtkAccelVolumeSliceMapper> precomputed;
    precomputed->PrecomputeGradientsOn();
    onTheFly->PrecomputeGradientsOff();
    const std::vector<float> a = RenderWith(onTheFly, image, true, true, perspective);
    const std::vector<float> b = RenderWith(precomputed, image, true, true, perspective);
    ok = accelvolume_test::Report("precomputed vs on-the-fly gradients",
           accelvolume_test::CompareImages(b, a, 4.0 / 255.0), 1.0 / 255.0, 0.01) &&
      ok;
  }
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
