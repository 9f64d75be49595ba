// Depth peeling of volumes (vtkRenderer::UseDepthPeelingForVolumes) with every mapper: the
// volume is drawn whole in the pass's first volumetric stage, so translucent geometry is
// composited over it (VTK's GPU mapper interleaves them; the bound below holds that difference
// for a sphere half inside the volume). Checked: (1) without translucent geometry the image is
// the one without peeling; (2) with a translucent sphere, close to vtkGPUVolumeRayCastMapper's
// peeled image; (3) a renderer in the right half of the window (the pass's targets are
// viewport-sized) draws what the left one does. Before, the peeling targets got garbage.
#include "AccelVolumeDropInScene.h"

#include "vtkActor.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkSphereSource.h"

namespace
{
using namespace accelvolume_dropin;
constexpr int Size = 160;

struct PeelScene
{
  vtkNew<vtkRenderWindow> Window;
  vtkNew<vtkRenderer> Renderers[2];
  vtkSmartPointer<vtkVolumeMapper> Mappers[2];
  vtkNew<vtkVolume> Volumes[2];
  vtkNew<vtkSphereSource> Sphere;
  vtkNew<vtkPolyDataMapper> SphereMapper;
  vtkNew<vtkActor> Spheres[2];

  // kind < 0: vtkGPUVolumeRayCastMapper. Two renderers side by side when `split`.
  PeelScene(int kind, vtkImageData* image, bool peeling, bool translucent, bool split)
  {
    this->Window->SetMultiSamples(0);
    this->Window->SetSize(split ? 2 * Size : Size, Size);
    this->Sphere->SetCenter(image->GetCenter()[0] + 12.0, image->GetCenter()[1],
      image->GetCenter()[2]);
    this->Sphere->SetRadius(12.0);
    this->Sphere->SetThetaResolution(32);
    this->Sphere->SetPhiResolution(32);
    this->SphereMapper->SetInputConnection(this->Sphere->GetOutputPort());
    for (int r = 0; r < (split ? 2 : 1); ++r)
    {
      if (kind < 0)
      {
        auto gpu = vtkSmartPointer<vtkGPUVolumeRayCastMapper>::New();
        gpu->SetAutoAdjustSampleDistances(0);
        gpu->SetSampleDistance(0.5);
        this->Mappers[r] = gpu;
      }
      else
      {
        this->Mappers[r] = MakeMapper(static_cast<Kind>(kind));
      }
      this->Mappers[r]->SetInputData(image);
      this->Volumes[r]->SetMapper(this->Mappers[r]);
      accelvolume_test::SetRampProperty(this->Volumes[r]->GetProperty(), 40.0, 900.0, true);
      vtkRenderer* renderer = this->Renderers[r];
      renderer->SetBackground(0.1, 0.1, 0.2);
      renderer->AddVolume(this->Volumes[r]);
      this->Spheres[r]->SetMapper(this->SphereMapper);
      this->Spheres[r]->GetProperty()->SetColor(0.9, 0.8, 0.3);
      this->Spheres[r]->GetProperty()->SetOpacity(translucent ? 0.4 : 1.0);
      renderer->AddActor(this->Spheres[r]);
      renderer->SetUseDepthPeeling(peeling ? 1 : 0);
      renderer->SetUseDepthPeelingForVolumes(peeling);
      renderer->SetMaximumNumberOfPeels(6);
      renderer->SetOcclusionRatio(0.0);
      if (split)
      {
        renderer->SetViewport(0.5 * r, 0.0, 0.5 * (r + 1), 1.0);
      }
      this->Window->AddRenderer(renderer);
      renderer->ResetCamera();
      vtkCamera* camera = renderer->GetActiveCamera();
      camera->SetParallelProjection(1);
      camera->Azimuth(30);
      camera->Elevation(20);
      camera->OrthogonalizeViewUp();
      renderer->ResetCamera();
    }
  }

  std::vector<float> Render()
  {
    this->Window->Render();
    return accelvolume_test::ReadPixels(this->Window);
  }
};

// One half (0 left, 1 right) of a 2 Size x Size image.
std::vector<float> Half(const std::vector<float>& image, int half)
{
  std::vector<float> out;
  out.reserve(image.size() / 2);
  for (int y = 0; y < Size; ++y)
  {
    const float* row = image.data() + 3 * (static_cast<size_t>(y) * 2 * Size + half * Size);
    out.insert(out.end(), row, row + 3 * Size);
  }
  return out;
}

bool Within(const std::string& what, const std::vector<float>& a, const std::vector<float>& b,
  double meanLimit, double fractionLimit)
{
  const auto d = CompareImages(a, b, 16.0 / 255.0);
  const bool ok = d.mean <= meanLimit && d.fractionAbove <= fractionLimit;
  std::cout << (ok ? "ok    " : "FAIL  ") << what << ": mean |diff| " << d.mean << " (limit "
            << meanLimit << "), pixels over 16/255 " << d.fractionAbove << " (limit "
            << fractionLimit << ")\n";
  return ok;
}
}

int TestAccelVolumeDepthPeeling(int, char*[])
{
  vtkSmartPointer<vtkImageData> image = Phantom();
  bool ok = true;
  const std::vector<float> vtkPeeled = PeelScene(-1, image, true, true, false).Render();
  for (Kind kind : accelvolume_test::AllMappers)
  {
    const std::string name = Name(kind);
    const int k = static_cast<int>(kind);
    const std::vector<float> plain = PeelScene(k, image, false, false, false).Render();
    const std::vector<float> peeledOpaque = PeelScene(k, image, true, false, false).Render();
    ok = Drawn(name + ": peeling, opaque sphere", peeledOpaque) && ok;
    ok = Within(name + ": peeling vs none, opaque sphere", peeledOpaque, plain, 1.0 / 255.0,
           0.002) &&
      ok;
    const std::vector<float> peeled = PeelScene(k, image, true, true, false).Render();
    ok = Within(name + ": peeling, translucent sphere, vs vtkGPUVolumeRayCastMapper's", peeled,
           vtkPeeled, 4.0 / 255.0, 0.12) &&
      ok;
    const std::vector<float> split = PeelScene(k, image, true, true, true).Render();
    ok = Drawn(name + ": peeling, right-hand renderer", Half(split, 1)) && ok;
    ok = Within(name + ": peeling, right-hand vs left-hand renderer", Half(split, 1),
           Half(split, 0), 1.0 / 255.0, 0.002) &&
      ok;
  }
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
