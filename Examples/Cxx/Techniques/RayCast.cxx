// RayCast: shaded composite on the CPU with vtkAccelVolumeRayCastMapper (a drop-in for
// vtkFixedPointVolumeRayCastMapper), using a distance map to leap over empty space: each cell
// stores the chessboard distance to the nearest cell that may be visible, so a ray in empty
// space jumps that far in one step. Every leap is exact, so the image equals LEAP_NONE's.
//
//   RayCast [output.png] [--check]
#include "ExampleCommon.h"

#include <vtkAccelVolumeRayCastMapper.h>
#include <vtkColorTransferFunction.h>
#include <vtkNew.h>
#include <vtkPiecewiseFunction.h>
#include <vtkVolumeProperty.h>

#include <cstdio>

int main(int argc, char* argv[])
{
  const example::Options options = example::ParseArguments(argc, argv, "RayCast");
  auto image = example::MakeVolume(64);

  vtkNew<vtkAccelVolumeRayCastMapper> mapper;
  mapper->SetInputData(image);
  mapper->SetBlendModeToComposite();
  mapper->SetLeapMode(vtkAccelVolumeRayCastMapper::LEAP_DISTANCE_MAP); // the default
  mapper->SetSampleDistance(0.5);     // world units: half a voxel
  mapper->SetNumberOfThreads(2);      // rays are split over threads; the image never changes
  mapper->AutoAdjustSampleDistancesOff(); // a still frame: full resolution

  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0, 0.0);
  opacity->AddPoint(50, 0.0); // empty below 50: the distance map leaps over it
  opacity->AddPoint(140, 0.5);
  opacity->AddPoint(255, 0.9);
  vtkNew<vtkColorTransferFunction> color;
  color->AddRGBPoint(50, 0.3, 0.7, 0.3);
  color->AddRGBPoint(160, 0.9, 0.6, 0.3);
  color->AddRGBPoint(255, 1.0, 1.0, 1.0);
  vtkNew<vtkVolumeProperty> property;
  property->SetColor(color);
  property->SetScalarOpacity(opacity);
  property->SetInterpolationTypeToLinear();
  property->ShadeOn();
  property->SetAmbient(0.2);
  property->SetDiffuse(0.7);
  property->SetSpecular(0.2);

  example::Scene scene(mapper, property);
  scene.Frame(30, 20, 1.5);
  if (!scene.Render("RayCast"))
  {
    return 1;
  }
  if (scene.Write(options) != 0)
  {
    return 1;
  }
  const double samples = static_cast<double>(mapper->GetLastNumberOfSamples());
  const double leaped = static_cast<double>(mapper->GetLastSamplesLeapedByDistanceMap());
  std::printf("RayCast: shaded composite, %lld rays, %.0f samples taken, %.0f leaped by the "
              "distance map (%.0f%%), %lld rays terminated early, %.1f ms -> %s\n",
    static_cast<long long>(mapper->GetLastNumberOfRays()), samples, leaped,
    samples + leaped > 0 ? 100.0 * leaped / (samples + leaped) : 0.0,
    static_cast<long long>(mapper->GetLastNumberOfTerminatedRays()),
    1000.0 * mapper->GetLastRenderTime(), options.Output.c_str());
  return 0;
}
