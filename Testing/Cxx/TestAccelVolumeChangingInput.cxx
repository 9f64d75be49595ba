// Inputs that change between frames: after each change the mapper's next frame equals a fresh
// mapper's image of the new input (same camera and property; 1/255), for the slice, ray cast,
// shear-warp and smart mappers. Changes: another image; the scalars edited in place; the same
// image object re-allocated with another type and dimensions; new spacing and origin; another
// active scalar array; a pipeline source whose extent changes; the transfer function and blend
// mode; the input removed (a clear "No input" error, background) and set again; unsupported
// scalars (a clear error) and then good ones again. Deleting the scene frees its input. Window
// resizes between frames are in TestAccelVolumeBadGeometry.
#include "AccelVolumeBadInputSupport.h"

#include "vtkRTAnalyticSource.h"
#include "vtkShortArray.h"
#include "vtkUnsignedIntArray.h"
#include "vtkWeakPointer.h"

#include <functional>

namespace
{
using namespace accelvolume_test;

const double Bounds[6] = { 0, 15, 0, 15, 0, 15 }; // one view for every input

void SetProperty(vtkVolumeProperty* property, double scale = 1.0)
{
  SetTransfer(property,
    { { 0, 0, 0, 0, 0 }, { 40 * scale, 0.2, 0.3, 0.9, 0.1 }, { 120 * scale, 0.9, 0.8, 0.2, 0.6 },
      { 250 * scale, 1, 1, 1, 0.9 } });
}

// A fresh mapper's image of `input` (an image or a pipeline), with that camera and property.
std::vector<float> Fresh(MapperKind kind, const std::function<void(vtkVolumeMapper*)>& connect,
  int blend, double scale, bool& ok)
{
  Probe probe(kind);
  connect(probe.Mapper);
  probe.LookAt(Bounds, 2, 30, 20);
  probe.Mapper->SetBlendMode(blend);
  SetProperty(probe.Volume->GetProperty(), scale);
  const std::vector<float> image = probe.Render();
  ok = CheckNoMessage(probe.Errors, probe.Name("fresh render: no error")) && ok;
  return image;
}

vtkSmartPointer<vtkImageData> Ramp(int type, int nx, int ny, int nz, double low, double high)
{
  auto image = BlockVolume(type, nx, ny, nz, low, high);
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  for (vtkIdType i = 0; i < scalars->GetNumberOfTuples(); i += 3)
  {
    scalars->SetTuple1(i, 0.5 * (low + high)); // some texture, so that the images differ
  }
  return image;
}

bool Sequence(MapperKind kind)
{
  bool ok = true;
  Probe probe(kind);
  probe.LookAt(Bounds, 2, 30, 20);
  SetProperty(probe.Volume->GetProperty());
  int blend = vtkVolumeMapper::COMPOSITE_BLEND;
  double scale = 1.0;
  // Renders the next frame; it must equal the fresh image of what `connect` connects.
  auto frame = [&](const std::string& what, const std::function<void(vtkVolumeMapper*)>& connect)
  {
    connect(probe.Mapper);
    const std::vector<float> image = probe.Render();
    bool good = CheckNoMessage(probe.Errors, probe.Name(what + ": no error"));
    good = CheckImage(image, Fresh(kind, connect, blend, scale, good), OneLevel,
             probe.Name(what + ": a fresh mapper's image")) &&
      good;
    good = Check(MaximumDifferenceFrom(image, Background) > 0.1,
             probe.Name(what + ": the volume is drawn")) &&
      good;
    return good;
  };

  auto first = Ramp(VTK_UNSIGNED_CHAR, 16, 16, 16, 20, 200);
  ok = frame("first input", [&](vtkVolumeMapper* m) { m->SetInputData(first); }) && ok;
  auto second = Ramp(VTK_UNSIGNED_CHAR, 16, 16, 16, 60, 130);
  ok = frame("another image", [&](vtkVolumeMapper* m) { m->SetInputData(second); }) && ok;
  vtkDataArray* values = second->GetPointData()->GetScalars();
  for (vtkIdType i = 0; i < values->GetNumberOfTuples(); i += 2)
  {
    values->SetTuple1(i, 250);
  }
  values->Modified();
  ok = frame("scalars edited in place", [&](vtkVolumeMapper* m) { m->SetInputData(second); }) && ok;
  // The same image object, re-allocated as short 20x12x9 with values to 240.
  second->SetDimensions(20, 12, 9);
  second->AllocateScalars(VTK_SHORT, 1);
  values = second->GetPointData()->GetScalars();
  for (vtkIdType i = 0; i < values->GetNumberOfTuples(); ++i)
  {
    values->SetTuple1(i, static_cast<double>((i * 37) % 240));
  }
  ok =
    frame("same image, short 20x12x9", [&](vtkVolumeMapper* m) { m->SetInputData(second); }) && ok;
  second->SetSpacing(0.8, 1.3, 1.6);
  second->SetOrigin(-2, 1, 0.5);
  ok = frame("new spacing and origin", [&](vtkVolumeMapper* m) { m->SetInputData(second); }) && ok;
  auto floats = Ramp(VTK_FLOAT, 13, 15, 17, 10.5, 240.5);
  ok = frame("float 13x15x17", [&](vtkVolumeMapper* m) { m->SetInputData(floats); }) && ok;
  vtkNew<vtkShortArray> other;
  other->SetName("other");
  other->SetNumberOfTuples(floats->GetNumberOfPoints());
  for (vtkIdType i = 0; i < other->GetNumberOfTuples(); ++i)
  {
    other->SetValue(i, static_cast<short>(i % 200));
  }
  floats->GetPointData()->AddArray(other);
  floats->GetPointData()->SetActiveScalars("other");
  ok = frame("another active array", [&](vtkVolumeMapper* m) { m->SetInputData(floats); }) && ok;

  // A pipeline whose output changes extent (and so dimensions) between frames.
  vtkNew<vtkRTAnalyticSource> source;
  source->SetWholeExtent(0, 11, 0, 13, 0, 9);
  ok = frame("pipeline 12x14x10",
         [&](vtkVolumeMapper* m) { m->SetInputConnection(source->GetOutputPort()); }) &&
    ok;
  source->SetWholeExtent(-3, 12, 0, 8, 2, 16);
  ok = frame("pipeline extent changed",
         [&](vtkVolumeMapper* m) { m->SetInputConnection(source->GetOutputPort()); }) &&
    ok;
  scale = 0.5;
  SetProperty(probe.Volume->GetProperty(), scale);
  ok = frame("transfer function changed",
         [&](vtkVolumeMapper* m) { m->SetInputConnection(source->GetOutputPort()); }) &&
    ok;
  blend = vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND;
  probe.Mapper->SetBlendMode(blend);
  ok = frame("blend mode changed",
         [&](vtkVolumeMapper* m) { m->SetInputConnection(source->GetOutputPort()); }) &&
    ok;

  // No input, then an input again.
  probe.Mapper->SetInputConnection(nullptr);
  std::vector<float> image = probe.Render();
  ok = CheckMessage(probe.Errors, "No input", probe.Name("input removed: error")) && ok;
  ok = CheckBackground(image, probe.Name("input removed: background")) && ok;
  probe.Errors->Messages.clear();
  probe.Errors->Count = 0;
  ok = frame("input set again", [&](vtkVolumeMapper* m) { m->SetInputData(first); }) && ok;

  // Unsupported scalars, then good ones.
  vtkNew<vtkImageData> wide;
  wide->SetDimensions(8, 8, 8);
  wide->AllocateScalars(VTK_BIT, 1);
  probe.Mapper->SetInputData(wide);
  image = probe.Render();
  ok =
    CheckMessage(probe.Errors, "Unsupported scalar type", probe.Name("bit: error")) && ok;
  ok = CheckBackground(image, probe.Name("bit: background")) && ok;
  probe.Errors->Messages.clear();
  probe.Errors->Count = 0;
  ok = frame("good scalars again", [&](vtkVolumeMapper* m) { m->SetInputData(first); }) && ok;
  return ok;
}

// Once the scene is gone, so is its input: no reference cycle keeps the image (and its
// producer) alive. VTK's own leak report is not built into Debian's VTK, so a weak pointer
// checks it.
bool InputReleased(MapperKind kind)
{
  vtkWeakPointer<vtkImageData> weak;
  {
    auto image = Ramp(VTK_UNSIGNED_CHAR, 16, 16, 16, 20, 200);
    weak = image;
    Probe probe(kind, image);
    SetProperty(probe.Volume->GetProperty());
    probe.Render();
    probe.Render();
  }
  return Check(weak == nullptr, std::string(MapperName(kind)) + ", scene deleted: input freed");
}
}

int TestAccelVolumeChangingInput(int, char*[])
{
  bool ok = true;
  for (MapperKind kind : AllMappers)
  {
    ok = Sequence(kind) && ok;
    ok = InputReleased(kind) && ok;
  }
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
