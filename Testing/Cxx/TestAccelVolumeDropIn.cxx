// Drop-in behaviour shared by every mapper (issue 16): one mapper object switched between blend
// modes draws what a fresh mapper draws; the inputs VTK's GPU mapper takes (unsigned int and
// 64-bit integers, cell scalars, rectilinear grids, a selected array) give the pictures of their
// one-component point-scalar equivalents; VectorMode reduces vectors as vtkSmartVolumeMapper;
// FinalColorWindow / Level transform the colours as VTK's mappers; VTK's enum values hold.
#include "AccelVolumeTestUtilities.h"
#include "vtkAccelVolumeRayCastMapper.h"
#include "vtkAccelVolumeShearWarpMapper.h"
#include "vtkAccelVolumeSliceMapper.h"
#include "vtkAccelVolumeSmartMapper.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCellData.h"
#include "vtkColorTransferFunction.h"
#include "vtkCommand.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkGPUVolumeRayCastMapper.h"
#include "vtkHardwareSelector.h"
#include "vtkInformation.h"
#include "vtkLongLongArray.h"
#include "vtkPointData.h"
#include "vtkVolumeProperty.h"
#include "vtkRectilinearGrid.h"
#include "vtkSelection.h"
#include "vtkSelectionNode.h"
#include "vtkSmartVolumeMapper.h"
#include "vtkUniformGrid.h"
#include "vtkUnsignedIntArray.h"

#include <functional>
#include <iostream>
#include <string>

namespace
{
using accelvolume_test::CompareImages;

// VTK's values, so code written for vtkSmartVolumeMapper means the same with ours.
constexpr bool SameValue(int ours, int vtks)
{
  return ours == vtks;
}
static_assert(SameValue(vtkAccelVolumeSmartMapper::DefaultRenderMode,
                vtkSmartVolumeMapper::DefaultRenderMode),
  "DefaultRenderMode");
static_assert(SameValue(vtkAccelVolumeSmartMapper::RayCastRenderMode,
                vtkSmartVolumeMapper::RayCastRenderMode),
  "RayCastRenderMode");
static_assert(
  SameValue(vtkAccelVolumeSmartMapper::GPURenderMode, vtkSmartVolumeMapper::GPURenderMode),
  "GPURenderMode");
static_assert(SameValue(vtkAccelVolumeSmartMapper::UndefinedRenderMode,
                vtkSmartVolumeMapper::UndefinedRenderMode),
  "UndefinedRenderMode");
static_assert(SameValue(vtkAccelVolumeSmartMapper::MAGNITUDE, vtkSmartVolumeMapper::MAGNITUDE) &&
    SameValue(vtkAccelVolumeSmartMapper::COMPONENT, vtkSmartVolumeMapper::COMPONENT) &&
    SameValue(vtkAccelVolumeSmartMapper::DISABLED, vtkSmartVolumeMapper::DISABLED),
  "VectorModeType");
static_assert(SameValue(vtkAccelVolumeSliceMapper::BinaryMaskType,
                vtkGPUVolumeRayCastMapper::BinaryMaskType) &&
    SameValue(vtkAccelVolumeSliceMapper::LabelMapMaskType,
      vtkGPUVolumeRayCastMapper::LabelMapMaskType),
  "mask types");

enum class Kind
{
  Slice,
  RayCast,
  ShearWarp,
  Smart
};

const char* Name(Kind kind)
{
  switch (kind)
  {
    case Kind::Slice:
      return "slice";
    case Kind::RayCast:
      return "raycast";
    case Kind::ShearWarp:
      return "shearwarp";
    default:
      return "smart";
  }
}

vtkSmartPointer<vtkVolumeMapper> MakeMapper(Kind kind)
{
  switch (kind)
  {
    case Kind::Slice:
      return vtkSmartPointer<vtkAccelVolumeSliceMapper>::New();
    case Kind::RayCast:
    {
      auto mapper = vtkSmartPointer<vtkAccelVolumeRayCastMapper>::New();
      mapper->SetAutoAdjustSampleDistances(0);
      return mapper;
    }
    case Kind::ShearWarp:
      return vtkSmartPointer<vtkAccelVolumeShearWarpMapper>::New();
    default:
    {
      auto mapper = vtkSmartPointer<vtkAccelVolumeSmartMapper>::New();
      mapper->SetRequestedRenderModeToRayCast();
      mapper->GetRayCastMapper()->SetAutoAdjustSampleDistances(0);
      return mapper;
    }
  }
}

// One scene: 160x160, parallel oblique view (shear-warp needs it), the phantom's ramp.
struct Scene
{
  vtkSmartPointer<vtkVolumeMapper> Mapper;
  vtkNew<vtkVolume> Volume;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkRenderWindow> Window;
  int Errors = 0;

  Scene(Kind kind, vtkDataSet* input, int blend)
  {
    this->Mapper = MakeMapper(kind);
    this->Mapper->SetInputData(input);
    this->Mapper->SetBlendMode(blend);
    this->Volume->SetMapper(this->Mapper);
    accelvolume_test::SetRampProperty(this->Volume->GetProperty(), 40.0, 900.0, true);
    this->Renderer->SetBackground(0.1, 0.1, 0.2);
    this->Renderer->AddVolume(this->Volume);
    accelvolume_test::SetupObliqueView(this->Window, this->Renderer, 160, 30, 20, false);
  }

  std::vector<float> Render()
  {
    this->Window->Render();
    return accelvolume_test::ReadPixels(this->Window);
  }
};

vtkSmartPointer<vtkImageData> Phantom()
{
  return accelvolume_test::MakePhantom("vessels", 40, 36, 32, 1.0, 1.0, 1.25);
}

bool Same(const std::string& what, const std::vector<float>& a, const std::vector<float>& b,
  double maximum = 0.0)
{
  const auto d = CompareImages(a, b, 1.0 / 255.0);
  const bool ok = d.maximum <= maximum + 1.0e-6;
  if (!ok)
  {
    static int dumped = 0;
    accelvolume_test::DumpImage("dropin-" + std::to_string(dumped) + "-got", a, 160, 160);
    accelvolume_test::DumpImage("dropin-" + std::to_string(dumped++) + "-expected", b, 160, 160);
  }
  std::cout << (ok ? "ok    " : "FAIL  ") << what << ": max |diff| " << d.maximum << " (limit "
            << maximum << "), mean " << d.mean << "\n";
  return ok;
}

bool Drawn(const std::string& what, const std::vector<float>& image)
{
  size_t covered = 0;
  for (size_t p = 0; p < image.size() / 3; ++p)
  {
    const double d = std::abs(image[3 * p] - 0.1) + std::abs(image[3 * p + 1] - 0.1) +
      std::abs(image[3 * p + 2] - 0.2);
    covered += d > 0.05 ? 1 : 0;
  }
  const bool ok = covered > image.size() / 3 / 20;
  std::cout << (ok ? "ok    " : "FAIL  ") << what << ": " << covered << " pixels drawn\n";
  return ok;
}

std::vector<int> BlendsOf(Kind kind)
{
  if (kind == Kind::ShearWarp)
  {
    return { vtkVolumeMapper::COMPOSITE_BLEND, vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND,
      vtkVolumeMapper::MINIMUM_INTENSITY_BLEND };
  }
  return { vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND, vtkVolumeMapper::COMPOSITE_BLEND,
    vtkVolumeMapper::ADDITIVE_BLEND, vtkVolumeMapper::MINIMUM_INTENSITY_BLEND,
    vtkVolumeMapper::AVERAGE_INTENSITY_BLEND, vtkVolumeMapper::COMPOSITE_BLEND,
    vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND };
}

// One mapper object through every blend mode, each frame against a fresh mapper's.
bool BlendSwitch(Kind kind)
{
  auto image = Phantom();
  bool ok = true;
  Scene switched(kind, image, vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND);
  for (int blend : BlendsOf(kind))
  {
    switched.Mapper->SetBlendMode(blend);
    const std::vector<float> got = switched.Render();
    Scene fresh(kind, image, blend);
    const std::vector<float> expected = fresh.Render();
    const std::string what = std::string(Name(kind)) + ": switched to blend " +
      std::to_string(blend) + " vs a fresh mapper";
    // A MinIP of this ramp is transparent: nothing to draw.
    ok = Same(what, got, expected) &&
      (blend == vtkVolumeMapper::MINIMUM_INTENSITY_BLEND || Drawn(what, got)) && ok;
  }
  return ok;
}

// `make` turns the phantom into another input kind; its picture must equal the phantom's
// (exactly: the engines see the same values) or `reference`'s when given.
bool SamePicture(Kind kind, const std::string& what,
  const std::function<vtkSmartPointer<vtkDataSet>(vtkImageData*)>& make,
  const std::function<void(vtkVolumeMapper*)>& configure = nullptr,
  vtkDataSet* reference = nullptr, double bound = 0.0)
{
  auto image = Phantom();
  vtkSmartPointer<vtkDataSet> input = make(image);
  Scene expectedScene(kind, reference ? reference : image.GetPointer(),
    vtkVolumeMapper::COMPOSITE_BLEND);
  Scene gotScene(kind, input, vtkVolumeMapper::COMPOSITE_BLEND);
  if (configure)
  {
    configure(gotScene.Mapper);
  }
  // The same camera (a cell-scalar input's bounds are half a cell larger).
  gotScene.Renderer->GetActiveCamera()->DeepCopy(expectedScene.Renderer->GetActiveCamera());
  const std::vector<float> expected = expectedScene.Render();
  const std::vector<float> got = gotScene.Render();
  const std::string label = std::string(Name(kind)) + ": " + what;
  return Same(label, got, expected, bound) && Drawn(label, got);
}

template <typename ArrayType>
vtkSmartPointer<vtkDataSet> WithType(vtkImageData* image)
{
  auto copy = vtkSmartPointer<vtkImageData>::New();
  copy->CopyStructure(image);
  vtkNew<ArrayType> values;
  values->DeepCopy(image->GetPointData()->GetScalars());
  copy->GetPointData()->SetScalars(values);
  return copy;
}

// The phantom's values as cell scalars of an image one voxel larger per axis, whose cell
// centres are the phantom's points.
vtkSmartPointer<vtkDataSet> AsCellScalars(vtkImageData* image)
{
  auto cells = vtkSmartPointer<vtkImageData>::New();
  int dims[3];
  image->GetDimensions(dims);
  double spacing[3];
  double origin[3];
  image->GetSpacing(spacing);
  image->GetOrigin(origin);
  cells->SetDimensions(dims[0] + 1, dims[1] + 1, dims[2] + 1);
  cells->SetSpacing(spacing);
  cells->SetOrigin(
    origin[0] - 0.5 * spacing[0], origin[1] - 0.5 * spacing[1], origin[2] - 0.5 * spacing[2]);
  cells->GetCellData()->SetScalars(image->GetPointData()->GetScalars());
  return cells;
}

vtkSmartPointer<vtkDataSet> AsRectilinear(vtkImageData* image, bool even)
{
  auto grid = vtkSmartPointer<vtkRectilinearGrid>::New();
  int dims[3];
  image->GetDimensions(dims);
  grid->SetDimensions(dims);
  vtkNew<vtkDoubleArray> axes[3];
  for (int a = 0; a < 3; ++a)
  {
    for (int i = 0; i < dims[a]; ++i)
    {
      const double wobble = !even && a == 0 && i == 3 ? 0.4 : 0.0;
      axes[a]->InsertNextValue(image->GetOrigin()[a] + image->GetSpacing()[a] * i + wobble);
    }
  }
  grid->SetXCoordinates(axes[0]);
  grid->SetYCoordinates(axes[1]);
  grid->SetZCoordinates(axes[2]);
  grid->GetPointData()->SetScalars(image->GetPointData()->GetScalars());
  return grid;
}

// A named second array that is not the active scalars (the active ones are zero).
vtkSmartPointer<vtkDataSet> AsSelectedArray(vtkImageData* image)
{
  auto copy = vtkSmartPointer<vtkImageData>::New();
  copy->CopyStructure(image);
  vtkNew<vtkFloatArray> zeros;
  zeros->SetName("zeros");
  zeros->SetNumberOfTuples(image->GetNumberOfPoints());
  zeros->FillComponent(0, 0.0);
  copy->GetPointData()->SetScalars(zeros);
  vtkDataArray* values = image->GetPointData()->GetScalars();
  vtkSmartPointer<vtkDataArray> named;
  named.TakeReference(values->NewInstance());
  named->DeepCopy(values);
  named->SetName("density");
  copy->GetPointData()->AddArray(named);
  return copy;
}

// Three-component vectors whose magnitude (or component 1) is the phantom's value.
vtkSmartPointer<vtkDataSet> AsVectors(vtkImageData* image)
{
  auto copy = vtkSmartPointer<vtkImageData>::New();
  copy->CopyStructure(image);
  vtkNew<vtkFloatArray> vectors;
  vectors->SetNumberOfComponents(3);
  vtkDataArray* values = image->GetPointData()->GetScalars();
  vectors->SetNumberOfTuples(values->GetNumberOfTuples());
  for (vtkIdType t = 0; t < values->GetNumberOfTuples(); ++t)
  {
    const double v = values->GetComponent(t, 0);
    vectors->SetTuple3(t, 0.6 * v, 0.8 * v, 0.0);
  }
  copy->GetPointData()->SetScalars(vectors);
  return copy;
}

vtkSmartPointer<vtkImageData> Scaled(vtkImageData* image, double factor)
{
  auto copy = vtkSmartPointer<vtkImageData>::New();
  copy->CopyStructure(image);
  vtkNew<vtkFloatArray> values;
  vtkDataArray* source = image->GetPointData()->GetScalars();
  values->SetNumberOfTuples(source->GetNumberOfTuples());
  for (vtkIdType t = 0; t < source->GetNumberOfTuples(); ++t)
  {
    values->SetValue(t, static_cast<float>(factor * source->GetComponent(t, 0)));
  }
  copy->GetPointData()->SetScalars(values);
  return copy;
}

bool InputKinds(Kind kind)
{
  bool ok = true;
  // Sampled as floats: the float copy's picture.
  auto image = Phantom();
  auto floats = WithType<vtkFloatArray>(
    vtkImageData::SafeDownCast(WithType<vtkUnsignedIntArray>(image)));
  ok = SamePicture(kind, "unsigned int scalars", WithType<vtkUnsignedIntArray>, nullptr, floats) &&
    ok;
  ok = SamePicture(kind, "long long scalars", WithType<vtkLongLongArray>, nullptr, floats) && ok;
  ok = SamePicture(kind, "cell scalars", AsCellScalars,
         [](vtkVolumeMapper* mapper) { mapper->SetScalarModeToUseCellData(); }) &&
    ok;
  ok = SamePicture(kind, "evenly spaced vtkRectilinearGrid",
         [](vtkImageData* image) { return AsRectilinear(image, true); }) &&
    ok;
  ok = SamePicture(kind, "selected point array", AsSelectedArray,
         [](vtkVolumeMapper* mapper)
         {
           mapper->SetScalarModeToUsePointFieldData();
           mapper->SelectScalarArray("density");
         }) &&
    ok;
  return ok;
}

bool UnevenRectilinearIsAnError()
{
  Scene scene(Kind::RayCast, AsRectilinear(Phantom(), false), vtkVolumeMapper::COMPOSITE_BLEND);
  vtkNew<vtkCallbackCommand> count;
  int errors = 0;
  count->SetClientData(&errors);
  count->SetCallback([](vtkObject*, unsigned long, void* client, void*)
    { ++*static_cast<int*>(client); });
  scene.Mapper->AddObserver(vtkCommand::ErrorEvent, count);
  scene.Render();
  const bool ok = errors > 0;
  std::cout << (ok ? "ok    " : "FAIL  ") << "uneven vtkRectilinearGrid: " << errors
            << " error(s)\n";
  return ok;
}

bool VectorModes()
{
  bool ok = true;
  auto configure = [](int mode, int component)
  {
    return [mode, component](vtkVolumeMapper* mapper)
    {
      auto* smart = vtkAccelVolumeSmartMapper::SafeDownCast(mapper);
      smart->SetVectorMode(mode);
      smart->SetVectorComponent(component);
    };
  };
  auto image = Phantom();
  // |(0.6 v, 0.8 v, 0)| = v; component 1 = 0.8 v.
  ok = SamePicture(Kind::Smart, "VectorMode MAGNITUDE", AsVectors,
         configure(vtkAccelVolumeSmartMapper::MAGNITUDE, 0), Scaled(image, 1.0), 1.0 / 255.0) &&
    ok;
  ok = SamePicture(Kind::Smart, "VectorMode COMPONENT 1", AsVectors,
         configure(vtkAccelVolumeSmartMapper::COMPONENT, 1), Scaled(image, 0.8), 1.0 / 255.0) &&
    ok;
  return ok;
}

// colour' = colour / window + (0.5 - level / window) * alpha, over the background.
bool FinalColorWindowLevel(Kind kind)
{
  auto image = Phantom();
  Scene plain(kind, image, vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND);
  plain.Renderer->SetBackground(0, 0, 0);
  const std::vector<float> before = plain.Render();
  auto* mapper = vtkAccelVolumeMapper::SafeDownCast(plain.Mapper);
  mapper->SetFinalColorWindow(0.5f);
  mapper->SetFinalColorLevel(0.5f);
  const std::vector<float> after = plain.Render();
  // With a black background, alpha only scales: the expected value needs the volume's alpha,
  // which a MIP of this ramp has where the colour is; check the mapping through the brightest
  // pixels instead: v' = 2 v - 0.5 a >= 2 v - 0.5 (clamped to [0, a]).
  size_t checked = 0;
  size_t wrong = 0;
  for (size_t i = 0; i < before.size(); ++i)
  {
    if (before[i] > 0.3f)
    {
      ++checked;
      const float lowest = std::max(0.0f, std::min(1.0f, 2.0f * before[i] - 0.5f));
      wrong += after[i] + 2.0f / 255.0f < lowest || after[i] > 2.0f * before[i] + 2.0f / 255.0f;
    }
  }
  const bool ok = checked > 100 && wrong == 0;
  std::cout << (ok ? "ok    " : "FAIL  ") << Name(kind) << ": FinalColorWindow 0.5, level 0.5: "
            << wrong << " of " << checked << " bright channels outside the expected range\n";
  return ok;
}

// Jitter is noise, as VTK's: seen through a volume that ramps along the view direction, the
// change jitter makes is proportional to each pixel's offset, so its correlation between nearby
// pixels is that of the offsets: near 0 for noise, large at some offset for a regular pattern.
bool JitterIsNoise()
{
  auto ramp = vtkSmartPointer<vtkImageData>::New();
  ramp->SetDimensions(32, 32, 32);
  ramp->AllocateScalars(VTK_FLOAT, 1);
  auto* values = static_cast<float*>(ramp->GetScalarPointer());
  for (int k = 0; k < 32; ++k)
  {
    for (int j = 0; j < 32 * 32; ++j)
    {
      values[k * 32 * 32 + j] = static_cast<float>(10 * k);
    }
  }
  vtkNew<vtkAccelVolumeSliceMapper> mapper;
  mapper->SetInputData(ramp);
  mapper->SetAutoAdjustSampleDistances(0);
  mapper->SetSampleDistance(2.0);
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  accelvolume_test::SetRampProperty(volume->GetProperty(), 0.0, 2000.0);
  vtkNew<vtkRenderer> renderer;
  renderer->AddVolume(volume);
  vtkNew<vtkRenderWindow> window;
  window->SetSize(96, 96);
  window->SetMultiSamples(0);
  window->AddRenderer(renderer);
  renderer->ResetCamera();
  renderer->GetActiveCamera()->ParallelProjectionOn();
  renderer->GetActiveCamera()->SetParallelScale(10.0); // the box fills the window
  window->Render();
  const std::vector<float> before = accelvolume_test::ReadPixels(window);
  mapper->UseJitteringOn();
  window->Render();
  const std::vector<float> after = accelvolume_test::ReadPixels(window);
  const int size = 96;
  std::vector<double> change(static_cast<size_t>(size) * size);
  double mean = 0;
  for (size_t p = 0; p < change.size(); ++p)
  {
    change[p] = after[3 * p] - before[3 * p];
    mean += change[p];
  }
  mean /= static_cast<double>(change.size());
  double variance = 0;
  for (double& c : change)
  {
    c -= mean;
    variance += c * c;
  }
  double worst = 0;
  for (int dy = 0; dy <= 4; ++dy)
  {
    for (int dx = dy == 0 ? 1 : -4; dx <= 4; ++dx)
    {
      double sum = 0;
      for (int y = 0; y + dy < size; ++y)
      {
        for (int x = std::max(0, -dx); x < size && x + dx < size; ++x)
        {
          sum += change[static_cast<size_t>(y) * size + x] *
            change[static_cast<size_t>(y + dy) * size + x + dx];
        }
      }
      worst = std::max(worst, std::abs(sum) / std::max(variance, 1.0e-12));
    }
  }
  const bool ok = variance > 1.0e-6 && worst < 0.15;
  std::cout << (ok ? "ok    " : "FAIL  ") << "slice: jitter change variance " << variance
            << ", largest correlation between pixels up to 4 apart " << worst << " (limit 0.15)\n";
  return ok;
}

// vtkHardwareSelector over the volume finds the volume prop (VTK's GPU mapper supports the
// actor pass with cell picking), and the next frame still shows the volume as before.
bool Picking(Kind kind)
{
  auto image = Phantom();
  Scene scene(kind, image, vtkVolumeMapper::COMPOSITE_BLEND);
  const std::vector<float> before = scene.Render();
  vtkNew<vtkHardwareSelector> selector;
  selector->SetRenderer(scene.Renderer);
  selector->SetFieldAssociation(vtkDataObject::FIELD_ASSOCIATION_CELLS);
  selector->SetArea(60, 60, 100, 100);
  vtkSmartPointer<vtkSelection> selection;
  selection.TakeReference(selector->Select());
  bool found = false;
  for (unsigned int n = 0; selection && n < selection->GetNumberOfNodes(); ++n)
  {
    vtkSelectionNode* node = selection->GetNode(n);
    found = found || node->GetProperties()->Get(vtkSelectionNode::PROP()) == scene.Volume.Get();
  }
  const std::vector<float> after = scene.Render();
  const std::string what = std::string(Name(kind)) + ": hardware selection";
  std::cout << (found ? "ok    " : "FAIL  ") << what << " finds the volume prop\n";
  return found && Same(what + ", next frame", after, before);
}

// ImageSampleDistance 2 on the slice mapper: a quarter of the fragments, magnified bilinearly;
// close to the full-resolution picture, and to vtkGPUVolumeRayCastMapper's with the same setting.
bool ImageSampleDistance()
{
  bool ok = true;
  auto image = Phantom();
  Scene full(Kind::Slice, image, vtkVolumeMapper::COMPOSITE_BLEND);
  Scene half(Kind::Slice, image, vtkVolumeMapper::COMPOSITE_BLEND);
  vtkAccelVolumeSliceMapper::SafeDownCast(half.Mapper)->SetImageSampleDistance(2.0f);
  const std::vector<float> fullImage = full.Render();
  const std::vector<float> halfImage = half.Render();
  const auto d = CompareImages(halfImage, fullImage, 24.0 / 255.0);
  const bool close = d.mean < 3.0 / 255.0 && d.fractionAbove < 0.05 && d.maximum > 0;
  std::cout << (close ? "ok    " : "FAIL  ") << "slice: ImageSampleDistance 2 vs 1: mean |diff| "
            << d.mean << " (limit " << 3.0 / 255.0 << "), fraction over 24 levels "
            << d.fractionAbove << " (limit 0.05), differs at all: " << (d.maximum > 0) << "\n";
  ok = close && ok;
  for (int blend : { vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND, vtkVolumeMapper::ADDITIVE_BLEND })
  {
    Scene fullBlend(Kind::Slice, image, blend);
    Scene halfBlend(Kind::Slice, image, blend);
    vtkAccelVolumeSliceMapper::SafeDownCast(halfBlend.Mapper)->SetImageSampleDistance(2.0f);
    const auto e = CompareImages(halfBlend.Render(), fullBlend.Render(), 24.0 / 255.0);
    const bool blendClose = e.mean < 3.0 / 255.0 && e.fractionAbove < 0.05;
    std::cout << (blendClose ? "ok    " : "FAIL  ") << "slice: ImageSampleDistance 2 vs 1, blend "
              << blend << ": mean |diff| " << e.mean << ", fraction over 24 levels "
              << e.fractionAbove << "\n";
    ok = blendClose && ok;
  }
  return ok;
}

// A camera moving into a volume of tiny spacing (VTK's TestGPURayCastCameraInsideSmallSpacing:
// 7e-6 sample distance and unit distance): the picture changes continuously as the camera
// crosses the box face (the rays' integrand over [near, far] does), and the slice mapper and the
// ray caster agree inside. vtkGPUVolumeRayCastMapper's picture jumps there (more blue in
// VTK's test), which is VTK's error, not ours.
bool CameraInsideSmallSpacing()
{
  const double spacing = 0.0005 / 40.0;
  auto image = accelvolume_test::MakePhantom("blobs", 40, 40, 40, spacing, spacing, spacing);
  auto meanColour = [&](Kind kind, double dolly, std::vector<float>* pixels)
  {
    Scene scene(kind, image, vtkVolumeMapper::COMPOSITE_BLEND);
    if (auto* slice = vtkAccelVolumeSliceMapper::SafeDownCast(scene.Mapper))
    {
      slice->SetAutoAdjustSampleDistances(0);
      slice->SetSampleDistance(7e-6);
    }
    if (auto* rayCast = vtkAccelVolumeRayCastMapper::SafeDownCast(scene.Mapper))
    {
      rayCast->SetSampleDistance(7e-6);
    }
    scene.Volume->GetProperty()->SetScalarOpacityUnitDistance(7e-6);
    scene.Renderer->ResetCamera();
    scene.Renderer->GetActiveCamera()->Dolly(dolly);
    scene.Renderer->ResetCameraClippingRange();
    std::vector<float> rgb = scene.Render();
    double sum = 0;
    for (float v : rgb)
    {
      sum += v;
    }
    if (pixels)
    {
      *pixels = rgb;
    }
    return sum / static_cast<double>(rgb.size());
  };
  // The dollies that leave the camera just outside the box and just inside it.
  double bounds[6];
  image->GetBounds(bounds);
  double insideDolly = 1.0;
  {
    Scene probe(Kind::RayCast, image, vtkVolumeMapper::COMPOSITE_BLEND);
    for (double dolly = 1.0; dolly < 100.0; dolly += 0.05)
    {
      probe.Renderer->ResetCamera();
      probe.Renderer->GetActiveCamera()->Dolly(dolly);
      const double* eye = probe.Renderer->GetActiveCamera()->GetPosition();
      bool in = true;
      for (int a = 0; a < 3; ++a)
      {
        in = in && eye[a] > bounds[2 * a] && eye[a] < bounds[2 * a + 1];
      }
      if (in)
      {
        insideDolly = dolly;
        break;
      }
    }
  }
  const double outsideDolly = insideDolly - 0.05;
  bool ok = insideDolly > 1.0;
  for (Kind kind : { Kind::Slice, Kind::RayCast })
  {
    const double outside = meanColour(kind, outsideDolly, nullptr);
    const double inside = meanColour(kind, insideDolly, nullptr);
    const bool continuous = std::abs(inside - outside) < 0.15 * std::max(outside, 1.0e-3);
    std::cout << (continuous ? "ok    " : "FAIL  ") << Name(kind)
              << ": camera crossing the face of a volume of spacing " << spacing
              << ": mean colour " << outside << " -> " << inside << " (limit 15%)\n";
    ok = continuous && ok;
  }
  std::vector<float> slice;
  std::vector<float> rayCast;
  meanColour(Kind::Slice, insideDolly + 0.5, &slice);
  meanColour(Kind::RayCast, insideDolly + 0.5, &rayCast);
  std::cout << "camera inside from dolly " << insideDolly << "\n";
  ok = Drawn("camera inside: slice", slice) && Drawn("camera inside: ray caster", rayCast) && ok;
  return Same("camera inside: slice vs ray caster (mean |diff| bounded)", slice, rayCast, 1.0) &&
    accelvolume_test::Report("camera inside: slice vs ray caster",
      CompareImages(slice, rayCast, 16.0 / 255.0), 4.0 / 255.0, 0.03) &&
    ok;
}

// A mask over the voxels with index x < 20 (binary) or labelling x >= 20 (label map).
vtkSmartPointer<vtkImageData> MaskOf(vtkImageData* image, bool labels)
{
  auto mask = vtkSmartPointer<vtkImageData>::New();
  mask->CopyStructure(image);
  mask->AllocateScalars(VTK_UNSIGNED_CHAR, 1);
  int dims[3];
  image->GetDimensions(dims);
  auto* values = static_cast<unsigned char*>(mask->GetScalarPointer());
  for (vtkIdType i = 0; i < image->GetNumberOfPoints(); ++i)
  {
    const bool left = i % dims[0] < 20;
    values[i] = labels ? (left ? 0 : 1) : (left ? 255 : 0);
  }
  return mask;
}

// Masks on the slice mapper: a binary mask keeps the samples whose nearest voxel is inside, so a
// mask of x < 20 draws what cropping at x = 19.5 draws; a label map recolours its labelled voxels
// by the blend factor, and blend factor 0 changes nothing.
bool Masks()
{
  bool ok = true;
  auto image = Phantom();
  for (int blend : { vtkVolumeMapper::COMPOSITE_BLEND, vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND })
  {
    Scene masked(Kind::Slice, image, blend);
    auto* maskedMapper = vtkAccelVolumeSliceMapper::SafeDownCast(masked.Mapper);
    maskedMapper->SetMaskInput(MaskOf(image, false));
    maskedMapper->SetMaskTypeToBinary();
    maskedMapper->BoundaryRerenderingOff();
    Scene cropped(Kind::Slice, image, blend);
    auto* croppedMapper = vtkAccelVolumeSliceMapper::SafeDownCast(cropped.Mapper);
    croppedMapper->BoundaryRerenderingOff();
    croppedMapper->CroppingOn();
    croppedMapper->SetCroppingRegionPlanes(0, 19.5, -1, 100, -1, 100);
    croppedMapper->SetCroppingRegionFlagsToSubVolume();
    const auto d = CompareImages(masked.Render(), cropped.Render(), 8.0 / 255.0);
    const bool same = d.fractionAbove < 0.002;
    std::cout << (same ? "ok    " : "FAIL  ") << "slice: binary mask x < 20 vs cropping at 19.5, blend "
              << blend << ": fraction over 8 levels " << d.fractionAbove << " (limit 0.002)\n";
    ok = same && ok;
  }
  {
    // Blanking (vtkUniformGrid::BlankPoint, a ghost array's HIDDENPOINT) hides those voxels as
    // a binary mask does.
    auto blanked = vtkSmartPointer<vtkUniformGrid>::New();
    blanked->ShallowCopy(image);
    int dims[3];
    image->GetDimensions(dims);
    for (vtkIdType i = 0; i < image->GetNumberOfPoints(); ++i)
    {
      if (i % dims[0] >= 20)
      {
        blanked->BlankPoint(i);
      }
    }
    Scene hidden(Kind::Slice, blanked, vtkVolumeMapper::COMPOSITE_BLEND);
    Scene masked(Kind::Slice, image, vtkVolumeMapper::COMPOSITE_BLEND);
    auto* maskedMapper = vtkAccelVolumeSliceMapper::SafeDownCast(masked.Mapper);
    maskedMapper->SetMaskInput(MaskOf(image, false));
    maskedMapper->SetMaskTypeToBinary();
    ok = Same("slice: blanked points vs the same binary mask", hidden.Render(), masked.Render()) &&
      ok;
  }
  Scene plain(Kind::Slice, image, vtkVolumeMapper::COMPOSITE_BLEND);
  const std::vector<float> unmasked = plain.Render();
  vtkNew<vtkColorTransferFunction> green;
  green->AddRGBPoint(0, 0, 1, 0);
  green->AddRGBPoint(1000, 0, 1, 0);
  plain.Volume->GetProperty()->SetLabelColor(1, green);
  auto* mapper = vtkAccelVolumeSliceMapper::SafeDownCast(plain.Mapper);
  mapper->SetMaskInput(MaskOf(image, true));
  mapper->SetMaskTypeToLabelMap();
  mapper->SetMaskBlendFactor(0.0f);
  ok = Same("slice: label map, blend factor 0 vs no mask", plain.Render(), unmasked) && ok;
  mapper->SetMaskBlendFactor(1.0f);
  const std::vector<float> labelled = plain.Render();
  double greener = 0;
  double redder = 0;
  for (size_t p = 0; p < labelled.size() / 3; ++p)
  {
    greener += labelled[3 * p + 1] - unmasked[3 * p + 1];
    redder += labelled[3 * p] - unmasked[3 * p];
  }
  const bool recoloured = greener > 50.0 && redder < 0.0;
  std::cout << (recoloured ? "ok    " : "FAIL  ") << "slice: label map, blend factor 1: green "
            << greener << " more, red " << redder << "\n";
  return recoloured && ok;
}

// RenderToImage: the scene keeps only its background; the colour image over the background is
// the normal frame (8-bit rounding), and the depth image is below 1 exactly where the volume
// contributes.
bool RenderToImage()
{
  auto image = Phantom();
  Scene normal(Kind::Slice, image, vtkVolumeMapper::COMPOSITE_BLEND);
  const std::vector<float> expected = normal.Render();
  Scene rtt(Kind::Slice, image, vtkVolumeMapper::COMPOSITE_BLEND);
  auto* mapper = vtkAccelVolumeSliceMapper::SafeDownCast(rtt.Mapper);
  mapper->RenderToImageOn();
  const std::vector<float> window = rtt.Render();
  vtkNew<vtkImageData> colour;
  vtkNew<vtkImageData> depth;
  mapper->GetColorImage(colour);
  mapper->GetDepthImage(depth);
  bool ok = colour->GetNumberOfPoints() == 160 * 160 && depth->GetNumberOfPoints() == 160 * 160 &&
    colour->GetNumberOfScalarComponents() == 4;
  if (!ok)
  {
    std::cout << "FAIL  slice: render-to-image gave no images\n";
    return false;
  }
  double worstOver = 0;
  size_t wrongDepth = 0;
  size_t backgroundOff = 0;
  const double background[3] = { 0.1, 0.1, 0.2 };
  const auto* rgba = static_cast<const unsigned char*>(colour->GetScalarPointer());
  const auto* z = static_cast<const float*>(depth->GetScalarPointer());
  for (size_t p = 0; p < expected.size() / 3; ++p)
  {
    const double alpha = rgba[4 * p + 3] / 255.0;
    for (int c = 0; c < 3; ++c)
    {
      const double over = rgba[4 * p + c] / 255.0 + (1.0 - alpha) * background[c];
      worstOver = std::max(worstOver, std::abs(over - expected[3 * p + c]));
      backgroundOff += std::abs(window[3 * p + c] - background[c]) > 1.0 / 255.0 ? 1 : 0;
    }
    wrongDepth += (alpha > 2.0 / 255.0 && !(z[p] < 1.0f)) || (rgba[4 * p + 3] == 0 && z[p] < 1.0f);
  }
  ok = worstOver <= 3.0 / 255.0 && wrongDepth == 0 && backgroundOff == 0;
  std::cout << (ok ? "ok    " : "FAIL  ") << "slice: render-to-image: colour over background vs "
            << "normal frame max " << worstOver << " (limit " << 3.0 / 255.0 << "), "
            << wrongDepth << " pixels with a wrong depth, " << backgroundOff
            << " window channels off the background\n";
  return ok;
}

bool VTKNames()
{
  bool ok = true;
  vtkNew<vtkAccelVolumeSliceMapper> slice;
  vtkNew<vtkRenderWindow> window;
  ok = slice->IsRenderSupported(window, nullptr) == 1 && ok;
  slice->UseJitteringOn();
  ok = slice->GetJittering() == 1 && slice->GetUseJittering() == 1 && ok;
  slice->SetPartitions(2, 1, 1);
  ok = slice->GetPartitions()[0] == 2 && ok;
  slice->SetMaxMemoryInBytes(1 << 20);
  ok = slice->GetGPUMemoryBudget() == static_cast<vtkIdType>(0.75 * (1 << 20)) && ok;
  vtkNew<vtkAccelVolumeRayCastMapper> rayCast;
  ok = rayCast->IsRenderSupported(window, nullptr) == 1 && ok;
  vtkNew<vtkAccelVolumeSmartMapper> smart;
  smart->SetRequestedRenderModeToGPU();
  ok = smart->GetRequestedRenderMode() == vtkSmartVolumeMapper::GPURenderMode && ok;
  ok = smart->GetLastUsedRenderMode() == vtkSmartVolumeMapper::UndefinedRenderMode && ok;
  std::cout << (ok ? "ok    " : "FAIL  ") << "VTK names and values\n";
  return ok;
}
}

int TestAccelVolumeDropIn(int, char*[])
{
  bool ok = VTKNames();
  for (Kind kind : { Kind::Slice, Kind::RayCast, Kind::ShearWarp, Kind::Smart })
  {
    ok = BlendSwitch(kind) && ok;
    ok = InputKinds(kind) && ok;
    ok = FinalColorWindowLevel(kind) && ok;
    ok = Picking(kind) && ok;
  }
  ok = UnevenRectilinearIsAnError() && ok;
  ok = VectorModes() && ok;
  ok = JitterIsNoise() && ok;
  ok = ImageSampleDistance() && ok;
  ok = CameraInsideSmallSpacing() && ok;
  ok = Masks() && ok;
  ok = RenderToImage() && ok;
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
