// Regression image: slice mapper, minimum intensity blend of the "shells" phantom.
#include "AccelVolumeTestScene.h"

int TestAccelVolumeMinIP(int argc, char* argv[])
{
  accelvolume_test::Scene scene("shells", vtkVolumeMapper::MINIMUM_INTENSITY_BLEND);
  // Opaque everywhere so the minimum along each ray shows; the cropped box keeps rays inside the
  // shells.
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0.0, 1.0);
  opacity->AddPoint(1000.0, 1.0);
  scene.Volume->GetProperty()->SetScalarOpacity(opacity);
  scene.Mapper->CroppingOn();
  scene.Mapper->SetCroppingRegionPlanes(12, 52, 10, 46, 10, 50);
  scene.Mapper->SetCroppingRegionFlagsToSubVolume();
  return scene.Regress(argc, argv);
}
