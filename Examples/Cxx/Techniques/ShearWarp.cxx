// ShearWarp: vtkAccelVolumeShearWarpMapper, Lacroute & Levoy's shear-warp factorization on the
// CPU: the classified volume is run-length encoded (only voxels that can contribute are
// stored), slices are sheared and composited front to back into an intermediate image with
// skip links over opaque pixels, then warped into the view. Scanline bands are balanced over
// the threads with the previous frame's costs, so the example renders a few turning frames.
//
//   ShearWarp [output.png] [--check]
#include "ExampleCommon.h"

#include <vtkAccelVolumeShearWarpMapper.h>
#include <vtkCamera.h>
#include <vtkColorTransferFunction.h>
#include <vtkNew.h>
#include <vtkPiecewiseFunction.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkVolume.h>
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

  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  volume->SetProperty(property);
  vtkNew<vtkRenderer> renderer;
  renderer->AddVolume(volume);
  renderer->SetBackground(0.1, 0.1, 0.2);
  renderer->GetActiveCamera()->ParallelProjectionOn(); // required: shear-warp is parallel only
  renderer->ResetCamera();
  renderer->GetActiveCamera()->Elevation(20);
  renderer->GetActiveCamera()->Zoom(1.5); // the bounding sphere leaves a wide margin

  // The warped image is shown as a textured quad: a headless OpenGL window from the factory.
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(0);
  window->SetSize(256, 256);
  window->AddRenderer(renderer);

  example::ErrorWatch errors;
  errors.Watch(mapper);
  errors.Watch(window);
  // Three frames turning 15 degrees each: the first encodes the volume, the later ones reuse
  // the encoding and balance their bands with the previous frame's per-scanline times.
  for (int frame = 0; frame < 3 && errors.GetErrors() == 0; ++frame)
  {
    renderer->GetActiveCamera()->Azimuth(15);
    renderer->ResetCameraClippingRange();
    window->Render();
  }
  if (errors.GetErrors() > 0)
  {
    std::fprintf(stderr, "ShearWarp: rendering failed\n");
    return 1;
  }
  if (example::WritePNG(window, renderer, options.Output, options.Check) != 0)
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
