// 2D transfer functions (vtkVolumeProperty::TF_2D, value x gradient magnitude): a table whose
// rows all repeat the 1D functions gives the 1D image; a gradient-dependent table changes it;
// per-fragment skipping stays exact with a 2D table.
#include "AccelVolumeTestUtilities.h"
#include "vtkAccelVolumeSliceMapper.h"

#include <cstdlib>

namespace
{
constexpr int Size = 160;
constexpr int Columns = 1024;
constexpr int Rows = 64;

// RGBA image: each row the 1D colour and opacity over the data range, times rowOpacity(y).
vtkSmartPointer<vtkImageData> MakeTable(
  vtkVolumeProperty* property, const double range[2], double minimumGradientFraction)
{
  std::vector<float> opacity(Columns);
  std::vector<float> colours(3 * Columns);
  property->GetScalarOpacity()->GetTable(range[0], range[1], Columns, opacity.data());
  property->GetRGBTransferFunction()->GetTable(range[0], range[1], Columns, colours.data());
  auto table = vtkSmartPointer<vtkImageData>::New();
  table->SetDimensions(Columns, Rows, 1);
  table->AllocateScalars(VTK_FLOAT, 4);
  auto* rgba = static_cast<float*>(table->GetScalarPointer());
  for (int y = 0; y < Rows; ++y)
  {
    const float rowOpacity = (y + 0.5) / Rows >= minimumGradientFraction ? 1.0f : 0.0f;
    for (int x = 0; x < Columns; ++x)
    {
      float* texel = rgba + 4 * (y * Columns + x);
      texel[0] = colours[3 * x];
      texel[1] = colours[3 * x + 1];
      texel[2] = colours[3 * x + 2];
      texel[3] = opacity[x] * rowOpacity;
    }
  }
  return table;
}

std::vector<float> Render(
  vtkImageData* image, bool use2D, double minimumGradientFraction, int skipping)
{
  vtkNew<vtkAccelVolumeSliceMapper> mapper;
  mapper->SetInputData(image);
  mapper->SetBlendModeToComposite();
  mapper->SetEarlyRayTermination(false);
  mapper->SetEmptySpaceSkipping(skipping);
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  accelvolume_test::SetRampProperty(volume->GetProperty(), 150.0, 900.0, true);
  double range[2];
  image->GetPointData()->GetScalars()->GetRange(range);
  if (use2D)
  {
    volume->GetProperty()->SetTransferFunction2D(
      MakeTable(volume->GetProperty(), range, minimumGradientFraction));
    volume->GetProperty()->SetTransferFunctionMode(vtkVolumeProperty::TF_2D);
  }
  vtkNew<vtkRenderer> renderer;
  renderer->AddVolume(volume);
  vtkNew<vtkRenderWindow> window;
  accelvolume_test::SetupObliqueView(window, renderer, Size, 20, 35, true);
  window->Render();
  return accelvolume_test::ReadPixels(window);
}
}

int TestAccelVolumeTransferFunction2D(int, char*[])
{
  using namespace accelvolume_test;
  auto image = MakePhantom("blobs", 56, 48, 44);
  const std::vector<float> oneD = Render(image, false, 0.0, vtkAccelVolumeSliceMapper::SKIP_NONE);
  const std::vector<float> flat2D = Render(image, true, 0.0, vtkAccelVolumeSliceMapper::SKIP_NONE);
  // Same classification through a 1024-column table instead of the 1024-entry 1D table.
  bool ok = Report("2D table of repeated 1D rows vs 1D", CompareImages(flat2D, oneD, 3.0 / 255.0),
    0.5 / 255.0, 0.002);
  // Rows below 32% of the gradient axis (VTK's: [0, a quarter of the data range]) transparent:
  // flat interiors vanish, edges stay.
  const std::vector<float> edges = Render(image, true, 0.32, vtkAccelVolumeSliceMapper::SKIP_NONE);
  const ImageDifference changed = CompareImages(edges, oneD, 8.0 / 255.0);
  double brightnessEdges = 0;
  double brightnessOneD = 0;
  for (size_t i = 0; i < edges.size(); ++i)
  {
    brightnessEdges += edges[i];
    brightnessOneD += oneD[i];
  }
  std::cout << "gradient-dependent 2D table vs 1D: fraction changed " << changed.fractionAbove
            << ", brightness " << brightnessEdges << " vs " << brightnessOneD << "\n";
  if (!(changed.fractionAbove > 0.02) || !(brightnessEdges > 0.2 * brightnessOneD))
  {
    std::cerr << "a 2D table that hides low gradients should change, not blank, the image\n";
    ok = false;
  }
  const std::vector<float> skipped =
    Render(image, true, 0.32, vtkAccelVolumeSliceMapper::SKIP_BOTH);
  ok = Report("2D table with skipping vs without", CompareImages(skipped, edges, 1.0 / 255.0), 0.0,
         0.0) &&
    ok;
  DumpImage("tf2d_flat", flat2D, Size, Size);
  DumpImage("tf2d_edges", edges, Size, Size);
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
