#include "vtkAccelVolumeDepthPeeling.h"

#include "vtkAbstractMapper.h"
#include "vtkDualDepthPeelingPass.h"
#include "vtkInformation.h"
#include "vtkInformationObjectBaseVectorKey.h"
#include "vtkOpenGLRenderPass.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkShaderProgram.h"
#include "vtkVolume.h"
#include "vtk_glew.h"

namespace
{
// A program with the sampler uniforms vtkDualDepthPeelingPass sets for volumes in each stage:
// which of them it sets tells the stage (the pass keeps the stage itself protected).
const char* const ProbeVertex = "//VTK::System::Dec\n"
                                "in vec4 vertexMC;\n"
                                "void main() { gl_Position = vertexMC; }\n";
const char* const ProbeFragment = "//VTK::System::Dec\n"
                                  "//VTK::Output::Dec\n"
                                  "uniform sampler2D outerDepthTex;\n"
                                  "uniform sampler2D lastFrontColorTex;\n"
                                  "uniform sampler2D depthRangeTex;\n"
                                  "void main()\n"
                                  "{\n"
                                  "  gl_FragData[0] = texture(outerDepthTex, vec2(0.5)) +\n"
                                  "    texture(lastFrontColorTex, vec2(0.5)) +\n"
                                  "    texture(depthRangeTex, vec2(0.5));\n"
                                  "}\n";
constexpr int Unset = 31; // a texture unit the pass never hands out first

int UniformValue(vtkShaderProgram* program, const char* name)
{
  const GLint location = glGetUniformLocation(static_cast<GLuint>(program->GetHandle()), name);
  GLint value = Unset;
  if (location >= 0)
  {
    glGetUniformiv(static_cast<GLuint>(program->GetHandle()), location, &value);
  }
  return value;
}
}

vtkAccelVolumePeelStage vtkAccelVolumeGetPeelStage(
  vtkOpenGLRenderWindow* window, vtkVolume* volume, vtkAbstractMapper* mapper)
{
  vtkInformation* keys = volume ? volume->GetPropertyKeys() : nullptr;
  if (!window || !keys || !keys->Has(vtkOpenGLRenderPass::RenderPasses()))
  {
    return vtkAccelVolumePeelStage::None;
  }
  vtkDualDepthPeelingPass* peeling = nullptr;
  const int passes = keys->Length(vtkOpenGLRenderPass::RenderPasses());
  for (int i = 0; i < passes && !peeling; ++i)
  {
    peeling =
      vtkDualDepthPeelingPass::SafeDownCast(keys->Get(vtkOpenGLRenderPass::RenderPasses(), i));
  }
  if (!peeling)
  {
    return vtkAccelVolumePeelStage::None;
  }
  vtkShaderProgram* probe =
    window->GetShaderCache()->ReadyShaderProgram(ProbeVertex, ProbeFragment, "");
  if (!probe)
  {
    return vtkAccelVolumePeelStage::OutsideRange;
  }
  for (const char* name : { "outerDepthTex", "lastFrontColorTex", "depthRangeTex" })
  {
    probe->SetUniformi(name, Unset);
  }
  peeling->SetShaderParameters(probe, mapper, volume, nullptr);
  const bool peel = UniformValue(probe, "lastFrontColorTex") != Unset;
  const bool alphaBlend = UniformValue(probe, "depthRangeTex") != Unset;
  const bool outside = UniformValue(probe, "outerDepthTex") != Unset;
  if (peel || alphaBlend)
  {
    return vtkAccelVolumePeelStage::Later;
  }
  return outside ? vtkAccelVolumePeelStage::OutsideRange : vtkAccelVolumePeelStage::Later;
}
