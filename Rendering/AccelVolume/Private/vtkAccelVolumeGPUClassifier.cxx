// The slice mapper's skipping textures classified on the GPU from a GPU-built octree.
#include "vtkAccelVolumeGPUClassifier.h"

#include "vtkAccelVolumeOctreeGPUBuilder.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include "AccelVolumeOctreeClassifyCS.h"

#include <string>

namespace
{
constexpr int GroupEdge = 4; // local_size_x, _y and _z of AccelVolumeOctreeClassifyCS

// An R8 3D texture of `size`, (re)allocated when its size changed; nearest sampling.
bool PrepareTexture(vtkOpenGLRenderWindow* window, vtkTextureObject* texture, const int size[3])
{
  if (texture->GetHandle() && static_cast<int>(texture->GetWidth()) == size[0] &&
    static_cast<int>(texture->GetHeight()) == size[1] &&
    static_cast<int>(texture->GetDepth()) == size[2] && texture->GetComponents() == 1)
  {
    return true;
  }
  texture->SetContext(window);
  std::vector<unsigned char> zeros(static_cast<size_t>(size[0]) * size[1] * size[2], 0);
  window->GetState()->vtkglPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  if (!texture->Create3DFromRaw(size[0], size[1], size[2], 1, VTK_UNSIGNED_CHAR, zeros.data()))
  {
    return false;
  }
  texture->SetMinificationFilter(vtkTextureObject::Nearest);
  texture->SetMagnificationFilter(vtkTextureObject::Nearest);
  return true;
}

GLuint GroupsFor(int count)
{
  return static_cast<GLuint>((count + GroupEdge - 1) / GroupEdge);
}
}

bool vtkAccelVolumeGPUClassifier::Classify(vtkOpenGLRenderWindow* window,
  unsigned int levelBuffer, const int leafGrid[3], const std::vector<float>& opacities,
  const double range[2], vtkTextureObject* leaves, vtkTextureObject* blocks,
  const int blockGrid[3], int blockLeaves, long long& transparentLeaves, std::string& error)
{
  const std::string source = AccelVolumeOctreeClassifyCS;
  if (!this->LeafProgram)
  {
    this->LeafProgram = vtkAccelVolumeOctreeGPUBuilder::CompileProgram(
      ("#version 430\n#define ACCELVOLUME_CLASSIFY_BLOCKS 0\n" + source).c_str(),
      "the octree leaf classification", error);
  }
  if (!this->BlockProgram)
  {
    this->BlockProgram = vtkAccelVolumeOctreeGPUBuilder::CompileProgram(
      ("#version 430\n#define ACCELVOLUME_CLASSIFY_BLOCKS 1\n" + source).c_str(),
      "the octree block classification", error);
  }
  if (!this->LeafProgram || !this->BlockProgram)
  {
    return false;
  }
  if (!PrepareTexture(window, leaves, leafGrid) || !PrepareTexture(window, blocks, blockGrid))
  {
    error = "the skipping textures could not be allocated";
    return false;
  }
  // Prefix counts of the table's non-zero opacities: a range of entries is transparent when the
  // counts at its ends agree.
  std::vector<GLuint> before(opacities.size() + 1, 0);
  for (size_t i = 0; i < opacities.size(); ++i)
  {
    before[i + 1] = before[i] + (opacities[i] > 0.0f ? 1u : 0u);
  }
  if (!this->PrefixBuffer)
  {
    glGenBuffers(1, &this->PrefixBuffer);
    glGenBuffers(1, &this->CountBuffer);
  }
  while (glGetError() != GL_NO_ERROR)
  {
    // Errors of earlier GL work are not this pass's to report.
  }
  GLint previousProgram = 0;
  glGetIntegerv(GL_CURRENT_PROGRAM, &previousProgram);
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, this->PrefixBuffer);
  glBufferData(GL_SHADER_STORAGE_BUFFER, static_cast<GLsizeiptr>(before.size() * sizeof(GLuint)),
    before.data(), GL_DYNAMIC_DRAW);
  const GLuint zero = 0;
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, this->CountBuffer);
  glBufferData(GL_SHADER_STORAGE_BUFFER, sizeof(GLuint), &zero, GL_DYNAMIC_READ);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, levelBuffer);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, this->PrefixBuffer);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, this->CountBuffer);

  const GLuint leaf = this->LeafProgram;
  glUseProgram(leaf);
  glUniform3i(glGetUniformLocation(leaf, "leafGrid"), leafGrid[0], leafGrid[1], leafGrid[2]);
  glUniform1f(glGetUniformLocation(leaf, "rangeLower"), static_cast<float>(range[0]));
  const double width = range[1] > range[0] ? range[1] - range[0] : 1.0;
  glUniform1f(glGetUniformLocation(leaf, "rangeWidth"), static_cast<float>(width));
  glUniform1i(
    glGetUniformLocation(leaf, "tableSize"), static_cast<GLint>(opacities.size()));
  glBindImageTexture(0, leaves->GetHandle(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_R8);
  glDispatchCompute(GroupsFor(leafGrid[0]), GroupsFor(leafGrid[1]), GroupsFor(leafGrid[2]));
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);

  const GLuint block = this->BlockProgram;
  glUseProgram(block);
  glUniform3i(glGetUniformLocation(block, "leafGrid"), leafGrid[0], leafGrid[1], leafGrid[2]);
  glUniform3i(glGetUniformLocation(block, "blockGrid"), blockGrid[0], blockGrid[1], blockGrid[2]);
  glUniform1i(glGetUniformLocation(block, "blockLeaves"), blockLeaves);
  glBindImageTexture(0, leaves->GetHandle(), 0, GL_TRUE, 0, GL_READ_ONLY, GL_R8);
  glBindImageTexture(1, blocks->GetHandle(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_R8);
  glDispatchCompute(GroupsFor(blockGrid[0]), GroupsFor(blockGrid[1]), GroupsFor(blockGrid[2]));
  // The slice passes sample both textures next.
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);

  GLuint count = 0;
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, this->CountBuffer);
  glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof(GLuint), &count);
  transparentLeaves = static_cast<long long>(count);

  for (GLuint binding = 0; binding < 3; ++binding)
  {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, 0);
  }
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
  glBindImageTexture(0, 0, 0, GL_TRUE, 0, GL_READ_ONLY, GL_R8);
  glBindImageTexture(1, 0, 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_R8);
  glUseProgram(static_cast<GLuint>(previousProgram));
  if (glGetError() != GL_NO_ERROR)
  {
    error = "OpenGL error in the octree classification passes";
    return false;
  }
  return true;
}

void vtkAccelVolumeGPUClassifier::ReleaseGraphicsResources()
{
  if (this->LeafProgram)
  {
    glDeleteProgram(this->LeafProgram);
  }
  if (this->BlockProgram)
  {
    glDeleteProgram(this->BlockProgram);
  }
  if (this->PrefixBuffer)
  {
    glDeleteBuffers(1, &this->PrefixBuffer);
    glDeleteBuffers(1, &this->CountBuffer);
  }
  this->LeafProgram = this->BlockProgram = this->PrefixBuffer = this->CountBuffer = 0;
}
