/**
 * @file   vtkAccelVolumeSliceCompute.h
 * @brief  The slice mapper's compute slices (internal): the accumulation pass of composite, MIP
 *         and MinIP frames run as one compute dispatch over the target instead of rasterised
 *         proxy slices blended into it (AccelVolumeSliceCS.glsl says how).
 *
 * VTK 9.1's vtkShaderProgram has no compute stage, so the programs are plain GL objects; their
 * uniforms are set through vtkAccelVolumeComputeProgram, which offers the vtkShaderProgram
 * calls the frame-uniform code uses. Programs are cached per prelude for one context.
 */
#ifndef vtkAccelVolumeSliceCompute_h
#define vtkAccelVolumeSliceCompute_h

#include <map>
#include <string>

class vtkMatrix4x4;
class vtkOpenGLRenderWindow;
class vtkAccelVolumeSliceResources;
class vtkWindow;
struct vtkAccelVolumeSliceFrame;

/** A linked GL compute program with vtkShaderProgram's uniform setters (locations cached). */
class vtkAccelVolumeComputeProgram
{
public:
  explicit vtkAccelVolumeComputeProgram(unsigned int handle = 0)
    : Handle(handle)
  {
  }
  unsigned int GetHandle() const { return this->Handle; }

  // As vtkShaderProgram's (the program must be current); false when the shader has no such
  // active uniform.
  bool SetUniformi(const char* name, int value);
  bool SetUniformf(const char* name, float value);
  bool SetUniform2f(const char* name, const float value[2]);
  bool SetUniform3f(const char* name, const float value[3]);
  bool SetUniform4f(const char* name, const float value[4]);
  bool SetUniform1iv(const char* name, int count, const int* values);
  bool SetUniform1fv(const char* name, int count, const float* values);
  bool SetUniform3fv(const char* name, int count, const float (*values)[3]);
  bool SetUniform4fv(const char* name, int count, const float (*values)[4]);
  bool SetUniformMatrix3x3(const char* name, float* matrix);
  /** VTK's row-major elements uploaded as they are (as vtkShaderProgram::SetUniformMatrix). */
  bool SetUniformMatrix(const char* name, vtkMatrix4x4* matrix);

private:
  int Location(const char* name);
  // Calls set(location) when the program has the active uniform `name`; whether it has.
  template <class Set>
  bool With(const char* name, Set&& set)
  {
    const int location = this->Location(name);
    if (location >= 0)
    {
      set(location);
    }
    return location >= 0;
  }
  unsigned int Handle = 0;
  std::map<std::string, int> Locations;
};

/** The compute programs of one context, by prelude. */
class vtkAccelVolumeSliceCompute
{
public:
  vtkAccelVolumeSliceCompute() = default;
  ~vtkAccelVolumeSliceCompute();

  /**
   * Whether `window`'s context runs compute slices: OpenGL 4.3 (compute shaders and image
   * stores), not disabled by ACCELVOLUME_DISABLE_COMPUTE; else why not.
   */
  static bool IsSupported(vtkOpenGLRenderWindow* window, std::string& why);

  /**
   * Fills resources.Accumulation (its size and format prepared, the scene depth copied) with
   * what the frame's blended proxy slices would leave there. frame.Samples gets the samples
   * taken when frame.CountSamples is set (a read-back that waits for the GPU). False with
   * `error` set when the program does not compile or the volume texture is unavailable.
   */
  bool Accumulate(vtkOpenGLRenderWindow* window, vtkAccelVolumeSliceResources& resources,
    const vtkAccelVolumeSliceFrame& frame, std::string& error);

  void ReleaseGraphicsResources(vtkWindow* window);

private:
  vtkAccelVolumeSliceCompute(const vtkAccelVolumeSliceCompute&) = delete;
  void operator=(const vtkAccelVolumeSliceCompute&) = delete;

  vtkAccelVolumeComputeProgram* ReadyProgram(const std::string& prelude, std::string& error);

  std::map<std::string, vtkAccelVolumeComputeProgram> Programs;
  unsigned int CounterBuffer = 0;
};

#endif
