// Masks, label maps and ghost arrays on the CPU ray caster (issue 16): the same samples hidden
// and coloured as by the slice mapper (and vtkGPUVolumeRayCastMapper for ghost cells), leaping
// exact with a mask (it is a skipping source for the distance map), thread counts identical,
// mask edits seen, malformed masks a clear error.
#include "AccelVolumeDropInScene.h"

#include "vtkContourValues.h"
#include "vtkUnsignedCharArray.h"

namespace
{
using namespace accelvolume_dropin;

// Voxels with index x < 20 inside (binary), or labelled 1 where x >= 20 (label map); `shift`
// moves the boundary.
vtkSmartPointer<vtkImageData> MaskOf(vtkImageData* image, bool labels, int boundary = 20)
{
  auto mask = vtkSmartPointer<vtkImageData>::New();
  mask->CopyStructure(image);
  mask->AllocateScalars(VTK_UNSIGNED_CHAR, 1);
  int dims[3];
  image->GetDimensions(dims);
  auto* values = static_cast<unsigned char*>(mask->GetScalarPointer());
  for (vtkIdType i = 0; i < image->GetNumberOfPoints(); ++i)
  {
    const bool left = i % dims[0] < boundary;
    values[i] = labels ? (left ? 0 : 1) : (left ? 255 : 0);
  }
  return mask;
}

vtkAccelVolumeRayCastMapper* RayCaster(Scene& scene)
{
  return vtkAccelVolumeRayCastMapper::SafeDownCast(scene.Mapper);
}

// Both mappers sample every 0.5 so that their pictures are comparable.
void FixSampling(Scene& scene)
{
  if (auto* slice = vtkAccelVolumeSliceMapper::SafeDownCast(scene.Mapper))
  {
    slice->SetAutoAdjustSampleDistances(0);
    slice->SetSampleDistance(0.5);
    slice->BoundaryRerenderingOff();
  }
  if (auto* rayCast = vtkAccelVolumeRayCastMapper::SafeDownCast(scene.Mapper))
  {
    rayCast->SetSampleDistance(0.5);
  }
}

void SetMask(Scene& scene, vtkImageData* mask, bool labelMap, float blend = 1.0f)
{
  if (auto* slice = vtkAccelVolumeSliceMapper::SafeDownCast(scene.Mapper))
  {
    slice->SetMaskInput(mask);
    slice->SetMaskType(labelMap ? vtkGPUVolumeRayCastMapper::LabelMapMaskType
                                : vtkGPUVolumeRayCastMapper::BinaryMaskType);
    slice->SetMaskBlendFactor(blend);
  }
  if (auto* rayCast = vtkAccelVolumeRayCastMapper::SafeDownCast(scene.Mapper))
  {
    rayCast->SetMaskInput(mask);
    rayCast->SetMaskType(labelMap ? vtkAccelVolumeRayCastMapper::LabelMapMaskType
                                  : vtkAccelVolumeRayCastMapper::BinaryMaskType);
    rayCast->SetMaskBlendFactor(blend);
  }
}

const char* BlendName(int blend)
{
  switch (blend)
  {
    case vtkVolumeMapper::COMPOSITE_BLEND:
      return "composite";
    case vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND:
      return "MIP";
    case vtkVolumeMapper::MINIMUM_INTENSITY_BLEND:
      return "MinIP";
    case vtkVolumeMapper::ADDITIVE_BLEND:
      return "additive";
    default:
      return "average";
  }
}

// A binary mask in every blend mode: the ray caster draws the slice mapper's picture, the mask
// changes the picture, and leaping / threads do not change a bit.
bool BinaryMasks()
{
  bool ok = true;
  auto image = Phantom();
  auto mask = MaskOf(image, false);
  for (int blend : { vtkVolumeMapper::COMPOSITE_BLEND, vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND,
         vtkVolumeMapper::MINIMUM_INTENSITY_BLEND, vtkVolumeMapper::ADDITIVE_BLEND,
         vtkVolumeMapper::AVERAGE_INTENSITY_BLEND })
  {
    const std::string name = BlendName(blend);
    Scene ours(Kind::RayCast, image, blend);
    Scene slice(Kind::Slice, image, blend);
    FixSampling(ours);
    FixSampling(slice);
    const std::vector<float> unmasked = ours.Render();
    SetMask(ours, mask, false);
    SetMask(slice, mask, false);
    const std::vector<float> masked = ours.Render();
    Scene theirs(Kind::Slice, image, blend);
    vtkNew<vtkGPUVolumeRayCastMapper> gpu;
    gpu->SetInputData(image);
    gpu->SetBlendMode(blend);
    gpu->SetAutoAdjustSampleDistances(0);
    gpu->SetSampleDistance(0.5);
    gpu->SetMaskInput(mask);
    gpu->SetMaskTypeToBinary();
    theirs.Volume->SetMapper(gpu);
    // MinIP: where every sample of a ray is masked VTK's GPU mapper shows its starting value
    // (the top of the range, opaque here); there is no minimum there, and ours draws nothing.
    if (blend != vtkVolumeMapper::MINIMUM_INTENSITY_BLEND)
    {
      ok = accelvolume_test::Report(
             ("ray caster vs vtkGPUVolumeRayCastMapper, binary mask, " + name).c_str(),
             CompareImages(masked, theirs.Render(), 16.0 / 255.0), 3.0 / 255.0, 0.02) &&
        ok;
    }
    ok = accelvolume_test::Report(("ray caster vs slice mapper, binary mask, " + name).c_str(),
           CompareImages(masked, slice.Render(), 16.0 / 255.0), 3.0 / 255.0, 0.02) &&
      ok;
    // (MinIP: the phantom's minimum is the background value along every ray, masked or not.)
    const double least = blend == vtkVolumeMapper::MINIMUM_INTENSITY_BLEND ? 0.0 : 0.01;
    const auto changed = CompareImages(masked, unmasked, 16.0 / 255.0);
    const bool hides = changed.fractionAbove >= least;
    std::cout << (hides ? "ok    " : "FAIL  ") << "ray caster: binary mask changes " << name
              << " (pixels over 16/255: " << changed.fractionAbove << ", at least " << least
              << ")\n";
    ok = hides &&
      (blend == vtkVolumeMapper::MINIMUM_INTENSITY_BLEND ||
        Drawn("ray caster: binary mask, " + name, masked)) &&
      ok;
    vtkAccelVolumeRayCastMapper* mapper = RayCaster(ours);
    const vtkTypeInt64 samples = mapper->GetLastNumberOfSamples();
    for (int leap : { vtkAccelVolumeRayCastMapper::LEAP_NONE,
           vtkAccelVolumeRayCastMapper::LEAP_OCTREE })
    {
      mapper->SetLeapMode(leap);
      ok = Same("ray caster: binary mask, " + name + ", leap mode " + std::to_string(leap) +
            " vs the distance map",
             ours.Render(), masked) &&
        ok;
    }
    mapper->SetLeapMode(vtkAccelVolumeRayCastMapper::LEAP_DISTANCE_MAP);
    mapper->SetNumberOfThreads(1);
    ok = Same("ray caster: binary mask, " + name + ", 1 thread vs all", ours.Render(), masked) &&
      ok;
    mapper->SetNumberOfThreads(0);
    if (blend == vtkVolumeMapper::COMPOSITE_BLEND)
    {
      // The mask is a skipping source: the hidden cells are leaped, not sampled.
      SetMask(ours, nullptr, false);
      ours.Render();
      const vtkTypeInt64 unmaskedSamples = mapper->GetLastNumberOfSamples();
      const bool fewer = samples < unmaskedSamples / 2 + unmaskedSamples / 4;
      std::cout << (fewer ? "ok    " : "FAIL  ") << "ray caster: composite samples with the mask "
                << samples << " vs " << unmaskedSamples << " without (must be under 75%)\n";
      ok = fewer && Same("ray caster: mask removed vs never masked", ours.Render(), unmasked) &&
        ok;
    }
  }
  return ok;
}

// A binary mask with multi-component scalars, and with ISOSURFACE_BLEND / SLICE_BLEND.
bool OtherModes()
{
  bool ok = true;
  auto image = Phantom();
  auto mask = MaskOf(image, false);
  {
    auto two = vtkSmartPointer<vtkImageData>::New();
    two->CopyStructure(image);
    two->AllocateScalars(VTK_FLOAT, 2);
    vtkDataArray* from = image->GetPointData()->GetScalars();
    vtkDataArray* to = two->GetPointData()->GetScalars();
    for (vtkIdType i = 0; i < image->GetNumberOfPoints(); ++i)
    {
      const double v = from->GetComponent(i, 0);
      to->SetComponent(i, 0, v);
      to->SetComponent(i, 1, 900.0 - v);
    }
    Scene ours(Kind::RayCast, two, vtkVolumeMapper::COMPOSITE_BLEND);
    Scene slice(Kind::Slice, two, vtkVolumeMapper::COMPOSITE_BLEND);
    for (Scene* scene : { &ours, &slice })
    {
      FixSampling(*scene);
      vtkVolumeProperty* property = scene->Volume->GetProperty();
      property->SetIndependentComponents(1);
      accelvolume_test::SetRampProperty(property, 40.0, 900.0, true);
      property->SetColor(1, property->GetRGBTransferFunction(0));
      property->SetScalarOpacity(1, property->GetScalarOpacity(0));
      property->SetShade(1, 1);
      SetMask(*scene, mask, false);
    }
    const std::vector<float> got = ours.Render();
    ok = accelvolume_test::Report("ray caster vs slice mapper, binary mask, 2 components",
           CompareImages(got, slice.Render(), 16.0 / 255.0), 3.0 / 255.0, 0.02) &&
      Drawn("ray caster: binary mask, 2 components", got) && ok;
    RayCaster(ours)->SetLeapMode(vtkAccelVolumeRayCastMapper::LEAP_NONE);
    ok = Same("ray caster: binary mask, 2 components, no leaping", ours.Render(), got) && ok;
  }
  for (int blend : { vtkVolumeMapper::ISOSURFACE_BLEND, vtkVolumeMapper::SLICE_BLEND })
  {
    const std::string name = blend == vtkVolumeMapper::SLICE_BLEND ? "slice" : "iso-surface";
    Scene ours(Kind::RayCast, image, blend);
    Scene slice(Kind::Slice, image, blend);
    vtkNew<vtkPlane> plane;
    plane->SetOrigin(image->GetCenter());
    plane->SetNormal(0.3, 0.2, 1.0);
    for (Scene* scene : { &ours, &slice })
    {
      FixSampling(*scene);
      vtkVolumeProperty* property = scene->Volume->GetProperty();
      property->GetIsoSurfaceValues()->SetValue(0, 400.0);
      property->SetSliceFunction(plane);
      if (blend == vtkVolumeMapper::SLICE_BLEND)
      {
        // An opaque cut: every point of the plane inside the volume is drawn.
        vtkNew<vtkPiecewiseFunction> opaque;
        opaque->AddPoint(-1.0e6, 1.0);
        opaque->AddPoint(1.0e6, 1.0);
        property->SetScalarOpacity(opaque);
      }
    }
    const std::vector<float> unmasked = ours.Render();
    SetMask(ours, mask, false);
    SetMask(slice, mask, false);
    const std::vector<float> masked = ours.Render();
    ok = accelvolume_test::Report(("ray caster vs slice mapper, binary mask, " + name).c_str(),
           CompareImages(masked, slice.Render(), 16.0 / 255.0), 3.0 / 255.0, 0.02) &&
      ok;
    const auto changed = CompareImages(masked, unmasked, 4.0 / 255.0);
    const double least = blend == vtkVolumeMapper::SLICE_BLEND ? 0.1 : 0.002;
    const bool hides = changed.fractionAbove > least;
    std::cout << (hides ? "ok    " : "FAIL  ") << "ray caster: binary mask changes " << name
              << " (pixels over 4/255: " << changed.fractionAbove << ", must exceed " << least
              << ")\n";
    ok = hides && ok;
  }
  return ok;
}

// A label map recolours labelled voxels by the blend factor (0: no change), as the slice mapper.
bool LabelMaps()
{
  bool ok = true;
  auto image = Phantom();
  auto labels = MaskOf(image, true);
  vtkNew<vtkColorTransferFunction> green;
  green->AddRGBPoint(0, 0, 1, 0);
  green->AddRGBPoint(1000, 0, 1, 0);
  vtkNew<vtkPiecewiseFunction> denser;
  denser->AddPoint(0, 0.0);
  denser->AddPoint(300, 0.6);
  denser->AddPoint(1000, 0.6);
  Scene ours(Kind::RayCast, image, vtkVolumeMapper::COMPOSITE_BLEND);
  Scene slice(Kind::Slice, image, vtkVolumeMapper::COMPOSITE_BLEND);
  for (Scene* scene : { &ours, &slice })
  {
    FixSampling(*scene);
    scene->Volume->GetProperty()->SetLabelColor(1, green);
    scene->Volume->GetProperty()->SetLabelScalarOpacity(1, denser);
  }
  const std::vector<float> unmasked = ours.Render();
  SetMask(ours, labels, true, 0.0f);
  ok = Same("ray caster: label map, blend factor 0 vs no mask", ours.Render(), unmasked) && ok;
  for (float blend : { 0.5f, 1.0f })
  {
    SetMask(ours, labels, true, blend);
    SetMask(slice, labels, true, blend);
    const std::vector<float> got = ours.Render();
    const std::string name = "label map, blend factor " + std::to_string(blend).substr(0, 3);
    ok = accelvolume_test::Report(("ray caster vs slice mapper, " + name).c_str(),
           CompareImages(got, slice.Render(), 16.0 / 255.0), 3.0 / 255.0, 0.02) &&
      ok;
    double greener = 0;
    for (size_t p = 0; p < got.size() / 3; ++p)
    {
      greener += got[3 * p + 1] - unmasked[3 * p + 1];
    }
    const bool recoloured = greener > 50.0;
    std::cout << (recoloured ? "ok    " : "FAIL  ") << "ray caster: " << name << ": green "
              << greener << " more\n";
    ok = recoloured && ok;
  }
  // Editing a label's function is seen on the next frame.
  const std::vector<float> before = ours.Render();
  green->AddRGBPoint(500, 1, 0, 1);
  const auto edited = CompareImages(ours.Render(), before, 16.0 / 255.0);
  const bool seen = edited.fractionAbove > 0.01;
  std::cout << (seen ? "ok    " : "FAIL  ") << "ray caster: label colour edit seen ("
            << edited.fractionAbove << " of pixels over 16/255)\n";
  return seen && ok;
}

// Ghost arrays: blanked points hide the samples of their cells, as in the slice mapper; a cell
// ghost array as vtkGPUVolumeRayCastMapper reads it.
bool Ghosts()
{
  bool ok = true;
  auto image = Phantom();
  int dims[3];
  image->GetDimensions(dims);
  auto blanked = vtkSmartPointer<vtkUniformGrid>::New();
  blanked->ShallowCopy(image);
  for (vtkIdType i = 0; i < image->GetNumberOfPoints(); ++i)
  {
    if (i % dims[0] >= 20)
    {
      blanked->BlankPoint(i);
    }
  }
  Scene ours(Kind::RayCast, blanked, vtkVolumeMapper::COMPOSITE_BLEND);
  Scene slice(Kind::Slice, blanked, vtkVolumeMapper::COMPOSITE_BLEND);
  FixSampling(ours);
  FixSampling(slice);
  const std::vector<float> got = ours.Render();
  ok = accelvolume_test::Report("ray caster vs slice mapper, blanked points",
         CompareImages(got, slice.Render(), 16.0 / 255.0), 3.0 / 255.0, 0.02) &&
    ok;
  RayCaster(ours)->SetLeapMode(vtkAccelVolumeRayCastMapper::LEAP_NONE);
  ok = Same("ray caster: blanked points, no leaping vs distance map", ours.Render(), got) && ok;

  auto ghosted = vtkSmartPointer<vtkImageData>::New();
  ghosted->ShallowCopy(image);
  ghosted->AllocateCellGhostArray();
  vtkUnsignedCharArray* ghosts = ghosted->GetCellGhostArray();
  for (int k = 0; k < dims[2] - 1; ++k)
  {
    for (int j = 8; j < 24; ++j)
    {
      for (int i = 10; i < 26; ++i)
      {
        ghosts->SetValue((static_cast<vtkIdType>(k) * (dims[1] - 1) + j) * (dims[0] - 1) + i,
          i < 18 ? vtkDataSetAttributes::HIDDENCELL : vtkDataSetAttributes::DUPLICATECELL);
      }
    }
  }
  Scene cells(Kind::RayCast, ghosted, vtkVolumeMapper::COMPOSITE_BLEND);
  Scene theirs(Kind::Slice, ghosted, vtkVolumeMapper::COMPOSITE_BLEND);
  FixSampling(cells);
  vtkNew<vtkGPUVolumeRayCastMapper> gpu;
  gpu->SetInputData(ghosted);
  gpu->SetAutoAdjustSampleDistances(0);
  gpu->SetSampleDistance(0.5);
  theirs.Volume->SetMapper(gpu);
  ok = accelvolume_test::Report("ray caster vs vtkGPUVolumeRayCastMapper, cell ghost array",
         CompareImages(cells.Render(), theirs.Render(), 16.0 / 255.0), 3.0 / 255.0, 0.02) &&
    ok;
  return ok;
}

// Mask edits are seen; a mask of other dimensions or components is one clear error per frame and
// draws no volume.
bool MaskChangesAndErrors()
{
  bool ok = true;
  auto image = Phantom();
  Scene ours(Kind::RayCast, image, vtkVolumeMapper::COMPOSITE_BLEND);
  FixSampling(ours);
  auto mask = MaskOf(image, false);
  SetMask(ours, mask, false);
  const std::vector<float> first = ours.Render();
  // In place: the boundary moves from x = 20 to x = 12.
  int dims[3];
  image->GetDimensions(dims);
  auto* values = static_cast<unsigned char*>(mask->GetScalarPointer());
  for (vtkIdType i = 0; i < image->GetNumberOfPoints(); ++i)
  {
    values[i] = i % dims[0] < 12 ? 255 : 0;
  }
  mask->Modified();
  const std::vector<float> edited = ours.Render();
  Scene fresh(Kind::RayCast, image, vtkVolumeMapper::COMPOSITE_BLEND);
  FixSampling(fresh);
  SetMask(fresh, MaskOf(image, false, 12), false);
  ok = Same("ray caster: mask edited in place vs a new mapper with that mask", edited,
         fresh.Render()) &&
    ok;
  const auto moved = CompareImages(edited, first, 16.0 / 255.0);
  std::cout << (moved.fractionAbove > 0.02 ? "ok    " : "FAIL  ")
            << "ray caster: mask edit changes the picture (" << moved.fractionAbove << ")\n";
  ok = moved.fractionAbove > 0.02 && ok;

  auto small = vtkSmartPointer<vtkImageData>::New();
  small->SetDimensions(4, 4, 4);
  small->AllocateScalars(VTK_UNSIGNED_CHAR, 1);
  auto pair = vtkSmartPointer<vtkImageData>::New();
  pair->CopyStructure(image);
  pair->AllocateScalars(VTK_UNSIGNED_CHAR, 2);
  for (vtkImageData* bad : { small.GetPointer(), pair.GetPointer() })
  {
    int errors = 0;
    vtkNew<vtkCallbackCommand> counter;
    counter->SetClientData(&errors);
    counter->SetCallback([](vtkObject*, unsigned long, void* count, void*)
      { ++*static_cast<int*>(count); });
    const unsigned long tag = ours.Mapper->AddObserver(vtkCommand::ErrorEvent, counter);
    SetMask(ours, bad, false);
    const std::vector<float> got = ours.Render();
    ours.Mapper->RemoveObserver(tag);
    size_t drawn = 0;
    for (size_t p = 0; p < got.size() / 3; ++p)
    {
      drawn += std::abs(got[3 * p] - 0.1) + std::abs(got[3 * p + 2] - 0.2) > 0.05 ? 1 : 0;
    }
    const bool refused = errors == 1 && drawn == 0;
    std::cout << (refused ? "ok    " : "FAIL  ") << "ray caster: malformed mask: " << errors
              << " error(s), " << drawn << " pixels drawn\n";
    ok = refused && ok;
  }
  return ok;
}
}

int TestAccelVolumeRayCastMasks(int, char*[])
{
  bool ok = BinaryMasks();
  ok = OtherModes() && ok;
  ok = LabelMaps() && ok;
  ok = Ghosts() && ok;
  ok = MaskChangesAndErrors() && ok;
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
