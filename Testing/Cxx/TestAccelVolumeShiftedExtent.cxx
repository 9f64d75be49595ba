// Images whose extent does not start at 0 (vtkRTAnalyticSource, ParaView's Wavelet, extracted
// sub-volumes) sit where VTK puts them: VTK's index-to-physical matrix is indexed by structured
// (extent) coordinates, the mappers count voxels from 0. The same voxels with extent 0.. and
// origin o, and with extent -13.. and origin o + 13 * spacing, occupy the same world box, so
// every mapper must draw the same picture (byte-identical: same samples), with and without
// cropping (cropping planes are in physical coordinates too).
#include "AccelVolumeTestUtilities.h"
#include "vtkAccelVolumeRayCastMapper.h"
#include "vtkAccelVolumeShearWarpMapper.h"
#include "vtkAccelVolumeSliceMapper.h"

#include <cstdlib>

namespace
{
const int Shift[3] = { -13, 5, -7 };
const double Spacing[3] = { 1.0, 1.25, 0.75 };

vtkSmartPointer<vtkImageData> MakeVolume(bool shifted)
{
  vtkSmartPointer<vtkImageData> image = accelvolume_test::MakePhantom(
    "blobs", 40, 36, 44, Spacing[0], Spacing[1], Spacing[2]);
  if (!image)
  {
    return nullptr;
  }
  double origin[3] = { 3.0, -2.0, 1.5 };
  if (shifted)
  {
    int extent[6];
    image->GetExtent(extent);
    for (int axis = 0; axis < 3; ++axis)
    {
      extent[2 * axis] += Shift[axis];
      extent[2 * axis + 1] += Shift[axis];
      origin[axis] -= Shift[axis] * Spacing[axis];
    }
    image->SetExtent(extent);
  }
  image->SetOrigin(origin);
  return image;
}

std::vector<float> Render(vtkVolumeMapper* mapper, vtkImageData* image, bool crop)
{
  mapper->SetInputData(image);
  mapper->SetBlendModeToComposite();
  if (crop)
  {
    double bounds[6];
    image->GetBounds(bounds);
    double planes[6];
    for (int axis = 0; axis < 3; ++axis)
    {
      const double length = bounds[2 * axis + 1] - bounds[2 * axis];
      planes[2 * axis] = bounds[2 * axis] + 0.2 * length;
      planes[2 * axis + 1] = bounds[2 * axis] + 0.7 * length;
    }
    mapper->CroppingOn();
    mapper->SetCroppingRegionPlanes(planes);
    mapper->SetCroppingRegionFlagsToSubVolume();
  }
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  accelvolume_test::SetRampProperty(volume->GetProperty(), 0.1, 1.0, true);
  vtkNew<vtkRenderer> renderer;
  renderer->AddVolume(volume);
  vtkNew<vtkRenderWindow> window;
  // A fixed camera, not fitted to the data, so a misplaced volume moves in the picture.
  window->SetSize(120, 120);
  window->SetMultiSamples(0);
  window->AddRenderer(renderer);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->ParallelProjectionOn();
  camera->SetFocalPoint(23.0, 20.0, 18.0);
  camera->SetPosition(23.0 + 80.0, 20.0 + 50.0, 18.0 + 60.0);
  camera->SetViewUp(0.0, 0.0, 1.0);
  camera->SetParallelScale(34.0);
  renderer->ResetCameraClippingRange();
  window->Render();
  return accelvolume_test::ReadPixels(window);
}

template <typename Mapper>
bool Check(const char* name, vtkImageData* plain, vtkImageData* shifted, bool crop)
{
  vtkNew<Mapper> plainMapper;
  vtkNew<Mapper> shiftedMapper;
  const std::vector<float> expected = Render(plainMapper, plain, crop);
  const std::vector<float> actual = Render(shiftedMapper, shifted, crop);
  const accelvolume_test::ImageDifference d =
    accelvolume_test::CompareImages(actual, expected, 1.0 / 255.0);
  size_t lit = 0;
  for (float v : expected)
  {
    lit += v > 0.05f ? 1 : 0;
  }
  const double litFraction = static_cast<double>(lit) / expected.size();
  const bool ok = d.maximum <= 1e-6 && litFraction > 0.05;
  std::cout << name << (crop ? ", cropped" : "") << ": max |diff| shifted vs 0-based extent "
            << d.maximum << ", lit fraction " << litFraction << (ok ? "" : "  FAILED") << "\n";
  return ok;
}
}

int TestAccelVolumeShiftedExtent(int, char*[])
{
  vtkSmartPointer<vtkImageData> plain = MakeVolume(false);
  vtkSmartPointer<vtkImageData> shifted = MakeVolume(true);
  if (!plain || !shifted)
  {
    return EXIT_FAILURE;
  }
  double a[6];
  double b[6];
  plain->GetBounds(a);
  shifted->GetBounds(b);
  for (int i = 0; i < 6; ++i)
  {
    if (std::fabs(a[i] - b[i]) > 1e-9)
    {
      std::cerr << "test set-up: the two volumes do not share their bounds\n";
      return EXIT_FAILURE;
    }
  }
  bool ok = true;
  for (bool crop : { false, true })
  {
    ok = Check<vtkAccelVolumeSliceMapper>("slice", plain, shifted, crop) && ok;
    ok = Check<vtkAccelVolumeRayCastMapper>("raycast", plain, shifted, crop) && ok;
  }
  // Shear-warp ignores cropping (it says so): uncropped only.
  ok = Check<vtkAccelVolumeShearWarpMapper>("shearwarp", plain, shifted, false) && ok;
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
