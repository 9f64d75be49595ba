// Numeric check of composite blending against the CPU reference (accelvolume::
// RenderReferenceComposite): opacity corrected for the slice spacing, front-to-back order,
// perspective, a clipping plane, and a non-convex cropping pattern drawn cell by cell.
#include "AccelVolumeTestUtilities.h"
#include "reference/ReferenceComposite.h"
#include "vtkAccelVolumeSliceMapper.h"

#include <cstdlib>

namespace
{
struct Case
{
  const char* Name;
  bool Perspective;
  bool CrossCrop;
  bool Clip;
  double SampleDistance;
};

bool RunCase(const Case& c)
{
  using namespace accelvolume_test;
  constexpr int Size = 150;
  auto image = MakePhantom("shells", 44, 40, 36, 1.0, 1.1, 1.3);
  vtkNew<vtkAccelVolumeSliceMapper> mapper;
  mapper->SetInputData(image);
  mapper->SetBlendModeToComposite();
  mapper->SetAutoAdjustSampleDistances(0);
  mapper->SetSampleDistance(c.SampleDistance);
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  SetRampProperty(volume->GetProperty(), 100.0, 1000.0, true);
  volume->GetProperty()->SetScalarOpacityUnitDistance(2.0);
  std::vector<accelvolume::Box> regions;
  std::vector<accelvolume::HalfSpace> clip;
  if (c.CrossCrop)
  {
    mapper->CroppingOn();
    mapper->SetCroppingRegionPlanes(10, 34, 9, 33, 8, 38);
    mapper->SetCroppingRegionFlagsToCross();
    const double planes[6] = { 10, 34, 9 / 1.1, 33 / 1.1, 8 / 1.3, 38 / 1.3 };
    accelvolume::Box whole;
    whole.upper = { 43, 39, 35 };
    regions = accelvolume::CroppingRegionBoxes(whole, planes, VTK_CROP_CROSS);
  }
  if (c.Clip)
  {
    vtkNew<vtkPlane> plane;
    plane->SetOrigin(22, 22, 23);
    plane->SetNormal(0.4, -0.5, 0.77);
    mapper->AddClippingPlane(plane);
    accelvolume::HalfSpace half;
    half.normal = { 0.4 * 1.0, -0.5 * 1.1, 0.77 * 1.3 };
    half.offset = -(0.4 * 22 - 0.5 * 22 + 0.77 * 23);
    clip.push_back(half);
  }
  vtkNew<vtkRenderer> renderer;
  renderer->AddVolume(volume);
  vtkNew<vtkRenderWindow> window;
  SetupObliqueView(window, renderer, Size, -35, 28, c.Perspective);
  window->Render();
  const std::vector<float> ours = ReadPixels(window);

  // The same tables the mapper builds, and the same physics, integrated finely.
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  double range[2];
  scalars->GetRange(range);
  accelvolume::ScalarVolume core;
  image->GetDimensions(core.dims);
  core.values.resize(static_cast<size_t>(scalars->GetNumberOfTuples()));
  for (size_t i = 0; i < core.values.size(); ++i)
  {
    core.values[i] = static_cast<float>(
      (scalars->GetTuple1(static_cast<vtkIdType>(i)) - range[0]) / (range[1] - range[0]));
  }
  core.indexToWorld = accelvolume::Affine::Identity();
  core.indexToWorld.m[1][1] = 1.1;
  core.indexToWorld.m[2][2] = 1.3;
  accelvolume::OpacityTable opacity;
  opacity.values.resize(TableSize);
  std::vector<float> colours(3 * TableSize);
  volume->GetProperty()->GetScalarOpacity()->GetTable(
    range[0], range[1], TableSize, opacity.values.data());
  volume->GetProperty()->GetRGBTransferFunction()->GetTable(
    range[0], range[1], TableSize, colours.data());
  if (regions.empty())
  {
    accelvolume::Box whole;
    whole.upper = { 43, 39, 35 };
    regions.push_back(whole);
  }
  accelvolume::CompositeOptions options;
  options.stepWorld = 0.05;
  options.opacityUnitDistance = 2.0;
  const auto pixels = accelvolume::RenderReferenceComposite(core, regions, clip, colours, opacity,
    ToCoreCamera(renderer->GetActiveCamera()), Size, Size, options);
  std::vector<float> reference(ours.size());
  const double* background = renderer->GetBackground();
  for (size_t p = 0; p < pixels.size(); ++p)
  {
    for (int k = 0; k < 3; ++k)
    {
      reference[3 * p + k] =
        pixels[p].rgba[k] + (1.0f - pixels[p].rgba[3]) * static_cast<float>(background[k]);
    }
  }
  DumpImage(std::string(c.Name) + "_ours", ours, Size, Size);
  DumpImage(std::string(c.Name) + "_reference", reference, Size, Size);
  // Slices every SampleDistance against a 0.05 midpoint rule: the opacity correction makes the
  // two agree to a few grey levels except where thin shell walls fall between slices.
  return Report(c.Name, CompareImages(ours, reference, 10.0 / 255.0), 3.0 / 255.0, 0.03);
}
}

int TestAccelVolumeCompositeReference(int, char*[])
{
  const Case cases[] = {
    { "composite parallel", false, false, false, 0.25 },
    { "composite perspective clip", true, false, true, 0.25 },
    { "composite cross crop", true, true, false, 0.25 },
    { "composite half-voxel slices", false, true, true, 0.5 },
  };
  bool ok = true;
  for (const Case& c : cases)
  {
    ok = RunCase(c) && ok;
  }
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
