// Regression image: composite (direct volume rendering) of the "blobs" phantom, colour ramp.
#include "AccelVolumeTestScene.h"

int TestAccelVolumeComposite(int argc, char* argv[])
{
  accelvolume_test::Scene scene("blobs", vtkVolumeMapper::COMPOSITE_BLEND);
  accelvolume_test::SetRampProperty(scene.Volume->GetProperty(), 100.0, 900.0, true);
  return scene.Regress(argc, argv);
}
