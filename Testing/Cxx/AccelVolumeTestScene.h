// A standard small scene for the one-feature regression image tests.
#ifndef AccelVolumeTestScene_h
#define AccelVolumeTestScene_h

#include "AccelVolumeTestUtilities.h"
#include "vtkAccelVolumeRayCastMapper.h"
#include "vtkActor.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkSphereSource.h"
#include "vtkAccelVolumeSliceMapper.h"
#include "vtkRegressionTestImage.h"

#include <cstdlib>
#include <string>

namespace accelvolume_test
{
template <typename MapperType>
struct SceneOf
{
  vtkSmartPointer<vtkImageData> Image;
  vtkNew<MapperType> Mapper;
  vtkNew<vtkVolume> Volume;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkRenderWindow> Window;

  // size x size window (300 unless a test without baseline asks for less), phantom volume,
  // grey (or colour) ramp, oblique view.
  explicit SceneOf(const char* phantom = "vessels",
    int blend = vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND, int size = 300)
  {
    this->Image = MakePhantom(phantom, 64, 56, 48, 1.0, 1.0, 1.25);
    this->Mapper->SetInputData(this->Image);
    this->Mapper->SetBlendMode(blend);
    this->Volume->SetMapper(this->Mapper);
    SetRampProperty(this->Volume->GetProperty(), 40.0, 900.0, true);
    this->Renderer->SetBackground(0.1, 0.1, 0.2);
    this->Renderer->AddVolume(this->Volume);
    this->Window->SetSize(size, size);
    this->Window->SetMultiSamples(0);
    this->Window->AddRenderer(this->Renderer);
    this->Renderer->ResetCamera();
    this->Renderer->GetActiveCamera()->Azimuth(30);
    this->Renderer->GetActiveCamera()->Elevation(20);
    this->Renderer->GetActiveCamera()->OrthogonalizeViewUp();
    this->Renderer->ResetCamera();
  }

  // Renders and compares with the baseline; returns a ctest exit code.
  int Regress(int argc, char* argv[])
  {
    this->Window->Render();
    const int result = vtkRegressionTestImage(this->Window);
    return result == vtkRegressionTester::FAILED ? EXIT_FAILURE : EXIT_SUCCESS;
  }
};

// An opaque, flat-coloured sphere (ambient only) added to a scene's renderer.
struct FlatSphere
{
  double Centre[3] = { 32, 28, 30 };
  double Radius = 14;
  double Colour[3] = { 0.2, 0.8, 0.3 };
};

template <typename SceneType>
void AddFlatSphere(SceneType& scene, const FlatSphere& sphere)
{
  vtkNew<vtkSphereSource> source;
  source->SetCenter(sphere.Centre[0], sphere.Centre[1], sphere.Centre[2]);
  source->SetRadius(sphere.Radius);
  source->SetThetaResolution(128);
  source->SetPhiResolution(128);
  vtkNew<vtkPolyDataMapper> sphereMapper;
  sphereMapper->SetInputConnection(source->GetOutputPort());
  vtkNew<vtkActor> actor;
  actor->SetMapper(sphereMapper);
  actor->GetProperty()->SetColor(sphere.Colour[0], sphere.Colour[1], sphere.Colour[2]);
  actor->GetProperty()->SetAmbient(1.0);
  actor->GetProperty()->SetDiffuse(0.0);
  actor->GetProperty()->SetSpecular(0.0);
  scene.Renderer->AddActor(actor);
}

// What a MIP scene with that sphere must show (size x size window): the CPU reference MIP along
// each ray up to the analytic sphere, composited over the sphere or the background.
template <typename SceneType>
std::vector<float> ExpectedMipOverSphere(SceneType& scene, const FlatSphere& sphere, int size)
{
  const accelvolume::Camera camera = ToCoreCamera(scene.Renderer->GetActiveCamera());
  std::vector<double> raysEnd(static_cast<size_t>(size) * size, 1.0e30);
  std::vector<bool> onSphere(raysEnd.size(), false);
  const accelvolume::Vec3 centre{ sphere.Centre[0], sphere.Centre[1], sphere.Centre[2] };
  for (int j = 0; j < size; ++j)
  {
    for (int i = 0; i < size; ++i)
    {
      const accelvolume::Ray ray = accelvolume::PixelRay(camera, size, size, i, j);
      const accelvolume::Vec3 toCentre = ray.origin - centre;
      const double b = accelvolume::Dot(toCentre, ray.direction);
      const double c = accelvolume::Dot(toCentre, toCentre) - sphere.Radius * sphere.Radius;
      if (b * b - c >= 0)
      {
        raysEnd[j * size + i] = -b - std::sqrt(b * b - c);
        onSphere[j * size + i] = true;
      }
    }
  }
  ReferenceSettings settings;
  settings.stepWorld = 0.05;
  std::vector<float> alpha;
  std::vector<float> expected = RenderReferenceImage(
    scene.Image, scene.Volume, scene.Renderer, size, size, settings, &raysEnd, &alpha);
  double background[3];
  scene.Renderer->GetBackground(background);
  for (size_t p = 0; p < alpha.size(); ++p)
  {
    const double* under = onSphere[p] ? sphere.Colour : background;
    for (int c = 0; c < 3; ++c)
    {
      expected[3 * p + c] += (1.0f - alpha[p]) * static_cast<float>(under[c]);
    }
  }
  return expected;
}

// True under scripts/sanitize.sh's test subset (ACCELVOLUME_TEST_SUBSET=sanitizer), where every
// loop runs 10-50x slower: the CPU mappers' exactness tests then check the same code paths on
// fewer cases or pixels.
inline bool SanitizerSubset()
{
  const char* subset = std::getenv("ACCELVOLUME_TEST_SUBSET");
  return subset != nullptr && std::string(subset) == "sanitizer";
}

using Scene = SceneOf<vtkAccelVolumeSliceMapper>;
using RayCastScene = SceneOf<vtkAccelVolumeRayCastMapper>;
}

#endif
