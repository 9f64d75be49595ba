// Empty-space skipping is exact, and so is back-to-front compositing: composite images with
// skipping per fragment, by octree leaves, or both, equal the unskipped image (same samples;
// skipped ones have opacity 0), on a procedural volume and on the engine CT, shaded, with early
// termination off.
#include "AccelVolumeTestUtilities.h"
#include "vtkAccelVolumeSliceMapper.h"

#include <cstdlib>

namespace
{
std::vector<float> Render(vtkImageData* image, int skipping, double low, double high,
  double* leafFraction, bool frontToBack = true)
{
  vtkNew<vtkAccelVolumeSliceMapper> mapper;
  mapper->SetInputData(image);
  mapper->SetBlendModeToComposite();
  mapper->SetFrontToBack(frontToBack);
  mapper->SetEarlyRayTermination(false);
  mapper->SetEmptySpaceSkipping(skipping);
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  accelvolume_test::SetRampProperty(volume->GetProperty(), low, high, true);
  volume->GetProperty()->ShadeOn();
  vtkNew<vtkRenderer> renderer;
  renderer->AddVolume(volume);
  vtkNew<vtkRenderWindow> window;
  accelvolume_test::SetupObliqueView(window, renderer, 160, -25, 30, true);
  window->Render();
  *leafFraction = mapper->GetLastTransparentLeafFraction();
  return accelvolume_test::ReadPixels(window);
}

bool Check(const char* name, vtkImageData* image, double low, double high)
{
  double fraction = 0;
  const std::vector<float> none =
    Render(image, vtkAccelVolumeSliceMapper::SKIP_NONE, low, high, &fraction);
  bool ok = true;
  for (int mode : { vtkAccelVolumeSliceMapper::SKIP_FRAGMENT,
         vtkAccelVolumeSliceMapper::SKIP_OCTREE, vtkAccelVolumeSliceMapper::SKIP_BOTH })
  {
    const std::vector<float> skipped = Render(image, mode, low, high, &fraction);
    const accelvolume_test::ImageDifference d =
      accelvolume_test::CompareImages(skipped, none, 1.0 / 255.0);
    // Identical samples: only float rounding of the blend may differ.
    const bool same = d.maximum <= 1.0 / 255.0 + 1e-6;
    std::cout << name << ", skipping mode " << mode << ": max |diff| " << d.maximum
              << ", transparent leaves " << fraction << (same ? "" : "  FAILED") << "\n";
    ok = same && ok;
    // Back to front ("over") composites the same samples in the other order.
    if (mode == vtkAccelVolumeSliceMapper::SKIP_BOTH)
    {
      const std::vector<float> backToFront = Render(image, mode, low, high, &fraction, false);
      const accelvolume_test::ImageDifference order =
        accelvolume_test::CompareImages(backToFront, skipped, 1.0 / 255.0);
      std::cout << name << ", back to front vs front to back: max |diff| " << order.maximum << "\n";
      ok = order.maximum <= 2.0 / 255.0 + 1e-6 && ok;
    }
    if (mode != vtkAccelVolumeSliceMapper::SKIP_FRAGMENT && !(fraction > 0.0))
    {
      std::cerr << name << ": the octree found no transparent leaf\n";
      ok = false;
    }
  }
  return ok;
}
}

int TestAccelVolumeEmptySpaceSkipping(int, char*[])
{
  bool ok = Check("blobs phantom", accelvolume_test::MakePhantom("blobs", 60, 52, 44), 150, 900);
  if (auto engine =
        accelvolume_test::LoadSharedVolume("engine_256x256x128_uint8.raw.gz", 256, 256, 128))
  {
    ok = Check("engine CT", engine, 60, 255) && ok;
  }
  else
  {
    std::cout << "engine CT not found: real-data case skipped\n";
  }
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
