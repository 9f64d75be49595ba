// The CPU ray cast mapper's accelerations change nothing: every leap mode with and without
// cell leaping gives byte-identical windows (shaded composite with cropping, a clipping plane
// and perspective; additive; MIP), any thread count gives the same image, the counters show
// that each mechanism actually ran, and NaN data renders without harm. Multi-component scalars
// too (independent and dependent): the octree and the distance map classify each component;
// their iso-surfaces and slice planes draw something and do not depend on the thread count.
#include "AccelVolumeTestScene.h"

#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkContourValues.h"
#include "vtkFloatArray.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPlane.h"
#include "vtkPointData.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>

namespace
{
using namespace accelvolume_test;

struct Frame
{
  std::vector<float> Pixels;
  vtkTypeInt64 Samples, Octree, Distance, Cell, EmptyCell;
};

// Under a sanitizer a 120x120 window: the same code paths on a sixth of the rays.
int WindowSize()
{
  return SanitizerSubset() ? 120 : 300;
}

Frame Render(RayCastScene& scene, int leap, bool cell, int threads)
{
  scene.Mapper->SetLeapMode(leap);
  scene.Mapper->SetCellLeaping(cell);
  scene.Mapper->SetNumberOfThreads(threads);
  scene.Window->Render();
  vtkAccelVolumeRayCastMapper* m = scene.Mapper;
  return { ReadPixels(scene.Window), m->GetLastNumberOfSamples(), m->GetLastSamplesLeapedByOctree(),
    m->GetLastSamplesLeapedByDistanceMap(), m->GetLastSamplesLeapedByCellTable(),
    m->GetLastSamplesInTransparentCells() };
}

bool CheckScene(
  const char* name, RayCastScene& scene, bool expectLeaps, bool expectCellLeaps = true)
{
  bool ok = true;
  const Frame plain = Render(scene, vtkAccelVolumeRayCastMapper::LEAP_NONE, false, 0);
  vtkTypeInt64 octree = 0, distance = 0, cell = 0;
  for (int leap : { vtkAccelVolumeRayCastMapper::LEAP_NONE,
         vtkAccelVolumeRayCastMapper::LEAP_OCTREE, vtkAccelVolumeRayCastMapper::LEAP_DISTANCE_MAP })
  {
    for (bool cellLeap : { false, true })
    {
      const Frame f = Render(scene, leap, cellLeap, 0);
      const bool same = f.Pixels == plain.Pixels;
      std::cout << name << ": leap " << leap << " cell " << cellLeap << ": samples " << f.Samples
                << " (plain " << plain.Samples << "), leaped octree " << f.Octree << ", distance "
                << f.Distance << ", cell table " << f.Cell << ", transparent cells " << f.EmptyCell
                << (same ? "" : "  IMAGE DIFFERS") << "\n";
      ok = ok && same && f.Samples <= plain.Samples;
      octree += f.Octree;
      distance += f.Distance;
      cell += f.Cell;
    }
  }
  if (expectLeaps && (octree == 0 || distance == 0 || (expectCellLeaps && cell == 0)))
  {
    std::cout << name << ": a leaping mechanism never ran  FAILED\n";
    ok = false;
  }
  for (int threads : { 1, 2, 3 })
  {
    const Frame f = Render(scene, vtkAccelVolumeRayCastMapper::LEAP_OCTREE, true, threads);
    if (f.Pixels != plain.Pixels)
    {
      std::cout << name << ": " << threads << " threads change the image  FAILED\n";
      ok = false;
    }
  }
  return ok;
}

double MeanOf(const std::vector<float>& pixels)
{
  double sum = 0.0;
  for (float value : pixels)
  {
    sum += value;
  }
  return pixels.empty() ? 0.0 : sum / pixels.size();
}

// The scene's volume as `components` components: 0 the blobs, 1 vessels, 2 a ramp, 3 their
// maximum (RGBA: colour 0-2, opacity 3), as unsigned char or float; with a table per
// independent component (component 1 weighted 0.6, 2 and 3 nearly transparent) or the dependent
// one.
void MakeComponents(RayCastScene& scene, int components, bool independent, bool unsignedChar)
{
  auto blobs = MakePhantom("blobs", 64, 56, 48, 1.0, 1.0, 1.25);
  auto vessels = MakePhantom("vessels", 64, 56, 48, 1.0, 1.0, 1.25);
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->CopyStructure(blobs);
  image->AllocateScalars(unsignedChar ? VTK_UNSIGNED_CHAR : VTK_FLOAT, components);
  vtkDataArray* out = image->GetPointData()->GetScalars();
  vtkDataArray* a = blobs->GetPointData()->GetScalars();
  vtkDataArray* b = vessels->GetPointData()->GetScalars();
  for (vtkIdType i = 0; i < image->GetNumberOfPoints(); ++i)
  {
    const double x = std::min(1.0, a->GetComponent(i, 0) / 1000.0);
    const double y = std::min(1.0, b->GetComponent(i, 0) / 1000.0);
    const double values[4] = { x, y, static_cast<double>(i % 64) / 63.0, std::max(x, y) };
    for (int c = 0; c < components; ++c)
    {
      out->SetComponent(
        i, c, unsignedChar ? std::floor(255.0 * values[c] + 0.5) : 1000.0 * values[c]);
    }
  }
  scene.Image = image;
  scene.Mapper->SetInputData(image);
  vtkVolumeProperty* property = scene.Volume->GetProperty();
  property->SetIndependentComponents(independent);
  const double top = unsignedChar ? 255.0 : 1000.0;
  for (int c = 0; c < (independent ? components : 1); ++c)
  {
    vtkNew<vtkColorTransferFunction> colours;
    colours->AddRGBPoint(0.0, c == 0 ? 1.0 : 0.1, 0.3, c == 1 ? 1.0 : 0.2);
    colours->AddRGBPoint(top, 1.0, 0.9, 0.5);
    vtkNew<vtkPiecewiseFunction> opacity;
    opacity->AddPoint(c < 2 ? 0.3 * top : 0.97 * top, 0.0);
    opacity->AddPoint(top, c < 2 ? 0.8 : 0.1);
    property->SetColor(c, colours);
    property->SetScalarOpacity(c, opacity);
    property->SetShade(c, 1);
  }
  property->SetComponentWeight(1, 0.6);
}
}

int TestAccelVolumeRayCastExact(int, char*[])
{
  bool ok = true;
  {
    RayCastScene scene("blobs", vtkVolumeMapper::COMPOSITE_BLEND, WindowSize());
    scene.Volume->GetProperty()->SetShade(1);
    scene.Mapper->SetCropping(1);
    scene.Mapper->SetCroppingRegionPlanes(6, 58, 4, 50, 3, 55);
    scene.Mapper->SetCroppingRegionFlagsToFence();
    vtkNew<vtkPlane> plane;
    plane->SetOrigin(32, 28, 30);
    plane->SetNormal(0.3, -0.2, 0.93);
    scene.Mapper->AddClippingPlane(plane);
    scene.Mapper->SetAutoAdjustSampleDistances(0);
    scene.Mapper->SetSampleDistance(0.5);
    ok = CheckScene("shaded composite", scene, true) && ok;
  }
  {
    // The image shown does not depend on earlier frames: the display keeps one texture while
    // the cast rectangle shrinks and grows with the camera. Zoomed out and back, the window is
    // what it was, and the zoomed-out window equals a fresh mapper's.
    RayCastScene scene("blobs", vtkVolumeMapper::COMPOSITE_BLEND, WindowSize());
    scene.Volume->GetProperty()->SetShade(1);
    const Frame first = Render(scene, vtkAccelVolumeRayCastMapper::LEAP_DISTANCE_MAP, false, 0);
    vtkCamera* camera = scene.Renderer->GetActiveCamera();
    camera->Zoom(0.5);
    const Frame smaller = Render(scene, vtkAccelVolumeRayCastMapper::LEAP_DISTANCE_MAP, false, 0);
    camera->Zoom(2.0);
    const Frame again = Render(scene, vtkAccelVolumeRayCastMapper::LEAP_DISTANCE_MAP, false, 0);
    RayCastScene fresh("blobs", vtkVolumeMapper::COMPOSITE_BLEND, WindowSize());
    fresh.Volume->GetProperty()->SetShade(1);
    fresh.Renderer->GetActiveCamera()->DeepCopy(camera);
    fresh.Renderer->GetActiveCamera()->Zoom(0.5);
    const Frame freshSmaller =
      Render(fresh, vtkAccelVolumeRayCastMapper::LEAP_DISTANCE_MAP, false, 0);
    const bool back = again.Pixels == first.Pixels;
    const bool same = smaller.Pixels == freshSmaller.Pixels && smaller.Pixels != first.Pixels;
    std::cout << "display across rectangles: zoomed back " << (back ? "same" : "DIFFERS")
              << ", zoomed out vs a fresh mapper " << (same ? "same" : "DIFFERS") << "\n";
    ok = ok && back && same;
  }
  {
    // VTK's mappers create a constant-1 gradient opacity function when they ask a property for
    // it: that function changes nothing (vtkFixedPointVolumeRayCastMapper skips it too), so the
    // ray caster must not take its gradient-opacity path for it. Unshaded, only that path needs
    // per-voxel gradients: the acceleration bytes show which path ran.
    RayCastScene scene("blobs", vtkVolumeMapper::COMPOSITE_BLEND, WindowSize());
    vtkVolumeProperty* property = scene.Volume->GetProperty();
    property->SetShade(0);
    const Frame without = Render(scene, vtkAccelVolumeRayCastMapper::LEAP_DISTANCE_MAP, false, 0);
    const vtkTypeInt64 bytesWithout = scene.Mapper->GetAccelerationBytes();
    property->GetGradientOpacity(); // VTK's default: 1 everywhere
    const Frame constant = Render(scene, vtkAccelVolumeRayCastMapper::LEAP_DISTANCE_MAP, false, 0);
    const vtkTypeInt64 bytesConstant = scene.Mapper->GetAccelerationBytes();
    vtkNew<vtkPiecewiseFunction> ramp;
    ramp->AddPoint(0.0, 0.2);
    ramp->AddPoint(100.0, 1.0);
    property->SetGradientOpacity(ramp);
    const Frame real = Render(scene, vtkAccelVolumeRayCastMapper::LEAP_DISTANCE_MAP, false, 0);
    const vtkTypeInt64 bytesReal = scene.Mapper->GetAccelerationBytes();
    std::cout << "gradient opacity: acceleration bytes without " << bytesWithout << ", constant 1 "
              << bytesConstant << ", ramp " << bytesReal << "\n";
    if (constant.Pixels != without.Pixels || bytesConstant != bytesWithout ||
      real.Pixels == without.Pixels || bytesReal <= bytesWithout)
    {
      std::cout << "a constant-1 gradient opacity must change nothing, a ramp must  FAILED\n";
      ok = false;
    }
  }
  {
    RayCastScene scene("blobs", vtkVolumeMapper::ADDITIVE_BLEND, WindowSize());
    scene.Renderer->GetActiveCamera()->SetParallelProjection(1);
    ok = CheckScene("additive", scene, true) && ok;
  }
  {
    RayCastScene scene("vessels", vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND, WindowSize());
    ok = CheckScene("MIP", scene, false) && ok;
  }
  const struct
  {
    const char* Name;
    int Components;
    bool Independent;
    bool UnsignedChar;
    int Blend;
  } multi[] = { { "2 independent components, shaded composite", 2, true, false,
                  vtkVolumeMapper::COMPOSITE_BLEND },
    { "4 independent components, raysum", 4, true, true, vtkVolumeMapper::ADDITIVE_BLEND },
    { "3 independent components, MIP", 3, true, true, vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND },
    { "2 independent components, MinIP", 2, true, false, vtkVolumeMapper::MINIMUM_INTENSITY_BLEND },
    { "dependent RGBA, MIP", 4, false, true, vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND },
    { "dependent luminance-alpha, MinIP", 2, false, false,
      vtkVolumeMapper::MINIMUM_INTENSITY_BLEND },
    { "dependent luminance-alpha, shaded composite", 2, false, false,
      vtkVolumeMapper::COMPOSITE_BLEND },
    { "dependent RGBA, shaded composite", 4, false, true, vtkVolumeMapper::COMPOSITE_BLEND },
    { "dependent RGBA, average", 4, false, true, vtkVolumeMapper::AVERAGE_INTENSITY_BLEND },
    { "3 independent components, shaded iso-surfaces", 3, true, false,
      vtkVolumeMapper::ISOSURFACE_BLEND },
    { "dependent luminance-alpha, iso-surfaces", 2, false, true,
      vtkVolumeMapper::ISOSURFACE_BLEND },
    { "2 independent components, slice plane", 2, true, false, vtkVolumeMapper::SLICE_BLEND },
    { "dependent RGBA, shaded slice plane", 4, false, true, vtkVolumeMapper::SLICE_BLEND } };
  // Under a sanitizer every third multi-component case: each runs the same loops.
  const int every = SanitizerSubset() ? 3 : 1;
  int index = 0;
  for (const auto& m : multi)
  {
    if (index++ % every != 0)
    {
      continue;
    }
    RayCastScene scene("blobs", m.Blend, WindowSize());
    MakeComponents(scene, m.Components, m.Independent, m.UnsignedChar);
    const double top = m.UnsignedChar ? 255.0 : 1000.0;
    vtkVolumeProperty* property = scene.Volume->GetProperty();
    property->GetIsoSurfaceValues()->SetValue(0, 0.4 * top);
    property->GetIsoSurfaceValues()->SetValue(1, 0.7 * top);
    vtkNew<vtkPlane> slicePlane;
    slicePlane->SetOrigin(32, 28, 30);
    slicePlane->SetNormal(0.5, -0.3, 0.8);
    property->SetSliceFunction(slicePlane);
    const bool planes =
      m.Blend == vtkVolumeMapper::ISOSURFACE_BLEND || m.Blend == vtkVolumeMapper::SLICE_BLEND;
    if (planes &&
      MeanOf(Render(scene, vtkAccelVolumeRayCastMapper::LEAP_NONE, false, 1).Pixels) < 1.0 / 255.0)
    {
      std::cout << m.Name << ": (almost) nothing drawn, the case proves nothing  FAILED\n";
      ok = false;
    }
    const bool leaps =
      m.Blend == vtkVolumeMapper::COMPOSITE_BLEND || m.Blend == vtkVolumeMapper::ADDITIVE_BLEND;
    ok = CheckScene(m.Name, scene, leaps, false) && ok;
    const vtkTypeInt64 cells = scene.Mapper->GetLastSamplesLeapedByCellTable();
    if (cells != 0)
    {
      std::cout << m.Name << ": the cell table leaped multi-component samples  FAILED\n";
      ok = false;
    }
    if (!leaps && !planes && m.Blend != vtkVolumeMapper::AVERAGE_INTENSITY_BLEND &&
      Render(scene, vtkAccelVolumeRayCastMapper::LEAP_OCTREE, false, 0).Octree == 0)
    {
      std::cout << m.Name << ": the components' octrees never leaped  FAILED\n";
      ok = false;
    }
  }
  {
    // Weight 0 on every component: nothing is visible, and leaping knows it (no samples).
    RayCastScene scene("blobs", vtkVolumeMapper::COMPOSITE_BLEND, WindowSize());
    MakeComponents(scene, 2, true, false);
    scene.Volume->GetProperty()->SetComponentWeight(0, 0.0);
    scene.Volume->GetProperty()->SetComponentWeight(1, 0.0);
    ok = CheckScene("2 independent components of weight 0", scene, false, false) && ok;
    const Frame f = Render(scene, vtkAccelVolumeRayCastMapper::LEAP_DISTANCE_MAP, false, 0);
    if (f.Samples != 0)
    {
      std::cout << "weight 0: " << f.Samples << " samples taken where nothing can show  FAILED\n";
      ok = false;
    }
  }
  {
    // NaN voxels are transparent / ignored, never a crash or garbage.
    RayCastScene scene("blobs", vtkVolumeMapper::COMPOSITE_BLEND, WindowSize());
    auto* values = vtkFloatArray::SafeDownCast(scene.Image->GetPointData()->GetScalars());
    for (vtkIdType i = 0; i < values->GetNumberOfValues(); i += 7)
    {
      values->SetValue(i, std::numeric_limits<float>::quiet_NaN());
    }
    values->Modified();
    ok = CheckScene("NaN voxels", scene, false) && ok;
  }
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
