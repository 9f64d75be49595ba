// Regression image: sub-volume cropping with the cut faces re-rendered (the default).
#include "AccelVolumeTestScene.h"

int TestAccelVolumeCropping(int argc, char* argv[])
{
  accelvolume_test::Scene scene("shells");
  scene.Mapper->CroppingOn();
  scene.Mapper->SetCroppingRegionPlanes(8, 40, 6, 44, 10, 52);
  scene.Mapper->SetCroppingRegionFlagsToSubVolume();
  scene.Mapper->SetNumberOfSlices(48); // coarse slices: the faces matter
  return scene.Regress(argc, argv);
}
