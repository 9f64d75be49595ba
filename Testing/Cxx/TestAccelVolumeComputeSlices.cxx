// Compute slices (SetSliceCompositing COMPUTE / AUTO): the same slice planes and samples as the
// rasterised proxy slices, composited per pixel in a compute pass. Checks, against the
// rasterised image of the same mapper settings:
// - composite without termination: equal up to rounding (shaded, octree skipping on, parallel
//   and perspective, whole volume, and under a crop, a clipping plane and opaque geometry with
//   a positional light; an image sample distance of 2; jitter);
// - composite with termination: within the termination bound (rays stop exactly at the
//   threshold instead of at the next mark pass);
// - empty-space leaping is exact: compute images with and without skipping are byte-identical,
//   and the leaping takes fewer samples (counted);
// - MIP and MinIP with boundary re-rendering under a crop and a clipping plane.
// Skipped (125) when the context has no OpenGL 4.3 compute shaders.
#include "AccelVolumeTestUtilities.h"
#include "vtkAccelVolumeSliceMapper.h"

#include "vtkActor.h"
#include "vtkLight.h"
#include "vtkPolyDataMapper.h"
#include "vtkSphereSource.h"
#include "vtkTesting.h"

#include <algorithm>
#include <cstdlib>

namespace
{
struct Scene
{
  int blend = vtkVolumeMapper::COMPOSITE_BLEND;
  bool perspective = false;
  bool cropped = false; // crop, clipping plane, an opaque sphere and a positional light
  bool termination = true;
  int skipping = vtkAccelVolumeSliceMapper::SKIP_BOTH;
  float imageSampleDistance = 1.0f;
  bool jitter = false;
};

struct Result
{
  std::vector<float> pixels;
  int compositing = -1;
  vtkIdType samples = -1;
};

Result Render(const Scene& scene, int compositing)
{
  using namespace accelvolume_test;
  constexpr int Size = 160;
  auto image = MakePhantom("vessels", 60, 52, 44, 1.0, 1.1, 1.3);
  vtkNew<vtkAccelVolumeSliceMapper> mapper;
  mapper->SetInputData(image);
  mapper->SetBlendMode(scene.blend);
  mapper->SetSliceCompositing(compositing);
  mapper->SetEarlyRayTermination(scene.termination);
  mapper->SetEmptySpaceSkipping(scene.skipping);
  mapper->SetImageSampleDistance(scene.imageSampleDistance);
  mapper->SetJittering(scene.jitter);
  mapper->SetCountSamples(true);
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  if (scene.blend == vtkVolumeMapper::MINIMUM_INTENSITY_BLEND)
  {
    SetMinimumProperty(volume->GetProperty());
  }
  else
  {
    SetRampProperty(volume->GetProperty(), 120.0, 700.0, true);
  }
  volume->GetProperty()->SetShade(scene.blend == vtkVolumeMapper::COMPOSITE_BLEND);
  volume->GetProperty()->SetScalarOpacityUnitDistance(0.5);
  vtkNew<vtkRenderer> renderer;
  renderer->AddVolume(volume);
  // Not black: a resolve that left blending off would show as opaque black over it.
  renderer->SetBackground(0.1, 0.1, 0.2);
  vtkNew<vtkPlane> plane;
  vtkNew<vtkSphereSource> sphere;
  vtkNew<vtkPolyDataMapper> sphereMapper;
  vtkNew<vtkActor> actor;
  vtkNew<vtkLight> light;
  if (scene.cropped)
  {
    mapper->CroppingOn();
    mapper->SetCroppingRegionPlanes(3.5, 52.2, 4.1, 50.0, 2.2, 52.5);
    mapper->SetCroppingRegionFlagsToSubVolume();
    plane->SetOrigin(30, 28, 28);
    plane->SetNormal(-0.3, 0.8, -0.5);
    mapper->AddClippingPlane(plane);
    sphere->SetCenter(34, 22, 30);
    sphere->SetRadius(8);
    sphereMapper->SetInputConnection(sphere->GetOutputPort());
    actor->SetMapper(sphereMapper);
    renderer->AddActor(actor);
    light->SetPositional(true);
    light->SetPosition(90, 80, 100);
    light->SetFocalPoint(30, 28, 28);
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
  result.compositing = mapper->GetLastSliceCompositing();
  result.samples = mapper->GetLastNumberOfSamples();
  return result;
}

std::string Name(const Scene& scene)
{
  const char* blend = scene.blend == vtkVolumeMapper::COMPOSITE_BLEND ? "composite"
    : scene.blend == vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND        ? "MIP"
                                                                      : "MinIP";
  return std::string(blend) + (scene.perspective ? ", perspective" : ", parallel") +
    (scene.cropped ? ", cropped + clipped + sphere" : ", whole volume") +
    (scene.termination ? ", ERT" : "") +
    (scene.skipping ? "" : ", no skipping") +
    (scene.imageSampleDistance > 1.0f ? ", image sample distance 2" : "") +
    (scene.jitter ? ", jitter" : "");
}

// Compute against raster for one scene; the compute result for further checks.
bool Compare(const Scene& scene, Result& computed)
{
  using Mapper = vtkAccelVolumeSliceMapper;
  const Result raster = Render(scene, Mapper::SLICE_COMPOSITING_RASTER);
  computed = Render(scene, Mapper::SLICE_COMPOSITING_COMPUTE);
  const std::string name = Name(scene);
  bool ok = true;
  if (raster.compositing != Mapper::SLICE_COMPOSITING_RASTER ||
    computed.compositing != Mapper::SLICE_COMPOSITING_COMPUTE)
  {
    std::cerr << name << ": compositing " << raster.compositing << " / " << computed.compositing
              << " (expected raster / compute)\n";
    ok = false;
  }
  if (*std::max_element(raster.pixels.begin(), raster.pixels.end()) < 0.3f)
  {
    std::cerr << name << ": the raster image is nearly black: the comparison proves nothing\n";
    ok = false;
  }
  if (computed.samples <= 0)
  {
    std::cerr << name << ": no samples counted (" << computed.samples << ")\n";
    ok = false;
  }
  // Without termination both take the same samples: rounding, and a few pixels on the edges of
  // the cut region, where rasterisation rules and the exact interval test disagree. With it, a
  // ray stops at the threshold instead of at the next mark pass: at most 1 - threshold (0.01)
  // of its colour changes.
  const bool terminated = scene.termination && scene.blend == vtkVolumeMapper::COMPOSITE_BLEND;
  const double threshold = (terminated ? 4.0 : 2.0) / 255.0;
  const double fraction = scene.cropped ? 0.004 : 0.0005;
  return accelvolume_test::Report(name.c_str(),
           accelvolume_test::CompareImages(computed.pixels, raster.pixels, threshold),
           0.1 / 255.0, fraction) &&
    ok;
}
}

int TestAccelVolumeComputeSlices(int, char*[])
{
  using Mapper = vtkAccelVolumeSliceMapper;
  {
    // Compute shaders at all? (AUTO falls back to raster without them.)
    Scene probe;
    if (Render(probe, Mapper::SLICE_COMPOSITING_COMPUTE).compositing !=
      Mapper::SLICE_COMPOSITING_COMPUTE)
    {
      std::cout << "no OpenGL 4.3 compute shaders: skipped\n";
      return VTK_SKIP_RETURN_CODE;
    }
  }
  bool ok = true;
  Result computed;
  for (bool perspective : { false, true })
  {
    for (bool cropped : { false, true })
    {
      for (bool termination : { false, true })
      {
        Scene scene;
        scene.perspective = perspective;
        scene.cropped = cropped;
        scene.termination = termination;
        ok = Compare(scene, computed) && ok;
        if (!termination)
        {
          // Leaping over transparent leaves and blocks is exact, and takes fewer samples.
          Scene plain = scene;
          plain.skipping = Mapper::SKIP_NONE;
          const Result unskipped = Render(plain, Mapper::SLICE_COMPOSITING_COMPUTE);
          const auto d = accelvolume_test::CompareImages(computed.pixels, unskipped.pixels, 0.0);
          std::cout << Name(scene) << ": skipping on / off max |diff| " << d.maximum
                    << ", samples " << computed.samples << " / " << unskipped.samples << "\n";
          if (d.maximum > 0.0 || !(computed.samples < unskipped.samples))
          {
            std::cerr << "  FAILED: leaping must be exact and take fewer samples\n";
            ok = false;
          }
        }
      }
    }
  }
  Scene reduced;
  reduced.imageSampleDistance = 2.0f;
  ok = Compare(reduced, computed) && ok;
  Scene jitter;
  jitter.jitter = true;
  jitter.perspective = true;
  ok = Compare(jitter, computed) && ok;
  for (int blend : { vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND,
         vtkVolumeMapper::MINIMUM_INTENSITY_BLEND })
  {
    for (bool cropped : { false, true })
    {
      Scene scene;
      scene.blend = blend;
      scene.cropped = cropped;
      scene.perspective = cropped;
      ok = Compare(scene, computed) && ok;
    }
  }
  // AUTO takes compute slices where they apply.
  if (Render(Scene(), Mapper::SLICE_COMPOSITING_AUTO).compositing !=
    Mapper::SLICE_COMPOSITING_COMPUTE)
  {
    std::cerr << "AUTO did not take compute slices for a plain composite frame\n";
    ok = false;
  }
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
