// Composite slabs (SetSlabSamples > 1): several slice depths composited per proxy fragment, one
// blend per slab, must give the image of plain one-plane-per-sample slicing (the same samples,
// so only rounding and early termination's batch edges differ), shaded, with octree culling and
// early termination, a positional light, parallel and perspective cameras; in a whole volume
// (against GPU-generated slices) and under a crop, a clipping plane and opaque geometry. The
// slabs must also draw far fewer proxy polygons.
#include "AccelVolumeTestUtilities.h"
#include "vtkAccelVolumeSliceMapper.h"

#include "vtkActor.h"
#include "vtkLight.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkSphereSource.h"

#include <algorithm>
#include <cstdlib>

namespace
{
struct Scene
{
  bool perspective = false;
  bool cropped = false; // crop, clipping plane, sphere and a positional light
  bool earlyTermination = true;
};

struct Result
{
  std::vector<float> pixels;
  int proxyPolygons = 0;
  int samplePlanes = 0;
};

Result Render(const Scene& scene, int slabSamples)
{
  using namespace accelvolume_test;
  constexpr int Size = 150;
  auto image = MakePhantom("vessels", 52, 46, 40, 1.0, 1.1, 1.3);
  vtkNew<vtkAccelVolumeSliceMapper> mapper;
  // A rasterisation feature: compute slices would take the same samples without it.
  mapper->SetSliceCompositing(vtkAccelVolumeSliceMapper::SLICE_COMPOSITING_RASTER);
  mapper->SetInputData(image);
  mapper->SetBlendModeToComposite();
  mapper->SetSlabSamples(slabSamples);
  mapper->SetEarlyRayTermination(scene.earlyTermination);
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  SetRampProperty(volume->GetProperty(), 120.0, 700.0, true);
  volume->GetProperty()->ShadeOn();
  volume->GetProperty()->SetScalarOpacityUnitDistance(0.4);
  vtkNew<vtkRenderer> renderer;
  renderer->AddVolume(volume);
  vtkNew<vtkPlane> plane;
  vtkNew<vtkSphereSource> sphere;
  vtkNew<vtkPolyDataMapper> sphereMapper;
  vtkNew<vtkActor> actor;
  vtkNew<vtkLight> light;
  if (scene.cropped)
  {
    mapper->CroppingOn();
    mapper->SetCroppingRegionPlanes(3.5, 47.2, 4.1, 46.0, 2.2, 48.5);
    mapper->SetCroppingRegionFlagsToSubVolume();
    plane->SetOrigin(26, 25, 26);
    plane->SetNormal(-0.3, 0.8, -0.5);
    mapper->AddClippingPlane(plane);
    sphere->SetCenter(30, 20, 30);
    sphere->SetRadius(8);
    sphereMapper->SetInputConnection(sphere->GetOutputPort());
    actor->SetMapper(sphereMapper);
    renderer->AddActor(actor);
    light->SetPositional(true);
    light->SetPosition(80, 70, 90);
    light->SetFocalPoint(26, 25, 26);
    light->SetConeAngle(60);
    renderer->AddLight(light);
  }
  vtkNew<vtkRenderWindow> window;
  SetupObliqueView(window, renderer, Size, -38, 24, scene.perspective);
  if (scene.perspective)
  {
    renderer->GetActiveCamera()->Dolly(1.4);
    renderer->ResetCameraClippingRange();
  }
  window->Render();
  Result result;
  result.pixels = ReadPixels(window);
  result.proxyPolygons = mapper->GetLastNumberOfProxyPolygons();
  result.samplePlanes = mapper->GetLastNumberOfSlices();
  std::cout << "slab samples " << slabSamples << ": " << result.proxyPolygons
            << " proxy polygons for " << result.samplePlanes << " sample planes\n";
  return result;
}
}

int TestAccelVolumeCompositeSlabs(int, char*[])
{
  bool ok = true;
  for (bool perspective : { false, true })
  {
    for (bool cropped : { false, true })
    {
      for (bool earlyTermination : { true, false })
      {
        const Scene scene{ perspective, cropped, earlyTermination };
        const Result plain = Render(scene, 1);
        if (*std::max_element(plain.pixels.begin(), plain.pixels.end()) < 0.3f)
        {
          std::cerr << "the plain image is nearly black: the comparison would prove nothing\n";
          ok = false;
        }
        for (int samples : { 4, 7 })
        {
          const Result slabs = Render(scene, samples);
          const std::string name = std::string(perspective ? "perspective" : "parallel") +
            (cropped ? ", cropped and clipped" : ", whole volume") +
            (earlyTermination ? ", ERT" : ", no ERT") + ", " + std::to_string(samples) +
            " samples per slab";
          // Same samples in the same order: without early termination only float rounding may
          // differ (none on llvmpipe); with it, where each ray stops (every 16 planes, or every
          // whole slab within them).
          const double threshold = (earlyTermination ? 3.0 : 1.0) / 255.0;
          ok = accelvolume_test::Report(name.c_str(),
                 accelvolume_test::CompareImages(slabs.pixels, plain.pixels, threshold),
                 0.05 / 255.0, 0.0005) &&
            ok;
          if (slabs.proxyPolygons * (samples - 1) > plain.proxyPolygons + 2 * samples)
          {
            std::cerr << name << ": " << slabs.proxyPolygons << " slab polygons against "
                      << plain.proxyPolygons << " slices\n";
            ok = false;
          }
        }
      }
    }
  }
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
