// The shear-warp mapper's warp on the GPU (WarpOnGPU, the default) shows the same pictures as its
// CPU warp: the texture unit resamples the intermediate image bilinearly where the CPU did, so
// the two differ only by the unit's filtering precision and the 16-bit texels. Checked in the
// window (8 bits per channel): composite shaded and MIP, an oblique and a steep view, a window
// larger and one smaller than the intermediate image (magnified and minified), a viewport that
// does not start at the window's corner, and the warp's edges against the background; the GPU
// draws only the bands of the intermediate image holding visible pixels, cut to their columns
// (the vessels leave much empty), which must cover every pixel the CPU warp shows and none
// twice. A camera shifted by one pixel must fail the same bound (the check can fail).
#include "AccelVolumeTestUtilities.h"
#include "vtkAccelVolumeShearWarpMapper.h"
#include "vtkMath.h"

#include <cstdlib>
#include <iostream>
#include <string>

namespace
{
using namespace accelvolume_test;

struct WarpCase
{
  const char* name;
  int blend;
  bool shade;
  int windowSize;
  double azimuth, elevation;
  double viewport[4];
};

std::vector<float> Render(vtkImageData* image, const WarpCase& c, bool onGPU, double shift)
{
  vtkNew<vtkAccelVolumeShearWarpMapper> mapper;
  mapper->SetInputData(image);
  mapper->SetBlendMode(c.blend);
  mapper->SetWarpOnGPU(onGPU);
  mapper->SetNumberOfThreads(1);
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  SetRampProperty(volume->GetProperty(), 40.0, 900.0, true);
  volume->GetProperty()->SetShade(c.shade);
  vtkNew<vtkRenderer> renderer;
  renderer->SetViewport(c.viewport);
  renderer->SetBackground(0.1, 0.1, 0.2);
  renderer->AddVolume(volume);
  vtkNew<vtkRenderWindow> window;
  window->SetSize(c.windowSize, c.windowSize);
  window->SetMultiSamples(0);
  window->AddRenderer(renderer);
  renderer->ResetCamera();
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetParallelProjection(1);
  camera->Azimuth(c.azimuth);
  camera->Elevation(c.elevation);
  camera->OrthogonalizeViewUp();
  renderer->ResetCamera();
  // Fixed: ResetCamera's scale depends on the viewport's aspect, which an offscreen window may
  // not know before its first frame (renders of one scene then differ in scale).
  camera->SetParallelScale(40);
  if (shift != 0)
  {
    // Move the camera sideways by `shift` pixels of the viewport.
    const double pixel =
      2.0 * camera->GetParallelScale() / (c.windowSize * (c.viewport[3] - c.viewport[1]));
    double right[3];
    vtkMath::Cross(camera->GetDirectionOfProjection(), camera->GetViewUp(), right);
    vtkMath::Normalize(right);
    double position[3], focal[3];
    camera->GetPosition(position);
    camera->GetFocalPoint(focal);
    for (int a = 0; a < 3; ++a)
    {
      position[a] += shift * pixel * right[a];
      focal[a] += shift * pixel * right[a];
    }
    camera->SetPosition(position);
    camera->SetFocalPoint(focal);
  }
  window->Render();
  return ReadPixels(window);
}
}

int TestAccelVolumeShearWarpGPUWarp(int, char*[])
{
  vtkSmartPointer<vtkImageData> image = MakePhantom("vessels", 64, 56, 48, 1.0, 1.0, 1.25);
  const WarpCase cases[] = {
    { "composite shaded, magnified", vtkVolumeMapper::COMPOSITE_BLEND, true, 300, 30, 20,
      { 0, 0, 1, 1 } },
    { "composite unshaded, minified", vtkVolumeMapper::COMPOSITE_BLEND, false, 40, 30, 20,
      { 0, 0, 1, 1 } },
    { "MIP, steep view, offset viewport", vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND, false, 300, -50,
      40, { 0.3, 0.2, 1, 1 } },
    { "MIP, steep view", vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND, false, 300, -50, 40,
      { 0, 0, 1, 1 } },
    { "MIP, offset viewport", vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND, false, 300, 30, 20,
      { 0.3, 0.2, 1, 1 } },
    { "composite, offset viewport", vtkVolumeMapper::COMPOSITE_BLEND, false, 300, 30, 20,
      { 0.3, 0.2, 1, 1 } },
  };
  bool ok = true;
  for (const WarpCase& c : cases)
  {
    const std::vector<float> cpu = Render(image, c, false, 0);
    const std::vector<float> gpu = Render(image, c, true, 0);
    // Measured on llvmpipe: at most 1/255 on a few hundred channels (the texels' 16 bits and
    // the unit's filter weights). Limits: 2/255 anywhere, mean 0.0005.
    const ImageDifference d = CompareImages(cpu, gpu, 2.5 / 255.0);
    DumpImage(std::string(c.name) + "-cpu", cpu, c.windowSize, c.windowSize);
    DumpImage(std::string(c.name) + "-gpu", gpu, c.windowSize, c.windowSize);
    ok = Report((std::string(c.name) + ": GPU warp vs CPU warp").c_str(), d, 0.0005, 0.0) && ok;
    if (c.windowSize >= 300)
    {
      const std::vector<float> shifted = Render(image, c, true, 1.0);
      const ImageDifference s = CompareImages(cpu, shifted, 2.5 / 255.0);
      const bool fails = !(s.mean <= 0.0005 && s.fractionAbove <= 0.0);
      std::cout << c.name << ": camera shifted one pixel, mean " << s.mean << ", fraction "
                << s.fractionAbove << (fails ? " (fails the bound, as it must)" : "  NOT DETECTED")
                << "\n";
      ok = fails && ok;
    }
  }
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
