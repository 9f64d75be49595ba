// Regression image: perspective camera close to the volume (rays diverge across slices).
#include "AccelVolumeTestScene.h"

int TestAccelVolumePerspective(int argc, char* argv[])
{
  accelvolume_test::Scene scene("vessels");
  scene.Renderer->GetActiveCamera()->SetParallelProjection(0);
  scene.Renderer->GetActiveCamera()->SetViewAngle(50);
  scene.Renderer->ResetCamera();
  scene.Renderer->GetActiveCamera()->Dolly(1.6);
  scene.Renderer->ResetCameraClippingRange();
  return scene.Regress(argc, argv);
}
