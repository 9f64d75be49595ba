// Early ray termination is (nearly) exact: composite images with and without it differ by at
// most the transparency left at the threshold, on a procedural volume and on real CT data, with
// rasterised slices (mark passes) and with compute slices (rays stop at the threshold and take
// fewer samples).
#include "AccelVolumeTestUtilities.h"
#include "vtkAccelVolumeSliceMapper.h"

#include "vtkDataArray.h"
#include "vtkTimerLog.h"

#include <cstdlib>

namespace
{
struct Frame
{
  double ms = 0;
  int passes = 0;
  vtkIdType samples = -1;
  int compositing = -1;
};

std::vector<float> Render(
  vtkImageData* image, bool ert, double low, double high, int compositing, Frame& frame)
{
  vtkNew<vtkAccelVolumeSliceMapper> mapper;
  mapper->SetInputData(image);
  mapper->SetBlendModeToComposite();
  mapper->SetEarlyRayTermination(ert);
  mapper->SetSliceCompositing(compositing);
  mapper->SetCountSamples(true);
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
  frame.ms = mapper->GetLastRenderTime() * 1000.0;
  frame.passes = mapper->GetLastNumberOfTerminationPasses();
  frame.samples = mapper->GetLastNumberOfSamples();
  frame.compositing = mapper->GetLastSliceCompositing();
  return accelvolume_test::ReadPixels(window);
}

bool Compare(const char* name, vtkImageData* image, double low, double high, int compositing)
{
  Frame off;
  Frame on;
  const std::vector<float> offImage = Render(image, false, low, high, compositing, off);
  const std::vector<float> onImage = Render(image, true, low, high, compositing, on);
  const bool compute = on.compositing == vtkAccelVolumeSliceMapper::SLICE_COMPOSITING_COMPUTE;
  if (compositing == vtkAccelVolumeSliceMapper::SLICE_COMPOSITING_COMPUTE && !compute)
  {
    std::cout << name << ": no compute slices in this context: skipped\n";
    return true;
  }
  std::cout << name << (compute ? " (compute)" : " (raster)") << ": " << off.ms
            << " ms without, " << on.ms << " ms with early termination (" << on.passes
            << " mark passes, " << on.samples << " samples against " << off.samples << ")\n";
  // At most 1 - 0.99 of the colour is lost where a ray stops, plus rounding.
  const accelvolume_test::ImageDifference d =
    accelvolume_test::CompareImages(onImage, offImage, 0.01 + 1.0 / 255.0);
  // Rasterised slices close pixels by mark passes; compute slices stop each ray.
  const bool terminated = compute ? (on.samples > 0 && on.samples < off.samples)
                                  : (on.passes > 0 && off.passes == 0);
  const bool ok = d.maximum <= 0.01 + 1.5 / 255.0 && terminated;
  std::cout << name << ": max |diff| " << d.maximum << " mean " << d.mean << (ok ? "" : "  FAILED")
            << "\n";
  return ok;
}

bool CompareBoth(const char* name, vtkImageData* image, double low, double high)
{
  return Compare(name, image, low, high, vtkAccelVolumeSliceMapper::SLICE_COMPOSITING_RASTER) &
    Compare(name, image, low, high, vtkAccelVolumeSliceMapper::SLICE_COMPOSITING_COMPUTE);
}
}

int TestAccelVolumeEarlyRayTermination(int, char*[])
{
  bool ok =
    CompareBoth("shells phantom", accelvolume_test::MakePhantom("shells", 64, 64, 64), 200, 1000);
  if (auto engine =
        accelvolume_test::LoadSharedVolume("engine_256x256x128_uint8.raw.gz", 256, 256, 128))
  {
    ok = CompareBoth("engine CT", engine, 60, 255) && ok;
  }
  else
  {
    std::cout << "engine CT not found: real-data case skipped\n";
  }
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
