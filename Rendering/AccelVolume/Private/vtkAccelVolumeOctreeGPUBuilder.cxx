// GPU min-max octree builder: volume upload, leaf and reduce compute passes, read-back.
#include "vtkAccelVolumeOctreeGPUBuilder.h"

#include "vtkAccelVolumeScalarEncoding.h"

#include "skipping/MinMaxOctree.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkPointData.h"
#include "vtkTextureUnitManager.h"
#include "vtkTimerLog.h"
#include "vtk_glew.h"

#include "AccelVolumeOctreeLeafCS.h"
#include "AccelVolumeOctreeReduceCS.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>

namespace
{
constexpr unsigned int GroupSize = 64;    // local_size_x of both shaders (leaf: one group a leaf)
constexpr unsigned int MaxGroups = 65535; // the guaranteed GL_MAX_COMPUTE_WORK_GROUP_COUNT

// Makes the window's context current and restores VTK's state and the bindings we touch on exit,
// so that VTK's next render (and its cached state) is unaffected.
class ScopedComputeState
{
public:
  explicit ScopedComputeState(vtkOpenGLRenderWindow* window)
    : State(window->GetState())
  {
    this->State->Push();
    glGetIntegerv(GL_CURRENT_PROGRAM, &this->Program);
    glGetIntegerv(GL_SHADER_STORAGE_BUFFER_BINDING, &this->GenericBuffer);
    glGetIntegerv(GL_COPY_READ_BUFFER_BINDING, &this->CopyReadBuffer);
    for (unsigned int i = 0; i < 2; ++i)
    {
      glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, i, &this->Indexed[i]);
      glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_START, i, &this->Start[i]);
      glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_SIZE, i, &this->Size[i]);
    }
  }
  ~ScopedComputeState()
  {
    for (unsigned int i = 0; i < 2; ++i)
    {
      if (this->Size[i] > 0)
      {
        glBindBufferRange(GL_SHADER_STORAGE_BUFFER, i, this->Indexed[i], this->Start[i],
          static_cast<GLsizeiptr>(this->Size[i]));
      }
      else
      {
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, i, this->Indexed[i]);
      }
    }
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, this->GenericBuffer);
    glBindBuffer(GL_COPY_READ_BUFFER, this->CopyReadBuffer);
    glUseProgram(this->Program);
    this->State->Pop();
  }

private:
  vtkOpenGLState* State;
  GLint Program = 0;
  GLint GenericBuffer = 0;
  GLint CopyReadBuffer = 0;
  GLint Indexed[2] = { 0, 0 };
  GLint64 Start[2] = { 0, 0 };
  GLint64 Size[2] = { 0, 0 };
};

bool MakeCurrent(vtkOpenGLRenderWindow* window, std::string& error)
{
  if (!window)
  {
    error = "no render window (SetRenderWindow) for the GPU builder";
    return false;
  }
  window->MakeCurrent();
  if (!window->IsCurrent())
  {
    // A window that never rendered has no context yet.
    window->Initialize();
    window->MakeCurrent();
  }
  if (!window->IsCurrent())
  {
    error = "could not make the render window's OpenGL context current";
    return false;
  }
  return true;
}

}

unsigned int vtkAccelVolumeOctreeGPUBuilder::CompileProgram(
  const char* source, const char* name, std::string& error)
{
  const GLuint shader = glCreateShader(GL_COMPUTE_SHADER);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  std::string log(4096, '\0');
  if (!ok)
  {
    glGetShaderInfoLog(shader, static_cast<GLsizei>(log.size()), nullptr, &log[0]);
    error = std::string(name) + " does not compile: " + log.c_str();
    glDeleteShader(shader);
    return 0;
  }
  const GLuint program = glCreateProgram();
  glAttachShader(program, shader);
  glLinkProgram(program);
  glDeleteShader(shader); // stays alive while attached
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok)
  {
    glGetProgramInfoLog(program, static_cast<GLsizei>(log.size()), nullptr, &log[0]);
    error = std::string(name) + " does not link: " + log.c_str();
    glDeleteProgram(program);
    return 0;
  }
  return program;
}

namespace
{

// `groups` workgroups in a grid whose second dimension lifts the 65535-group limit of x.
bool DispatchGroups(unsigned long long groups, std::string& error)
{
  const unsigned long long x = std::min<unsigned long long>(std::max(groups, 1ULL), MaxGroups);
  const unsigned long long y = (groups + x - 1) / x;
  if (y > MaxGroups)
  {
    error = "octree level too large for one dispatch";
    return false;
  }
  glDispatchCompute(static_cast<GLuint>(x), static_cast<GLuint>(std::max(y, 1ULL)), 1);
  return true;
}

// One invocation per item (the reduce passes).
bool Dispatch(unsigned long long items, std::string& error)
{
  return DispatchGroups((items + GroupSize - 1) / GroupSize, error);
}

unsigned long long LevelLength(const accelvolume::OctreeLevel& level)
{
  return accelvolume::MortonEncode(static_cast<std::uint32_t>(std::max(level.gridSize[0], 1) - 1),
           static_cast<std::uint32_t>(std::max(level.gridSize[1], 1) - 1),
           static_cast<std::uint32_t>(std::max(level.gridSize[2], 1) - 1)) +
    1;
}

}

vtkAccelVolumeOctreeGPUBuilder::Decode vtkAccelVolumeOctreeGPUBuilder::DecodeOf(
  const vtkAccelVolumeEncodedScalars& encoding)
{
  Decode decode;
  decode.roundTexel = !encoding.Normalized;
  if (encoding.Normalized)
  {
    const double* range = encoding.Range;
    decode.scale = range[1] > range[0] ? range[1] - range[0] : 1.0;
    decode.offset = range[0];
    // Normalising and decoding each round twice in float (~2^-24 relative to the range's
    // magnitude); widen by a few of those so the ranges stay conservative.
    decode.margin = std::ldexp(std::fabs(range[0]) + std::fabs(range[1]), -20);
  }
  else
  {
    decode.scale = encoding.DecodeScale;
    decode.offset = encoding.DecodeOffset;
  }
  return decode;
}

vtkAccelVolumeOctreeGPUBuilder::vtkAccelVolumeOctreeGPUBuilder() = default;
vtkAccelVolumeOctreeGPUBuilder::~vtkAccelVolumeOctreeGPUBuilder() = default;

bool vtkAccelVolumeOctreeGPUBuilder::IsSupported(vtkOpenGLRenderWindow* window, std::string& why)
{
  // Lets users with a broken compute driver, and the tests, take the no-compute path.
  const char* disable = std::getenv("ACCELVOLUME_DISABLE_COMPUTE");
  if (disable && *disable && std::string(disable) != "0")
  {
    why = "compute shaders are disabled by ACCELVOLUME_DISABLE_COMPUTE";
    return false;
  }
  if (!MakeCurrent(window, why))
  {
    return false;
  }
  GLint major = 0;
  GLint minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  if (major < 4 || (major == 4 && minor < 3) || !glDispatchCompute || !glMemoryBarrier)
  {
    why = "the GPU octree builder needs OpenGL 4.3 compute shaders; the context offers " +
      std::to_string(major) + "." + std::to_string(minor);
    return false;
  }
  return true;
}

bool vtkAccelVolumeOctreeGPUBuilder::EnsurePrograms(std::string& error)
{
  if (!this->LeafProgram)
  {
    this->LeafProgram = CompileProgram(AccelVolumeOctreeLeafCS, "AccelVolumeOctreeLeafCS", error);
  }
  if (!this->ReduceProgram)
  {
    this->ReduceProgram =
      CompileProgram(AccelVolumeOctreeReduceCS, "AccelVolumeOctreeReduceCS", error);
  }
  return this->LeafProgram && this->ReduceProgram;
}

bool vtkAccelVolumeOctreeGPUBuilder::BuildFromTexture(vtkOpenGLRenderWindow* window,
  unsigned int texture, const Decode& decode, const accelvolume::MinMaxOctree& octree,
  std::string& error)
{
  if (!IsSupported(window, error))
  {
    return false;
  }
  ScopedComputeState scope(window);
  return this->BuildCurrent(window, texture, decode, octree, error);
}

bool vtkAccelVolumeOctreeGPUBuilder::BuildCurrent(vtkOpenGLRenderWindow* window,
  unsigned int texture, const Decode& decode, const accelvolume::MinMaxOctree& octree,
  std::string& error)
{
  if (this->Context && this->Context != window)
  {
    this->ReleaseGraphicsResources(this->Context);
    window->MakeCurrent();
  }
  this->Context = window;
  if (!this->EnsurePrograms(error))
  {
    return false;
  }
  const int depth = octree.GetDepth();
  if (depth < 0)
  {
    error = "the octree is not configured";
    return false;
  }
  // One SSBO per level, reused while the layout stays the same.
  std::vector<unsigned long long> lengths(depth + 1);
  for (int level = 0; level <= depth; ++level)
  {
    lengths[level] = LevelLength(octree.GetLevel(level));
  }
  if (lengths != this->Lengths)
  {
    if (!this->Buffers.empty())
    {
      glDeleteBuffers(static_cast<GLsizei>(this->Buffers.size()), this->Buffers.data());
    }
    this->Buffers.assign(lengths.size(), 0);
    glGenBuffers(static_cast<GLsizei>(this->Buffers.size()), this->Buffers.data());
    for (size_t level = 0; level < lengths.size(); ++level)
    {
      glBindBuffer(GL_SHADER_STORAGE_BUFFER, this->Buffers[level]);
      glBufferData(GL_SHADER_STORAGE_BUFFER,
        static_cast<GLsizeiptr>(lengths[level] * 2 * sizeof(float)), nullptr, GL_DYNAMIC_COPY);
    }
    this->Lengths = lengths;
    if (glGetError() == GL_OUT_OF_MEMORY)
    {
      error = "out of GPU memory for the octree levels";
      this->Lengths.clear();
      return false;
    }
  }

  // Leaf pass: the volume texture on a free unit, sampled with texelFetch (no filtering).
  vtkTextureUnitManager* units = window->GetTextureUnitManager();
  const int unit = units->Allocate();
  if (unit < 0)
  {
    error = "no free texture unit for the volume";
    return false;
  }
  window->GetState()->vtkglActiveTexture(GL_TEXTURE0 + unit);
  GLint previousTexture = 0;
  glGetIntegerv(GL_TEXTURE_BINDING_3D, &previousTexture);
  glBindTexture(GL_TEXTURE_3D, texture);

  const int* dims = octree.GetDimensions();
  const int* leaves = octree.GetLevel(0).gridSize;
  const GLuint leaf = this->LeafProgram;
  glUseProgram(leaf);
  glUniform1i(glGetUniformLocation(leaf, "volume"), unit);
  glUniform3i(glGetUniformLocation(leaf, "dims"), dims[0], dims[1], dims[2]);
  glUniform3i(glGetUniformLocation(leaf, "leafGrid"), leaves[0], leaves[1], leaves[2]);
  glUniform1i(glGetUniformLocation(leaf, "leafSize"), octree.GetLeafSize());
  glUniform1ui(glGetUniformLocation(leaf, "nodeCount"), static_cast<GLuint>(lengths[0]));
  glUniform1f(glGetUniformLocation(leaf, "decodeScale"), static_cast<float>(decode.scale));
  glUniform1f(glGetUniformLocation(leaf, "decodeOffset"), static_cast<float>(decode.offset));
  glUniform1i(glGetUniformLocation(leaf, "roundTexel"), decode.roundTexel ? 1 : 0);
  glUniform1f(glGetUniformLocation(leaf, "margin"), static_cast<float>(decode.margin));
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, this->Buffers[0]);
  // One workgroup per leaf (a shared-memory reduction over its voxels).
  bool ok = DispatchGroups(lengths[0], error);

  glBindTexture(GL_TEXTURE_3D, static_cast<GLuint>(previousTexture));
  units->Free(unit);

  // Reduce passes, finest parent level first; each reads what the previous pass wrote.
  const GLuint reduce = this->ReduceProgram;
  glUseProgram(reduce);
  const GLint parentCount = glGetUniformLocation(reduce, "parentCount");
  const GLint childCount = glGetUniformLocation(reduce, "childCount");
  for (int level = 1; ok && level <= depth; ++level)
  {
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glUniform1ui(parentCount, static_cast<GLuint>(lengths[level]));
    glUniform1ui(childCount, static_cast<GLuint>(lengths[level - 1]));
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, this->Buffers[level - 1]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, this->Buffers[level]);
    ok = Dispatch(lengths[level], error);
  }
  // Later readers: shaders (a ray caster's SSBO reads) and glGetBufferSubData.
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  // Timers around the build must see finished work, not queued commands.
  glFinish();
  const GLenum glError = glGetError();
  if (ok && glError != GL_NO_ERROR)
  {
    error = "OpenGL error " + std::to_string(glError) + " in the octree compute passes";
    ok = false;
  }
  return ok;
}

bool vtkAccelVolumeOctreeGPUBuilder::Build(vtkOpenGLRenderWindow* window, vtkImageData* image,
  const accelvolume::MinMaxOctree& octree, std::string& error)
{
  vtkDataArray* scalars = image ? image->GetPointData()->GetScalars() : nullptr;
  if (!scalars || scalars->GetNumberOfComponents() != 1)
  {
    error = "the GPU builder needs single-component point scalars";
    return false;
  }
  if (!IsSupported(window, error))
  {
    return false;
  }
  int dims[3];
  image->GetDimensions(dims);
  GLint maximumSize = 0;
  glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &maximumSize);
  if (dims[0] > maximumSize || dims[1] > maximumSize || dims[2] > maximumSize)
  {
    error = "volume exceeds GL_MAX_3D_TEXTURE_SIZE " + std::to_string(maximumSize);
    return false;
  }
  vtkNew<vtkTimerLog> timer;
  timer->StartTimer();
  double range[2] = { 0.0, 1.0 };
  scalars->GetFiniteRange(range, 0);
  if (!(range[0] <= range[1]))
  {
    range[0] = range[1] = 0.0; // no finite value at all
  }
  vtkAccelVolumeEncodedScalars encoded;
  if (!vtkAccelVolumeEncodeScalars(scalars, range, encoded, error))
  {
    return false;
  }
  const void* upload = encoded.Data;
  GLenum internalFormat = GL_R32F;
  GLenum type = GL_FLOAT;
  if (encoded.TextureType == VTK_UNSIGNED_CHAR)
  {
    internalFormat = GL_R8;
    type = GL_UNSIGNED_BYTE;
  }
  else if (encoded.TextureType == VTK_UNSIGNED_SHORT)
  {
    internalFormat = GL_R16;
    type = GL_UNSIGNED_SHORT;
  }
  const Decode decode = DecodeOf(encoded);

  ScopedComputeState scope(window);
  vtkOpenGLState* state = window->GetState();
  GLint previousTexture = 0;
  glGetIntegerv(GL_TEXTURE_BINDING_3D, &previousTexture);
  GLint previousAlignment = 4;
  glGetIntegerv(GL_UNPACK_ALIGNMENT, &previousAlignment);
  GLuint texture = 0;
  glGenTextures(1, &texture);
  glBindTexture(GL_TEXTURE_3D, texture);
  // texelFetch needs a complete texture: one level, no mipmap filtering.
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_BASE_LEVEL, 0);
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAX_LEVEL, 0);
  state->vtkglPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage3D(GL_TEXTURE_3D, 0, static_cast<GLint>(internalFormat), dims[0], dims[1], dims[2], 0,
    GL_RED, type, upload);
  state->vtkglPixelStorei(GL_UNPACK_ALIGNMENT, previousAlignment);
  glBindTexture(GL_TEXTURE_3D, static_cast<GLuint>(previousTexture));
  bool ok = true;
  if (glGetError() == GL_OUT_OF_MEMORY)
  {
    error = "could not create the 3D texture (out of GPU memory?)";
    ok = false;
  }
  glFinish();
  timer->StopTimer();
  this->LastUploadTime = timer->GetElapsedTime();
  ok = ok && this->BuildCurrent(window, texture, decode, octree, error);
  glDeleteTextures(1, &texture);
  return ok;
}

bool vtkAccelVolumeOctreeGPUBuilder::ReadBack(
  vtkOpenGLRenderWindow* window, accelvolume::MinMaxOctree& octree, std::string& error)
{
  if (this->Buffers.empty() || window != this->Context ||
    static_cast<int>(this->Buffers.size()) != octree.GetDepth() + 1)
  {
    error = "no GPU octree to read back";
    return false;
  }
  if (!MakeCurrent(window, error))
  {
    return false;
  }
  ScopedComputeState scope(window);
  std::vector<float> interleaved;
  for (size_t level = 0; level < this->Buffers.size(); ++level)
  {
    const size_t length = static_cast<size_t>(this->Lengths[level]);
    interleaved.resize(2 * length);
    glBindBuffer(GL_COPY_READ_BUFFER, this->Buffers[level]);
    glGetBufferSubData(GL_COPY_READ_BUFFER, 0,
      static_cast<GLsizeiptr>(interleaved.size() * sizeof(float)), interleaved.data());
    accelvolume::OctreeLevel& target = octree.GetLevel(static_cast<int>(level));
    target.minimum.resize(length);
    target.maximum.resize(length);
    constexpr float infinity = std::numeric_limits<float>::infinity();
    for (size_t i = 0; i < length; ++i)
    {
      // Padding is written as the infinities' bit patterns; snap anything at the float limits
      // so CPU code comparing against +/-inf sees exactly the core's convention.
      const float low = interleaved[2 * i];
      const float high = interleaved[2 * i + 1];
      target.minimum[i] = low >= std::numeric_limits<float>::max() ? infinity : low;
      target.maximum[i] = high <= -std::numeric_limits<float>::max() ? -infinity : high;
    }
  }
  if (glGetError() != GL_NO_ERROR)
  {
    error = "OpenGL error while reading the octree back";
    return false;
  }
  return true;
}

unsigned int vtkAccelVolumeOctreeGPUBuilder::GetLevelBuffer(int level) const
{
  return level >= 0 && level < static_cast<int>(this->Buffers.size()) ? this->Buffers[level] : 0;
}

void vtkAccelVolumeOctreeGPUBuilder::ReleaseGraphicsResources(vtkOpenGLRenderWindow* window)
{
  if (!window || window != this->Context)
  {
    return;
  }
  if (this->LeafProgram || this->ReduceProgram || !this->Buffers.empty())
  {
    window->MakeCurrent();
    if (!this->Buffers.empty())
    {
      glDeleteBuffers(static_cast<GLsizei>(this->Buffers.size()), this->Buffers.data());
    }
    if (this->LeafProgram)
    {
      glDeleteProgram(this->LeafProgram);
    }
    if (this->ReduceProgram)
    {
      glDeleteProgram(this->ReduceProgram);
    }
  }
  this->Buffers.clear();
  this->Lengths.clear();
  this->LeafProgram = 0;
  this->ReduceProgram = 0;
  this->Context = nullptr;
}
