// Regression image: slice mapper, maximum intensity blend of the "vessels" phantom.
#include "AccelVolumeTestScene.h"

int TestAccelVolumeMIP(int argc, char* argv[])
{
  accelvolume_test::Scene scene("vessels", vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND);

  return scene.Regress(argc, argv);
}
