// The slice mapper's frame settings for shading, gradients, components, masks and the
// projection modes' scales (the parts of vtkInternals::FillFrame that read the property).
#include "vtkAccelVolumeSliceMapperInternals.h"

#include "vtkAccelVolumeMapperSupport.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkMatrix4x4.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkVolumeProperty.h"

#include <algorithm>

namespace
{
// Gradient opacity is on when one of the first `components` functions is set and enabled.
bool HasGradientOpacity(vtkVolumeProperty* property, int components)
{
  for (int c = 0; c < components; ++c)
  {
    if (property->HasGradientOpacity(c) && !property->GetDisableGradientOpacity(c))
    {
      return true;
    }
  }
  return false;
}

// Composite shading inputs: VTK's light model in eye space (at most MaximumLights lights: more
// are reported and dropped) and the matrix taking an index-space gradient to eye space (the
// inverse transpose of index -> eye).
void FillShading(vtkAccelVolumeSliceMapper* self, vtkAccelVolumeSliceFrame& frame,
  vtkRenderer* renderer, vtkVolumeProperty* property, vtkMatrix4x4* indexToEye, vtkMatrix4x4* view)
{
  vtkAccelVolumeLights lights;
  vtkAccelVolumeGetLights(renderer, property, indexToEye, view, lights);
  const accelvolume::LightModel& model = lights.Model;
  frame.Lighting[0] = model.ambient;
  frame.Lighting[1] = model.diffuse;
  frame.Lighting[2] = model.specular;
  frame.Lighting[3] = model.specularPower;
  frame.TwoSidedLighting = model.twoSided;
  frame.HeadlightOnly = model.headlightOnly;
  constexpr int Maximum = vtkAccelVolumeSliceFrame::MaximumLights;
  const int count = static_cast<int>(std::min<size_t>(model.lights.size(), Maximum));
  if (model.lights.size() > static_cast<size_t>(Maximum))
  {
    vtkWarningWithObjectMacro(self,
      "The slice mapper shades with the first " << Maximum << " of the renderer's "
                                                << model.lights.size() << " lights");
  }
  frame.LightCount = count;
  for (int i = 0; i < count; ++i)
  {
    const accelvolume::SceneLight& light = model.lights[i];
    frame.LightPositional[i] = light.positional ? 1 : 0;
    std::copy(light.axis, light.axis + 3, frame.LightAxis[i]);
    std::copy(light.position, light.position + 3, frame.LightPosition[i]);
    std::copy(light.ambient, light.ambient + 3, frame.LightAmbient[i]);
    std::copy(light.diffuse, light.diffuse + 3, frame.LightDiffuse[i]);
    std::copy(light.specular, light.specular + 3, frame.LightSpecular[i]);
    std::copy(light.attenuation, light.attenuation + 3, frame.LightAttenuation[i]);
    frame.LightCosCone[i] = light.cosCone;
    frame.LightExponent[i] = light.exponent;
  }
  // GLSL mat3 is column-major: column c goes to elements 3c .. 3c+2.
  for (int c = 0; c < 3; ++c)
  {
    for (int r = 0; r < 3; ++r)
    {
      frame.NormalMatrix[3 * c + r] = static_cast<float>(lights.NormalMatrix[r][c]);
    }
  }
}

}

void vtkAccelVolumeSliceMapper::vtkInternals::FillComponentsAndMasks(
  vtkAccelVolumeSliceMapper* self, vtkDataArray* scalars, vtkVolumeProperty* property,
  const vtkAccelVolumeSliceView& view)
{
  vtkAccelVolumeSliceFrame& frame = this->Frame;
  frame.Components = scalars->GetNumberOfComponents();
  frame.IndependentComponents = property->GetIndependentComponents() != 0;
  for (int c = 0; c < 4; ++c)
  {
    frame.ComponentWeights[c] = static_cast<float>(property->GetComponentWeight(c));
    // Dependent components correct opacity with the last component's unit distance, as VTK.
    const int unitComponent = frame.IndependentComponents ? c : frame.Components - 1;
    // Independent components are lit with their own coefficients (VTK's in_ambient[c], ...).
    const int lit = frame.IndependentComponents ? c : 0;
    frame.ComponentLighting[c][0] = static_cast<float>(property->GetAmbient(lit));
    frame.ComponentLighting[c][1] = static_cast<float>(property->GetDiffuse(lit));
    frame.ComponentLighting[c][2] = static_cast<float>(property->GetSpecular(lit));
    frame.ComponentLighting[c][3] = static_cast<float>(property->GetSpecularPower(lit));
    frame.ComponentUnitDistances[c] =
      static_cast<float>(std::max(1.0e-6, property->GetScalarOpacityUnitDistance(unitComponent)));
  }
  const bool ghostMask =
    this->GhostMask && this->GhostMask->GetNumberOfPoints() > 0 && this->UsedGhostMask;
  frame.MaskMode = ghostMask
    ? 1
    : (!self->MaskInput ? 0
                        : (self->UsesLabelMap() ? 2 : (self->MaskType == BinaryMaskType ? 1 : 0)));
  frame.MaskNeighbours = ghostMask;
  frame.MaskBlendFactor = self->MaskBlendFactor;
  frame.MaskTexture = this->Mask.GetTexture();
  frame.LabelTable = this->Mask.GetLabelTable();
  for (int c = 0; c < 3; ++c)
  {
    frame.MaskMaximum[c] = static_cast<float>(std::max(0, view.Dimensions[c] - 1));
  }
}

void vtkAccelVolumeSliceMapper::vtkInternals::FillProjectionScales(
  vtkAccelVolumeSliceMapper* self, vtkVolumeProperty* property, const double range[2])
{
  vtkAccelVolumeSliceFrame& frame = this->Frame;
  const double unit = self->AdditiveUnitDistance > 0
    ? self->AdditiveUnitDistance
    : std::max(1.0e-6, property->GetScalarOpacityUnitDistance(0)); // VTK's unit
  frame.AdditiveScale = static_cast<float>(1.0 / unit);
  const double rangeWidth = range[1] > range[0] ? range[1] - range[0] : 1.0;
  frame.AverageRange[0] =
    static_cast<float>((self->AverageIPScalarRange[0] - range[0]) / rangeWidth);
  frame.AverageRange[1] =
    static_cast<float>((self->AverageIPScalarRange[1] - range[0]) / rangeWidth);
  for (int c = 0; c < 4; ++c)
  {
    // Each component is normalised to its own range on upload.
    const double* componentRange = this->Resources.ComponentRanges[c];
    const double componentWidth =
      componentRange[1] > componentRange[0] ? componentRange[1] - componentRange[0] : 1.0;
    frame.AverageLower[c] =
      static_cast<float>((self->AverageIPScalarRange[0] - componentRange[0]) / componentWidth);
    frame.AverageUpper[c] =
      static_cast<float>((self->AverageIPScalarRange[1] - componentRange[0]) / componentWidth);
  }
}

void vtkAccelVolumeSliceMapper::vtkInternals::FillShadingAndGradients(
  vtkAccelVolumeSliceMapper* self, vtkRenderer* renderer, vtkOpenGLRenderWindow* window,
  vtkImageData* input, vtkDataArray* scalars, vtkVolumeProperty* property, const double range[2],
  const vtkAccelVolumeSliceView& view)
{
  const bool composite = vtkAccelVolumeCompositeLike(self->BlendMode);
  vtkAccelVolumeSliceFrame& frame = this->Frame;
  frame.Shade = composite && property->GetShade(0) != 0;
  // Independent components: VTK applies every component's gradient opacity to each (below).
  frame.GradientOpacity = self->BlendMode == COMPOSITE_BLEND &&
    HasGradientOpacity(
      property, frame.Components > 1 && frame.IndependentComponents ? frame.Components : 1);
  frame.ScalarRangeWidth = static_cast<float>(range[1] > range[0] ? range[1] - range[0] : 1.0);
  if (frame.Shade || frame.GradientOpacity || frame.TransferFunction2D)
  {
    FillShading(self, frame, renderer, property, view.IndexToEye, view.View);
    double axisScale[3];
    vtkAccelVolumeGradientAxisScale(input, axisScale);
    for (int a = 0; a < 3; ++a)
    {
      frame.GradientAxisScale[a] = static_cast<float>(axisScale[a]);
    }
    constexpr double GradientTextureBudget = 1024.0 * 1024.0 * 1024.0; // bytes
    const int* dims = view.Dimensions;
    const double gradientBytes = 8.0 * dims[0] * dims[1] * dims[2];
    // Bricks take central differences: their texels reach one voxel past what they own.
    frame.GradientTexture = self->PrecomputeGradients && frame.Components == 1 &&
      this->Resources.GetBrickLayout().Single() && gradientBytes <= GradientTextureBudget &&
      this->Resources.UpdateGradients(window, input, scalars, range);
    frame.GradientTextureScale = this->Resources.GradientScale;
  }
  else
  {
    frame.GradientTexture = false;
  }
  if (frame.GradientOpacity)
  {
    // VTK's GPU mapper's table: [0, a quarter of the data range] (SCALAR range type); each
    // independent component over its own range.
    const double maximum = 0.25 * frame.ScalarRangeWidth;
    frame.GradientTableMaximum = static_cast<float>(maximum);
    double maxima[4] = { maximum, maximum, maximum, maximum };
    const int rows = frame.Components > 1 && frame.IndependentComponents ? frame.Components : 1;
    for (int c = 0; c < rows && frame.Components > 1; ++c)
    {
      const double* componentRange = this->Resources.ComponentRanges[c];
      maxima[c] = 0.25 * std::max(componentRange[1] - componentRange[0], 1.0e-30);
    }
    this->Resources.UpdateGradientOpacityTable(window, property, maxima, rows);
  }
}
