// The CPU mappers' multi-component tables: vtkAccelVolumeCPUInputs::UpdateComponents (declared
// in vtkAccelVolumeMapperSupport.h), classified as vtkGPUVolumeRayCastMapper and the slice mapper
// classify multi-component scalars.
#include "vtkAccelVolumeMapperSupport.h"

#include "vtkColorTransferFunction.h"
#include "vtkDataArray.h"
#include "vtkPiecewiseFunction.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <cmath>

namespace
{
bool SameTable(
  const accelvolume::RayCastComponentTable& a, const accelvolume::RayCastComponentTable& b)
{
  return a.rgba == b.rgba && a.gradientOpacity == b.gradientOpacity &&
    std::equal(a.colourRange, a.colourRange + 2, b.colourRange) &&
    std::equal(a.opacityRange, a.opacityRange + 2, b.opacityRange) &&
    a.opacityUnitDistance == b.opacityUnitDistance && a.weight == b.weight &&
    a.ambient == b.ambient && a.diffuse == b.diffuse && a.specular == b.specular &&
    a.specularPower == b.specularPower;
}

bool SameComponents(
  const accelvolume::RayCastComponents& a, const accelvolume::RayCastComponents& b)
{
  if (a.count != b.count || a.independent != b.independent || a.tables.size() != b.tables.size() ||
    !std::equal(a.colourScale, a.colourScale + 3, b.colourScale) ||
    !std::equal(a.colourBias, a.colourBias + 3, b.colourBias))
  {
    return false;
  }
  for (int c = 0; c < 4; ++c)
  {
    if (a.ranges[c][0] != b.ranges[c][0] || a.ranges[c][1] != b.ranges[c][1])
    {
      return false;
    }
  }
  for (std::size_t t = 0; t < a.tables.size(); ++t)
  {
    if (!SameTable(a.tables[t], b.tables[t]))
    {
      return false;
    }
  }
  return true;
}

// Table `t` of the property: colour (grey or RGB function t) over colourRange, opacity
// (function t) over opacityRange.
std::vector<float> ComponentTable(vtkVolumeProperty* property, int t, const double colourRange[2],
  const double opacityRange[2], int size)
{
  std::vector<float> rgb(3 * static_cast<std::size_t>(size));
  std::vector<float> alpha(size);
  if (property->GetColorChannels(t) == 1)
  {
    property->GetGrayTransferFunction(t)->GetTable(
      colourRange[0], colourRange[1], size, alpha.data());
    for (int i = 0; i < size; ++i)
    {
      rgb[3 * i] = rgb[3 * i + 1] = rgb[3 * i + 2] = alpha[i];
    }
  }
  else
  {
    property->GetRGBTransferFunction(t)->GetTable(colourRange[0], colourRange[1], size, rgb.data());
  }
  property->GetScalarOpacity(t)->GetTable(opacityRange[0], opacityRange[1], size, alpha.data());
  std::vector<float> table(4 * static_cast<std::size_t>(size));
  for (int i = 0; i < size; ++i)
  {
    std::copy(&rgb[3 * i], &rgb[3 * i] + 3, &table[4 * i]);
    table[4 * i + 3] = alpha[i];
  }
  return table;
}
}

double vtkAccelVolumeColourComponentScale(int dataType)
{
  switch (dataType)
  {
    case VTK_UNSIGNED_CHAR:
      return 1.0 / 255.0;
    case VTK_CHAR:
    case VTK_SIGNED_CHAR:
      return 1.0 / 127.0;
    case VTK_SHORT:
      return 1.0 / 32767.0;
    case VTK_UNSIGNED_SHORT:
      return 1.0 / 65535.0;
    case VTK_FLOAT:
    case VTK_DOUBLE:
      return 1.0;
    default:
      return 0.0;
  }
}

void vtkAccelVolumeCPUInputs::UpdateComponents(vtkVolumeProperty* property, vtkDataArray* scalars,
  bool composite, accelvolume::RayCastTransfer& transfer)
{
  accelvolume::RayCastComponents components;
  const int count = std::min(scalars->GetNumberOfComponents(), 4);
  components.count = std::max(count, 1);
  components.independent = property->GetIndependentComponents() != 0;
  if (count > 1)
  {
    for (int c = 0; c < count; ++c)
    {
      double* range = components.ranges[c];
      scalars->GetFiniteRange(range, c);
      if (!(range[0] <= range[1]) || !std::isfinite(range[0]) || !std::isfinite(range[1]))
      {
        range[0] = 0.0;
        range[1] = 1.0;
      }
      if (!(range[1] > range[0]))
      {
        range[1] = range[0] + 1.0; // as the slice mapper's upload
      }
    }
    const int tables = components.independent ? count : 1;
    bool gradientOpacity = false;
    for (int t = 0; t < tables; ++t)
    {
      gradientOpacity = gradientOpacity ||
        (property->HasGradientOpacity(t) && !property->GetDisableGradientOpacity(t));
    }
    gradientOpacity = gradientOpacity && composite;
    for (int t = 0; t < tables; ++t)
    {
      accelvolume::RayCastComponentTable table;
      // Dependent: colour over component 0, opacity (function 0) over the last component, whose
      // unit distance corrects it; lit with component 0's coefficients.
      const int opacityComponent = components.independent ? t : count - 1;
      std::copy(components.ranges[t], components.ranges[t] + 2, table.colourRange);
      std::copy(components.ranges[opacityComponent], components.ranges[opacityComponent] + 2,
        table.opacityRange);
      table.rgba = ComponentTable(property, t, table.colourRange, table.opacityRange, TableSize);
      if (gradientOpacity)
      {
        // Over [0, a quarter of the component's range], VTK's units (as the slice mapper).
        const double maximum = 0.25 * (components.ranges[t][1] - components.ranges[t][0]);
        vtkAccelVolumeGradientOpacityTable(property, t, maximum, TableSize, table.gradientOpacity);
      }
      table.opacityUnitDistance =
        std::max(1.0e-6, property->GetScalarOpacityUnitDistance(opacityComponent));
      table.weight = components.independent ? property->GetComponentWeight(t) : 1.0;
      table.ambient = static_cast<float>(property->GetAmbient(t));
      table.diffuse = static_cast<float>(property->GetDiffuse(t));
      table.specular = static_cast<float>(property->GetSpecular(t));
      table.specularPower = static_cast<float>(property->GetSpecularPower(t));
      components.tables.push_back(std::move(table));
    }
    if (!components.independent && count == 4)
    {
      const double scale = vtkAccelVolumeColourComponentScale(scalars->GetDataType());
      for (int c = 0; c < 3; ++c)
      {
        const double* range = components.ranges[c];
        components.colourScale[c] = scale > 0 ? scale : 1.0 / (range[1] - range[0]);
        components.colourBias[c] = scale > 0 ? 0.0 : -range[0] / (range[1] - range[0]);
      }
    }
  }
  if (!SameComponents(components, this->Components))
  {
    this->Components = components;
    ++this->TransferVersion;
  }
  transfer.components = std::move(components);
}
