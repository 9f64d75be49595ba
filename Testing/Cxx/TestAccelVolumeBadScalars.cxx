// Scalars no mapper renders get one clear error and leave the window's background untouched, for
// the slice, ray cast, shear-warp and smart mappers: 2, 3 and 4 components (independent or
// dependent), unsigned int / long / unsigned long / long long / unsigned long long / vtkIdType /
// bit arrays (the error names the type), zero, negative and inverted dimensions, a scalar array
// that does not match the dimensions, cell scalars, no input, an empty image.
#include "AccelVolumeBadInputSupport.h"

#include "vtkBitArray.h"
#include "vtkCellData.h"
#include "vtkUnsignedCharArray.h"

#include <functional>

namespace
{
using namespace accelvolume_test;

// Renders `image` (prepared by `configure`) with the mapper; the error must contain `text`
// and every pixel must stay the background.
bool ExpectError(MapperKind kind, const std::string& what, vtkImageData* image,
  const std::string& text, const std::function<void(Probe&)>& configure = nullptr)
{
  Probe probe(kind, image);
  const double bounds[6] = { 0, 3, 0, 3, 0, 3 }; // bad inputs have no usable bounds
  probe.LookAt(bounds);
  SetRampProperty(probe.Volume->GetProperty(), 0, 255);
  if (configure)
  {
    configure(probe);
  }
  const std::vector<float> pixels = probe.Render();
  bool ok = CheckMessage(probe.Errors, text, probe.Name(what) + ": error");
  ok = CheckBackground(pixels, probe.Name(what) + ": background untouched") && ok;
  return ok;
}

vtkSmartPointer<vtkImageData> WithScalars(vtkDataArray* scalars, int nx = 4, int ny = 4, int nz = 4)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(nx, ny, nz);
  scalars->SetNumberOfTuples(static_cast<vtkIdType>(nx) * ny * nz);
  for (int c = 0; c < scalars->GetNumberOfComponents(); ++c)
  {
    scalars->FillComponent(c, 1.0);
  }
  image->GetPointData()->SetScalars(scalars);
  return image;
}

bool Components(MapperKind kind)
{
  bool ok = true;
  auto withComponents = [](int components)
  {
    vtkNew<vtkUnsignedCharArray> scalars;
    scalars->SetNumberOfComponents(components);
    return WithScalars(scalars);
  };
  if (kind != MapperKind::ShearWarp)
  {
    // 2-4 components render (TestAccelVolumeVsGPURayCastFeatures); the rest is
    // refused clearly.
    ok = ExpectError(
           kind, "5 components", withComponents(5), "At most 4 scalar components are supported") &&
      ok;
    ok = ExpectError(kind, "3 dependent components", withComponents(3),
           "Dependent components must be 2 (luminance, alpha) or 4 (RGBA), not 3",
           [](Probe& probe) { probe.Volume->GetProperty()->SetIndependentComponents(false); }) &&
      ok;
    return ok;
  }
  for (int components : { 2, 3, 4 })
  {
    for (bool independent : { true, false })
    {
      const std::string what =
        std::to_string(components) + " components, " + (independent ? "independent" : "dependent");
      ok = ExpectError(kind, what, withComponents(components),
             "Only single-component scalars are supported by this mapper (input has " +
               std::to_string(components) + " components",
             [independent](Probe& probe)
             { probe.Volume->GetProperty()->SetIndependentComponents(independent); }) &&
        ok;
    }
  }
  return ok;
}

bool Types(MapperKind kind)
{
  bool ok = true;
  // unsigned int and the 64-bit integers render (as floats: TestAccelVolumeInputKinds).
  const std::vector<vtkSmartPointer<vtkDataArray>> arrays = { vtkSmartPointer<vtkBitArray>::New() };
  for (vtkDataArray* array : arrays)
  {
    const std::string type = array->GetDataTypeAsString();
    ok = ExpectError(
           kind, type + " scalars", WithScalars(array), "Unsupported scalar type " + type + " ") &&
      ok;
  }
  return ok;
}

bool Dimensions(MapperKind kind)
{
  bool ok = true;
  {
    vtkNew<vtkImageData> image;
    image->SetDimensions(0, 4, 4);
    image->AllocateScalars(VTK_UNSIGNED_CHAR, 1);
    ok = ExpectError(kind, "dimensions 0x4x4", image, "Empty input image (dimensions 0x4x4)") && ok;
  }
  {
    vtkNew<vtkImageData> image;
    image->SetDimensions(4, -3, 4);
    image->AllocateScalars(VTK_UNSIGNED_CHAR, 1);
    ok =
      ExpectError(kind, "dimensions 4x-3x4", image, "Empty input image (dimensions 4x-3x4)") && ok;
  }
  {
    vtkNew<vtkImageData> image;
    image->SetExtent(0, 3, 0, 3, 5, 2); // inverted: max < min
    image->AllocateScalars(VTK_UNSIGNED_CHAR, 1);
    ok = ExpectError(kind, "inverted extent", image, "Empty input image (dimensions 4x4x-2)") && ok;
  }
  {
    vtkNew<vtkImageData> empty;
    ok = ExpectError(kind, "empty image", empty, "Empty input image") && ok;
  }
  {
    vtkNew<vtkUnsignedCharArray> scalars;
    auto image = WithScalars(scalars);
    scalars->SetNumberOfTuples(60); // 64 points
    ok = ExpectError(kind, "60 scalars for 64 points", image,
           "Scalar array size (60 tuples) does not match the image's 64 points") &&
      ok;
  }
  {
    vtkNew<vtkImageData> image;
    image->SetDimensions(4, 4, 4);
    // Cell scalars render (TestAccelVolumeInputKinds); a wrong count is still an error.
    vtkNew<vtkUnsignedCharArray> cells;
    cells->SetNumberOfTuples(20);
    cells->FillComponent(0, 9);
    image->GetCellData()->SetScalars(cells);
    ok = ExpectError(kind, "20 cell scalars for 27 cells", image,
           "Scalar array size (20 tuples) does not match the input's 27 cells",
           [](Probe& probe) { probe.Mapper->SetScalarModeToUseCellData(); }) &&
      ok;
  }
  ok = ExpectError(kind, "no input", nullptr, "No input: connect a vtkImageData") && ok;
  return ok;
}
}

int TestAccelVolumeBadScalars(int, char*[])
{
  bool ok = true;
  for (MapperKind kind : AllMappers)
  {
    ok = Components(kind) && ok;
    ok = Types(kind) && ok;
    ok = Dimensions(kind) && ok;
  }
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
