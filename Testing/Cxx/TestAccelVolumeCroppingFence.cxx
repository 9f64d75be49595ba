// Regression image: a non-convex cropping pattern (VTK's fence flags) drawn cell by cell.
#include "AccelVolumeTestScene.h"

int TestAccelVolumeCroppingFence(int argc, char* argv[])
{
  accelvolume_test::Scene scene("blobs");
  scene.Mapper->CroppingOn();
  scene.Mapper->SetCroppingRegionPlanes(16, 48, 14, 42, 15, 45);
  scene.Mapper->SetCroppingRegionFlagsToFence();
  return scene.Regress(argc, argv);
}
