// Regression image plus numeric check: an opaque sphere inside the volume ends the rays that
// hit it. Expected pixels: the CPU reference MIP along each ray up to the sphere, composited
// over the flat-shaded sphere or the background.
#include "AccelVolumeTestScene.h"


int TestAccelVolumeMixedGeometry(int argc, char* argv[])
{
  using namespace accelvolume_test;
  Scene scene("vessels");
  const FlatSphere sphere;
  AddFlatSphere(scene, sphere);
  scene.Mapper->SetAutoAdjustSampleDistances(0);
  scene.Mapper->SetSampleDistance(0.25);
  scene.Window->Render();
  const std::vector<float> ours = ReadPixels(scene.Window);

  const int size = 300;
  const std::vector<float> expected = ExpectedMipOverSphere(scene, sphere, size);
  // The tessellated sphere's silhouette differs from the analytic one by a pixel: allow a thin
  // fraction of outliers.
  const bool matches = Report(
    "MIP ended by opaque geometry", CompareImages(ours, expected, 12.0 / 255.0), 3.0 / 255.0, 0.02);
  const int result = scene.Regress(argc, argv);
  return matches ? result : EXIT_FAILURE;
}
