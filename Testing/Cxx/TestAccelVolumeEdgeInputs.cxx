// Odd but valid inputs render without errors: every scalar type, one-voxel-thick volumes,
// a constant volume, NaN in float data, and a crop that culls everything.
#include "AccelVolumeTestUtilities.h"
#include "vtkAccelVolumeSliceMapper.h"

#include "vtkCommand.h"
#include "vtkDoubleArray.h"

#include <cstdlib>
#include <limits>

namespace
{

// Renders and returns the centre pixel's brightness; -1 on an error.
double RenderCentre(vtkImageData* image, int blend = vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND,
  const double* crop = nullptr)
{
  vtkNew<vtkAccelVolumeSliceMapper> mapper;
  vtkNew<accelvolume_test::ErrorRecorder> errors;
  mapper->AddObserver(vtkCommand::ErrorEvent, errors);
  mapper->SetInputData(image);
  mapper->SetBlendMode(blend);
  if (crop)
  {
    mapper->CroppingOn();
    mapper->SetCroppingRegionPlanes(crop);
  }
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  double range[2];
  image->GetPointData()->GetScalars()->GetFiniteRange(range, 0);
  accelvolume_test::SetRampProperty(
    volume->GetProperty(), range[0], range[1] > range[0] ? range[1] : range[0] + 1);
  vtkNew<vtkRenderer> renderer;
  renderer->AddVolume(volume);
  renderer->GetActiveCamera()->Elevation(30);
  renderer->GetActiveCamera()->Azimuth(20);
  renderer->ResetCamera();
  vtkNew<vtkRenderWindow> window;
  window->SetSize(48, 48);
  window->AddRenderer(renderer);
  window->Render();
  if (errors->Count > 0)
  {
    return -1;
  }
  const std::vector<float> pixels = accelvolume_test::ReadPixels(window);
  return pixels[3 * (24 * 48 + 24)];
}

vtkSmartPointer<vtkImageData> Ramp(int type, int nx, int ny, int nz)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(nx, ny, nz);
  image->AllocateScalars(type, 1);
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  for (vtkIdType i = 0; i < scalars->GetNumberOfTuples(); ++i)
  {
    // A bright centre so MIP shows something whatever the type's range.
    int ijk[3] = { static_cast<int>(i % nx), static_cast<int>((i / nx) % ny),
      static_cast<int>(i / (nx * ny)) };
    const bool centre = std::abs(ijk[0] - nx / 2) <= nx / 4 &&
      std::abs(ijk[1] - ny / 2) <= ny / 4 && std::abs(ijk[2] - nz / 2) <= nz / 4;
    scalars->SetTuple1(i,
      centre ? 100.0
             : (type == VTK_CHAR || type == VTK_SIGNED_CHAR || type == VTK_SHORT ? -50.0 : 0.0));
  }
  return image;
}
}

int TestAccelVolumeEdgeInputs(int, char*[])
{
  bool ok = true;
  for (int type : { VTK_UNSIGNED_CHAR, VTK_SIGNED_CHAR, VTK_CHAR, VTK_UNSIGNED_SHORT, VTK_SHORT,
         VTK_INT, VTK_FLOAT, VTK_DOUBLE })
  {
    const double centre = RenderCentre(Ramp(type, 9, 8, 7));
    std::cout << vtkImageScalarTypeNameMacro(type) << ": centre " << centre << "\n";
    // The bright block maps to white at full opacity: every type must show it the same way.
    ok = centre > 0.9 && ok;
  }
  for (const int* dims :
    { (const int[3]){ 1, 12, 10 }, (const int[3]){ 12, 1, 10 }, (const int[3]){ 12, 10, 1 } })
  {
    auto slab = Ramp(VTK_FLOAT, dims[0], dims[1], dims[2]);
    const double centre = RenderCentre(slab);
    std::cout << dims[0] << "x" << dims[1] << "x" << dims[2] << ": centre " << centre << "\n";
    ok = centre >= 0 && ok;
  }
  auto constant = Ramp(VTK_FLOAT, 6, 6, 6);
  constant->GetPointData()->GetScalars()->Fill(5.0);
  ok = RenderCentre(constant, vtkVolumeMapper::AVERAGE_INTENSITY_BLEND) >= 0 && ok;
  auto withNaN = Ramp(VTK_DOUBLE, 8, 8, 8);
  withNaN->GetPointData()->GetScalars()->SetTuple1(100, std::numeric_limits<double>::quiet_NaN());
  withNaN->GetPointData()->GetScalars()->SetTuple1(101, std::numeric_limits<double>::infinity());
  const double nanCentre = RenderCentre(withNaN, vtkVolumeMapper::ADDITIVE_BLEND);
  std::cout << "NaN/Inf: centre " << nanCentre << "\n";
  // The bright centre block stays visible: NaN/Inf neither stretch the range nor break the sum.
  ok = nanCentre > 0.1 && ok;
  const double outside[6] = { 100, 200, 100, 200, 100, 200 };
  ok = RenderCentre(Ramp(VTK_UNSIGNED_CHAR, 8, 8, 8), vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND,
         outside) == 0.0 &&
    ok;
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
