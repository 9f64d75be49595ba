// The CPU ray cast mapper stops its rays at opaque geometry already drawn: an opaque sphere in
// the volume, MIP; expected pixels are the CPU reference MIP up to the sphere, composited over
// the flat sphere or the background.
#include "AccelVolumeTestScene.h"

int TestAccelVolumeRayCastMixedGeometry(int, char*[])
{
  using namespace accelvolume_test;
  RayCastScene scene("vessels");
  const FlatSphere sphere;
  AddFlatSphere(scene, sphere);
  scene.Mapper->SetAutoAdjustSampleDistances(0);
  scene.Mapper->SetSampleDistance(0.1);
  scene.Window->Render();
  const std::vector<float> ours = ReadPixels(scene.Window);

  const int size = 300;
  const std::vector<float> expected = ExpectedMipOverSphere(scene, sphere, size);
  // The tessellated sphere's silhouette differs from the analytic one by a pixel: allow a thin
  // fraction of outliers.
  const bool matches = Report("ray cast MIP ended by opaque geometry",
    CompareImages(ours, expected, 12.0 / 255.0), 3.0 / 255.0, 0.02);
  return matches ? EXIT_SUCCESS : EXIT_FAILURE;
}
