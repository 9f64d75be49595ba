// Regression image: opaque-surface composite (the paper's tf2 kind) with Phong shading and
// gradient opacity, early termination and empty-space skipping on (the defaults).
#include "AccelVolumeTestScene.h"

int TestAccelVolumeCompositeShaded(int argc, char* argv[])
{
  accelvolume_test::Scene scene("shells", vtkVolumeMapper::COMPOSITE_BLEND);
  vtkVolumeProperty* property = scene.Volume->GetProperty();
  vtkNew<vtkColorTransferFunction> colours;
  colours->AddRGBPoint(300.0, 0.85, 0.75, 0.6);
  colours->AddRGBPoint(1000.0, 0.95, 0.9, 0.85);
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(300.0, 0.0);
  opacity->AddPoint(340.0, 1.0);
  opacity->AddPoint(1000.0, 1.0);
  vtkNew<vtkPiecewiseFunction> gradient;
  gradient->AddPoint(0.0, 0.2);
  gradient->AddPoint(40.0, 1.0);
  property->SetColor(colours);
  property->SetScalarOpacity(opacity);
  property->SetGradientOpacity(gradient);
  property->ShadeOn();
  property->SetAmbient(0.2);
  property->SetDiffuse(0.7);
  property->SetSpecular(0.4);
  property->SetSpecularPower(20.0);
  scene.Mapper->CroppingOn();
  scene.Mapper->SetCroppingRegionPlanes(0, 40, 0, 36, 0, 70);
  scene.Mapper->SetCroppingRegionFlagsToSubVolume();
  return scene.Regress(argc, argv);
}
