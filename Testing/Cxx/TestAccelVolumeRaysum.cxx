// Regression image: slice mapper, additive blend of the "blobs" phantom.
#include "AccelVolumeTestScene.h"

int TestAccelVolumeRaysum(int argc, char* argv[])
{
  accelvolume_test::Scene scene("blobs", vtkVolumeMapper::ADDITIVE_BLEND);
  scene.Mapper->SetAdditiveUnitDistance(20.0);
  return scene.Regress(argc, argv);
}
