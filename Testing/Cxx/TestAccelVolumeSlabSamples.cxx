// Exactness of slab sampling: MIP / MinIP with several slice depths per proxy fragment must
// give the image of classic one-plane-per-sample slicing (same samples), with cropping, a
// clipping plane, opaque geometry, parallel and perspective cameras.
#include "AccelVolumeTestUtilities.h"
#include "vtkAccelVolumeSliceMapper.h"

#include "vtkActor.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkSphereSource.h"

#include <cstdlib>

namespace
{
std::vector<float> Render(int blend, bool perspective, int slabSamples)
{
  using namespace accelvolume_test;
  constexpr int Size = 160;
  auto image = MakePhantom("vessels", 50, 44, 40, 1.0, 1.1, 1.3);
  vtkNew<vtkAccelVolumeSliceMapper> mapper;
  // A rasterisation feature: compute slices would take the same samples without it.
  mapper->SetSliceCompositing(vtkAccelVolumeSliceMapper::SLICE_COMPOSITING_RASTER);
  mapper->SetInputData(image);
  mapper->SetBlendMode(blend);
  mapper->SetSlabSamples(slabSamples);
  mapper->CroppingOn();
  mapper->SetCroppingRegionPlanes(3.5, 45.2, 4.1, 44.0, 2.2, 47.5);
  mapper->SetCroppingRegionFlagsToSubVolume();
  vtkNew<vtkPlane> plane;
  plane->SetOrigin(25, 24, 26);
  plane->SetNormal(-0.3, 0.8, -0.5);
  mapper->AddClippingPlane(plane);
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  SetRampProperty(volume->GetProperty(), 30.0, 900.0, true);
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(30, 20, 30);
  sphere->SetRadius(8);
  vtkNew<vtkPolyDataMapper> sphereMapper;
  sphereMapper->SetInputConnection(sphere->GetOutputPort());
  vtkNew<vtkActor> actor;
  actor->SetMapper(sphereMapper);
  vtkNew<vtkRenderer> renderer;
  renderer->AddVolume(volume);
  renderer->AddActor(actor);
  vtkNew<vtkRenderWindow> window;
  SetupObliqueView(window, renderer, Size, -38, 24, perspective);
  if (perspective)
  {
    renderer->GetActiveCamera()->Dolly(1.4);
    renderer->ResetCameraClippingRange();
  }
  window->Render();
  std::cout << "slab samples " << slabSamples << ": " << mapper->GetLastNumberOfProxyPolygons()
            << " proxy polygons for " << mapper->GetLastNumberOfSlices() << " sample planes\n";
  return ReadPixels(window);
}
}

int TestAccelVolumeSlabSamples(int, char*[])
{
  bool ok = true;
  for (int blend :
    { vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND, vtkVolumeMapper::MINIMUM_INTENSITY_BLEND })
  {
    for (bool perspective : { false, true })
    {
      const std::vector<float> plain = Render(blend, perspective, 1);
      for (int samples : { 4, 7 })
      {
        const std::vector<float> slabs = Render(blend, perspective, samples);
        const std::string name =
          std::string(blend == vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND ? "MIP" : "MinIP") +
          (perspective ? " perspective" : " parallel") + ", " + std::to_string(samples) +
          " samples per slab";
        // Same samples; only rasterisation of the polygon edges and float rounding differ.
        ok = accelvolume_test::Report(name.c_str(),
               accelvolume_test::CompareImages(slabs, plain, 3.0 / 255.0), 0.3 / 255.0, 0.003) &&
          ok;
      }
    }
  }
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
