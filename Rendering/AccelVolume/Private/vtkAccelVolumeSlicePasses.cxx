// The slice mapper's OpenGL passes: accumulate slices and cut faces, then resolve to colour.
#include "vtkAccelVolumeSlicePasses.h"

#include "vtkAccelVolumeSliceDraw.h"

#include "vtkAccelVolumeDepthCopy.h"
#include "vtkAccelVolumeSliceResolve.h"
#include "vtkAccelVolumeSliceResources.h"
#include "vtkImageData.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkOpenGLBufferObject.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtkVolumeMapper.h"
#include "vtk_glew.h"

#include "AccelVolumeSliceComponentsFS.h"
#include "AccelVolumeSliceSampling.h"

#include <algorithm>
#include <string>
#include <utility>

namespace
{
// The shaders read matrices as GLSL column-major; vtkShaderProgram uploads VTK's row-major
// elements untransposed, so hand it the transpose.
template <class Program>
void SetMatrixUniform(Program* program, const char* name, vtkMatrix4x4* matrix)
{
  vtkNew<vtkMatrix4x4> transposed;
  vtkMatrix4x4::Transpose(matrix, transposed);
  program->SetUniformMatrix(name, transposed);
}

std::string BlendName(int blendMode)
{
  switch (blendMode)
  {
    case vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND:
      return "MAXIMUM";
    case vtkVolumeMapper::MINIMUM_INTENSITY_BLEND:
      return "MINIMUM";
    case vtkVolumeMapper::ADDITIVE_BLEND:
      return "ADDITIVE";
    case vtkVolumeMapper::COMPOSITE_BLEND:
      return "COMPOSITE";
    default:
      return "AVERAGE";
  }
}

// The lights as compile-time constants of the shading code (see shadeWith): their count, whether
// any is positional, two-sided lighting, VTK's single-headlight ambient rule.
// Unshaded frames: none (fewer variants; the shading code is compiled out).
std::string LightingPrelude(const vtkAccelVolumeSliceFrame& frame)
{
  const bool composite = frame.BlendMode == vtkVolumeMapper::COMPOSITE_BLEND;
  const int count = composite && frame.Shade
    ? std::clamp(frame.LightCount, 0, vtkAccelVolumeSliceFrame::MaximumLights)
    : 0;
  const bool positional = std::any_of(frame.LightPositional, frame.LightPositional + count,
    [](int value) { return value != 0; });
  return "#define ACCELVOLUME_LIGHT_COUNT " + std::to_string(count) +
    "\n#define ACCELVOLUME_POSITIONAL_LIGHTS " + (positional ? "1" : "0") +
    "\n#define ACCELVOLUME_TWO_SIDED " + (count > 0 && frame.TwoSidedLighting ? "1" : "0") +
    "\n#define ACCELVOLUME_HEADLIGHT_ONLY " + (count > 0 && frame.HeadlightOnly ? "1" : "0") +
    "\n";
}

// True when the projection's w row depends on eye x or y (an explicit projection matrix): a
// slice plane then maps to the window projectively rather than affinely.
bool ProjectiveSlices(const vtkAccelVolumeSliceFrame& frame)
{
  return frame.Projection->GetElement(3, 0) != 0.0 || frame.Projection->GetElement(3, 1) != 0.0;
}

// Uploads the maps from a fragment's window position (x, y, 1) to the point it shows on a slice
// plane z = -depth, as 3x3 matrices (columns: per x, per y, constant) at ReferenceDepth plus their
// change per unit of depth; index and eye points are map * (x, y, 1) / dot(pixelWeight, (x, y, 1)).
// With (nx, ny) the pixel's NDC, Cramer's rule on nx * w_clip = x_clip and ny * w_clip = y_clip
// gives the homogeneous eye point (X, Y, W) linear in (nx, ny, 1), with coefficients linear in
// (alpha, beta, omega) = (P02, P12, P32) z + (P03, P13, P33) and W free of z. Double precision
// here, and depths relative to a depth near the volume, keep the float maps accurate.
template <class Program>
void SetSliceMapUniforms(Program* program, const vtkAccelVolumeSliceFrame& frame)
{
  vtkMatrix4x4* p = frame.Projection;
  auto P = [p](int r, int c) { return p->GetElement(r, c); };
  auto eyeRows = [&P](double alpha, double beta, double omega, double rows[3][3])
  {
    const double x[3] = { omega * P(1, 1) - P(3, 1) * beta, alpha * P(3, 1) - P(0, 1) * omega,
      P(0, 1) * beta - alpha * P(1, 1) };
    const double y[3] = { P(3, 0) * beta - omega * P(1, 0), P(0, 0) * omega - alpha * P(3, 0),
      alpha * P(1, 0) - P(0, 0) * beta };
    std::copy(x, x + 3, rows[0]);
    std::copy(y, y + 3, rows[1]);
  };
  const double weight[3] = { P(3, 1) * P(1, 0) - P(3, 0) * P(1, 1),
    P(0, 1) * P(3, 0) - P(0, 0) * P(3, 1), P(0, 0) * P(1, 1) - P(0, 1) * P(1, 0) };
  const double z = -frame.ReferenceDepth;
  double eye[3][3];     // at the reference depth, in NDC
  double eyePerZ[3][3]; // per unit of eye z
  eyeRows(P(0, 3) + P(0, 2) * z, P(1, 3) + P(1, 2) * z, P(3, 3) + P(3, 2) * z, eye);
  eyeRows(P(0, 2), P(1, 2), P(3, 2), eyePerZ);
  for (int j = 0; j < 3; ++j)
  {
    eye[2][j] = z * weight[j]; // Z = z W
    eyePerZ[2][j] = weight[j];
  }
  // Index = eyeToIndex applied to the homogeneous eye point.
  vtkMatrix4x4* e = frame.EyeToIndex;
  double index[3][3];
  double indexPerZ[3][3];
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      index[i][j] = e->GetElement(i, 3) * weight[j];
      indexPerZ[i][j] = 0.0;
      for (int k = 0; k < 3; ++k)
      {
        index[i][j] += e->GetElement(i, k) * eye[k][j];
        indexPerZ[i][j] += e->GetElement(i, k) * eyePerZ[k][j];
      }
    }
  }
  // Window (x, y, 1) -> NDC: nx = 2x / width - 1, likewise y. Scaled so that W is 1 at the
  // viewport centre (everywhere, unless projective); per unit of depth = -(per unit of z).
  const double sx = 2.0 / frame.Width;
  const double sy = 2.0 / frame.Height;
  const double scale = weight[2] != 0.0 ? 1.0 / weight[2] : 1.0;
  auto toWindow = [sx, sy, scale](const double m[3][3], double sign, float out[9])
  {
    for (int i = 0; i < 3; ++i)
    {
      // GLSL mat3 is column-major: column j (the coefficient of x, y or 1) at 3j .. 3j+2.
      out[i] = static_cast<float>(sign * scale * m[i][0] * sx);
      out[3 + i] = static_cast<float>(sign * scale * m[i][1] * sy);
      out[6 + i] = static_cast<float>(sign * scale * (m[i][2] - m[i][0] - m[i][1]));
    }
  };
  float matrix[9];
  toWindow(index, 1.0, matrix);
  program->SetUniformMatrix3x3("indexMap", matrix);
  toWindow(indexPerZ, -1.0, matrix);
  program->SetUniformMatrix3x3("indexMapPerDepth", matrix);
  toWindow(eye, 1.0, matrix);
  program->SetUniformMatrix3x3("eyeMap", matrix);
  toWindow(eyePerZ, -1.0, matrix);
  program->SetUniformMatrix3x3("eyeMapPerDepth", matrix);
  const float pixelWeight[3] = { static_cast<float>(scale * weight[0] * sx),
    static_cast<float>(scale * weight[1] * sy),
    static_cast<float>(scale * (weight[2] - weight[0] - weight[1])) };
  program->SetUniform3f("pixelWeight", pixelWeight);
}

}

std::string vtkAccelVolumeSliceShaderVariant(
  const char* source, const vtkAccelVolumeSliceFrame& frame, int slabSamples, bool boundaryFace)
{
  return vtkAccelVolumeSliceAssembleShader(
    source, vtkAccelVolumeSliceShaderPrelude(frame, slabSamples, boundaryFace));
}

std::string vtkAccelVolumeSliceShaderPrelude(
  const vtkAccelVolumeSliceFrame& frame, int slabSamples, bool boundaryFace)
{
  const bool composite = frame.BlendMode == vtkVolumeMapper::COMPOSITE_BLEND;
  return LightingPrelude(frame) + "#define ACCELVOLUME_BLEND_" + BlendName(frame.BlendMode) +
    "\n#define ACCELVOLUME_SLAB_SAMPLES " + std::to_string(slabSamples) +
    "\n#define ACCELVOLUME_BOUNDARY_FACE " + (boundaryFace ? "1" : "0") +
    "\n#define ACCELVOLUME_SHADE " + (composite && frame.Shade ? "1" : "0") +
    "\n#define ACCELVOLUME_GRADIENT_OPACITY " + (composite && frame.GradientOpacity ? "1" : "0") +
    "\n#define ACCELVOLUME_SKIP_TRANSPARENT " +
    (composite && frame.SkipTransparentSamples ? "1" : "0") + "\n#define ACCELVOLUME_SKIP_OCTREE " +
    (composite && frame.SkipEmptyLeaves ? "1" : "0") + "\n#define ACCELVOLUME_TF2D " +
    (composite && frame.TransferFunction2D ? "1" : "0") +
    "\n#define ACCELVOLUME_GRADIENT_TEXTURE " + (composite && frame.GradientTexture ? "1" : "0") +
    "\n#define ACCELVOLUME_JITTER " + (composite && frame.Jitter ? "1" : "0") +
    "\n#define ACCELVOLUME_PROJECTIVE_SLICES " + (ProjectiveSlices(frame) ? "1" : "0") +
    "\n#define ACCELVOLUME_BRICKED " + (frame.Bricked ? "1" : "0") +
    "\n#define ACCELVOLUME_REDUCED " + (vtkAccelVolumeSliceReducedTarget(frame) ? "1" : "0") +
    "\n#define ACCELVOLUME_RENDER_TO_IMAGE " + (frame.RenderToImage ? "1" : "0") +
    "\n#define ACCELVOLUME_ISOSURFACE " + (composite && frame.IsoSurface ? "1" : "0") +
    "\n#define ACCELVOLUME_SLICE_PLANE " + (composite && frame.SlicePlane ? "1" : "0") +
    "\n#define ACCELVOLUME_MASK_NEIGHBOURS " + (frame.MaskNeighbours ? "1" : "0") +
    "\n#define ACCELVOLUME_COMPONENTS " + std::to_string(frame.Components) +
    "\n#define ACCELVOLUME_INDEPENDENT " + (frame.IndependentComponents ? "1" : "0") +
    "\n#define ACCELVOLUME_DEPTH_PASS " + std::to_string(composite ? frame.DepthPassStage : 0) +
    "\n#define ACCELVOLUME_MASK " +
    std::to_string(composite || frame.MaskMode == 1 ? frame.MaskMode : 0) + "\n";
}

std::string vtkAccelVolumeSliceInsertSampling(const char* source)
{
  std::string text = source;
  // The shared sampling first: the components part is inserted inside it.
  const std::pair<const char*, const char*> parts[] = {
    { "//ACCELVOLUME::Sampling::Dec", AccelVolumeSliceSampling },
    { "//ACCELVOLUME::ComponentsAndIsoSurfaces::Dec", AccelVolumeSliceComponentsFS }
  };
  for (const auto& part : parts)
  {
    const size_t at = text.find(part.first);
    if (at != std::string::npos)
    {
      text.replace(at, std::char_traits<char>::length(part.first), part.second);
    }
  }
  return text;
}

std::string vtkAccelVolumeSliceAssembleShader(const char* source, const std::string& prelude)
{
  std::string text = vtkAccelVolumeSliceInsertSampling(source);
  const size_t at = text.find("//VTK::Output::Dec");
  text.insert(at == std::string::npos ? 0 : at, prelude);
  return text;
}

template <class Program>
void vtkAccelVolumeSliceSetFrameUniforms(Program* program,
  vtkAccelVolumeSliceResources& resources, const vtkAccelVolumeSliceFrame& frame)
{
  program->SetUniformi("transferTable", resources.TransferTable->GetTextureUnit());
  program->SetUniformi("sceneDepth", resources.SceneDepth->GetTextureUnit());
  program->SetUniformf("scalarScale", resources.ScalarScale);
  program->SetUniformf("scalarBias", resources.ScalarBias);
  program->SetUniformf("tableSize", static_cast<float>(vtkAccelVolumeSliceResources::TableSize));
  SetMatrixUniform(program, "indexToClip", frame.IndexToClip);
  SetMatrixUniform(program, "indexToEye", frame.IndexToEye);
  SetMatrixUniform(program, "eyeToIndex", frame.EyeToIndex);
  SetMatrixUniform(program, "inverseProjection", frame.InverseProjection);
  SetSliceMapUniforms(program, frame);
  const float viewport[2] = { static_cast<float>(frame.Width), static_cast<float>(frame.Height) };
  program->SetUniform2f("viewportSize", viewport);
  program->SetUniformi("clipPlaneCount", frame.ClipPlaneCount);
  program->SetUniform4fv(
    "clipPlanes", vtkAccelVolumeSliceFrame::MaximumClipPlanes, frame.ClipPlanes);
  program->SetUniformf("sliceSpacing", frame.SliceSpacing);
  program->SetUniformf("slicePhase", frame.SlicePhase);
  program->SetUniformi("boundaryRerendering", frame.BoundaryRerendering ? 1 : 0);
  program->SetUniformi("parallelProjection", frame.Parallel ? 1 : 0);
  program->SetUniformf("additiveScale", frame.AdditiveScale);
  program->SetUniformf("opacityUnitDistance", frame.OpacityUnitDistance);
  if (frame.SkipEmptyLeaves)
  {
    program->SetUniformi("emptyLeaves", resources.EmptyLeaves->GetTextureUnit());
    program->SetUniformf("leafSize", frame.LeafSize);
    program->SetUniform3f("leafGridMaximum", frame.LeafGridMaximum);
    if (frame.ComputeSlices)
    {
      program->SetUniformi("emptyBlocks", resources.EmptyBlocks->GetTextureUnit());
      program->SetUniform3f("blockGridMaximum", frame.BlockGridMaximum);
    }
  }
  if (frame.GradientTexture)
  {
    program->SetUniformi("gradientTexture", resources.Gradients->GetTextureUnit());
    program->SetUniformf("gradientTextureScale", frame.GradientTextureScale);
  }
  if (frame.TransferFunction2D)
  {
    program->SetUniformi("transferTable2D", resources.TransferTable2D->GetTextureUnit());
    program->SetUniformf("gradient2DMaximum", frame.Gradient2DMaximum);
  }
  if (frame.Shade || frame.GradientOpacity || frame.TransferFunction2D)
  {
    program->SetUniformMatrix3x3("normalMatrix", const_cast<float*>(frame.NormalMatrix));
    program->SetUniformf("scalarRangeWidth", frame.ScalarRangeWidth);
    program->SetUniformi("gradientOpacityTable", resources.GradientOpacityTable->GetTextureUnit());
    program->SetUniformf("gradientTableMaximum", frame.GradientTableMaximum);
    program->SetUniform3f("gradientAxisScale", frame.GradientAxisScale);
    constexpr int Lights = vtkAccelVolumeSliceFrame::MaximumLights;
    program->SetUniformi("lightCount", frame.LightCount);
    program->SetUniform1iv("lightPositional", Lights, frame.LightPositional);
    program->SetUniform3fv("lightAxis", Lights, frame.LightAxis);
    program->SetUniform3fv("lightPosition", Lights, frame.LightPosition);
    program->SetUniform3fv("lightAmbient", Lights, frame.LightAmbient);
    program->SetUniform3fv("lightDiffuse", Lights, frame.LightDiffuse);
    program->SetUniform3fv("lightSpecular", Lights, frame.LightSpecular);
    program->SetUniform3fv("lightAttenuation", Lights, frame.LightAttenuation);
    program->SetUniform1fv("lightCosCone", Lights, frame.LightCosCone);
    program->SetUniform1fv("lightExponent", Lights, frame.LightExponent);
    program->SetUniformi("twoSidedLighting", frame.TwoSidedLighting ? 1 : 0);
    program->SetUniformi("headlightOnly", frame.HeadlightOnly ? 1 : 0);
    program->SetUniform4f("lighting", frame.Lighting);
  }
  program->SetUniform2f("averageRange", frame.AverageRange);
  program->SetUniform4f("averageLower", frame.AverageLower);
  program->SetUniform4f("averageUpper", frame.AverageUpper);
  if (frame.IsoSurface || frame.DepthPassStage == 1)
  {
    program->SetUniformi("isoSurfaceCount", frame.IsoSurfaceCount);
    program->SetUniformi("isoComponent", frame.IsoComponent);
    const float maximum[3] = { std::max(0.0f, frame.Dimensions[0] - 1),
      std::max(0.0f, frame.Dimensions[1] - 1), std::max(0.0f, frame.Dimensions[2] - 1) };
    program->SetUniform3f("volumeIndexMaximum", maximum);
    program->SetUniform1fv(
      "isoSurfaceValues", vtkAccelVolumeSliceFrame::MaximumIsoSurfaces, frame.IsoSurfaceValues);
  }
  if (frame.Components > 1)
  {
    program->SetUniformi("componentTables", resources.ComponentTables->GetTextureUnit());
    program->SetUniform4f("componentWeights", frame.ComponentWeights);
    program->SetUniform4f("componentUnitDistances", frame.ComponentUnitDistances);
    program->SetUniform4fv("componentLighting", 4, frame.ComponentLighting);
  }
  if (frame.MaskMode != 0)
  {
    program->SetUniformi("maskTexture", frame.MaskTexture->GetTextureUnit());
    program->SetUniform3f("maskMaximum", frame.MaskMaximum);
    if (frame.MaskMode == 2)
    {
      program->SetUniformi("labelTable", frame.LabelTable->GetTextureUnit());
      program->SetUniformf("maskBlendFactor", frame.MaskBlendFactor);
    }
  }
}

template void vtkAccelVolumeSliceSetFrameUniforms<vtkShaderProgram>(
  vtkShaderProgram*, vtkAccelVolumeSliceResources&, const vtkAccelVolumeSliceFrame&);
template void vtkAccelVolumeSliceSetFrameUniforms<vtkAccelVolumeComputeProgram>(
  vtkAccelVolumeComputeProgram*, vtkAccelVolumeSliceResources&, const vtkAccelVolumeSliceFrame&);

namespace
{

// Dependent multi-component MIP / MinIP keep one whole sample: a depth test on its last
// component (AuxiliaryDepth) replaces blending.
bool DependentExtreme(const vtkAccelVolumeSliceFrame& frame)
{
  return frame.Components > 1 && !frame.IndependentComponents &&
    (frame.BlendMode == vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND ||
      frame.BlendMode == vtkVolumeMapper::MINIMUM_INTENSITY_BLEND);
}

// Draw buffers 0 (accumulation), 1 (RenderToImage depth), then the second accumulation.
void ActivateAccumulationBuffers(
  vtkAccelVolumeSliceResources& resources, const vtkAccelVolumeSliceFrame& frame)
{
  unsigned int attachments[3] = { 0, 1, 2 };
  int count = frame.RenderToImage ? 2 : 1;
  if (vtkAccelVolumeSliceSecondAccumulation(frame))
  {
    attachments[count++] = 2;
  }
  resources.Framebuffer->ActivateDrawBuffers(attachments, count);
}

// UseDepthPass, first stage: the window depth of each ray's first contour crossing into the
// auxiliary depth buffer (the nearest kept by the depth test; no colour). The accumulation
// then starts its rays there.
bool DrawContourDepth(vtkOpenGLRenderWindow* window, vtkAccelVolumeSliceResources& resources,
  const vtkAccelVolumeSliceFrame& frame, std::string& error)
{
  vtkAccelVolumeSliceFrame contour = frame;
  contour.DepthPassStage = 1;
  contour.EarlyTermination = false;
  vtkOpenGLState* state = window->GetState();
  resources.AttachAuxiliaryDepth(true);
  state->vtkglColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  state->vtkglDepthMask(GL_TRUE);
  state->vtkglClearDepth(1.0);
  state->vtkglClear(GL_DEPTH_BUFFER_BIT);
  state->vtkglDepthFunc(GL_LESS);
  const bool ok = vtkAccelVolumeSliceDrawBricks(window, resources, contour, error);
  resources.AttachAuxiliaryDepth(false);
  state->vtkglColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  state->vtkglDepthMask(GL_FALSE);
  return ok;
}

// The tables and textures the slice shaders of this frame sample: activated (bound to
// texture units) before the passes, deactivated after.
void ActivateFrameTextures(
  vtkAccelVolumeSliceResources& resources, const vtkAccelVolumeSliceFrame& frame, bool active)
{
  vtkTextureObject* textures[] = { resources.TransferTable, resources.SceneDepth,
    frame.GradientOpacity ? resources.GradientOpacityTable.GetPointer() : nullptr,
    frame.SkipEmptyLeaves ? resources.EmptyLeaves.GetPointer() : nullptr,
    frame.SkipEmptyLeaves && frame.ComputeSlices ? resources.EmptyBlocks.GetPointer() : nullptr,
    frame.TransferFunction2D ? resources.TransferTable2D.GetPointer() : nullptr,
    frame.GradientTexture ? resources.Gradients.GetPointer() : nullptr,
    frame.Components > 1 ? resources.ComponentTables.GetPointer() : nullptr,
    frame.MaskMode != 0 ? frame.MaskTexture : nullptr,
    frame.MaskMode == 2 ? frame.LabelTable : nullptr };
  for (vtkTextureObject* texture : textures)
  {
    if (texture && active)
    {
      texture->Activate();
    }
    else if (texture)
    {
      texture->Deactivate();
    }
  }
}

// Pass 1: MAX / MIN / additive blending of one value per fragment into the float target.
bool Accumulate(vtkOpenGLRenderWindow* window, vtkAccelVolumeSliceResources& resources,
  const vtkAccelVolumeSliceFrame& frame, std::string& error)
{
  vtkOpenGLState* state = window->GetState();
  resources.Framebuffer->SaveCurrentBindingsAndBuffers();
  resources.Framebuffer->Bind();
  ActivateAccumulationBuffers(resources, frame);
  state->vtkglViewport(0, 0, frame.Width, frame.Height);
  state->vtkglDisable(GL_SCISSOR_TEST);
  // The scene depth is the target's depth buffer: fragments behind opaque geometry fail early.
  state->vtkglEnable(GL_DEPTH_TEST);
  state->vtkglDepthFunc(GL_LESS);
  state->vtkglDepthMask(GL_FALSE);
  state->vtkglDisable(GL_CULL_FACE);
  state->vtkglColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  const bool maximum = frame.BlendMode == vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND;
  const bool minimum = frame.BlendMode == vtkVolumeMapper::MINIMUM_INTENSITY_BLEND;
  const bool composite = frame.BlendMode == vtkVolumeMapper::COMPOSITE_BLEND;
  // Cleared to values no sample reaches, so the resolve pass can tell uncovered pixels.
  if (maximum)
  {
    state->vtkglClearColor(-1.0f, -1.0f, -1.0f, -1.0f);
  }
  else if (minimum)
  {
    state->vtkglClearColor(2.0f, 2.0f, 2.0f, 2.0f);
  }
  else
  {
    state->vtkglClearColor(0.0f, 0.0f, 0.0f, 0.0f);
  }
  state->vtkglClear(GL_COLOR_BUFFER_BIT);
  const bool dependentExtreme = DependentExtreme(frame);
  if (dependentExtreme)
  {
    // Ties pass, so the last drawn of equal samples (slices go back to front) stays.
    resources.AttachAuxiliaryDepth(true);
    state->vtkglClearDepth(maximum ? 0.0 : 1.0);
    state->vtkglDepthMask(GL_TRUE);
    state->vtkglClear(GL_DEPTH_BUFFER_BIT);
    state->vtkglDepthFunc(maximum ? GL_GEQUAL : GL_LEQUAL);
  }
  state->vtkglEnable(GL_BLEND);
  state->vtkglBlendEquation(maximum ? GL_MAX : (minimum ? GL_MIN : GL_FUNC_ADD));
  if (composite && frame.FrontToBack)
  {
    // Front to back "under": the new premultiplied sample goes behind what is there.
    state->vtkglBlendFuncSeparate(GL_ONE_MINUS_DST_ALPHA, GL_ONE, GL_ONE_MINUS_DST_ALPHA, GL_ONE);
  }
  else if (composite)
  {
    // Back to front "over".
    state->vtkglBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  }
  else
  {
    state->vtkglBlendFunc(GL_ONE, GL_ONE);
  }
  // RenderToImage: attachment 1 keeps the nearest contributing depth (MIN blending), cleared
  // to the far plane; its per-buffer blend state is put back after the passes.
  GLint savedEquation = GL_FUNC_ADD;
  GLint savedSource = GL_ONE;
  GLint savedDestination = GL_ZERO;
  if (frame.RenderToImage)
  {
    const GLfloat far[4] = { 1.0f, 1.0f, 1.0f, 1.0f };
    glClearBufferfv(GL_COLOR, 1, far);
    glGetIntegeri_v(GL_BLEND_EQUATION_RGB, 1, &savedEquation);
    glGetIntegeri_v(GL_BLEND_SRC_RGB, 1, &savedSource);
    glGetIntegeri_v(GL_BLEND_DST_RGB, 1, &savedDestination);
    glBlendEquationi(1, GL_MIN);
    glBlendFunci(1, GL_ONE, GL_ONE);
  }
  if (dependentExtreme)
  {
    glDisablei(GL_BLEND, 0); // the depth test keeps the sample
  }

  if (!frame.Vertices->empty())
  {
    resources.VertexBuffer->Upload(*frame.Vertices, vtkOpenGLBufferObject::ArrayBuffer);
  }
  if (frame.GeneratedSlices)
  {
    resources.SliceRecordBuffer->Upload(*frame.SliceRecords, vtkOpenGLBufferObject::ArrayBuffer);
  }
  ActivateFrameTextures(resources, frame, true);
  // Per brick, slices then faces: every blend here but composite's is order-independent, and
  // composite has no faces.
  bool ok = frame.DepthPassStage == 0 || DrawContourDepth(window, resources, frame, error);
  if (ok && frame.DepthPassStage != 0)
  {
    // The contour's depth becomes the depth buffer: fragments in front of it fail early (the
    // shader tests the scene's depth instead).
    resources.AttachAuxiliaryDepth(true);
    state->vtkglDepthFunc(GL_GEQUAL);
  }
  ok = ok && vtkAccelVolumeSliceDrawBricks(window, resources, frame, error);
  if (frame.DepthPassStage != 0)
  {
    resources.AttachAuxiliaryDepth(false);
    state->vtkglDepthFunc(GL_LESS);
  }
  ActivateFrameTextures(resources, frame, false);
  if (frame.RenderToImage)
  {
    if (ok && frame.DepthImage)
    {
      frame.DepthImage->SetDimensions(frame.Width, frame.Height, 1);
      frame.DepthImage->AllocateScalars(VTK_FLOAT, 1);
      glReadBuffer(GL_COLOR_ATTACHMENT1);
      state->vtkglPixelStorei(GL_PACK_ALIGNMENT, 1);
      glReadPixels(
        0, 0, frame.Width, frame.Height, GL_RED, GL_FLOAT, frame.DepthImage->GetScalarPointer());
      glReadBuffer(GL_COLOR_ATTACHMENT0);
    }
    glBlendEquationi(1, static_cast<GLenum>(savedEquation));
    glBlendFunci(1, static_cast<GLenum>(savedSource), static_cast<GLenum>(savedDestination));
  }
  if (dependentExtreme)
  {
    glEnablei(GL_BLEND, 0);
    resources.AttachAuxiliaryDepth(false);
    state->vtkglClearDepth(1.0);
    state->vtkglDepthMask(GL_FALSE);
    state->vtkglDepthFunc(GL_LESS);
  }
  resources.Framebuffer->RestorePreviousBindingsAndBuffers();
  return ok;
}

// Compute slices: one dispatch fills the whole target (no clear, no blending).
bool ComputeAccumulate(vtkOpenGLRenderWindow* window, vtkAccelVolumeSliceResources& resources,
  const vtkAccelVolumeSliceFrame& frame, std::string& error)
{
  ActivateFrameTextures(resources, frame, true);
  const bool ok = resources.Compute.Accumulate(window, resources, frame, error);
  ActivateFrameTextures(resources, frame, false);
  return ok;
}

}

bool vtkAccelVolumeSliceReducedTarget(const vtkAccelVolumeSliceFrame& frame)
{
  return frame.Width != frame.ViewportWidth || frame.Height != frame.ViewportHeight;
}

bool vtkAccelVolumeSliceSecondAccumulation(const vtkAccelVolumeSliceFrame& frame)
{
  return frame.Components > 2 && frame.IndependentComponents &&
    frame.BlendMode == vtkVolumeMapper::AVERAGE_INTENSITY_BLEND;
}

bool vtkAccelVolumeRenderSlicePasses(vtkOpenGLRenderWindow* window,
  vtkAccelVolumeSliceResources& resources, const vtkAccelVolumeSliceFrame& frame,
  std::string& error)
{
  if (frame.Bricks.empty())
  {
    return true; // everything cropped or clipped away
  }
  vtkOpenGLState* state = window->GetState();
  state->Push();
  state->PushFramebufferBindings();
  // Extremes need one float channel (less blending traffic); sums also need their weight;
  // compositing needs premultiplied colour and alpha.
  const bool extremum = frame.BlendMode == vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND ||
    frame.BlendMode == vtkVolumeMapper::MINIMUM_INTENSITY_BLEND;
  // Multi-component extremes keep a value per component (independent) or the whole sample;
  // the independent average a (sum, weight) pair per component.
  const bool composite = frame.BlendMode == vtkVolumeMapper::COMPOSITE_BLEND;
  const bool fourChannels = composite || (frame.Components > 1 && extremum) ||
    (frame.Components > 1 && frame.IndependentComponents &&
      frame.BlendMode == vtkVolumeMapper::AVERAGE_INTENSITY_BLEND);
  const int channels = fourChannels ? 4 : (extremum ? 1 : 2);
  // One query of the read framebuffer's depth format per frame (targets and copies use it).
  const int depthFormat = vtkAccelVolumeReadDepthFormat();
  // Sums (raysum, average) grow past 1, where an 11-bit mantissa drops whole levels: 32-bit.
  const bool halfFloat = frame.HalfFloatTarget && (composite || extremum);
  bool ok =
    resources.PrepareTargets(window, frame.Width, frame.Height, channels, depthFormat, halfFloat) &&
    resources.PrepareImageTargets(window, frame.Width, frame.Height, frame.RenderToImage) &&
    resources.PrepareExtraTargets(window, frame.Width, frame.Height,
      DependentExtreme(frame) || frame.DepthPassStage != 0,
      vtkAccelVolumeSliceSecondAccumulation(frame));
  if (ok)
  {
    // Opaque geometry drawn so far limits the rays.
    ok = vtkAccelVolumeSliceCopySceneDepth(window, resources, frame, depthFormat);
    if (!ok)
    {
      error = "the scene depth could not be copied";
    }
    ok = ok &&
      (frame.ComputeSlices ? ComputeAccumulate(window, resources, frame, error)
                           : Accumulate(window, resources, frame, error));
    if (ok && frame.RenderToImage)
    {
      ok = vtkAccelVolumeSliceResolveToImage(window, resources, frame);
      if (!ok)
      {
        error = "the render-to-image pass failed";
      }
    }
    else if (ok && !vtkAccelVolumeSliceResolve(window, resources, frame, frame.DrawLowerLeft))
    {
      error = "the resolve shader did not compile";
      ok = false;
    }
  }
  else
  {
    error = "the float target (" + std::to_string(frame.Width) + "x" +
      std::to_string(frame.Height) + ") could not be allocated";
  }
  state->PopFramebufferBindings();
  state->Pop();
  return ok;
}
