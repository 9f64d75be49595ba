// Builds accelvolume::MinMaxOctree levels with OpenGL 4.3 compute shaders (private to the module).
/**
 * @class   vtkAccelVolumeOctreeGPUBuilder
 * @brief   GPU builder of the min-max octree (Lim and Shin 2009, with compute shaders instead of
 *          CUDA): a leaf pass (one workgroup per leaf: its invocations stride over the leaf's
 *          voxels with texelFetch, with the one-voxel overlap of the core layout, and reduce
 *          their extremes in shared memory) and one reduce pass per level (one invocation per
 *          parent reading children 8p .. 8p+7).
 *
 * Each level lives in its own shader storage buffer of interleaved (min, max) floats in Morton
 * order, the same layout as accelvolume::OctreeLevel; padding nodes are (+inf, -inf). The
 * levels stay on the GPU; ReadBack() copies them into the core octree for CPU queries.
 *
 * All calls need the window's context (they make it current), save VTK's state with
 * vtkOpenGLState::Push()/Pop() and restore every buffer, texture and program binding they
 * change. Not wrapped, not installed.
 */
#ifndef vtkAccelVolumeOctreeGPUBuilder_h
#define vtkAccelVolumeOctreeGPUBuilder_h

#include <string>
#include <vector>

class vtkImageData;
class vtkOpenGLRenderWindow;
struct vtkAccelVolumeEncodedScalars;

namespace accelvolume
{
class MinMaxOctree;
}

class vtkAccelVolumeOctreeGPUBuilder
{
public:
  vtkAccelVolumeOctreeGPUBuilder();
  ~vtkAccelVolumeOctreeGPUBuilder();

  /**
   * Whether the window's context offers compute shaders (OpenGL >= 4.3) and they are not
   * disabled (ACCELVOLUME_DISABLE_COMPUTE set and not "0"); else why not.
   */
  static bool IsSupported(vtkOpenGLRenderWindow* window, std::string& why);

  /**
   * Compiles and links one compute shader in the current context (also the slice mapper's
   * compute slices): the program name, or 0 with `error` set to "NAME does not compile: log" /
   * "... does not link: ...".
   */
  static unsigned int CompileProgram(const char* source, const char* name, std::string& error);

  /**
   * How texels of a one-channel 3D texture decode to raw scalar values:
   * value = (roundTexel ? round(texel * scale) : texel * scale) + offset. roundTexel makes the
   * normalised 8/16-bit integer encodings exact. margin widens every non-empty leaf range
   * (min - margin, max + margin) so that lossy encodings (floats normalised to the data range)
   * still give conservative ranges.
   */
  struct Decode
  {
    double scale = 1.0;
    double offset = 0.0;
    bool roundTexel = false;
    double margin = 0.0;
  };

  /** How to decode a texture holding scalars of this encoding (vtkAccelVolumeScalarEncoding). */
  static Decode DecodeOf(const vtkAccelVolumeEncodedScalars& encoding);

  /**
   * Builds every level of `octree` (already Configure()d for the texture's dimensions) from a
   * 3D texture the caller owns (e.g. the slice mapper's volume texture). Leaves the levels on
   * the GPU (GetLevelBuffer); the core levels are untouched until ReadBack(). Ends with
   * glFinish so that callers' timers measure the real work.
   */
  bool BuildFromTexture(vtkOpenGLRenderWindow* window, unsigned int texture, const Decode& decode,
    const accelvolume::MinMaxOctree& octree, std::string& error);

  /**
   * Convenience: uploads the image's point scalars as the slice mapper does (R8 / R16 for 8/16-bit
   * integers, signed types offset to unsigned; other types normalised to their finite range in an
   * R32F texture), builds, then frees the texture.
   */
  bool Build(vtkOpenGLRenderWindow* window, vtkImageData* image,
    const accelvolume::MinMaxOctree& octree, std::string& error);

  /** Copies every level into the core octree (padding becomes exact +/-inf). */
  bool ReadBack(
    vtkOpenGLRenderWindow* window, accelvolume::MinMaxOctree& octree, std::string& error);

  /** Buffer name of a level (0 when not built or out of range). */
  unsigned int GetLevelBuffer(int level) const;
  int GetNumberOfLevels() const { return static_cast<int>(this->Buffers.size()); }

  /** Seconds spent in the last Build()'s texture upload (0 for BuildFromTexture). */
  double GetLastUploadTime() const { return this->LastUploadTime; }

  /** Frees the buffers and programs (needs the context that created them). */
  void ReleaseGraphicsResources(vtkOpenGLRenderWindow* window);

private:
  vtkAccelVolumeOctreeGPUBuilder(const vtkAccelVolumeOctreeGPUBuilder&) = delete;
  void operator=(const vtkAccelVolumeOctreeGPUBuilder&) = delete;

  bool EnsurePrograms(std::string& error);
  bool BuildCurrent(vtkOpenGLRenderWindow* window, unsigned int texture, const Decode& decode,
    const accelvolume::MinMaxOctree& octree, std::string& error);

  vtkOpenGLRenderWindow* Context = nullptr;
  unsigned int LeafProgram = 0;
  unsigned int ReduceProgram = 0;
  std::vector<unsigned int> Buffers;       // one SSBO per level
  std::vector<unsigned long long> Lengths; // nodes per level
  double LastUploadTime = 0.0;
};

#endif
