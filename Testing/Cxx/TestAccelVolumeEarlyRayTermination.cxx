// Early ray termination is (nearly) exact: composite images with and without it differ by at
// most the transparency left at the threshold, on a procedural volume and on real CT data.
#include "AccelVolumeTestUtilities.h"
#include "vtkAccelVolumeSliceMapper.h"

#include "vtkDataArray.h"
#include "vtkTimerLog.h"

#include <cstdlib>

namespace
{
std::vector<float> Render(
  vtkImageData* image, bool ert, double low, double high, double* ms, int* passes)
{
  vtkNew<vtkAccelVolumeSliceMapper> mapper;
  mapper->SetInputData(image);
  mapper->SetBlendModeToComposite();
  mapper->SetEarlyRayTermination(ert);
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  // Opaque surfaces (the paper's tf2): rays saturate early.
  vtkNew<vtkColorTransferFunction> colours;
  colours->AddRGBPoint(low, 0.8, 0.6, 0.4);
  colours->AddRGBPoint(high, 1.0, 0.95, 0.9);
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(low, 0.0);
  opacity->AddPoint(low + 0.05 * (high - low), 1.0);
  opacity->AddPoint(high, 1.0);
  volume->GetProperty()->SetColor(colours);
  volume->GetProperty()->SetScalarOpacity(opacity);
  volume->GetProperty()->ShadeOn();
  vtkNew<vtkRenderer> renderer;
  renderer->AddVolume(volume);
  vtkNew<vtkRenderWindow> window;
  accelvolume_test::SetupObliqueView(window, renderer, 200, 30, 20, true);
  window->Render();
  window->Render();
  *ms = mapper->GetLastRenderTime() * 1000.0;
  *passes = mapper->GetLastNumberOfTerminationPasses();
  return accelvolume_test::ReadPixels(window);
}

bool Compare(const char* name, vtkImageData* image, double low, double high)
{
  double msOff = 0;
  double msOn = 0;
  int passesOff = 0;
  int passesOn = 0;
  const std::vector<float> off = Render(image, false, low, high, &msOff, &passesOff);
  const std::vector<float> on = Render(image, true, low, high, &msOn, &passesOn);
  std::cout << name << ": " << msOff << " ms without, " << msOn << " ms with early termination ("
            << passesOn << " mark passes)\n";
  // At most 1 - 0.99 of the colour is lost where a ray stops, plus rounding.
  const accelvolume_test::ImageDifference d =
    accelvolume_test::CompareImages(on, off, 0.01 + 1.0 / 255.0);
  const bool ok = d.maximum <= 0.01 + 1.5 / 255.0 && passesOn > 0 && passesOff == 0;
  std::cout << name << ": max |diff| " << d.maximum << " mean " << d.mean << (ok ? "" : "  FAILED")
            << "\n";
  return ok;
}
}

int TestAccelVolumeEarlyRayTermination(int, char*[])
{
  bool ok =
    Compare("shells phantom", accelvolume_test::MakePhantom("shells", 64, 64, 64), 200, 1000);
  if (auto engine =
        accelvolume_test::LoadSharedVolume("engine_256x256x128_uint8.raw.gz", 256, 256, 128))
  {
    ok = Compare("engine CT", engine, 60, 255) && ok;
  }
  else
  {
    std::cout << "engine CT not found: real-data case skipped\n";
  }
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
