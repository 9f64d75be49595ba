// Regression image: the same cropped view with face re-rendering off (shows the staircase).
#include "AccelVolumeTestScene.h"

int TestAccelVolumeCroppingNoRerender(int argc, char* argv[])
{
  accelvolume_test::Scene scene("shells");
  scene.Mapper->CroppingOn();
  scene.Mapper->SetCroppingRegionPlanes(8, 40, 6, 44, 10, 52);
  scene.Mapper->SetCroppingRegionFlagsToSubVolume();
  scene.Mapper->SetNumberOfSlices(48);
  scene.Mapper->BoundaryRerenderingOff();
  return scene.Regress(argc, argv);
}
