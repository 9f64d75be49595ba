// Regression image: slice mapper, average intensity blend of the "blobs" phantom.
#include "AccelVolumeTestScene.h"

int TestAccelVolumeAverage(int argc, char* argv[])
{
  accelvolume_test::Scene scene("blobs", vtkVolumeMapper::AVERAGE_INTENSITY_BLEND);
  scene.Mapper->SetAverageIPScalarRange(50.0, 1000.0);
  return scene.Regress(argc, argv);
}
