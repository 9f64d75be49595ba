// UseDepthPass (vtkGPUVolumeRayCastMapper's depth pass, issue 16): composite rays start where they
// first cross a contour value and pixels whose rays cross none draw nothing. The slice mapper is
// compared with VTK's GPU mapper on the same scene (one and two contour values, shaded and not, a
// parallel and a perspective view); the picture must also differ clearly from the one without
// the depth pass, so the comparison proves the pass is applied. Without contour values the
// setting changes nothing.
#include "AccelVolumeTestUtilities.h"
#include "vtkAccelVolumeSliceMapper.h"
#include "vtkCamera.h"
#include "vtkContourValues.h"
#include "vtkGPUVolumeRayCastMapper.h"
#include "vtkPointData.h"
#include "vtkVolumeProperty.h"

#include <initializer_list>
#include <iostream>
#include <string>
#include <vector>

namespace
{
constexpr int Size = 200;

template <typename MapperType>
std::vector<float> Render(vtkImageData* image, std::initializer_list<double> contours, bool shade,
  bool parallel, bool depthPass = true)
{
  vtkNew<MapperType> mapper;
  mapper->SetAutoAdjustSampleDistances(0);
  mapper->SetSampleDistance(0.5);
  mapper->SetInputData(image);
  mapper->SetUseDepthPass(depthPass);
  int n = 0;
  for (double value : contours)
  {
    mapper->GetDepthPassContourValues()->SetValue(n++, value);
  }
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  // Semi-transparent, so what lies in front of the contour shows when it is not skipped.
  accelvolume_test::SetRampProperty(volume->GetProperty(), 40.0, 900.0, shade);
  vtkVolumeProperty* property = volume->GetProperty();
  for (int c = 1; c < image->GetPointData()->GetScalars()->GetNumberOfComponents(); ++c)
  {
    // Transparent at the box's edge values too: VTK's rays crossing no contour start at the
    // far plane and still pick up edge samples there (an artefact not reproduced).
    property->SetScalarOpacity(c, property->GetScalarOpacity(0));
    property->SetColor(c, property->GetRGBTransferFunction(0));
  }
  vtkNew<vtkRenderer> renderer;
  renderer->AddVolume(volume);
  vtkNew<vtkRenderWindow> window;
  accelvolume_test::SetupObliqueView(window, renderer, Size, 35, -25, parallel);
  window->Render();
  return accelvolume_test::ReadPixels(window);
}
}

int TestAccelVolumeDepthPass(int, char*[])
{
  auto image = accelvolume_test::MakePhantom("blobs", 48, 40, 36, 1.0, 1.0, 1.25);
  bool ok = true;
  struct Scene
  {
    const char* Name;
    std::initializer_list<double> Contours;
    bool Shade;
    bool Parallel;
  };
  const Scene scenes[] = { { "contour 500, unshaded, parallel", { 500.0 }, false, true },
    { "contours 300 and 700, shaded, perspective", { 300.0, 700.0 }, true, false } };
  for (const Scene& scene : scenes)
  {
    const std::vector<float> vtk =
      Render<vtkGPUVolumeRayCastMapper>(image, scene.Contours, scene.Shade, scene.Parallel);
    const std::vector<float> slice =
      Render<vtkAccelVolumeSliceMapper>(image, scene.Contours, scene.Shade, scene.Parallel);
    const std::vector<float> without =
      Render<vtkAccelVolumeSliceMapper>(image, scene.Contours, scene.Shade, scene.Parallel, false);
    accelvolume_test::DumpImage(std::string("depthpass_vtk_") + scene.Name, vtk, Size, Size);
    accelvolume_test::DumpImage(std::string("depthpass_slice_") + scene.Name, slice, Size, Size);
    ok = accelvolume_test::Report(
           (std::string("slice vs vtkGPUVolumeRayCastMapper, depth pass, ") + scene.Name).c_str(),
           accelvolume_test::CompareImages(slice, vtk, 16.0 / 255.0), 4.0 / 255.0, 0.03) &&
      ok;
    const accelvolume_test::ImageDifference change =
      accelvolume_test::CompareImages(slice, without, 16.0 / 255.0);
    if (change.mean < 3.0 / 255.0)
    {
      std::cerr << "FAILED the depth pass barely changes the picture (" << scene.Name << "): mean "
                << change.mean << "\n";
      ok = false;
    }
  }
  // Two independent components: the contour of component 0 (vtkContourFilter's).
  {
    auto pair = vtkSmartPointer<vtkImageData>::New();
    pair->CopyStructure(image);
    pair->AllocateScalars(VTK_FLOAT, 2);
    vtkDataArray* source = image->GetPointData()->GetScalars();
    vtkDataArray* target = pair->GetPointData()->GetScalars();
    for (vtkIdType i = 0; i < source->GetNumberOfTuples(); ++i)
    {
      target->SetComponent(i, 0, source->GetComponent(i, 0));
      target->SetComponent(i, 1, 0.6 * source->GetComponent(i, 0));
    }
    const std::vector<float> vtk = Render<vtkGPUVolumeRayCastMapper>(pair, { 500.0 }, false, true);
    const std::vector<float> slice =
      Render<vtkAccelVolumeSliceMapper>(pair, { 500.0 }, false, true);
    ok = accelvolume_test::Report(
           "slice vs vtkGPUVolumeRayCastMapper, depth pass, 2 independent components",
           accelvolume_test::CompareImages(slice, vtk, 16.0 / 255.0), 4.0 / 255.0, 0.03) &&
      ok;
  }
  // No contour value: the setting warns once and changes nothing.
  const std::vector<float> plain = Render<vtkAccelVolumeSliceMapper>(image, {}, false, true, false);
  const std::vector<float> empty = Render<vtkAccelVolumeSliceMapper>(image, {}, false, true, true);
  ok = accelvolume_test::Report("slice, depth pass without contour values = no depth pass",
         accelvolume_test::CompareImages(empty, plain, 1.0 / 255.0), 0.0, 0.0) &&
    ok;
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
