// Bricking in the slice mapper: a bricked volume draws the unbricked image (every blend mode,
// composite in both orders and projections, cropping with cut faces, clipping), with no seams;
// a GPU memory budget below the volume streams bricks every frame and draws the same image;
// bricks the octree finds empty are never uploaded; a budget below one brick is a clear error;
// and a volume longer than GL_MAX_3D_TEXTURE_SIZE renders (checked against the CPU ray caster,
// seam columns included).
#include "AccelVolumeTestUtilities.h"
#include "vtkAccelVolumeRayCastMapper.h"
#include "vtkAccelVolumeSliceMapper.h"

#include "vtkCommand.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPlane.h"
#include "vtkPlaneCollection.h"
#include "vtkTextureObject.h"
#include "vtkUnsignedShortArray.h"

#include <cstdlib>
#include <functional>
#include <string>

namespace
{
constexpr int Size = 128;

struct Scene
{
  int blend = vtkVolumeMapper::COMPOSITE_BLEND;
  bool perspective = true;
  bool shade = false;
  bool crop = false;
  bool clip = false;
  bool frontToBack = true;
  double azimuth = 35;
  double elevation = 25;
};

struct Result
{
  std::vector<float> pixels;
  int bricks = 0;
  int bricksDrawn = 0;
  int uploads = 0; // last frame
  int totalUploads = 0;
  vtkIdType residentBytes = 0;
  std::string errors;
};

using Configure = std::function<void(vtkAccelVolumeSliceMapper*)>;

// Renders `frames` frames of the scene (same view) and reports the last one.
Result Render(vtkImageData* image, const Scene& scene, const Configure& configure, int frames = 1)
{
  vtkNew<vtkAccelVolumeSliceMapper> mapper;
  vtkNew<accelvolume_test::ErrorRecorder> errors;
  mapper->AddObserver(vtkCommand::ErrorEvent, errors);
  mapper->SetInputData(image);
  mapper->SetBlendMode(scene.blend);
  mapper->SetFrontToBack(scene.frontToBack);
  mapper->PrecomputeGradientsOff(); // bricks take central differences: compare like with like
  // Bricks are rasterised: so is the unbricked reference (compute slices stop rays elsewhere).
  mapper->SetSliceCompositing(vtkAccelVolumeSliceMapper::SLICE_COMPOSITING_RASTER);
  double range[2];
  image->GetPointData()->GetScalars()->GetRange(range);
  if (scene.crop)
  {
    const double* b = image->GetBounds();
    mapper->CroppingOn();
    mapper->SetCroppingRegionPlanes(0.5 * (b[0] + b[1]) - 3.3, 0.7 * b[1], b[2] + 5.2,
      0.5 * (b[2] + b[3]) + 1.7, 0.3 * b[5], b[5] - 4.1);
    mapper->SetCroppingRegionFlagsToInvertedCross();
  }
  if (scene.clip)
  {
    vtkNew<vtkPlane> plane;
    const double* b = image->GetBounds();
    plane->SetOrigin(0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5]));
    plane->SetNormal(0.6, -0.5, 0.62);
    mapper->AddClippingPlane(plane);
  }
  configure(mapper);
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  const bool minimum = scene.blend == vtkVolumeMapper::MINIMUM_INTENSITY_BLEND;
  accelvolume_test::SetRampProperty(volume->GetProperty(),
    range[0] + (minimum ? 0.0 : 0.15) * (range[1] - range[0]), range[1], true);
  volume->GetProperty()->SetShade(scene.shade);
  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(0.1, 0.2, 0.3);
  renderer->AddVolume(volume);
  vtkNew<vtkRenderWindow> window;
  accelvolume_test::SetupObliqueView(
    window, renderer, Size, scene.azimuth, scene.elevation, scene.perspective);
  Result result;
  for (int frame = 0; frame < frames; ++frame)
  {
    window->Render();
    result.totalUploads += mapper->GetLastNumberOfBrickUploads();
  }
  result.pixels = accelvolume_test::ReadPixels(window);
  result.bricks = mapper->GetLastNumberOfBricks();
  result.bricksDrawn = mapper->GetLastNumberOfBricksDrawn();
  result.uploads = mapper->GetLastNumberOfBrickUploads();
  result.residentBytes = mapper->GetLastResidentBytes();
  result.errors = errors->Messages;
  return result;
}

vtkSmartPointer<vtkImageData> ToUnsignedShort(vtkImageData* image)
{
  auto converted = vtkSmartPointer<vtkImageData>::New();
  converted->CopyStructure(image);
  vtkDataArray* source = image->GetPointData()->GetScalars();
  double range[2];
  source->GetRange(range);
  vtkNew<vtkUnsignedShortArray> values;
  values->SetNumberOfValues(source->GetNumberOfTuples());
  for (vtkIdType i = 0; i < source->GetNumberOfTuples(); ++i)
  {
    values->SetValue(i,
      static_cast<unsigned short>(
        4000.0 * (source->GetComponent(i, 0) - range[0]) / (range[1] - range[0]) + 0.5));
  }
  converted->GetPointData()->SetScalars(values);
  return converted;
}

// Bricked against unbricked: the same samples from the same texels, so only the texture
// coordinate arithmetic differs (brick-relative); allow 2/255 on a few pixels.
bool Same(const char* what, const Result& whole, const Result& bricked, int minimumBricks)
{
  const accelvolume_test::ImageDifference d =
    accelvolume_test::CompareImages(whole.pixels, bricked.pixels, 2.5 / 255.0);
  const bool ok = whole.errors.empty() && bricked.errors.empty() &&
    bricked.bricks >= minimumBricks && whole.bricks == 1 && d.mean <= 2.0e-4 &&
    d.fractionAbove <= 1.0e-3;
  std::cout << what << ": " << bricked.bricks << " bricks (" << bricked.bricksDrawn
            << " drawn), mean |diff| " << d.mean << " (limit 2e-4), max " << d.maximum * 255
            << "/255, pixels over 2.5/255 " << d.fractionAbove << " (limit 1e-3)"
            << (ok ? "" : "  FAILED") << "\n"
            << whole.errors << bricked.errors;
  accelvolume_test::DumpImage(std::string("bricking-") + what + "-whole", whole.pixels, Size, Size);
  accelvolume_test::DumpImage(std::string("bricking-") + what + "-bricked", bricked.pixels, Size, Size);
  return ok;
}

bool CompareModes(vtkImageData* image, const char* type)
{
  bool ok = true;
  const Configure whole = [](vtkAccelVolumeSliceMapper*) {};
  // 20-texel bricks: 17 owned cells each, so a 70 x 62 x 54 volume is 5 x 4 x 4 bricks and
  // every brick face, edge and corner crosses the view.
  const Configure bricked = [](vtkAccelVolumeSliceMapper* m) { m->SetMaximumBrickSize(20); };
  struct Case
  {
    const char* name;
    Scene scene;
  };
  std::vector<Case> cases;
  Scene scene;
  cases.push_back({ "composite", scene });
  scene.shade = true;
  cases.push_back({ "composite-shaded", scene });
  scene.perspective = false;
  cases.push_back({ "composite-shaded-parallel", scene });
  scene.frontToBack = false;
  cases.push_back({ "composite-back-to-front", scene });
  scene = Scene();
  scene.crop = true;
  cases.push_back({ "composite-cropped", scene });
  for (int blend : { vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND,
         vtkVolumeMapper::MINIMUM_INTENSITY_BLEND, vtkVolumeMapper::ADDITIVE_BLEND,
         vtkVolumeMapper::AVERAGE_INTENSITY_BLEND })
  {
    scene = Scene();
    scene.blend = blend;
    cases.push_back({ blend == vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND ? "mip"
          : blend == vtkVolumeMapper::MINIMUM_INTENSITY_BLEND           ? "minip"
          : blend == vtkVolumeMapper::ADDITIVE_BLEND                    ? "additive"
                                                                        : "average",
      scene });
  }
  scene = Scene();
  scene.blend = vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND;
  scene.crop = true;
  cases.push_back({ "mip-cropped-cut-faces", scene });
  scene.blend = vtkVolumeMapper::ADDITIVE_BLEND;
  scene.clip = true;
  scene.perspective = false;
  cases.push_back({ "additive-cropped-clipped", scene });
  for (const Case& c : cases)
  {
    const std::string name = std::string(type) + "-" + c.name;
    ok = Same(name.c_str(), Render(image, c.scene, whole), Render(image, c.scene, bricked), 60) &&
      ok;
  }
  return ok;
}

// A budget below the volume: bricks stream every frame, the image does not change; a budget
// above it: after the first frame nothing is uploaded.
bool CheckBudget(vtkImageData* image)
{
  Scene scene;
  scene.shade = true;
  const Result whole = Render(image, scene, [](vtkAccelVolumeSliceMapper*) {});
  const vtkIdType volumeBytes = 4 * image->GetNumberOfPoints(); // float texels
  const Result streamed = Render(
    image, scene, [volumeBytes](vtkAccelVolumeSliceMapper* m) { m->SetGPUMemoryBudget(volumeBytes / 3); },
    3);
  bool ok = Same("budget-streamed", whole, streamed, 8);
  ok = streamed.uploads > 0 && streamed.residentBytes <= volumeBytes / 3 && ok;
  std::cout << "budget " << volumeBytes / 3 << " bytes: " << streamed.uploads
            << " uploads in the third frame, " << streamed.residentBytes << " bytes resident\n";
  const Result cached = Render(image, scene,
    [](vtkAccelVolumeSliceMapper* m) { m->SetMaximumBrickSize(20); }, 3);
  ok = cached.uploads == 0 && cached.totalUploads == cached.bricksDrawn && ok;
  std::cout << "no budget: " << cached.uploads << " uploads in the third frame (want 0), "
            << cached.totalUploads << " in all for " << cached.bricksDrawn << " bricks drawn\n";
  const Result tooSmall = Render(image, scene,
    [](vtkAccelVolumeSliceMapper* m) { m->SetGPUMemoryBudget(1000); });
  const bool reported =
    tooSmall.errors.find("GPU memory budget (1000 bytes) is smaller than one brick") !=
    std::string::npos;
  std::cout << "budget of 1000 bytes: " << (reported ? "reported" : "NOT reported") << ": "
            << tooSmall.errors;
  return ok && reported;
}

// Composite with octree skipping and a transfer function that leaves one corner visible: the
// empty bricks are neither drawn nor uploaded, and the image is the unbricked one.
bool CheckEmptyBricks()
{
  vtkNew<vtkImageData> image;
  image->SetDimensions(64, 64, 64);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 1);
  auto* values = static_cast<unsigned char*>(image->GetScalarPointer());
  for (int k = 0; k < 64; ++k)
  {
    for (int j = 0; j < 64; ++j)
    {
      for (int i = 0; i < 64; ++i)
      {
        const bool corner = i < 20 && j < 24 && k < 18;
        values[(k * 64 + j) * 64 + i] = static_cast<unsigned char>(corner ? 100 + (i + j + k) : 10);
      }
    }
  }
  Scene scene;
  const Configure whole = [](vtkAccelVolumeSliceMapper*) {};
  const Configure bricked = [](vtkAccelVolumeSliceMapper* m) { m->SetMaximumBrickSize(20); };
  const Result a = Render(image, scene, whole);
  const Result b = Render(image, scene, bricked, 2);
  bool ok = Same("empty-bricks", a, b, 27);
  ok = b.bricksDrawn < b.bricks / 2 && b.totalUploads == b.bricksDrawn && ok;
  std::cout << "empty bricks: " << b.bricksDrawn << " of " << b.bricks << " drawn, "
            << b.totalUploads << " uploads in two frames\n";
  return ok;
}

// Real data under a small budget (1 MiB for the 8 MiB engine CT): streamed bricks, composite
// with its accelerations on (shaded, early termination, octree skipping) and MIP.
bool CheckRealData()
{
  vtkSmartPointer<vtkImageData> engine =
    accelvolume_test::LoadSharedVolume("engine_256x256x128_uint8.raw.gz", 256, 256, 128);
  if (!engine)
  {
    std::cout << "engine CT not found (ACCELVOLUME_DATA_DIR): real-data check skipped\n";
    return true;
  }
  const Configure whole = [](vtkAccelVolumeSliceMapper*) {};
  const Configure budget = [](vtkAccelVolumeSliceMapper* m) { m->SetGPUMemoryBudget(1 << 20); };
  Scene scene;
  scene.shade = true;
  const Result streamed = Render(engine, scene, budget, 2);
  bool ok = Same("engine-composite-1MiB", Render(engine, scene, whole), streamed, 8);
  ok = streamed.uploads > 0 && streamed.residentBytes <= (1 << 20) && ok;
  std::cout << "engine, 1 MiB: " << streamed.uploads << " uploads in the second frame\n";
  scene = Scene();
  scene.blend = vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND;
  ok = Same("engine-mip-1MiB", Render(engine, scene, whole), Render(engine, scene, budget, 2), 8) &&
    ok;
  return ok;
}

// Longer than the texture limit (emulated where the GPU allows more than 2100 texels): the CPU
// ray caster is the reference; no column near a brick face may stand out.
bool CheckBeyondTextureLimit(vtkRenderWindow* probe)
{
  const int limit = vtkTextureObject::GetMaximumTextureSize3D(
    vtkOpenGLRenderWindow::SafeDownCast(probe));
  const int length = 2100;
  vtkNew<vtkImageData> image;
  image->SetDimensions(length, 64, 64);
  image->SetSpacing(1.0 / 16.0, 1.0, 1.0); // a 131 x 63 x 63 box, seen whole
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 1);
  auto* values = static_cast<unsigned char*>(image->GetScalarPointer());
  for (int k = 0; k < 64; ++k)
  {
    for (int j = 0; j < 64; ++j)
    {
      for (int i = 0; i < length; ++i)
      {
        // Rings along x, a rod through the middle: structure everywhere, including the faces.
        const double x = i / 16.0;
        const double r = std::hypot(j - 31.5, k - 31.5);
        const double v = 120.0 + 100.0 * std::sin(x * 0.35) * std::cos(r * 0.25);
        values[(static_cast<size_t>(k) * 64 + j) * length + i] =
          static_cast<unsigned char>(std::max(0.0, std::min(255.0, v)));
      }
    }
  }
  Scene scene;
  scene.blend = vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND;
  scene.perspective = false;
  scene.azimuth = 0;
  scene.elevation = 30;
  const Result ours = Render(image, scene,
    [limit](vtkAccelVolumeSliceMapper* m) { m->SetMaximumBrickSize(limit >= 2100 ? 2048 : 0); });
  std::cout << "2100 x 64 x 64 (GL_MAX_3D_TEXTURE_SIZE " << limit << "): " << ours.bricks
            << " bricks\n"
            << ours.errors;
  // The same scene through the CPU ray caster.
  vtkNew<vtkAccelVolumeRayCastMapper> reference;
  reference->SetInputData(image);
  reference->SetBlendMode(scene.blend);
  vtkNew<vtkVolume> volume;
  volume->SetMapper(reference);
  double range[2];
  image->GetPointData()->GetScalars()->GetRange(range);
  accelvolume_test::SetRampProperty(
    volume->GetProperty(), range[0] + 0.15 * (range[1] - range[0]), range[1], true);
  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(0.1, 0.2, 0.3);
  renderer->AddVolume(volume);
  vtkNew<vtkRenderWindow> window;
  accelvolume_test::SetupObliqueView(window, renderer, Size, scene.azimuth, scene.elevation, false);
  window->Render();
  const std::vector<float> expected = accelvolume_test::ReadPixels(window);
  accelvolume_test::DumpImage("bricking-2100-raycast", expected, Size, Size);
  accelvolume_test::DumpImage("bricking-2100-slices", ours.pixels, Size, Size);
  // Slices and rays sample differently; the agreement tests bound that difference the same way.
  const accelvolume_test::ImageDifference d =
    accelvolume_test::CompareImages(expected, ours.pixels, 0.1);
  bool ok = ours.errors.empty() && ours.bricks >= 2 &&
    accelvolume_test::Report("2100-long vs ray caster", d, 0.01, 0.01);
  // Seams: the brick faces are planes x = const, seen as columns; their error must not exceed
  // that of the columns around them by more than a grey level.
  double seam = 0.0;
  double elsewhere = 0.0;
  const double* b = image->GetBounds();
  for (int column = 0; column < Size; ++column)
  {
    double columnError = 0.0;
    for (int row = 0; row < Size; ++row)
    {
      for (int c = 0; c < 3; ++c)
      {
        const size_t at = 3 * (static_cast<size_t>(row) * Size + column) + c;
        columnError += std::fabs(expected[at] - ours.pixels[at]);
      }
    }
    columnError /= 3.0 * Size;
    // The column's x index (the view looks square on the x axis); faces are evenly spaced.
    renderer->SetDisplayPoint(column + 0.5, Size / 2.0, 0.0);
    renderer->DisplayToWorld();
    const double* world = renderer->GetWorldPoint();
    const double x = world[3] != 0 ? world[0] / world[3] : world[0];
    const double index = (x - b[0]) * 16.0;
    const double faceSpacing = (length - 1.0) / ours.bricks;
    const double toFace = std::fabs(index - faceSpacing * std::round(index / faceSpacing));
    if (toFace < 16.0 && std::round(index / faceSpacing) > 0 &&
      std::round(index / faceSpacing) < ours.bricks)
    {
      seam = std::max(seam, columnError);
    }
    else
    {
      elsewhere = std::max(elsewhere, columnError);
    }
  }
  const bool seamless = seam <= elsewhere + 1.0 / 255.0;
  std::cout << "columns at brick faces: worst mean error " << seam * 255 << "/255; elsewhere "
            << elsewhere * 255 << "/255" << (seamless ? "" : "  SEAM") << "\n";
  return ok && seamless;
}
}

int TestAccelVolumeBricking(int, char*[])
{
  vtkSmartPointer<vtkImageData> blobs = accelvolume_test::MakePhantom("blobs", 70, 62, 54);
  bool ok = CompareModes(blobs, "float");
  ok = CompareModes(ToUnsignedShort(blobs), "ushort") && ok;
  ok = CheckBudget(blobs) && ok;
  ok = CheckEmptyBricks() && ok;
  ok = CheckRealData() && ok;
  vtkNew<vtkRenderWindow> probe;
  probe->SetSize(8, 8);
  probe->Render();
  ok = CheckBeyondTextureLimit(probe) && ok;
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
