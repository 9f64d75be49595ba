// Regression image: composite with a non-convex (cross) cropping pattern, drawn depth-major
// across the cells so every ray stays in front-to-back order.
#include "AccelVolumeTestScene.h"

int TestAccelVolumeCompositeCropping(int argc, char* argv[])
{
  accelvolume_test::Scene scene("shells", vtkVolumeMapper::COMPOSITE_BLEND);
  accelvolume_test::SetRampProperty(scene.Volume->GetProperty(), 100.0, 1000.0, true);
  scene.Mapper->CroppingOn();
  scene.Mapper->SetCroppingRegionPlanes(16, 48, 14, 42, 15, 45);
  scene.Mapper->SetCroppingRegionFlagsToCross();
  return scene.Regress(argc, argv);
}
