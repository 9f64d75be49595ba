// Numeric check of the paper's claim and of the raysum weighting: with coarse slices through an
// oblique crop, re-rendering the cut faces brings MIP and raysum closer to a fine CPU reference;
// and the raysum does not change with the slice count.
#include "AccelVolumeTestUtilities.h"
#include "vtkAccelVolumeSliceMapper.h"

#include <cstdlib>

namespace
{
constexpr int Size = 160;

struct Result
{
  std::vector<float> Image;
  std::vector<float> Reference;
};

Result Render(int blend, int slices, bool rerender, bool wantReference)
{
  using namespace accelvolume_test;
  auto image =
    MakePhantom(blend == vtkVolumeMapper::ADDITIVE_BLEND ? "blobs" : "shells", 48, 48, 48);
  vtkNew<vtkAccelVolumeSliceMapper> mapper;
  mapper->SetInputData(image);
  mapper->SetBlendMode(blend);
  mapper->SetNumberOfSlices(slices);
  mapper->SetBoundaryRerendering(rerender);
  mapper->SetAdditiveUnitDistance(12.0);
  mapper->CroppingOn();
  mapper->SetCroppingRegionPlanes(7.3, 37.9, 5.6, 41.2, 9.1, 40.4);
  mapper->SetCroppingRegionFlagsToSubVolume();
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  if (blend == vtkVolumeMapper::ADDITIVE_BLEND)
  {
    SetRampProperty(volume->GetProperty(), 0.0, 400.0, false);
  }
  else
  {
    SetRampProperty(volume->GetProperty(), 0.0, 1000.0, false);
  }
  vtkNew<vtkRenderer> renderer;
  renderer->AddVolume(volume);
  vtkNew<vtkRenderWindow> window;
  SetupObliqueView(window, renderer, Size, 33, 27, false);
  window->Render();
  Result result;
  result.Image = ReadPixels(window);
  if (wantReference)
  {
    ReferenceSettings settings;
    settings.blendMode = blend;
    settings.stepWorld = 0.05;
    settings.additiveUnit = 12.0;
    accelvolume::Box box;
    box.lower = { 7.3, 5.6, 9.1 };
    box.upper = { 37.9, 41.2, 40.4 };
    settings.regions.push_back(box);
    result.Reference = RenderReferenceImage(image, volume, renderer, Size, Size, settings);
  }
  return result;
}
}

int TestAccelVolumeBoundaryRerendering(int, char*[])
{
  using namespace accelvolume_test;
  bool ok = true;
  for (int blend : { vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND, vtkVolumeMapper::ADDITIVE_BLEND })
  {
    const char* name = blend == vtkVolumeMapper::ADDITIVE_BLEND ? "raysum" : "MIP";
    // 12 slices through ~80 voxels of depth: far too few, so the cut faces alias.
    const Result without = Render(blend, 12, false, true);
    const Result with = Render(blend, 12, true, false);
    const ImageDifference errorWithout =
      CompareImages(without.Image, without.Reference, 4.0 / 255.0);
    const ImageDifference errorWith = CompareImages(with.Image, without.Reference, 4.0 / 255.0);
    std::cout << name << " with 12 slices: mean error without re-rendering " << errorWithout.mean
              << ", with " << errorWith.mean << "\n";
    if (!(errorWith.mean < 0.8 * errorWithout.mean))
    {
      std::cerr << name << ": re-rendering the faces did not reduce the error by 20%\n";
      ok = false;
    }
  }
  // Raysum is a line integral: 24 and 96 slices agree (with faces re-rendered).
  const Result coarse = Render(vtkVolumeMapper::ADDITIVE_BLEND, 24, true, false);
  const Result fine = Render(vtkVolumeMapper::ADDITIVE_BLEND, 96, true, false);
  ok = Report("raysum 24 vs 96 slices", CompareImages(coarse.Image, fine.Image, 6.0 / 255.0),
         2.0 / 255.0, 0.02) &&
    ok;
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
