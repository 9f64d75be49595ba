// The CPU ray cast mapper's accelerations change nothing: every leap mode with and without
// cell leaping gives byte-identical windows (shaded composite with cropping, a clipping plane
// and perspective; additive; MIP), any thread count gives the same image, the counters show
// that each mechanism actually ran, and NaN data renders without harm.
#include "AccelVolumeTestScene.h"

#include "vtkFloatArray.h"

#include <cstdlib>
#include <limits>

namespace
{
using namespace accelvolume_test;

struct Frame
{
  std::vector<float> Pixels;
  vtkTypeInt64 Samples, Octree, Distance, Cell, EmptyCell;
};

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

bool CheckScene(const char* name, RayCastScene& scene, bool expectLeaps)
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
  if (expectLeaps && (octree == 0 || distance == 0 || cell == 0))
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
}

int TestAccelVolumeRayCastExact(int, char*[])
{
  bool ok = true;
  {
    RayCastScene scene("blobs", vtkVolumeMapper::COMPOSITE_BLEND);
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
    RayCastScene scene("blobs", vtkVolumeMapper::ADDITIVE_BLEND);
    scene.Renderer->GetActiveCamera()->SetParallelProjection(1);
    ok = CheckScene("additive", scene, true) && ok;
  }
  {
    RayCastScene scene("vessels", vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND);
    ok = CheckScene("MIP", scene, false) && ok;
  }
  {
    // NaN voxels are transparent / ignored, never a crash or garbage.
    RayCastScene scene("blobs", vtkVolumeMapper::COMPOSITE_BLEND);
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
