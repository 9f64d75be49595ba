// Numeric agreement of the shear-warp mapper's pictures with the CPU ray caster
// (vtkAccelVolumeRayCastMapper, fine samples) on the same parallel scenes, and with the CPU
// reference oracle for MIP and MinIP: composite unshaded, composite shaded (lookup-table and
// per-voxel Phong shading), MIP and MinIP, on smooth procedural volumes.
//
// Shear-warp is not expected to match a ray caster exactly. Its differences, all bounded:
//  - pre-classification: colour, opacity and shading are evaluated per voxel and the classified
//    values are resampled, where the ray casters classify the interpolated scalar
//    (post-classification); on a smooth volume this differs by a few grey levels, most at steep
//    transfer-function slopes and silhouettes;
//  - one sample per slice, resampled bilinearly within the slice (no interpolation across
//    slices), with the opacity corrected for the slice-to-slice ray length;
//  - the intermediate image has one pixel per voxel and is warped bilinearly into the window,
//    which blurs features smaller than a voxel and shifts edges by up to half a pixel.
// MIP / MinIP: the extreme of bilinear in-slice samples at the slices differs from the extreme
// of trilinear samples along the ray by the curvature of the field between slices.
//
// The extra shear-warp error concentrates on silhouettes: edges of the volume that are
// diagonal in the intermediate image (formed by the sheared stack of slice footprints) come out
// as a staircase one voxel high, and every silhouette gets a one-pixel fringe from the bilinear
// warp; inside, the pictures agree within a few grey levels.
//
// Measured (llvmpipe / 2 cores, OSMesa; the CPU mappers' images do not depend on the GL backend
// or the thread count), 200x200 windows, mean |diff| per channel over the whole window and the
// fraction of pixels differing by more than 24/255 (vs the ray caster, sample distance 0.1) or
// 16/255 (vs the CPU reference, step 0.05):
//   case                        vs ray caster: mean, fraction   vs CPU reference: mean, fraction
//   composite unshaded          0.00255, 0.0033                 -
//   composite shaded (table)    0.00140, 0.00055                -
//   composite shaded (Phong)    0.00140, 0.00055                -
//   composite, 45-degree view   0.00208, 0.0043                 -
//   MIP blobs                   0.00071, 0.0008                 0.00079, 0.0023
//   MIP waves                   0.00128, 0.0029                 0.00157, 0.0058
//   MinIP waves                 0.00275, 0.0155                 0.00312, 0.0198
// (MinIP shows the staircase most: its colours are nearly opaque up to the silhouette.) The
// limits in `cases` are about 2.5x these: the method's own error passes, and the sensitivity
// checks at the end show that real errors fail (measured: composite shifted one pixel 0.0042,
// 0.0143; opacity unit distance halved 0.0096, 0.074; MIP waves shifted two pixels 0.0046;
// MinIP waves shifted two pixels 0.0073).
#include "AccelVolumeTestScene.h"
#include "vtkAccelVolumeShearWarpMapper.h"

#include "vtkMath.h"

#include <cmath>
#include <cstdlib>
#include <string>

namespace
{
using namespace accelvolume_test;
constexpr int Size = 200;

// A smooth field over the whole volume in [100, 900]: sums of low-frequency sines, so MIP and
// MinIP vary everywhere (no flat background) and every derivative is bounded.
vtkSmartPointer<vtkImageData> MakeWaves(int nx, int ny, int nz, double sz)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(nx, ny, nz);
  image->SetSpacing(1.0, 1.0, sz);
  vtkNew<vtkFloatArray> scalars;
  scalars->SetName("scalars");
  scalars->SetNumberOfValues(static_cast<vtkIdType>(nx) * ny * nz);
  constexpr double Pi = 3.14159265358979323846;
  vtkIdType index = 0;
  for (int k = 0; k < nz; ++k)
  {
    for (int j = 0; j < ny; ++j)
    {
      for (int i = 0; i < nx; ++i)
      {
        const double x = static_cast<double>(i) / (nx - 1);
        const double y = static_cast<double>(j) / (ny - 1);
        const double z = static_cast<double>(k) / (nz - 1);
        const double value = 500.0 +
          150.0 * std::sin(2 * Pi * (1.1 * x + 0.3 * y) + 0.4) * std::cos(2 * Pi * 0.8 * z) +
          150.0 * std::cos(2 * Pi * (0.7 * y - 0.5 * z) + 1.0) * std::sin(Pi * x + 0.3) +
          100.0 * std::sin(2 * Pi * (0.6 * x + 0.9 * z)) * std::sin(2 * Pi * 0.5 * y + 0.7);
        scalars->SetValue(index++, static_cast<float>(value));
      }
    }
  }
  image->GetPointData()->SetScalars(scalars);
  return image;
}

struct Case
{
  const char* Name;
  int Blend;
  const char* Volume; // "blobs" (phantom) or "waves" (above)
  bool Shade;
  int ShadingMode;
  double Azimuth, Elevation;
  // Limits against the ray caster: mean |diff| per channel, fraction of pixels over 24/255.
  double MeanLimit, FractionLimit;
  // Against the CPU reference (MIP / MinIP only; < 0: not compared): mean, fraction over 16/255.
  double ReferenceMeanLimit, ReferenceFractionLimit;
};

vtkSmartPointer<vtkVolume> MakeVolume(vtkVolumeMapper* mapper, vtkImageData* image, const Case& c)
{
  mapper->SetInputData(image);
  mapper->SetBlendMode(c.Blend);
  auto volume = vtkSmartPointer<vtkVolume>::New();
  volume->SetMapper(mapper);
  vtkVolumeProperty* property = volume->GetProperty();
  if (c.Blend == vtkVolumeMapper::MINIMUM_INTENSITY_BLEND)
  {
    // Opaque over the values the minimum runs through ([100, 500]), colour ramp over them.
    vtkNew<vtkColorTransferFunction> colours;
    colours->AddRGBPoint(100.0, 1.0, 0.9, 0.6);
    colours->AddRGBPoint(500.0, 0.1, 0.2, 0.6);
    vtkNew<vtkPiecewiseFunction> opacity;
    opacity->AddPoint(100.0, 1.0);
    opacity->AddPoint(500.0, 0.4);
    property->SetColor(colours);
    property->SetScalarOpacity(opacity);
    property->SetInterpolationTypeToLinear();
  }
  else if (std::string(c.Volume) == "waves")
  {
    SetRampProperty(property, 450.0, 950.0, true);
  }
  else if (c.Blend == vtkVolumeMapper::COMPOSITE_BLEND)
  {
    // Opaque enough that the blobs' insides and the shading dominate the picture.
    SetRampProperty(property, 60.0, 450.0, true);
  }
  else
  {
    SetRampProperty(property, 40.0, 900.0, true);
  }
  property->SetShade(c.Shade);
  property->SetAmbient(0.2);
  property->SetDiffuse(0.7);
  property->SetSpecular(0.3);
  property->SetSpecularPower(12.0);
  property->SetScalarOpacityUnitDistance(2.0);
  return volume;
}

// Deliberate errors for the sensitivity check: the camera moved sideways by pixelShift pixels,
// the opacity unit distance scaled.
struct Perturbation
{
  double PixelShift = 0;
  double OpacityUnitScale = 1;
};

std::vector<float> RenderWith(vtkVolumeMapper* mapper, vtkImageData* image, const Case& c,
  std::vector<float>* reference = nullptr, const Perturbation& perturbation = Perturbation())
{
  auto volume = MakeVolume(mapper, image, c);
  volume->GetProperty()->SetScalarOpacityUnitDistance(
    volume->GetProperty()->GetScalarOpacityUnitDistance() * perturbation.OpacityUnitScale);
  vtkNew<vtkRenderer> renderer;
  renderer->AddVolume(volume);
  vtkNew<vtkRenderWindow> window;
  SetupObliqueView(window, renderer, Size, c.Azimuth, c.Elevation, false);
  if (perturbation.PixelShift != 0)
  {
    vtkCamera* camera = renderer->GetActiveCamera();
    double direction[3], up[3], right[3], position[3], focal[3];
    camera->GetDirectionOfProjection(direction);
    camera->GetViewUp(up);
    vtkMath::Cross(direction, up, right);
    vtkMath::Normalize(right);
    const double step = perturbation.PixelShift * 2.0 * camera->GetParallelScale() / Size;
    camera->GetPosition(position);
    camera->GetFocalPoint(focal);
    for (int a = 0; a < 3; ++a)
    {
      position[a] += step * right[a];
      focal[a] += step * right[a];
    }
    camera->SetPosition(position);
    camera->SetFocalPoint(focal);
  }
  window->Render();
  if (reference)
  {
    ReferenceSettings settings;
    settings.blendMode = c.Blend;
    settings.stepWorld = 0.05;
    *reference = RenderReferenceImage(image, volume, renderer, Size, Size, settings);
  }
  return ReadPixels(window);
}
}

int TestAccelVolumeShearWarpAgreement(int, char*[])
{
  constexpr int MIP = vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND;
  constexpr int MinIP = vtkVolumeMapper::MINIMUM_INTENSITY_BLEND;
  constexpr int Composite = vtkVolumeMapper::COMPOSITE_BLEND;
  constexpr int Table = vtkAccelVolumeShearWarpMapper::SHADING_LOOKUP_TABLE;
  constexpr int Phong = vtkAccelVolumeShearWarpMapper::SHADING_PHONG;
  const Case cases[] = {
    { "composite unshaded", Composite, "blobs", false, Table, 40, -20, 0.0065, 0.009, -1, -1 },
    { "composite shaded (table)", Composite, "blobs", true, Table, 40, -20, 0.0035, 0.0015, -1,
      -1 },
    { "composite shaded (Phong)", Composite, "blobs", true, Phong, 40, -20, 0.0035, 0.0015, -1,
      -1 },
    { "composite, 45-degree view", Composite, "blobs", false, Table, 45, 35, 0.0055, 0.011, -1,
      -1 },
    { "MIP blobs", MIP, "blobs", false, Table, 40, -20, 0.002, 0.002, 0.002, 0.006 },
    { "MIP waves", MIP, "waves", false, Table, 30, 25, 0.0032, 0.0075, 0.004, 0.015 },
    { "MinIP waves", MinIP, "waves", false, Table, -35, 15, 0.007, 0.04, 0.008, 0.05 },
  };
  bool ok = true;
  for (const Case& c : cases)
  {
    auto image = std::string(c.Volume) == "waves" ? MakeWaves(48, 40, 36, 1.25)
                                                  : MakePhantom(c.Volume, 48, 40, 36, 1.0, 1.0, 1.25);
    vtkNew<vtkAccelVolumeShearWarpMapper> shearWarp;
    shearWarp->SetShadingMode(c.ShadingMode);
    vtkNew<accelvolume_test::ErrorRecorder> errors;
    shearWarp->AddObserver(vtkCommand::ErrorEvent, errors);
    std::vector<float> reference;
    const bool projection = c.ReferenceMeanLimit >= 0;
    const std::vector<float> ours = RenderWith(shearWarp, image, c, projection ? &reference : nullptr);
    if (errors->Count > 0)
    {
      std::cout << c.Name << ": the shear-warp mapper reported " << errors->Messages << "  FAILED\n";
      ok = false;
      continue;
    }
    auto rayCast = vtkSmartPointer<vtkAccelVolumeRayCastMapper>::New();
    rayCast->SetAutoAdjustSampleDistances(0);
    rayCast->SetSampleDistance(0.1);
    const std::vector<float> rayCastImage = RenderWith(rayCast, image, c);
    DumpImage(std::string("shearwarp_") + c.Name, ours, Size, Size);
    DumpImage(std::string("shearwarp_raycast_") + c.Name, rayCastImage, Size, Size);
    ok = Report((std::string("shear-warp vs ray caster, ") + c.Name).c_str(),
           CompareImages(ours, rayCastImage, 24.0 / 255.0), c.MeanLimit, c.FractionLimit) &&
      ok;
    if (projection)
    {
      DumpImage(std::string("shearwarp_reference_") + c.Name, reference, Size, Size);
      ok = Report((std::string("shear-warp vs CPU reference, ") + c.Name).c_str(),
             CompareImages(ours, reference, 16.0 / 255.0), c.ReferenceMeanLimit,
             c.ReferenceFractionLimit) &&
        ok;
    }
  }
  // Sensitivity: the limits must catch real errors. A shear-warp picture shifted sideways (one
  // pixel for composite; two for MIP / MinIP, whose error is dominated by the silhouettes'
  // staircase, so that a one-pixel shift in their smooth insides only doubles the mean) or with
  // the opacity unit distance halved has to fail the bounds of its case.
  struct Sensitivity
  {
    const char* Name;
    int CaseIndex;
    Perturbation Error;
  };
  Perturbation shifted;
  shifted.PixelShift = 1.0;
  Perturbation shiftedTwo;
  shiftedTwo.PixelShift = 2.0;
  Perturbation opacity;
  opacity.OpacityUnitScale = 0.5;
  const Sensitivity checks[] = {
    { "composite unshaded, shifted one pixel", 0, shifted },
    { "composite unshaded, opacity unit distance halved", 0, opacity },
    { "MIP waves, shifted two pixels", 5, shiftedTwo },
    { "MinIP waves, shifted two pixels", 6, shiftedTwo },
  };
  for (const Sensitivity& check : checks)
  {
    const Case& c = cases[check.CaseIndex];
    auto image = std::string(c.Volume) == "waves" ? MakeWaves(48, 40, 36, 1.25)
                                                  : MakePhantom(c.Volume, 48, 40, 36, 1.0, 1.0, 1.25);
    vtkNew<vtkAccelVolumeShearWarpMapper> shearWarp;
    const std::vector<float> wrong = RenderWith(shearWarp, image, c, nullptr, check.Error);
    auto rayCast = vtkSmartPointer<vtkAccelVolumeRayCastMapper>::New();
    rayCast->SetAutoAdjustSampleDistances(0);
    rayCast->SetSampleDistance(0.1);
    const std::vector<float> rayCastImage = RenderWith(rayCast, image, c);
    const ImageDifference d = CompareImages(wrong, rayCastImage, 24.0 / 255.0);
    const bool caught = d.mean > c.MeanLimit || d.fractionAbove > c.FractionLimit;
    std::cout << "sensitivity, " << check.Name << ": mean |diff| " << d.mean << " (limit "
              << c.MeanLimit << "), fraction over threshold " << d.fractionAbove << " (limit "
              << c.FractionLimit << ")" << (caught ? ": caught" : ": NOT CAUGHT  FAILED") << "\n";
    ok = caught && ok;
  }
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
