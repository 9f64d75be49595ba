// Odd cropping, clipping and window geometry, for the slice, ray cast, shear-warp and smart
// mappers (a 16^3 block volume, parallel camera):
// - a crop box wholly outside the volume leaves the background;
// - an inverted crop box (min plane > max plane on every axis) is normalised: the image equals
//   the ordered box's, for the sub-volume and the fence flags;
// - NaN crop planes, and clipping planes with a non-finite normal or origin or a zero normal,
//   are refused with a clear error (nothing drawn; +-Inf crop planes are valid: clamped);
// - clipping planes that cull everything (one plane past the volume; two planes that exclude
//   each other) leave the background;
// - the shear-warp mapper ignores cropping and clipping with a warning: its image equals the
//   uncropped one;
// - a 0x0 window: VTK's windows render it at their default size (300x300), without a message,
//   as a fresh render at that size; the next frame at 40x40 equals a fresh render; a zero-area
//   viewport draws nothing (no message); a 1x1 window shows the centre ray's colour (the centre
//   pixel of a 41x41 render);
// - a resize between frames gives the image of a fresh render at the new size, and back.
#include "AccelVolumeBadInputSupport.h"

#include <functional>
#include <limits>
#include <memory>

namespace
{
using namespace accelvolume_test;

vtkSmartPointer<vtkImageData> Volume()
{
  return BlockVolume(VTK_UNSIGNED_CHAR, 16, 16, 16, 30, 200);
}

const std::vector<TransferPoint> Transfer = { { 0, 0, 0, 0, 0 }, { 30, 0.1, 0.8, 0.3, 0.05 },
  { 200, 1.0, 0.7, 0.2, 0.8 } };

std::unique_ptr<Probe> Render(MapperKind kind, const std::function<void(Probe&)>& configure,
  std::vector<float>& image, int size = 40)
{
  auto probe = std::make_unique<Probe>(kind, Volume(), size);
  const double bounds[6] = { 0, 15, 0, 15, 0, 15 };
  probe->LookAt(bounds, 2, 25, 20);
  SetTransfer(probe->Volume->GetProperty(), Transfer);
  probe->Mapper->SetBlendModeToComposite();
  if (configure)
  {
    configure(*probe);
  }
  image = probe->Render();
  return probe;
}

void Crop(Probe& probe, const double planes[6], int flags)
{
  probe.Mapper->CroppingOn();
  probe.Mapper->SetCroppingRegionPlanes(planes);
  probe.Mapper->SetCroppingRegionFlags(flags);
}

void AddPlane(Probe& probe, double ox, double oy, double oz, double nx, double ny, double nz)
{
  vtkNew<vtkPlane> plane;
  plane->SetOrigin(ox, oy, oz);
  plane->SetNormal(nx, ny, nz);
  probe.Mapper->AddClippingPlane(plane);
}

// A case that culls everything: background, quiet; shear-warp: the plain image and a warning.
bool ExpectCulled(MapperKind kind, const std::string& name,
  const std::function<void(Probe&)>& configure, const std::vector<float>& plain)
{
  std::vector<float> image;
  auto probe = Render(kind, configure, image);
  const std::string what = probe->Name(name);
  bool ok = CheckNoMessage(probe->Errors, what + ": no error");
  if (kind == MapperKind::ShearWarp)
  {
    ok =
      CheckMessage(probe->Warnings, "ignores cropping, clipping planes", what + ": warning") && ok;
    return CheckImage(image, plain, 0, what + ": the uncropped image") && ok;
  }
  ok = CheckNoMessage(probe->Warnings, what + ": no warning") && ok;
  return CheckBackground(image, what + ": background") && ok;
}

// A refused case: the error text, nothing drawn.
bool ExpectRefused(MapperKind kind, const std::string& name,
  const std::function<void(Probe&)>& configure, const std::string& text)
{
  std::vector<float> image;
  auto probe = Render(kind, configure, image);
  const std::string what = probe->Name(name);
  bool ok = CheckMessage(probe->Errors, text, what + ": error");
  return CheckBackground(image, what + ": background") && ok;
}

bool Cropping(MapperKind kind, const std::vector<float>& plain)
{
  bool ok = true;
  const double outside[6] = { 100, 200, 100, 200, 100, 200 };
  ok =
    ExpectCulled(
      kind, "crop box outside", [&](Probe& p) { Crop(p, outside, VTK_CROP_SUBVOLUME); }, plain) &&
    ok;
  const double ordered[6] = { 3, 12, 2, 13, 4, 11 };
  const double inverted[6] = { 12, 3, 13, 2, 11, 4 };
  for (int flags : { VTK_CROP_SUBVOLUME, VTK_CROP_FENCE })
  {
    const std::string name =
      std::string("inverted crop box, ") + (flags == VTK_CROP_FENCE ? "fence" : "sub-volume");
    std::vector<float> expected;
    Render(
      kind, [&](Probe& p) { Crop(p, ordered, flags); }, expected);
    std::vector<float> image;
    auto probe = Render(
      kind, [&](Probe& p) { Crop(p, inverted, flags); }, image);
    ok = CheckNoMessage(probe->Errors, probe->Name(name) + ": no error") && ok;
    ok = CheckImage(image, expected, 0, probe->Name(name) + ": the ordered box's image") && ok;
    if (kind != MapperKind::ShearWarp)
    {
      ok = Check(MaximumDifference(image, plain) > 0.1, probe->Name(name) + ": cropped") && ok;
    }
  }
  // +-Inf planes are valid: they clamp to the volume (as the planes -1000 and 1000 do).
  const double inf = std::numeric_limits<double>::infinity();
  const double infinite[6] = { -inf, inf, -inf, 8, 5, inf };
  const double large[6] = { -1000, 1000, -1000, 8, 5, 1000 };
  std::vector<float> expected;
  Render(
    kind, [&](Probe& p) { Crop(p, large, VTK_CROP_SUBVOLUME); }, expected);
  std::vector<float> image;
  auto probe = Render(
    kind, [&](Probe& p) { Crop(p, infinite, VTK_CROP_SUBVOLUME); }, image);
  ok = CheckNoMessage(probe->Errors, probe->Name("infinite crop planes: no error")) && ok;
  ok = CheckImage(image, expected, 0, probe->Name("infinite crop planes: as +-1000")) && ok;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double withNaN[6] = { 3, nan, 2, 13, 4, 11 };
  ok = ExpectRefused(
         kind, "NaN crop plane", [&](Probe& p) { Crop(p, withNaN, VTK_CROP_SUBVOLUME); },
         "Cropping region planes must be numbers, not NaN") &&
    ok;
  return ok;
}

bool Clipping(MapperKind kind, const std::vector<float>& plain)
{
  bool ok = true;
  ok = ExpectCulled(
         kind, "clipping plane past the volume", [](Probe& p) { AddPlane(p, 1000, 0, 0, 1, 0, 0); },
         plain) &&
    ok;
  ok = ExpectCulled(
         kind, "two clipping planes excluding each other",
         [](Probe& p)
         {
           AddPlane(p, 10, 0, 0, 1, 0, 0); // keeps x >= 10
           AddPlane(p, 5, 0, 0, -1, 0, 0); // keeps x <= 5
         },
         plain) &&
    ok;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  ok = ExpectRefused(
         kind, "clipping plane with a NaN origin",
         [nan](Probe& p) { AddPlane(p, nan, 0, 0, 1, 0, 0); }, "Clipping plane 0") &&
    ok;
  ok = ExpectRefused(
         kind, "clipping plane with a zero normal",
         [](Probe& p)
         {
           AddPlane(p, 8, 8, 8, 0, 0, 1);
           AddPlane(p, 8, 8, 8, 0, 0, 0);
         },
         "Clipping plane 1") &&
    ok;
  return ok;
}

// A fresh probe's image at width x height.
std::vector<float> FreshAt(MapperKind kind, int width, int height)
{
  std::vector<float> image;
  Render(
    kind, [&](Probe& p) { p.Window->SetSize(width, height); }, image);
  return image;
}

bool Windows(MapperKind kind)
{
  bool ok = true;
  // 0x0: VTK's windows take their default size instead (300x300) and render normally.
  std::vector<float> image;
  auto probe = Render(
    kind, [](Probe& p) { p.Window->SetSize(0, 0); }, image);
  const int width = probe->Window->GetSize()[0], height = probe->Window->GetSize()[1];
  ok = CheckNoMessage(probe->Errors, probe->Name("0x0 window: no error")) && ok;
  if (width > 0 && height > 0)
  {
    ok = CheckImage(image, FreshAt(kind, width, height), OneLevel,
           probe->Name("0x0 window (became " + std::to_string(width) + "x" +
             std::to_string(height) + "): a fresh render at that size")) &&
      ok;
  }
  probe->Window->SetSize(40, 40);
  image = probe->Render();
  ok = CheckImage(image, FreshAt(kind, 40, 40), OneLevel,
         probe->Name("0x0 window, then 40x40: a fresh render")) &&
    ok;

  // A zero-area viewport over a full-window backdrop.
  std::vector<float> backdrop;
  probe = Render(
    kind,
    [](Probe& p)
    {
      p.Renderer->SetViewport(0.3, 0.2, 0.3, 0.9);
      vtkNew<vtkRenderer> under;
      under->SetBackground(Background[0], Background[1], Background[2]);
      under->SetLayer(0);
      p.Renderer->SetLayer(1);
      p.Window->SetNumberOfLayers(2);
      p.Window->AddRenderer(under);
    },
    backdrop);
  ok = CheckNoMessage(probe->Errors, probe->Name("zero-area viewport: no error")) && ok;
  ok = CheckBackground(backdrop, probe->Name("zero-area viewport: nothing drawn")) && ok;

  // 1x1: the centre ray.
  std::vector<float> odd;
  Render(kind, nullptr, odd, 41);
  std::vector<float> single;
  probe = Render(kind, nullptr, single, 1);
  ok = CheckNoMessage(probe->Errors, probe->Name("1x1 window: no error")) && ok;
  ok = CheckImage(single, PixelAt(odd, 41, 20, 20), 2 * OneLevel,
         probe->Name("1x1 window: the centre pixel of 41x41")) &&
    ok;

  // Resizes between frames.
  std::vector<float> square;
  probe = Render(kind, nullptr, square);
  probe->Window->SetSize(56, 44);
  ok = CheckImage(probe->Render(), FreshAt(kind, 56, 44), OneLevel,
         probe->Name("resize 40x40 -> 56x44: a fresh 56x44 render")) &&
    ok;
  probe->Window->SetSize(40, 40);
  ok = CheckImage(probe->Render(), square, OneLevel, probe->Name("resize back to 40x40")) && ok;
  ok = CheckNoMessage(probe->Errors, probe->Name("resizes: no error")) && ok;
  return ok;
}
}

int TestAccelVolumeBadGeometry(int, char*[])
{
  bool ok = true;
  for (MapperKind kind : AllMappers)
  {
    std::vector<float> plain;
    Render(kind, nullptr, plain);
    ok = Cropping(kind, plain) && ok;
    ok = Clipping(kind, plain) && ok;
    ok = Windows(kind) && ok;
  }
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
