// Drop-in semantics against vtkGPUVolumeRayCastMapper on the same scene (issue 16): VTK's light
// model (a vtkLightKit's five coloured lights, a positional spot light with attenuation, two-
// sided lighting off), gradient opacity in VTK's units on anisotropic spacing, and raysum as VTK's
// per-sample sum at a sample distance other than the voxel spacing. The slice mapper and the ray
// caster must give VTK's picture within the bound each case states (mean |difference| <= 4 grey
// levels, <= 3% of pixels off by more than 16). Specular is off in the VTK
// comparisons: VTK 9.1's GPU shader keeps only the last light's highlight and takes its half
// vector from a negated sample position (see vtkAccelVolumeSliceMapper's documentation); the
// highlights are compared between our two mappers instead, which share one light model.
#include "AccelVolumeTestUtilities.h"
#include "vtkAccelVolumeRayCastMapper.h"
#include "vtkAccelVolumeSliceMapper.h"
#include "vtkColorTransferFunction.h"
#include "vtkContourValues.h"
#include "vtkGPUVolumeRayCastMapper.h"
#include "vtkLight.h"
#include "vtkLightKit.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPlane.h"
#include "vtkPointData.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <string>

namespace
{
constexpr int Size = 200;

struct Case
{
  const char* Name;
  int Blend;
  double ZSpacing;
  double SampleDistance;
  std::function<void(vtkRenderer*, vtkVolumeProperty*)> Configure;
  double MeanLimit;     // mean |difference| allowed, per channel
  double FractionLimit; // of pixels differing by more than 16 grey levels
};

std::vector<float> RenderWith(vtkVolumeMapper* mapper, const Case& c)
{
  auto image = accelvolume_test::MakePhantom("blobs", 48, 40, 36, 1.0, 1.0, c.ZSpacing);
  mapper->SetInputData(image);
  mapper->SetBlendMode(c.Blend);
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  accelvolume_test::SetRampProperty(volume->GetProperty(), 40.0, 900.0, true);
  vtkNew<vtkRenderer> renderer;
  renderer->AddVolume(volume);
  vtkNew<vtkRenderWindow> window;
  accelvolume_test::SetupObliqueView(window, renderer, Size, 35, -25, true);
  if (c.Configure)
  {
    c.Configure(renderer, volume->GetProperty());
  }
  window->Render();
  return accelvolume_test::ReadPixels(window);
}

template <typename MapperType>
vtkSmartPointer<MapperType> Fixed(double sampleDistance)
{
  auto mapper = vtkSmartPointer<MapperType>::New();
  mapper->SetAutoAdjustSampleDistances(0);
  mapper->SetSampleDistance(sampleDistance);
  return mapper;
}

void Shaded(vtkVolumeProperty* property, double specular)
{
  property->ShadeOn();
  property->SetAmbient(0.2);
  property->SetDiffuse(0.8);
  property->SetSpecular(specular);
  property->SetSpecularPower(20.0);
}

// An oblique plane through the volume, every value somewhat opaque (the whole section shows).
void SlicePlaneProperty(vtkVolumeProperty* property)
{
  vtkNew<vtkPlane> plane;
  plane->SetOrigin(24.0, 20.0, 22.0);
  plane->SetNormal(1.0, 0.6, 0.4);
  property->SetSliceFunction(plane);
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0.0, 0.5);
  opacity->AddPoint(1000.0, 1.0);
  property->SetScalarOpacity(opacity);
}

void LightKit(vtkRenderer* renderer)
{
  vtkNew<vtkLightKit> kit;
  kit->SetKeyLightWarmth(0.75); // coloured lights: every light's colour counts
  kit->SetFillLightWarmth(0.3);
  kit->AddLightsToRenderer(renderer);
}

void SpotLight(vtkRenderer* renderer)
{
  vtkNew<vtkLight> spot;
  spot->SetLightTypeToSceneLight();
  spot->SetPositional(1);
  spot->SetPosition(90, 80, 70);
  spot->SetFocalPoint(24, 20, 22);
  spot->SetConeAngle(25);
  spot->SetExponent(2);
  spot->SetAttenuationValues(0.5, 0.004, 0.0);
  spot->SetDiffuseColor(1.0, 0.9, 0.7);
  renderer->AddLight(spot);
  renderer->TwoSidedLightingOff();
}
}

// Multi-component scalars (the slice mapper and the ray caster vs VTK's GPU mapper): independent
// components with their own functions and weights, dependent luminance-alpha and RGBA.
vtkSmartPointer<vtkImageData> Components(int components, bool unsignedChar, bool equal = false)
{
  auto a = accelvolume_test::MakePhantom("blobs", 48, 40, 36, 1.0, 1.0, 1.25);
  auto b = accelvolume_test::MakePhantom("vessels", 48, 40, 36, 1.0, 1.0, 1.25);
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->CopyStructure(a);
  image->AllocateScalars(unsignedChar ? VTK_UNSIGNED_CHAR : VTK_FLOAT, components);
  vtkDataArray* out = image->GetPointData()->GetScalars();
  vtkDataArray* va = a->GetPointData()->GetScalars();
  vtkDataArray* vb = b->GetPointData()->GetScalars();
  double ra[2];
  double rb[2];
  va->GetRange(ra);
  vb->GetRange(rb);
  for (vtkIdType i = 0; i < image->GetNumberOfPoints(); ++i)
  {
    const double x = (va->GetComponent(i, 0) - ra[0]) / (ra[1] - ra[0]);
    const double y = (vb->GetComponent(i, 0) - rb[0]) / (rb[1] - rb[0]);
    // Component 2 spans half the range: RGBA colours are not normalised to it (VTK).
    const double values[4] = { x, equal ? x : y, 0.5 * (1.0 - x), std::max(x, y) };
    for (int c = 0; c < components; ++c)
    {
      out->SetComponent(
        i, c, unsignedChar ? std::floor(255.0 * values[c] + 0.5) : 1000.0 * values[c]);
    }
  }
  return image;
}

double Mean(const std::vector<float>& pixels)
{
  double sum = 0.0;
  for (float value : pixels)
  {
    sum += value;
  }
  return pixels.empty() ? 0.0 : sum / pixels.size();
}

struct MultiCase
{
  const char* Name;
  int Components;
  bool Independent;
  bool UnsignedChar;
  int Blend = vtkVolumeMapper::COMPOSITE_BLEND;
  bool GradientOpacity = false;
  bool Shaded = false;  // each component with its own ambient and diffuse coefficients
  double Weight1 = 0.5; // component 1's weight
};

// One multi-component frame. `mirrored`: every function point x moves to top - x (for data
// mirrored the same way, which VTK's per-component ranges map onto 1 - the normalised value).
// `lowOpaque`: opacity falls with the value (MinIP pictures that are not empty).
std::vector<float> RenderComponents(const MultiCase& m, vtkImageData* image,
  vtkVolumeMapper* mapper, int blend, bool mirrored, bool lowOpaque)
{
  mapper->SetInputData(image);
  mapper->SetBlendMode(blend);
  const double top = m.UnsignedChar ? 255.0 : 1000.0;
  // Averages over the bright samples only: a picture, and a test of the range.
  mapper->SetAverageIPScalarRange(0.3 * top, 2.0 * top);
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  vtkVolumeProperty* property = volume->GetProperty();
  property->SetIndependentComponents(m.Independent);
  const auto at = [&](double x) { return mirrored ? top - x : x; };
  for (int c = 0; c < (m.Independent ? m.Components : 1); ++c)
  {
    vtkNew<vtkColorTransferFunction> colours;
    colours->AddRGBPoint(at(0.0), c == 0 ? 1.0 : 0.1, 0.2, c == 0 ? 0.1 : 1.0);
    colours->AddRGBPoint(at(top), 1.0, c == 0 ? 0.9 : 0.4, 0.6);
    vtkNew<vtkPiecewiseFunction> opacity;
    if (lowOpaque)
    {
      opacity->AddPoint(at(0.0), c == 0 ? 0.8 : 0.6);
      opacity->AddPoint(at(0.7 * top), 0.05);
    }
    else if (blend == vtkVolumeMapper::SLICE_BLEND)
    {
      // The whole section shows (most of a plane through the phantom is dark).
      opacity->AddPoint(at(0.0), c == 0 ? 0.5 : 0.3);
      opacity->AddPoint(at(top), 1.0);
    }
    else
    {
      opacity->AddPoint(at(0.15 * top), 0.0);
      opacity->AddPoint(at(top), c == 0 ? 0.6 : 0.9);
    }
    property->SetColor(c, colours);
    property->SetScalarOpacity(c, opacity);
    if (m.Shaded)
    {
      property->ShadeOn();
      property->SetAmbient(c, c == 0 ? 0.1 : 0.5);
      property->SetDiffuse(c, c == 0 ? 0.9 : 0.4);
      property->SetSpecular(c, 0.0); // VTK's highlights differ on purpose (file comment)
    }
    if (m.GradientOpacity)
    {
      // VTK's units: data values per mean voxel step, table over [0, range / 4].
      vtkNew<vtkPiecewiseFunction> gradient;
      gradient->AddPoint(0.0, c == 0 ? 0.05 : 0.2);
      gradient->AddPoint(0.06 * top, 1.0);
      property->SetGradientOpacity(c, gradient);
    }
  }
  property->SetComponentWeight(1, m.Weight1);
  vtkNew<vtkPlane> plane;
  plane->SetOrigin(24.0, 20.0, 22.0);
  plane->SetNormal(1.0, 0.6, 0.4);
  property->SetSliceFunction(plane);
  // Iso-surfaces (of the component of the largest weight).
  property->GetIsoSurfaceValues()->SetValue(0, 0.35 * top);
  property->GetIsoSurfaceValues()->SetValue(1, 0.6 * top);
  property->SetInterpolationTypeToLinear();
  vtkNew<vtkRenderer> renderer;
  renderer->AddVolume(volume);
  vtkNew<vtkRenderWindow> window;
  accelvolume_test::SetupObliqueView(window, renderer, Size, 35, -25, true);
  window->Render();
  return accelvolume_test::ReadPixels(window);
}

bool MultiComponent()
{
  const MultiCase cases[] = { { "composite, 2 independent components", 2, true, false },
    { "composite, dependent luminance-alpha", 2, false, false },
    { "composite, dependent RGBA", 4, false, true },
    { "composite, 2 independent components, gradient opacity", 2, true, false,
      vtkVolumeMapper::COMPOSITE_BLEND, true },
    { "composite, 2 independent components, shaded with their own coefficients", 2, true, false,
      vtkVolumeMapper::COMPOSITE_BLEND, false, true },
    { "iso-surfaces of component 1 (the larger weight), shaded", 2, true, false,
      vtkVolumeMapper::ISOSURFACE_BLEND, false, true, 2.0 },
    { "iso-surfaces of component 0, 3 independent components", 3, true, true,
      vtkVolumeMapper::ISOSURFACE_BLEND },
    { "iso-surfaces, dependent luminance-alpha", 2, false, false,
      vtkVolumeMapper::ISOSURFACE_BLEND },
    { "iso-surfaces, dependent RGBA", 4, false, true, vtkVolumeMapper::ISOSURFACE_BLEND },
    { "slice plane, dependent luminance-alpha", 2, false, false, vtkVolumeMapper::SLICE_BLEND },
    { "slice plane, dependent RGBA", 4, false, true, vtkVolumeMapper::SLICE_BLEND },
    // VTK 9.1's shader does not compile for independent slices: our two mappers compared.
    { "slice plane, 2 independent components, shaded", 2, true, false, vtkVolumeMapper::SLICE_BLEND,
      false, true },
    { "composite, dependent luminance-alpha, gradient opacity", 2, false, false,
      vtkVolumeMapper::COMPOSITE_BLEND, true },
    { "composite, dependent RGBA, gradient opacity", 4, false, true,
      vtkVolumeMapper::COMPOSITE_BLEND, true },
    { "raysum, 2 independent components", 2, true, false, vtkVolumeMapper::ADDITIVE_BLEND },
    { "raysum, dependent RGBA", 4, false, true, vtkVolumeMapper::ADDITIVE_BLEND },
    { "average, dependent RGBA", 4, false, true, vtkVolumeMapper::AVERAGE_INTENSITY_BLEND },
    { "average, 2 independent components", 2, true, false,
      vtkVolumeMapper::AVERAGE_INTENSITY_BLEND },
    { "average, 4 independent components", 4, true, false,
      vtkVolumeMapper::AVERAGE_INTENSITY_BLEND },
    { "MIP, 2 independent components", 2, true, false, vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND },
    { "MIP, 3 independent components", 3, true, true, vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND },
    { "MIP, dependent RGBA", 4, false, true, vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND },
    { "MinIP, dependent RGBA", 4, false, true, vtkVolumeMapper::MINIMUM_INTENSITY_BLEND } };
  bool ok = true;
  for (const MultiCase& m : cases)
  {
    auto image = Components(m.Components, m.UnsignedChar);
    const bool lowOpaque = m.Blend == vtkVolumeMapper::MINIMUM_INTENSITY_BLEND;
    const std::vector<float> slice =
      RenderComponents(m, image, Fixed<vtkAccelVolumeSliceMapper>(0.5), m.Blend, false, lowOpaque);
    const std::vector<float> rays = RenderComponents(
      m, image, Fixed<vtkAccelVolumeRayCastMapper>(0.5), m.Blend, false, lowOpaque);
    const bool vtkDraws = !(m.Blend == vtkVolumeMapper::SLICE_BLEND && m.Independent);
    const std::vector<float> reference = vtkDraws
      ? RenderComponents(m, image, Fixed<vtkGPUVolumeRayCastMapper>(0.5), m.Blend, false, lowOpaque)
      : slice;
    const std::string peer = vtkDraws ? "vtkGPUVolumeRayCastMapper" : "the slice mapper";
    const std::string tag = std::string("multi_") + std::to_string(m.Components) +
      (m.Independent ? "i" : "d") + std::to_string(m.Blend) + (m.GradientOpacity ? "g" : "") +
      (m.Shaded ? "s" : "");
    if (Mean(reference) < 1.0 / 255.0)
    {
      std::cerr << m.Name << ": the reference picture is (almost) empty, the case proves nothing\n";
      ok = false;
    }
    accelvolume_test::DumpImage(tag + "_vtk", reference, Size, Size);
    accelvolume_test::DumpImage(tag + "_slice", slice, Size, Size);
    accelvolume_test::DumpImage(tag + "_raycast", rays, Size, Size);
    if (vtkDraws)
    {
      ok = accelvolume_test::Report(
             (std::string("slice vs vtkGPUVolumeRayCastMapper, ") + m.Name).c_str(),
             accelvolume_test::CompareImages(slice, reference, 16.0 / 255.0), 4.0 / 255.0, 0.03) &&
        ok;
    }
    ok = accelvolume_test::Report(("ray caster vs " + peer + ", " + m.Name).c_str(),
           accelvolume_test::CompareImages(rays, reference, 16.0 / 255.0), 4.0 / 255.0, 0.03) &&
      ok;
  }
  return ok;
}

// Dependent luminance-alpha MIP / MinIP keep the sample whose alpha (component 1) is extreme.
// VTK 9.1's GPU mapper tests the texture's w there, which is 1 for a two-channel texture, so it
// keeps the first sample of the ray: not compared. Identity instead: with both components equal
// the kept sample is the single-component extreme, compared with VTK's single-component MIP /
// MinIP of that component under the same functions.
bool DependentLuminanceAlphaExtremes()
{
  bool ok = true;
  const MultiCase single = { "", 1, true, false };
  const MultiCase pair = { "", 2, false, false };
  auto one = Components(1, false);
  auto two = Components(2, false, true);
  for (int blend :
    { vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND, vtkVolumeMapper::MINIMUM_INTENSITY_BLEND })
  {
    const bool low = blend == vtkVolumeMapper::MINIMUM_INTENSITY_BLEND;
    const std::vector<float> reference =
      RenderComponents(single, one, Fixed<vtkGPUVolumeRayCastMapper>(0.5), blend, false, low);
    const std::vector<float> slice =
      RenderComponents(pair, two, Fixed<vtkAccelVolumeSliceMapper>(0.5), blend, false, low);
    const std::string name = std::string("slice, ") +
      (blend == vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND ? "MIP" : "MinIP") +
      " of luminance-alpha with equal components vs VTK's one-component picture";
    ok = accelvolume_test::Report(name.c_str(),
           accelvolume_test::CompareImages(slice, reference, 16.0 / 255.0), 2.0 / 255.0, 0.01) &&
      ok;
  }
  return ok;
}

// Multi-component octree skipping: dependent components by the octree of their opacity
// component, independent ones where every component of non-zero weight is transparent. The
// picture must stay that of no skipping (within 1/255, TestAccelVolumeEmptySpaceSkipping's
// bound) while leaves are actually skipped; a component of weight 0 does not keep leaves.
bool ComponentOctreeSkipping()
{
  bool ok = true;
  double bothWeighted = -1.0;
  double firstOnly = -1.0;
  for (const MultiCase& m : { MultiCase{ "dependent luminance-alpha", 2, false, false },
         MultiCase{ "dependent RGBA", 4, false, true },
         MultiCase{ "2 independent components", 2, true, false },
         MultiCase{ "3 independent components", 3, true, true },
         MultiCase{ "2 independent components, weight 1 = 0", 2, true, false,
           vtkVolumeMapper::COMPOSITE_BLEND, false, false, 0.0 },
         MultiCase{ "2 independent components, shaded", 2, true, false,
           vtkVolumeMapper::COMPOSITE_BLEND, false, true } })
  {
    auto image = Components(m.Components, m.UnsignedChar);
    auto skipping = Fixed<vtkAccelVolumeSliceMapper>(0.5);
    auto plain = Fixed<vtkAccelVolumeSliceMapper>(0.5);
    plain->SetEmptySpaceSkipping(vtkAccelVolumeSliceMapper::SKIP_NONE);
    // Early termination off, as TestAccelVolumeEmptySpaceSkipping: skipping alone is exact.
    skipping->SetEarlyRayTermination(false);
    plain->SetEarlyRayTermination(false);
    const std::vector<float> skipped =
      RenderComponents(m, image, skipping, vtkVolumeMapper::COMPOSITE_BLEND, false, false);
    const std::vector<float> reference =
      RenderComponents(m, image, plain, vtkVolumeMapper::COMPOSITE_BLEND, false, false);
    const double fraction = skipping->GetLastTransparentLeafFraction();
    const double area = skipping->GetLastProxyAreaFraction();
    const std::string name = std::string("slice, octree skipping of ") + m.Name +
      " = no skipping (transparent leaves " + std::to_string(fraction) + ", slice area kept " +
      std::to_string(area) + ")";
    const accelvolume_test::ImageDifference d =
      accelvolume_test::CompareImages(skipped, reference, 1.0 / 255.0);
    ok = accelvolume_test::Report(name.c_str(), d, 1.0 / 255.0, 0.0) && ok;
    // Component 2 (0.5 (1 - x), over its own range) is visible nearly everywhere: with it, no
    // leaf is transparent for all three, so nothing may be culled.
    const bool expectSkipped = m.Components != 3;
    if (Mean(reference) < 2.0 / 255.0 ||
      (expectSkipped ? !(fraction > 0.05) || !(area < 1.0) : fraction > 0.01))
    {
      std::cerr << "FAILED transparent leaves not as expected (or nothing drawn) for " << m.Name
                << "\n";
      ok = false;
    }
    if (m.Independent && m.Components == 2 && !m.Shaded)
    {
      (m.Weight1 > 0.0 ? bothWeighted : firstOnly) = fraction;
    }
  }
  if (!(firstOnly > bothWeighted))
  {
    std::cerr << "FAILED a component of weight 0 kept leaves: transparent fraction " << firstOnly
              << " with it unweighted, " << bothWeighted << " weighted\n";
    ok = false;
  }
  return ok;
}

// Independent MinIP is not compared with VTK 9.1's GPU mapper, whose shader keeps each
// component's maximum there and leaves alpha 0 (two slips in vtkVolumeShaderComposer.h). It is
// checked against an identity instead: the minimum of the data under functions f is the maximum
// of the mirrored data (top - value) under the mirrored functions f(top - x).
bool IndependentMinimumMirrorsMaximum()
{
  const MultiCase m = { "", 2, true, false };
  auto image = Components(m.Components, m.UnsignedChar);
  auto mirrored = vtkSmartPointer<vtkImageData>::New();
  mirrored->DeepCopy(image);
  vtkDataArray* values = mirrored->GetPointData()->GetScalars();
  for (vtkIdType i = 0; i < values->GetNumberOfTuples(); ++i)
  {
    for (int c = 0; c < m.Components; ++c)
    {
      values->SetComponent(i, c, 1000.0 - values->GetComponent(i, c));
    }
  }
  const std::vector<float> minimum = RenderComponents(m, image,
    Fixed<vtkAccelVolumeSliceMapper>(0.5), vtkVolumeMapper::MINIMUM_INTENSITY_BLEND, false, true);
  const std::vector<float> maximum = RenderComponents(m, mirrored,
    Fixed<vtkAccelVolumeSliceMapper>(0.5), vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND, true, true);
  if (Mean(minimum) < 2.0 / 255.0)
  {
    std::cerr << "independent MinIP drew (almost) nothing: the identity would prove nothing\n";
    return false;
  }
  return accelvolume_test::Report("slice, MinIP of 2 independent components = MIP of the mirror",
    accelvolume_test::CompareImages(minimum, maximum, 16.0 / 255.0), 1.0 / 255.0, 0.005);
}

int TestAccelVolumeVsGPURayCastFeatures(int, char*[])
{
  const Case cases[] = {
    { "composite, vtkLightKit (diffuse)", vtkVolumeMapper::COMPOSITE_BLEND, 1.25, 0.5,
      [](vtkRenderer* r, vtkVolumeProperty* p)
      {
        Shaded(p, 0.0);
        LightKit(r);
      },
      4.0 / 255.0, 0.03 },
    { "composite, positional spot light, one-sided", vtkVolumeMapper::COMPOSITE_BLEND, 1.25, 0.5,
      [](vtkRenderer* r, vtkVolumeProperty* p)
      {
        Shaded(p, 0.0);
        SpotLight(r);
      },
      4.0 / 255.0, 0.03 },
    { "composite, gradient opacity, spacing 1 x 1 x 2.5", vtkVolumeMapper::COMPOSITE_BLEND, 2.5,
      0.5,
      [](vtkRenderer*, vtkVolumeProperty* p)
      {
        vtkNew<vtkPiecewiseFunction> gradient;
        gradient->AddPoint(0, 0.0);
        gradient->AddPoint(60, 1.0);
        p->SetGradientOpacity(gradient);
      },
      4.0 / 255.0, 0.03 },
    { "raysum, sample distance 0.5", vtkVolumeMapper::ADDITIVE_BLEND, 1.25, 0.5, nullptr,
      4.0 / 255.0, 0.03 },
    { "isosurfaces 300 and 600, shaded (diffuse)", vtkVolumeMapper::ISOSURFACE_BLEND, 1.25, 0.5,
      [](vtkRenderer*, vtkVolumeProperty* p)
      {
        Shaded(p, 0.0);
        p->GetIsoSurfaceValues()->SetValue(0, 300.0);
        p->GetIsoSurfaceValues()->SetValue(1, 600.0);
      },
      4.0 / 255.0, 0.03 },
    // SLICE_BLEND: the property's plane, one classified sample per pixel (oblique plane).
    { "slice plane, unshaded", vtkVolumeMapper::SLICE_BLEND, 1.25, 0.5,
      [](vtkRenderer*, vtkVolumeProperty* p) { SlicePlaneProperty(p); }, 2.0 / 255.0, 0.01 },
    { "slice plane, shaded (diffuse)", vtkVolumeMapper::SLICE_BLEND, 1.25, 0.5,
      [](vtkRenderer*, vtkVolumeProperty* p)
      {
        Shaded(p, 0.0);
        SlicePlaneProperty(p);
      },
      4.0 / 255.0, 0.06 },
    // Thin voxels: a unit of one voxel spacing would saturate; VTK's unit is the property's.
    { "raysum, z spacing 0.3", vtkVolumeMapper::ADDITIVE_BLEND, 0.3, 0.25, nullptr, 4.0 / 255.0,
      0.03 },
  };
  bool ok = true;
  for (const Case& c : cases)
  {
    const std::vector<float> reference =
      RenderWith(Fixed<vtkGPUVolumeRayCastMapper>(c.SampleDistance), c);
    const std::vector<float> slice =
      RenderWith(Fixed<vtkAccelVolumeSliceMapper>(c.SampleDistance), c);
    const std::vector<float> rayCast =
      RenderWith(Fixed<vtkAccelVolumeRayCastMapper>(c.SampleDistance), c);
    const std::string name(c.Name);
    accelvolume_test::DumpImage("features_" + name.substr(0, 12) + "_vtk", reference, Size, Size);
    accelvolume_test::DumpImage("features_" + name.substr(0, 12) + "_slice", slice, Size, Size);
    accelvolume_test::DumpImage("features_" + name.substr(0, 12) + "_raycast", rayCast, Size, Size);
    ok = accelvolume_test::Report(("slice vs vtkGPUVolumeRayCastMapper, " + name).c_str(),
           accelvolume_test::CompareImages(slice, reference, 16.0 / 255.0), c.MeanLimit,
           c.FractionLimit) &&
      ok;
    ok = (accelvolume_test::Report(("ray cast vs vtkGPUVolumeRayCastMapper, " + name).c_str(),
           accelvolume_test::CompareImages(rayCast, reference, 16.0 / 255.0), c.MeanLimit,
           c.FractionLimit)) &&
      ok;
  }
  // Highlights: one light model in both of our mappers (VTK's has the quirks named above).
  const Case specular = { "composite, vtkLightKit with specular", vtkVolumeMapper::COMPOSITE_BLEND,
    1.25, 0.5,
    [](vtkRenderer* r, vtkVolumeProperty* p)
    {
      Shaded(p, 0.6);
      LightKit(r);
    },
    4.0 / 255.0, 0.03 };
  const std::vector<float> slice =
    RenderWith(Fixed<vtkAccelVolumeSliceMapper>(specular.SampleDistance), specular);
  const std::vector<float> rayCast =
    RenderWith(Fixed<vtkAccelVolumeRayCastMapper>(specular.SampleDistance), specular);
  ok = accelvolume_test::Report("slice vs ray cast, composite, vtkLightKit with specular",
         accelvolume_test::CompareImages(slice, rayCast, 16.0 / 255.0), specular.MeanLimit,
         specular.FractionLimit) &&
    ok;
  ok = MultiComponent() && ok;
  ok = IndependentMinimumMirrorsMaximum() && ok;
  ok = DependentLuminanceAlphaExtremes() && ok;
  ok = ComponentOctreeSkipping() && ok;
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
