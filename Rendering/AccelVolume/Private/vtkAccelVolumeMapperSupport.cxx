// vtkAccelVolumeMapperSupport: scene and input handling shared by the AccelVolume mappers.
#include "vtkAccelVolumeMapperSupport.h"

#include "vtkAccelVolumeInputAdapter.h"

#include "vtkAlgorithm.h"
#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkDataArray.h"
#include "vtkHardwareSelector.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPlane.h"
#include "vtkPlaneCollection.h"
#include "vtkRenderer.h"
#include "vtkSMPTools.h"
#include "vtkTimeStamp.h"
#include "vtkVolume.h"
#include "vtkVolumeMapper.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>

namespace
{
// NaN planes make no box (every comparison fails); +-Inf are fine: they clamp to the volume.
bool CroppingPlanesValid(const double planes[6], std::string& error)
{
  if (std::none_of(planes, planes + 6, [](double p) { return std::isnan(p); }))
  {
    return true;
  }
  std::ostringstream message;
  message << "Cropping region planes must be numbers, not NaN (planes";
  for (int i = 0; i < 6; ++i)
  {
    message << " " << planes[i];
  }
  message << ")";
  error = message.str();
  return false;
}

// A half-space needs a finite origin and a finite, non-zero normal.
bool ClippingPlaneValid(vtkPlane* plane, int index, std::string& error)
{
  double normal[3];
  double origin[3];
  plane->GetNormal(normal);
  plane->GetOrigin(origin);
  const bool finite = std::all_of(normal, normal + 3, [](double v) { return std::isfinite(v); }) &&
    std::all_of(origin, origin + 3, [](double v) { return std::isfinite(v); });
  if (finite && (normal[0] != 0 || normal[1] != 0 || normal[2] != 0))
  {
    return true;
  }
  std::ostringstream message;
  message << "Clipping plane " << index << " has "
          << (finite ? "a zero normal" : "a non-finite origin or normal") << " (origin "
          << origin[0] << " " << origin[1] << " " << origin[2] << ", normal " << normal[0] << " "
          << normal[1] << " " << normal[2] << ")";
  error = message.str();
  return false;
}

// Whether float / double scalars hold a NaN or an infinity (one parallel pass; the answer does
// not depend on the thread count).
template <typename T>
bool HasNonFinite(const T* values, vtkIdType count)
{
  std::atomic<bool> found(false);
  vtkSMPTools::For(0, count,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType i = begin; i < end && !found.load(std::memory_order_relaxed); ++i)
      {
        if (!std::isfinite(values[i]))
        {
          found = true;
        }
      }
    });
  return found;
}

// count values of `components` interleaved components; component c's non-finite values become
// the ends of ranges[c].
template <typename T>
void ReplaceNonFinite(T* values, vtkIdType count, int components, const double (*ranges)[2])
{
  vtkSMPTools::For(0, count,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType i = begin; i < end; ++i)
      {
        const T v = values[i];
        const double* range = ranges[i % components];
        if (std::isnan(v) || v == -std::numeric_limits<T>::infinity())
        {
          values[i] = static_cast<T>(range[0]);
        }
        else if (v == std::numeric_limits<T>::infinity())
        {
          values[i] = static_cast<T>(range[1]);
        }
      }
    });
}
}

bool vtkAccelVolumeCheckInput(
  vtkImageData* input, vtkDataArray* scalars, std::string& error, int maximumComponents)
{
  std::ostringstream message;
  if (!input)
  {
    error = "No input: connect a vtkImageData to the mapper";
    return false;
  }
  int dims[3];
  input->GetDimensions(dims);
  if (dims[0] < 1 || dims[1] < 1 || dims[2] < 1 || input->GetNumberOfPoints() < 1)
  {
    message << "Empty input image (dimensions " << dims[0] << "x" << dims[1] << "x" << dims[2]
            << ")";
    error = message.str();
    return false;
  }
  if (!scalars)
  {
    error = "Input has no point scalars to render";
    return false;
  }
  if (scalars->GetNumberOfComponents() < 1 || scalars->GetNumberOfComponents() > maximumComponents)
  {
    // Rendering component 0 of independent components, or colour without the opacity channel,
    // would be a silently wrong picture: refuse both.
    message << (maximumComponents == 1 ? "Only single-component scalars are supported"
                                       : "At most 4 scalar components are supported")
            << " by this mapper (input has " << scalars->GetNumberOfComponents()
            << " components; the slice mapper renders 2-4 components, independent or dependent, "
               "and vtkAccelVolumeSmartMapper's VectorMode reduces vectors to one; or pick one "
               "with vtkImageExtractComponents)";
    error = message.str();
    return false;
  }
  if (scalars->GetNumberOfTuples() != input->GetNumberOfPoints())
  {
    message << "Scalar array size (" << scalars->GetNumberOfTuples()
            << " tuples) does not match the image's " << input->GetNumberOfPoints() << " points";
    error = message.str();
    return false;
  }
  switch (scalars->GetDataType())
  {
    case VTK_CHAR:
    case VTK_SIGNED_CHAR:
    case VTK_UNSIGNED_CHAR:
    case VTK_SHORT:
    case VTK_UNSIGNED_SHORT:
    case VTK_INT:
    case VTK_FLOAT:
    case VTK_DOUBLE:
      return true;
    default:
      message << "Unsupported scalar type " << scalars->GetDataTypeAsString()
              << " (the mappers render char, signed or unsigned char, short, unsigned short, "
                 "int, unsigned int, long, long long, float or double, e.g. through vtkImageCast)";
      error = message.str();
      return false;
  }
}

bool vtkAccelVolumeCheckGeometry(vtkVolumeMapper* mapper, std::string& error)
{
  if (mapper->GetCropping() && !CroppingPlanesValid(mapper->GetCroppingRegionPlanes(), error))
  {
    return false;
  }
  vtkPlaneCollection* planes = mapper->GetClippingPlanes();
  for (int i = 0; planes && i < planes->GetNumberOfItems(); ++i)
  {
    if (!ClippingPlaneValid(planes->GetItem(i), i, error))
    {
      return false;
    }
  }
  return true;
}

vtkSmartPointer<vtkDataArray> vtkAccelVolumeFiniteScalars(
  vtkDataArray* scalars, const double range[2])
{
  const int components = std::max(1, std::min(scalars->GetNumberOfComponents(), 4));
  const vtkIdType count = scalars->GetNumberOfTuples() * components;
  // Component 0 keeps the given range; the others their own finite ranges.
  double ranges[4][2] = { { range[0], range[1] } };
  for (int c = 1; c < components; ++c)
  {
    scalars->GetFiniteRange(ranges[c], c);
    if (!(ranges[c][0] <= ranges[c][1]) || !std::isfinite(ranges[c][0]) ||
      !std::isfinite(ranges[c][1]))
    {
      ranges[c][0] = 0.0;
      ranges[c][1] = 1.0;
    }
  }
  vtkSmartPointer<vtkDataArray> finite;
  switch (scalars->GetDataType())
  {
    case VTK_FLOAT:
      if (HasNonFinite(static_cast<const float*>(scalars->GetVoidPointer(0)), count))
      {
        finite = vtkSmartPointer<vtkDataArray>::Take(scalars->NewInstance());
        finite->DeepCopy(scalars);
        ReplaceNonFinite(static_cast<float*>(finite->GetVoidPointer(0)), count, components, ranges);
      }
      break;
    case VTK_DOUBLE:
      if (HasNonFinite(static_cast<const double*>(scalars->GetVoidPointer(0)), count))
      {
        finite = vtkSmartPointer<vtkDataArray>::Take(scalars->NewInstance());
        finite->DeepCopy(scalars);
        ReplaceNonFinite(static_cast<double*>(finite->GetVoidPointer(0)), count, components, ranges);
      }
      break;
    default:
      break; // integers are always finite
  }
  return finite;
}

void vtkAccelVolumeScalarRange(vtkDataArray* scalars, double range[2])
{
  scalars->GetFiniteRange(range, 0); // NaN and +/-Inf must not stretch the range
  // Without any finite value VTK reports an inverted (or non-finite) range: a unit range keeps
  // the tables defined.
  if (!(range[0] <= range[1]) || !std::isfinite(range[0]) || !std::isfinite(range[1]))
  {
    range[0] = 0.0;
    range[1] = 1.0;
  }
}

std::vector<float> vtkAccelVolumeTransferTable(
  vtkVolumeProperty* property, const double range[2], int size)
{
  const double high = range[1] > range[0] ? range[1] : range[0] + 1.0;
  std::vector<float> opacities(size);
  std::vector<float> colours(3 * size);
  property->GetScalarOpacity(0)->GetTable(range[0], high, size, opacities.data());
  if (property->GetColorChannels(0) == 1)
  {
    std::vector<float> greys(size);
    property->GetGrayTransferFunction(0)->GetTable(range[0], high, size, greys.data());
    for (int i = 0; i < size; ++i)
    {
      colours[3 * i] = colours[3 * i + 1] = colours[3 * i + 2] = greys[i];
    }
  }
  else
  {
    property->GetRGBTransferFunction(0)->GetTable(range[0], high, size, colours.data());
  }
  std::vector<float> table(4 * size);
  for (int i = 0; i < size; ++i)
  {
    std::copy(&colours[3 * i], &colours[3 * i] + 3, &table[4 * i]);
    table[4 * i + 3] = opacities[i];
  }
  return table;
}

accelvolume::Box vtkAccelVolumeIndexBox(const int dims[3])
{
  accelvolume::Box box;
  box.lower = { dims[0] > 1 ? 0.0 : -0.5, dims[1] > 1 ? 0.0 : -0.5, dims[2] > 1 ? 0.0 : -0.5 };
  box.upper = { dims[0] > 1 ? dims[0] - 1.0 : 0.5, dims[1] > 1 ? dims[1] - 1.0 : 0.5,
    dims[2] > 1 ? dims[2] - 1.0 : 0.5 };
  return box;
}

void vtkAccelVolumeIndexToWorld(vtkVolume* volume, vtkImageData* input, vtkMatrix4x4* indexToWorld)
{
  const int* extent = input->GetExtent();
  vtkNew<vtkMatrix4x4> extentShift;
  for (int axis = 0; axis < 3; ++axis)
  {
    extentShift->SetElement(axis, 3, extent[2 * axis]);
  }
  vtkNew<vtkMatrix4x4> indexToPhysical;
  vtkMatrix4x4::Multiply4x4(input->GetIndexToPhysicalMatrix(), extentShift, indexToPhysical);
  vtkMatrix4x4::Multiply4x4(volume->GetMatrix(), indexToPhysical, indexToWorld);
}

std::vector<accelvolume::Box> vtkAccelVolumeRegions(
  vtkVolumeMapper* mapper, vtkImageData* input, const accelvolume::Box& volumeBox)
{
  if (!mapper->GetCropping())
  {
    return { volumeBox };
  }
  // Cropping planes are in data (physical) coordinates along the image axes.
  double origin[3];
  double spacing[3];
  input->GetOrigin(origin);
  input->GetSpacing(spacing);
  const int* extent = input->GetExtent();
  const double* planes = mapper->GetCroppingRegionPlanes();
  std::string error;
  if (!CroppingPlanesValid(planes, error))
  {
    // No region rather than an arbitrary one; CPU mappers refuse earlier (CheckGeometry).
    vtkErrorWithObjectMacro(mapper, << error);
    return {};
  }
  double indexPlanes[6];
  for (int i = 0; i < 6; ++i)
  {
    const int axis = i / 2;
    // Structured coordinate (extent-based) to 0-based index.
    indexPlanes[i] = (planes[i] - origin[axis]) / spacing[axis] - extent[2 * axis];
  }
  return accelvolume::CroppingRegionBoxes(volumeBox, indexPlanes, mapper->GetCroppingRegionFlags());
}

accelvolume::HalfSpace vtkAccelVolumeIndexHalfSpace(vtkPlane* plane, vtkMatrix4x4* indexToWorld)
{
  double normal[3];
  double origin[3];
  plane->GetNormal(normal);
  plane->GetOrigin(origin);
  // World half-space n.(x - o) >= 0 with x = A p + t becomes (A^T n).p + n.(t - o) >= 0.
  double indexNormal[3] = { 0, 0, 0 };
  double offset = 0;
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      indexNormal[c] += indexToWorld->GetElement(r, c) * normal[r];
    }
    offset += normal[r] * (indexToWorld->GetElement(r, 3) - origin[r]);
  }
  accelvolume::HalfSpace halfSpace;
  halfSpace.normal = { indexNormal[0], indexNormal[1], indexNormal[2] };
  halfSpace.offset = offset;
  return halfSpace;
}

std::vector<accelvolume::HalfSpace> vtkAccelVolumeClipHalfSpaces(
  vtkPlaneCollection* planes, vtkMatrix4x4* indexToWorld)
{
  std::vector<accelvolume::HalfSpace> clip;
  for (int i = 0; planes && i < planes->GetNumberOfItems(); ++i)
  {
    vtkPlane* plane = planes->GetItem(i);
    double normal[3];
    double origin[3];
    plane->GetNormal(normal);
    plane->GetOrigin(origin);
    std::string error;
    if (!ClippingPlaneValid(plane, i, error))
    {
      // An undefined plane keeps nothing (0.p - 1 < 0) rather than an arbitrary part; the
      // mappers report it (vtkAccelVolumeCheckGeometry).
      accelvolume::HalfSpace none;
      none.normal = { 0.0, 0.0, 0.0 };
      none.offset = -1.0;
      clip.push_back(none);
      continue;
    }
    const accelvolume::HalfSpace halfSpace = vtkAccelVolumeIndexHalfSpace(plane, indexToWorld);
    clip.push_back(halfSpace);
  }
  return clip;
}

double vtkAccelVolumeSmallestSpacing(vtkMatrix4x4* indexToWorld, const int dims[3])
{
  double spacing = VTK_DOUBLE_MAX;
  for (int c = 0; c < 3; ++c)
  {
    if (dims[c] > 1)
    {
      const double length =
        std::sqrt(indexToWorld->GetElement(0, c) * indexToWorld->GetElement(0, c) +
          indexToWorld->GetElement(1, c) * indexToWorld->GetElement(1, c) +
          indexToWorld->GetElement(2, c) * indexToWorld->GetElement(2, c));
      spacing = std::min(spacing, length);
    }
  }
  return spacing == VTK_DOUBLE_MAX || spacing <= 0 ? 1.0 : spacing;
}

void vtkAccelVolumeGetLights(vtkRenderer* renderer, vtkVolumeProperty* property,
  vtkMatrix4x4* indexToEye, vtkMatrix4x4* view, vtkAccelVolumeLights& lights)
{
  accelvolume::LightModel& model = lights.Model;
  model.ambient = static_cast<float>(property->GetAmbient(0));
  model.diffuse = static_cast<float>(property->GetDiffuse(0));
  model.specular = static_cast<float>(property->GetSpecular(0));
  model.specularPower = static_cast<float>(property->GetSpecularPower(0));
  model.twoSided = renderer->GetTwoSidedLighting() != 0;
  model.lights.clear();
  model.anyPositional = false;
  vtkLightCollection* collection = renderer->GetLights();
  vtkCollectionSimpleIterator iterator;
  collection->InitTraversal(iterator);
  bool singleHeadlight = true;
  while (vtkLight* light = collection->GetNextLight(iterator))
  {
    if (!light->GetSwitch())
    {
      continue;
    }
    singleHeadlight =
      model.lights.empty() && light->LightTypeIsHeadlight() && light->GetIntensity() == 1.0;
    accelvolume::SceneLight scene;
    const double intensity = light->GetIntensity();
    double colour[3];
    light->GetAmbientColor(colour);
    for (int c = 0; c < 3; ++c)
    {
      scene.ambient[c] = static_cast<float>(colour[c] * intensity);
    }
    light->GetDiffuseColor(colour);
    for (int c = 0; c < 3; ++c)
    {
      scene.diffuse[c] = static_cast<float>(colour[c] * intensity);
    }
    light->GetSpecularColor(colour);
    for (int c = 0; c < 3; ++c)
    {
      scene.specular[c] = static_cast<float>(colour[c] * intensity);
    }
    // World placement (the renderer has moved headlights and camera lights already), then eye.
    const double* position = light->GetTransformedPosition();
    const double* focal = light->GetTransformedFocalPoint();
    double axis[3] = { focal[0] - position[0], focal[1] - position[1], focal[2] - position[2] };
    double eyeAxis[3] = { 0, 0, 0 };
    double eyePosition[3] = { 0, 0, 0 };
    for (int r = 0; r < 3; ++r)
    {
      eyePosition[r] = view->GetElement(r, 3);
      for (int c = 0; c < 3; ++c)
      {
        eyeAxis[r] += view->GetElement(r, c) * axis[c];
        eyePosition[r] += view->GetElement(r, c) * position[c];
      }
    }
    if (vtkMath::Normalize(eyeAxis) == 0.0)
    {
      eyeAxis[0] = eyeAxis[1] = 0.0;
      eyeAxis[2] = -1.0;
    }
    for (int c = 0; c < 3; ++c)
    {
      scene.axis[c] = static_cast<float>(eyeAxis[c]);
      scene.position[c] = static_cast<float>(eyePosition[c]);
    }
    scene.positional = light->GetPositional() != 0;
    if (scene.positional)
    {
      const double* attenuation = light->GetAttenuationValues();
      for (int c = 0; c < 3; ++c)
      {
        scene.attenuation[c] = static_cast<float>(attenuation[c]);
      }
      if (light->GetConeAngle() <= 90.0)
      {
        scene.cosCone =
          static_cast<float>(std::cos(vtkMath::RadiansFromDegrees(light->GetConeAngle())));
        scene.exponent = static_cast<float>(light->GetExponent());
      }
    }
    model.lights.push_back(scene);
  }
  // VTK's single default headlight shines from the camera itself, and its ambient term ignores
  // the light's ambient colour.
  model.headlightOnly = singleHeadlight && model.lights.size() == 1;
  if (model.headlightOnly)
  {
    accelvolume::SceneLight& head = model.lights.front();
    head.positional = true;
    std::fill(head.position, head.position + 3, 0.0f);
    std::fill(head.attenuation, head.attenuation + 3, 0.0f);
    head.attenuation[0] = 1.0f;
    head.cosCone = -2.0f;
  }
  for (const accelvolume::SceneLight& light : model.lights)
  {
    model.anyPositional = model.anyPositional || light.positional;
  }
  double linear[3][3];
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      linear[r][c] = indexToEye->GetElement(r, c);
    }
  }
  double inverse[3][3];
  vtkMath::Invert3x3(linear, inverse);
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      lights.NormalMatrix[r][c] = inverse[c][r];
    }
  }
}

bool vtkAccelVolumeScalarType(int vtkType, accelvolume::ScalarType& type)
{
  switch (vtkType)
  {
    case VTK_CHAR:
    case VTK_SIGNED_CHAR:
      type = accelvolume::ScalarType::Int8;
      return true;
    case VTK_UNSIGNED_CHAR:
      type = accelvolume::ScalarType::UInt8;
      return true;
    case VTK_SHORT:
      type = accelvolume::ScalarType::Int16;
      return true;
    case VTK_UNSIGNED_SHORT:
      type = accelvolume::ScalarType::UInt16;
      return true;
    case VTK_INT:
      type = accelvolume::ScalarType::Int32;
      return true;
    case VTK_FLOAT:
      type = accelvolume::ScalarType::Float32;
      return true;
    case VTK_DOUBLE:
      type = accelvolume::ScalarType::Float64;
      return true;
    default:
      return false;
  }
}

bool vtkAccelVolumeView(vtkImageData* input, vtkDataArray* scalars, accelvolume::VolumeView& view)
{
  view.data = scalars->GetVoidPointer(0);
  input->GetDimensions(view.dims);
  return vtkAccelVolumeScalarType(scalars->GetDataType(), view.type);
}

accelvolume::ParallelFor vtkAccelVolumeSMPParallelFor()
{
  return [](std::size_t count, const std::function<void(std::size_t, std::size_t)>& body)
  { vtkSMPTools::For(0, count, 1, [&](std::size_t begin, std::size_t end) { body(begin, end); }); };
}

void vtkAccelVolumeCPUInputs::UpdateVolume(vtkImageData* input, vtkDataArray* scalars)
{
  if (scalars != this->Scalars || scalars->GetMTime() != this->ScalarsTime ||
    input->GetMTime() != this->InputTime)
  {
    this->Scalars = scalars;
    this->ScalarsTime = scalars->GetMTime();
    this->InputTime = input->GetMTime();
    double range[2];
    vtkAccelVolumeScalarRange(scalars, range);
    this->Finite = vtkAccelVolumeFiniteScalars(scalars, range);
    ++this->VolumeVersion;
  }
}

vtkDataArray* vtkAccelVolumeCPUInputs::GetScalars() const
{
  return this->Finite ? this->Finite.GetPointer() : this->Scalars;
}

void vtkAccelVolumeGradientAxisScale(vtkImageData* input, double scale[3])
{
  double spacing[3];
  input->GetSpacing(spacing);
  const double mean = (std::abs(spacing[0]) + std::abs(spacing[1]) + std::abs(spacing[2])) / 3.0;
  for (int a = 0; a < 3; ++a)
  {
    scale[a] = std::abs(spacing[a]) > 0 && mean > 0 ? mean / std::abs(spacing[a]) : 1.0;
  }
}

void vtkAccelVolumeGradientOpacityTable(
  vtkVolumeProperty* property, int index, double maximum, int size, std::vector<float>& table)
{
  table.resize(static_cast<std::size_t>(size));
  property->GetGradientOpacity(index)->GetTable(0.0, maximum, size, table.data());
  if (std::all_of(table.begin(), table.end(), [](float value) { return value == 1.0f; }))
  {
    table.clear();
  }
}

void vtkAccelVolumeCPUInputs::UpdateTransfer(vtkVolumeProperty* property, const double range[2],
  bool composite, vtkImageData* input, accelvolume::RayCastTransfer& transfer, double& high)
{
  high = range[1] > range[0] ? range[1] : range[0] + 1.0;
  transfer.rgba = vtkAccelVolumeTransferTable(property, range, TableSize);
  transfer.opacityUnitDistance = std::max(1.0e-6, property->GetScalarOpacityUnitDistance(0));
  transfer.gradientOpacity.clear();
  vtkAccelVolumeGradientAxisScale(input, transfer.gradientAxisScale); // multi-component too
  if (composite && property->HasGradientOpacity(0) && !property->GetDisableGradientOpacity(0))
  {
    // VTK's GPU mapper's table: [0, a quarter of the data range] (SCALAR range type).
    transfer.gradientOpacityMaximum = 0.25 * (high - range[0]);
    vtkAccelVolumeGradientOpacityTable(
      property, 0, transfer.gradientOpacityMaximum, TableSize, transfer.gradientOpacity);
  }
  if (transfer.rgba != this->Table || transfer.gradientOpacity != this->GradientTable ||
    range[0] != this->TableRange[0] || high != this->TableRange[1])
  {
    this->Table = transfer.rgba;
    this->GradientTable = transfer.gradientOpacity;
    this->TableRange[0] = range[0];
    this->TableRange[1] = high;
    ++this->TransferVersion;
  }
}

int vtkAccelVolumeSelectionMode(vtkRenderer* renderer, float colour[3])
{
  colour[0] = colour[1] = colour[2] = 0.0f;
  vtkHardwareSelector* selector = renderer ? renderer->GetSelector() : nullptr;
  if (!selector)
  {
    return 0;
  }
  const int pass = selector->GetCurrentPass();
  if (pass == vtkHardwareSelector::ACTOR_PASS || pass == vtkHardwareSelector::PROCESS_PASS)
  {
    // The selector turns the renderer's current prop id into this pass's colour.
    selector->BeginRenderProp();
    selector->GetPropColorValue(colour);
    selector->EndRenderProp();
    return 1;
  }
  return 2;
}

void vtkAccelVolumeCPULighting(vtkRenderer* renderer, vtkVolumeProperty* property,
  vtkMatrix4x4* indexToWorld, const int dims[3], vtkCamera* camera, bool shade,
  accelvolume::RayCastLighting& lighting)
{
  lighting.shade = shade;
  vtkMatrix4x4* viewMatrix = camera->GetViewTransformMatrix();
  vtkNew<vtkMatrix4x4> indexToEye;
  vtkMatrix4x4::Multiply4x4(viewMatrix, indexToWorld, indexToEye);
  vtkAccelVolumeLights lights;
  vtkAccelVolumeGetLights(renderer, property, indexToEye, viewMatrix, lights);
  lighting.model = lights.Model;
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      lighting.normalMatrix[r][c] = lights.NormalMatrix[r][c];
      lighting.indexToEye[r][c] = indexToEye->GetElement(r, c);
    }
    lighting.indexToEyeOffset[r] = indexToEye->GetElement(r, 3);
    lighting.centre[r] = indexToEye->GetElement(r, 3);
    for (int c = 0; c < 3; ++c)
    {
      lighting.centre[r] += indexToEye->GetElement(r, c) * 0.5 * std::max(0, dims[c] - 1);
    }
  }
}

vtkOpenGLRenderWindow* vtkAccelVolumeBeginCPURender(vtkVolumeMapper* mapper,
  vtkAccelVolumeInputAdapter& adapter, vtkRenderer* renderer, vtkVolume* volume,
  vtkImageData*& input, vtkDataArray*& scalars, vtkVolumeProperty*& property)
{
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(renderer->GetRenderWindow());
  if (!window)
  {
    vtkErrorWithObjectMacro(
      mapper, << mapper->GetClassName() << " needs an OpenGL render window to show its image");
    return nullptr;
  }
  std::string error;
  if (!adapter.Fetch(mapper, input, scalars, error) || !vtkAccelVolumeCheckGeometry(mapper, error))
  {
    vtkErrorWithObjectMacro(mapper, << error);
    return nullptr;
  }
  property = volume->GetProperty();
  if (!property)
  {
    vtkErrorWithObjectMacro(mapper, "The volume has no property");
    return nullptr;
  }
  return window;
}
