// Regression image: an oblique clipping plane with its cut face re-rendered.
#include "AccelVolumeTestScene.h"

int TestAccelVolumeClippingPlane(int argc, char* argv[])
{
  accelvolume_test::Scene scene("shells");
  vtkNew<vtkPlane> plane;
  plane->SetOrigin(32, 28, 30);
  plane->SetNormal(0.5, -0.4, -0.77);
  scene.Mapper->AddClippingPlane(plane);
  return scene.Regress(argc, argv);
}
