// Drop-in behaviour shared by every mapper (issue 16): one mapper object switched between blend
// modes draws what a fresh mapper draws; the inputs VTK's GPU mapper takes (unsigned int and
// 64-bit integers, cell scalars, rectilinear grids, a selected array) give the pictures of their
// one-component point-scalar equivalents; VectorMode reduces vectors as vtkSmartVolumeMapper;
// FinalColorWindow / Level transform the colours as VTK's mappers; VTK's enum values hold.
// (The slice mapper's own drop-in checks: TestAccelVolumeSliceDropIn.)
#include "AccelVolumeDropInScene.h"

namespace
{
using namespace accelvolume_dropin;

// VTK's values, so code written for vtkSmartVolumeMapper means the same with ours.
constexpr bool SameValue(int ours, int vtks)
{
  return ours == vtks;
}
static_assert(
  SameValue(vtkAccelVolumeSmartMapper::DefaultRenderMode, vtkSmartVolumeMapper::DefaultRenderMode),
  "DefaultRenderMode");
static_assert(
  SameValue(vtkAccelVolumeSmartMapper::RayCastRenderMode, vtkSmartVolumeMapper::RayCastRenderMode),
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
static_assert(
  SameValue(vtkAccelVolumeSliceMapper::BinaryMaskType, vtkGPUVolumeRayCastMapper::BinaryMaskType) &&
    SameValue(
      vtkAccelVolumeSliceMapper::LabelMapMaskType, vtkGPUVolumeRayCastMapper::LabelMapMaskType),
  "mask types");

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
  const std::function<void(vtkVolumeMapper*)>& configure = nullptr, vtkDataSet* reference = nullptr,
  double bound = 0.0)
{
  auto image = Phantom();
  vtkSmartPointer<vtkDataSet> input = make(image);
  Scene expectedScene(
    kind, reference ? reference : image.GetPointer(), vtkVolumeMapper::COMPOSITE_BLEND);
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
  auto floats =
    WithType<vtkFloatArray>(vtkImageData::SafeDownCast(WithType<vtkUnsignedIntArray>(image)));
  ok =
    SamePicture(kind, "unsigned int scalars", WithType<vtkUnsignedIntArray>, nullptr, floats) && ok;
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

// An unevenly spaced rectilinear grid is resampled onto a regular grid. With a field linear in
// x, y and z every trilinear sampling is exact, so the uneven grid must draw the picture of a
// regular image of the same field and bounds (every mapper); cell scalars there are an error.
vtkSmartPointer<vtkDataSet> LinearField(bool uneven)
{
  constexpr int N = 24;
  const auto field = [](double x, double y, double z) { return 20.0 * x + 9.0 * y + 14.0 * z; };
  if (!uneven)
  {
    auto image = vtkSmartPointer<vtkImageData>::New();
    image->SetDimensions(N, N, N);
    image->SetSpacing(1.5, 1.5, 1.5);
    image->AllocateScalars(VTK_FLOAT, 1);
    for (int k = 0; k < N; ++k)
      for (int j = 0; j < N; ++j)
        for (int i = 0; i < N; ++i)
          image->SetScalarComponentFromDouble(i, j, k, 0, field(1.5 * i, 1.5 * j, 1.5 * k));
    return image;
  }
  auto grid = vtkSmartPointer<vtkRectilinearGrid>::New();
  grid->SetDimensions(N, N, N);
  vtkNew<vtkDoubleArray> axes[3];
  for (int a = 0; a < 3; ++a)
  {
    for (int i = 0; i < N; ++i)
    {
      // Steps of 0.75 .. 2.25, ending at 1.5 * (N - 1) like the image.
      const double t = static_cast<double>(i) / (N - 1);
      axes[a]->InsertNextValue(1.5 * (N - 1) * (0.5 * t + 0.5 * t * t));
    }
  }
  grid->SetXCoordinates(axes[0]);
  grid->SetYCoordinates(axes[1]);
  grid->SetZCoordinates(axes[2]);
  vtkNew<vtkFloatArray> values;
  values->SetName("linear");
  for (int k = 0; k < N; ++k)
    for (int j = 0; j < N; ++j)
      for (int i = 0; i < N; ++i)
        values->InsertNextValue(static_cast<float>(
          field(axes[0]->GetValue(i), axes[1]->GetValue(j), axes[2]->GetValue(k))));
  grid->GetPointData()->SetScalars(values);
  return grid;
}

bool UnevenRectilinear(Kind kind)
{
  Scene image(kind, LinearField(false), vtkVolumeMapper::COMPOSITE_BLEND);
  Scene grid(kind, LinearField(true), vtkVolumeMapper::COMPOSITE_BLEND);
  for (Scene* scene : { &image, &grid })
  {
    // The same samples along the rays whatever the voxel size (the resampled grid is finer).
    if (auto* slice = vtkAccelVolumeSliceMapper::SafeDownCast(scene->Mapper))
    {
      slice->SetAutoAdjustSampleDistances(0);
      slice->SetSampleDistance(0.5);
    }
  }
  const std::vector<float> expected = image.Render();
  const std::vector<float> got = grid.Render();
  const auto d = CompareImages(got, expected, 4.0 / 255.0);
  // Shear-warp samples once per voxel slice: the finer resampled grid takes twice the samples.
  const bool shearWarp = kind == Kind::ShearWarp;
  const double meanLimit = (shearWarp ? 5.0 : 1.0) / 255.0;
  const double fractionLimit = shearWarp ? 0.25 : 0.01;
  const bool same = d.mean <= meanLimit && d.fractionAbove <= fractionLimit && grid.Errors == 0;
  std::cout << (same ? "ok    " : "FAIL  ") << Name(kind)
            << ": uneven vtkRectilinearGrid vs the image of the same linear field: mean |diff| "
            << d.mean << " (limit " << meanLimit << "), pixels over 4/255 " << d.fractionAbove
            << " (limit " << fractionLimit << ")\n";
  return Drawn(std::string(Name(kind)) + ": uneven vtkRectilinearGrid", got) && same;
}

bool UnevenRectilinearCellsAreAnError()
{
  vtkSmartPointer<vtkDataSet> field = LinearField(true);
  auto* grid = vtkRectilinearGrid::SafeDownCast(field);
  vtkNew<vtkFloatArray> cells;
  cells->SetNumberOfTuples(grid->GetNumberOfCells());
  cells->FillComponent(0, 1.0);
  grid->GetCellData()->SetScalars(cells);
  grid->GetPointData()->SetScalars(nullptr);
  Scene scene(Kind::RayCast, grid, vtkVolumeMapper::COMPOSITE_BLEND);
  scene.Mapper->SetScalarModeToUseCellData();
  vtkNew<vtkCallbackCommand> count;
  int errors = 0;
  count->SetClientData(&errors);
  count->SetCallback(
    [](vtkObject*, unsigned long, void* client, void*) { ++*static_cast<int*>(client); });
  scene.Mapper->AddObserver(vtkCommand::ErrorEvent, count);
  scene.Render();
  const bool ok = errors > 0;
  std::cout << (ok ? "ok    " : "FAIL  ")
            << "cell scalars on an uneven vtkRectilinearGrid: " << errors << " error(s)\n";
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
  std::cout << (ok ? "ok    " : "FAIL  ") << Name(kind)
            << ": FinalColorWindow 0.5, level 0.5: " << wrong << " of " << checked
            << " bright channels outside the expected range\n";
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
  for (Kind kind : accelvolume_test::AllMappers)
  {
    ok = UnevenRectilinear(kind) && ok;
  }
  ok = UnevenRectilinearCellsAreAnError() && ok;
  ok = VectorModes() && ok;
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}