// The slice mapper's compute slices: one dispatch fills the accumulation target.
#include "vtkAccelVolumeSliceCompute.h"

#include "vtkAccelVolumeOctreeGPUBuilder.h"
#include "vtkAccelVolumeSliceDraw.h"
#include "vtkAccelVolumeSlicePasses.h"
#include "vtkAccelVolumeSliceResolve.h"
#include "vtkAccelVolumeSliceResources.h"
#include "vtkMatrix4x4.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkTextureObject.h"
#include "vtkVolumeMapper.h"
#include "vtk_glew.h"

#include "AccelVolumeSliceCS.h"

#include <string>

namespace
{
constexpr unsigned int GroupSize = 8; // local_size_x and _y of AccelVolumeSliceCS

// The image format of the accumulation texture: its GLSL layout name and GL enum.
void TargetFormat(int channels, bool halfFloat, std::string& name, GLenum& format)
{
  if (channels <= 1)
  {
    name = halfFloat ? "r16f" : "r32f";
    format = halfFloat ? GL_R16F : GL_R32F;
  }
  else if (channels == 2)
  {
    name = halfFloat ? "rg16f" : "rg32f";
    format = halfFloat ? GL_RG16F : GL_RG32F;
  }
  else
  {
    name = halfFloat ? "rgba16f" : "rgba32f";
    format = halfFloat ? GL_RGBA16F : GL_RGBA32F;
  }
}

}

int vtkAccelVolumeComputeProgram::Location(const char* name)
{
  const auto found = this->Locations.find(name);
  if (found != this->Locations.end())
  {
    return found->second;
  }
  const int location = glGetUniformLocation(this->Handle, name);
  this->Locations.emplace(name, location);
  return location;
}

bool vtkAccelVolumeComputeProgram::SetUniformi(const char* name, int value)
{
  return this->With(name, [&](int location) { glUniform1i(location, value); });
}

bool vtkAccelVolumeComputeProgram::SetUniformf(const char* name, float value)
{
  return this->With(name, [&](int location) { glUniform1f(location, value); });
}

bool vtkAccelVolumeComputeProgram::SetUniform2f(const char* name, const float value[2])
{
  return this->With(name, [&](int location) { glUniform2fv(location, 1, value); });
}

bool vtkAccelVolumeComputeProgram::SetUniform3f(const char* name, const float value[3])
{
  return this->With(name, [&](int location) { glUniform3fv(location, 1, value); });
}

bool vtkAccelVolumeComputeProgram::SetUniform4f(const char* name, const float value[4])
{
  return this->With(name, [&](int location) { glUniform4fv(location, 1, value); });
}

bool vtkAccelVolumeComputeProgram::SetUniform1iv(const char* name, int count, const int* values)
{
  return this->With(name, [&](int location) { glUniform1iv(location, count, values); });
}

bool vtkAccelVolumeComputeProgram::SetUniform1fv(const char* name, int count, const float* values)
{
  return this->With(name, [&](int location) { glUniform1fv(location, count, values); });
}

bool vtkAccelVolumeComputeProgram::SetUniform3fv(
  const char* name, int count, const float (*values)[3])
{
  return this->With(name, [&](int location) { glUniform3fv(location, count, &values[0][0]); });
}

bool vtkAccelVolumeComputeProgram::SetUniform4fv(
  const char* name, int count, const float (*values)[4])
{
  return this->With(name, [&](int location) { glUniform4fv(location, count, &values[0][0]); });
}

bool vtkAccelVolumeComputeProgram::SetUniformMatrix3x3(const char* name, float* matrix)
{
  return this->With(
    name, [&](int location) { glUniformMatrix3fv(location, 1, GL_FALSE, matrix); });
}

bool vtkAccelVolumeComputeProgram::SetUniformMatrix(const char* name, vtkMatrix4x4* matrix)
{
  return this->With(name,
    [&](int location)
    {
      float elements[16];
      for (int i = 0; i < 16; ++i)
      {
        elements[i] = static_cast<float>(matrix->GetElement(i / 4, i % 4));
      }
      glUniformMatrix4fv(location, 1, GL_FALSE, elements);
    });
}

vtkAccelVolumeSliceCompute::~vtkAccelVolumeSliceCompute() = default;

bool vtkAccelVolumeSliceCompute::IsSupported(vtkOpenGLRenderWindow* window, std::string& why)
{
  if (!vtkAccelVolumeOctreeGPUBuilder::IsSupported(window, why))
  {
    return false;
  }
  if (!glBindImageTexture)
  {
    why = "the context has no image load / store (glBindImageTexture)";
    return false;
  }
  return true;
}

vtkAccelVolumeComputeProgram* vtkAccelVolumeSliceCompute::ReadyProgram(
  const std::string& prelude, std::string& error)
{
  const auto found = this->Programs.find(prelude);
  if (found != this->Programs.end())
  {
    return &found->second;
  }
  const std::string source =
    "#version 430 core\n" + prelude + vtkAccelVolumeSliceInsertSampling(AccelVolumeSliceCS);
  const GLuint handle =
    vtkAccelVolumeOctreeGPUBuilder::CompileProgram(source.c_str(), "the compute-slice shader", error);
  if (!handle)
  {
    return nullptr;
  }
  return &this->Programs.emplace(prelude, vtkAccelVolumeComputeProgram(handle)).first->second;
}

bool vtkAccelVolumeSliceCompute::Accumulate(vtkOpenGLRenderWindow* window,
  vtkAccelVolumeSliceResources& resources, const vtkAccelVolumeSliceFrame& frame,
  std::string& error)
{
  const vtkAccelVolumeSliceFrame::BrickDraw& brick = frame.Bricks.front();
  std::string formatName;
  GLenum format = GL_RGBA32F;
  TargetFormat(
    resources.Accumulation->GetComponents(), resources.AccumulationHalfFloat, formatName, format);
  const bool composite = frame.BlendMode == vtkVolumeMapper::COMPOSITE_BLEND;
  const std::string prelude = vtkAccelVolumeSliceShaderPrelude(frame, 1, false) +
    "#define ACCELVOLUME_TARGET_FORMAT " + formatName + "\n#define ACCELVOLUME_TERMINATE " +
    (composite && frame.EarlyTermination ? "1" : "0") + "\n#define ACCELVOLUME_COUNT_SAMPLES " +
    (frame.CountSamples ? "1" : "0") + "\n";
  vtkAccelVolumeComputeProgram* program = this->ReadyProgram(prelude, error);
  if (!program)
  {
    return false;
  }
  vtkTextureObject* texture = resources.Bricks.Acquire(window, brick.Brick, frame.Linear, error);
  if (!texture)
  {
    return false;
  }
  GLint previousProgram = 0;
  glGetIntegerv(GL_CURRENT_PROGRAM, &previousProgram);
  glUseProgram(program->GetHandle());
  texture->Activate();
  vtkAccelVolumeSliceSetFrameUniforms(program, resources, frame);
  program->SetUniformi("volumeTexture", texture->GetTextureUnit());
  program->SetUniform3f("volumeDimensions", brick.TextureSize);
  program->SetUniform3f("textureOrigin", brick.TextureOrigin);
  if (!brick.Cells.empty())
  {
    program->SetUniform3f("regionLower", brick.Cells.front().Lower.data());
    program->SetUniform3f("regionUpper", brick.Cells.front().Upper.data());
  }
  program->SetUniformf("sliceBase", frame.SliceBase);
  program->SetUniformf("referenceDepth", static_cast<float>(frame.ReferenceDepth));
  program->SetUniformf("terminationThreshold", frame.TerminationThreshold);
  glBindImageTexture(0, resources.Accumulation->GetHandle(), 0, GL_FALSE, 0, GL_WRITE_ONLY, format);
  if (frame.CountSamples)
  {
    if (!this->CounterBuffer)
    {
      glGenBuffers(1, &this->CounterBuffer);
    }
    const GLuint zero = 0;
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, this->CounterBuffer);
    glBufferData(GL_SHADER_STORAGE_BUFFER, sizeof(GLuint), &zero, GL_DYNAMIC_READ);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, this->CounterBuffer);
  }
  glDispatchCompute((static_cast<GLuint>(frame.Width) + GroupSize - 1) / GroupSize,
    (static_cast<GLuint>(frame.Height) + GroupSize - 1) / GroupSize, 1);
  // The resolve samples the target (and the next frame's passes may draw into it).
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT |
    GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  frame.Samples = -1;
  if (frame.CountSamples)
  {
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    GLuint samples = 0;
    glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof(GLuint), &samples);
    frame.Samples = static_cast<long long>(samples);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, 0);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
  }
  glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, format);
  texture->Deactivate();
  glUseProgram(static_cast<GLuint>(previousProgram));
  return true;
}

void vtkAccelVolumeSliceCompute::ReleaseGraphicsResources(vtkWindow*)
{
  // Called with the context current (vtkAccelVolumeSliceResources::UseContext and the
  // mapper's ReleaseGraphicsResources make sure of it).
  for (auto& entry : this->Programs)
  {
    glDeleteProgram(entry.second.GetHandle());
  }
  this->Programs.clear();
  if (this->CounterBuffer)
  {
    glDeleteBuffers(1, &this->CounterBuffer);
    this->CounterBuffer = 0;
  }
}
