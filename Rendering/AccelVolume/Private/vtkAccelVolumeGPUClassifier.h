/**
 * @file   vtkAccelVolumeGPUClassifier.h
 * @brief  The slice mapper's skipping textures classified on the GPU (internal): from a
 *         GPU-built octree's leaf level and the transfer table's opacities, straight into the
 *         empty-leaf and empty-block textures, with no read-back of the levels
 *         (AccelVolumeOctreeClassifyCS.glsl), so a time-varying volume's octree is rebuilt and
 *         classified on the GPU alone.
 *
 * A leaf is transparent when every table entry that a sample of its value range reads (the
 * shader interpolates the table linearly) has opacity 0: conservative for the samples the
 * shaders take, so skipping stays exact. It may differ from the CPU classification (which tests
 * the opacity function itself), never in a way that changes an image.
 */
#ifndef vtkAccelVolumeGPUClassifier_h
#define vtkAccelVolumeGPUClassifier_h

#include <string>
#include <vector>

class vtkOpenGLRenderWindow;
class vtkTextureObject;

class vtkAccelVolumeGPUClassifier
{
public:
  vtkAccelVolumeGPUClassifier() = default;
  ~vtkAccelVolumeGPUClassifier() = default;

  /**
   * Classifies the leaves of `levelBuffer` (interleaved raw (min, max) floats in Morton order,
   * vtkAccelVolumeOctreeGPUBuilder's level 0; `leafGrid` leaves per axis) against `opacities`
   * (the transfer table's entries over [range[0], range[1]]) into `leaves` (R8, leafGrid) and
   * `blocks` (R8, blockGrid, `blockLeaves`^3 leaves a block), 1 = transparent, allocating the
   * textures when their size changed. `transparentLeaves` gets the count (a read-back of one
   * number). False with `error` set when a program does not compile or a texture cannot be
   * made. Needs the window's context current.
   */
  bool Classify(vtkOpenGLRenderWindow* window, unsigned int levelBuffer, const int leafGrid[3],
    const std::vector<float>& opacities, const double range[2], vtkTextureObject* leaves,
    vtkTextureObject* blocks, const int blockGrid[3], int blockLeaves, long long& transparentLeaves,
    std::string& error);

  /** Frees the programs and buffers (with the context that made them current). */
  void ReleaseGraphicsResources();

private:
  vtkAccelVolumeGPUClassifier(const vtkAccelVolumeGPUClassifier&) = delete;
  void operator=(const vtkAccelVolumeGPUClassifier&) = delete;

  unsigned int LeafProgram = 0;
  unsigned int BlockProgram = 0;
  unsigned int PrefixBuffer = 0;
  unsigned int CountBuffer = 0;
};

#endif
