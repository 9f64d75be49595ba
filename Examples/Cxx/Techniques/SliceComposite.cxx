// SliceComposite: shaded composite rendering with vtkAccelVolumeSliceMapper and the two
// accelerations of Lee 2005's slice renderer: early ray termination (a mark pass every few
// slices stops pixels that are already opaque) and exact empty-space skipping with a min-max
// octree (slices are clipped to the non-empty octree boxes). Both are exact: the image equals
// the unaccelerated one up to the termination threshold.
//
//   SliceComposite [output.png] [--check]
#include "ExampleCommon.h"

#include <vtkAccelVolumeSliceMapper.h>
#include <vtkColorTransferFunction.h>
#include <vtkNew.h>
#include <vtkPiecewiseFunction.h>
#include <vtkVolumeProperty.h>

#include <cstdio>

int main(int argc, char* argv[])
{
  const example::Options options = example::ParseArguments(argc, argv, "SliceComposite");
  auto image = example::MakeVolume(64);

  vtkNew<vtkAccelVolumeSliceMapper> mapper;
  mapper->SetInputData(image);
  mapper->SetBlendModeToComposite();
  mapper->EarlyRayTerminationOn();            // default on: mark pass every 16 slices
  mapper->SetEarlyRayTerminationInterval(8);  // test more often: the blobs are opaque fast
  mapper->SetEarlyRayTerminationThreshold(0.99);
  // SKIP_BOTH = octree culling of whole empty blocks + per-fragment skipping of shading.
  mapper->SetEmptySpaceSkipping(vtkAccelVolumeSliceMapper::SKIP_BOTH);
  mapper->SetOctreeLeafSize(8);

  // Values below 40 are fully transparent: most of the box is empty space to skip.
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0, 0.0);
  opacity->AddPoint(40, 0.0);
  opacity->AddPoint(120, 0.6);
  opacity->AddPoint(255, 0.9);
  vtkNew<vtkColorTransferFunction> color;
  color->AddRGBPoint(40, 0.8, 0.3, 0.2);
  color->AddRGBPoint(150, 0.9, 0.8, 0.4);
  color->AddRGBPoint(255, 1.0, 1.0, 1.0);
  vtkNew<vtkVolumeProperty> property;
  property->SetColor(color);
  property->SetScalarOpacity(opacity);
  property->SetInterpolationTypeToLinear();
  property->ShadeOn(); // Phong with VTK's light kit and these coefficients
  property->SetAmbient(0.2);
  property->SetDiffuse(0.7);
  property->SetSpecular(0.3);
  property->SetSpecularPower(20);

  example::Scene scene(mapper, property);
  scene.Frame(30, 20, 1.5);
  if (!scene.Render("SliceComposite"))
  {
    return 1;
  }
  if (scene.Write(options) != 0)
  {
    return 1;
  }
  std::printf("SliceComposite: shaded composite, %d slices, %d termination passes, %.0f%% of "
              "octree leaves empty, %.0f%% of slice area kept, %.1f ms -> %s\n",
    mapper->GetLastNumberOfSlices(), mapper->GetLastNumberOfTerminationPasses(),
    100.0 * mapper->GetLastTransparentLeafFraction(), 100.0 * mapper->GetLastProxyAreaFraction(),
    1000.0 * mapper->GetLastRenderTime(), options.Output.c_str());
  return 0;
}
