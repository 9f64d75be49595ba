// Degenerate transfer functions give VTK's meaning of them, exactly, with no message, for the
// slice, ray cast, shear-warp and smart mappers (a 12^3 volume: 0 around a block of 200):
// - scalar opacity with no points is 0 everywhere: composite, MIP and MinIP leave the background;
// - one opacity point is that opacity everywhere: opacity 1 shows the first sample's colour
//   (composite: colour(0) of the outer shell) or the extreme's (MIP: colour(200));
// - a colour function with no points is black;
// - all-zero opacity leaves the background (composite, MIP, MinIP); raysum and average weight
//   the value by opacity and show black (the shear-warp mapper refuses them clearly);
// - gradient opacity with no points makes every sample transparent (background);
// - a volume whose property was never set gets VTK's default property (grey ramp over
//   [0, 1024], opacity 1): MIP shows grey 200 / 1024;
// - TF_2D mode without a 2D function: the slice mapper refuses it with an error naming
//   SetTransferFunction2D; the CPU mappers (and so the smart mapper) warn and use the 1D
//   functions: the image equals the TF_1D image.
#include "AccelVolumeBadInputSupport.h"

#include <functional>
#include <memory>

namespace
{
using namespace accelvolume_test;

vtkSmartPointer<vtkImageData> Volume()
{
  return BlockVolume(VTK_UNSIGNED_CHAR, 12, 12, 12, 0, 200);
}

struct Case
{
  std::string Name;
  int Blend;
  std::function<void(vtkVolumeProperty*)> Configure;
};

// The probe that rendered the case (its messages) and its image.
std::unique_ptr<Probe> Render(MapperKind kind, const Case& c, std::vector<float>& image)
{
  auto probe = std::make_unique<Probe>(kind, Volume());
  const double bounds[6] = { 0, 11, 0, 11, 0, 11 };
  probe->LookAt(bounds, 2, 20, 15);
  probe->Mapper->SetBlendMode(c.Blend);
  if (c.Configure)
  {
    c.Configure(probe->Volume->GetProperty());
  }
  image = probe->Render();
  return probe;
}

// Renders the case; the centre must be `expected` (background when null) and the mapper quiet.
bool Expect(MapperKind kind, const Case& c, const double* expected)
{
  std::vector<float> image;
  const std::unique_ptr<Probe> probe = Render(kind, c, image);
  const std::string what = probe->Name(c.Name);
  bool ok = CheckNoMessage(probe->Errors, what + ": no error");
  ok = CheckNoMessage(probe->Warnings, what + ": no warning") && ok;
  if (!expected)
  {
    ok = CheckBackground(image, what + ": background") && ok;
  }
  else
  {
    ok = CheckCentre(image, 40, expected, 2 * OneLevel, what + ": centre colour") && ok;
  }
  return ok;
}

void Colours(vtkVolumeProperty* property)
{
  vtkNew<vtkColorTransferFunction> colours;
  colours->AddRGBPoint(0, 0.2, 0.9, 0.3);
  colours->AddRGBPoint(200, 1.0, 0.6, 0.1);
  property->SetColor(colours);
}

void Opacity(vtkVolumeProperty* property, std::vector<std::pair<double, double>> points)
{
  vtkNew<vtkPiecewiseFunction> opacity;
  for (const auto& p : points)
  {
    opacity->AddPoint(p.first, p.second);
  }
  property->SetScalarOpacity(opacity);
}

bool Cases(MapperKind kind)
{
  bool ok = true;
  const bool shearWarp = kind == MapperKind::ShearWarp;
  for (int blend : { vtkVolumeMapper::COMPOSITE_BLEND, vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND,
         vtkVolumeMapper::MINIMUM_INTENSITY_BLEND })
  {
    const std::string name = blend == 0 ? "composite" : (blend == 1 ? "MIP" : "MinIP");
    ok = Expect(kind,
           { "no opacity points, " + name, blend,
             [](vtkVolumeProperty* p)
             {
               Colours(p);
               Opacity(p, {});
             } },
           nullptr) &&
      ok;
    ok = Expect(kind,
           { "all-zero opacity, " + name, blend,
             [](vtkVolumeProperty* p)
             {
               Colours(p);
               Opacity(p, { { 0, 0 }, { 100, 0 }, { 200, 0 } });
             } },
           nullptr) &&
      ok;
  }
  const double outer[3] = { 0.2, 0.9, 0.3 };
  const double block[3] = { 1.0, 0.6, 0.1 };
  const double black[3] = { 0, 0, 0 };
  ok = Expect(kind,
         { "one opacity point (1 at 50), composite", vtkVolumeMapper::COMPOSITE_BLEND,
           [](vtkVolumeProperty* p)
           {
             Colours(p);
             Opacity(p, { { 50, 1 } });
           } },
         outer) &&
    ok;
  ok = Expect(kind,
         { "one opacity point (1 at 50), MIP", vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND,
           [](vtkVolumeProperty* p)
           {
             Colours(p);
             Opacity(p, { { 50, 1 } });
           } },
         block) &&
    ok;
  ok = Expect(kind,
         { "no colour points, composite", vtkVolumeMapper::COMPOSITE_BLEND,
           [](vtkVolumeProperty* p)
           {
             vtkNew<vtkColorTransferFunction> none;
             p->SetColor(none);
             Opacity(p, { { 0, 1 }, { 200, 1 } });
           } },
         black) &&
    ok;
  ok = Expect(kind,
         { "gradient opacity with no points, composite", vtkVolumeMapper::COMPOSITE_BLEND,
           [](vtkVolumeProperty* p)
           {
             Colours(p);
             Opacity(p, { { 0, 1 }, { 200, 1 } });
             vtkNew<vtkPiecewiseFunction> none;
             p->SetGradientOpacity(none);
           } },
         nullptr) &&
    ok;
  const double grey = 200.0 / 1024.0;
  const double defaultGrey[3] = { grey, grey, grey };
  ok = Expect(kind, { "default property, MIP", vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND, nullptr },
         defaultGrey) &&
    ok;
  if (!shearWarp)
  {
    for (int blend : { vtkVolumeMapper::ADDITIVE_BLEND, vtkVolumeMapper::AVERAGE_INTENSITY_BLEND })
    {
      ok = Expect(kind,
             { std::string("all-zero opacity, ") +
                 (blend == vtkVolumeMapper::ADDITIVE_BLEND ? "additive" : "average"),
               blend,
               [](vtkVolumeProperty* p)
               {
                 Colours(p);
                 Opacity(p, { { 0, 0 }, { 200, 0 } });
               } },
             black) &&
        ok;
    }
  }

  // TF_2D without a 2D function.
  const auto configure = [](vtkVolumeProperty* p)
  {
    Colours(p);
    Opacity(p, { { 0, 0 }, { 200, 0.8 } });
  };
  std::vector<float> expected;
  Render(kind, { "TF_1D", vtkVolumeMapper::COMPOSITE_BLEND, configure }, expected);
  std::vector<float> image;
  const std::unique_ptr<Probe> twoD = Render(kind,
    { "TF_2D", vtkVolumeMapper::COMPOSITE_BLEND,
      [&configure](vtkVolumeProperty* p)
      {
        configure(p);
        p->SetTransferFunctionMode(vtkVolumeProperty::TF_2D);
      } },
    image);
  const std::string what = twoD->Name("TF_2D without a 2D function");
  if (kind == MapperKind::Slice)
  {
    ok = CheckMessage(twoD->Errors, "SetTransferFunction2D", what + ": error") && ok;
    ok = CheckBackground(image, what + ": background") && ok;
  }
  else
  {
    ok = CheckNoMessage(twoD->Errors, what + ": no error") && ok;
    ok = CheckMessage(twoD->Warnings, "2D transfer functions", what + ": warning") && ok;
    ok = CheckImage(image, expected, 0, what + ": the TF_1D image") && ok;
  }
  return ok;
}
}

int TestAccelVolumeBadTransferFunctions(int, char*[])
{
  bool ok = true;
  for (MapperKind kind : AllMappers)
  {
    ok = Cases(kind) && ok;
  }
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
