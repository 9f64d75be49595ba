// ShearWarp: vtkAccelVolumeShearWarpMapper, Lacroute & Levoy's shear-warp factorization on the
// CPU: the classified volume is run-length encoded (only voxels that can contribute are
// stored), slices are sheared and composited front to back into an intermediate image with
// skip links over opaque pixels, then warped into the view. Scanline bands are balanced over
// the threads with the previous frame's costs, so the example renders a few turning frames.
//
//   ShearWarp [output.png] [--check]
#include "ExampleCommon.h"

#include <vtkAccelVolumeShearWarpMapper.h>
#include <vtkColorTransferFunction.h>
#include <vtkNew.h>
#include <vtkPiecewiseFunction.h>
#include <vtkVolumeProperty.h>

#include <cstdio>

int main(int argc, char* argv[])
{
  const example::Options options = example::ParseArguments(argc, argv, "ShearWarp");
  auto image = example::MakeVolume(64);

  vtkNew<vtkAccelVolumeShearWarpMapper> mapper;
  mapper->SetInputData(image);
  mapper->SetBlendModeToComposite();
  mapper->RunLengthEncodingOn();   // default: store and visit only contributing voxels
  mapper->EarlyRayTerminationOn(); // default: skip links jump over saturated pixels
  mapper->LoadBalancingOn();       // default: bands sized by the previous frame's costs
  mapper->SetNumberOfThreads(0);   // 0 = every core this process may use
  mapper->SetShadingMode(vtkAccelVolumeShearWarpMapper::SHADING_LOOKUP_TABLE);

  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0, 0.0);
  opacity->AddPoint(50, 0.0); // transparent voxels are not even stored
  opacity->AddPoint(150, 0.5);
  opacity->AddPoint(255, 0.9);
  vtkNew<vtkColorTransferFunction> color;
  color->AddRGBPoint(50, 0.4, 0.4, 0.9);
  color->AddRGBPoint(150, 0.9, 0.5, 0.3);
  color->AddRGBPoint(255, 1.0, 1.0, 1.0);
  vtkNew<vtkVolumeProperty> property;
  property->SetColor(color);
  property->SetScalarOpacity(opacity);
  property->SetInterpolationTypeToLinear();
  property->ShadeOn();

  // shear-warp renders parallel projections only
  example::Scene scene(mapper, property, true);
  scene.Frame(0, 20, 1.5);
  // Three frames turning 15 degrees each: the first encodes the volume, the later ones reuse
  // the encoding and balance their bands with the previous frame's per-scanline times.
  if (!scene.Render("ShearWarp", 3, 15))
  {
    return 1;
  }
  if (scene.Write(options) != 0)
  {
    return 1;
  }
  std::printf("ShearWarp: shaded composite, parallel, %d bands, last frame %.1f ms, imbalance "
              "%.2f, principal axis %d, %lld voxels stored, %lld encoded bytes, %lld pixel "
              "visits skipped -> %s\n",
    mapper->GetLastNumberOfBands(), 1000.0 * mapper->GetLastRenderTime(),
    mapper->GetLastImbalance(), mapper->GetLastPrincipalAxis(),
    static_cast<long long>(mapper->GetLastNumberOfStoredVoxels()),
    static_cast<long long>(mapper->GetEncodedBytes()),
    static_cast<long long>(mapper->GetLastNumberOfSkippedPixels()), options.Output.c_str());
  return 0;
}
