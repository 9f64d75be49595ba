/**
 * @class   vtkAccelVolumeMinMaxOctree
 * @brief   Min-max octree of a volume in Morton (Z) order, built in parallel on the CPU
 *          (vtkSMPTools) or on the GPU (OpenGL compute shaders), classified by a transfer
 *          function for empty-space skipping.
 *
 * Implements the structure of Lim and Shin 2009 ("Min-max octree generation using CUDA") for the
 * slice and ray-casting mappers: leaves are LeafSize^3 voxel blocks (with one voxel of overlap,
 * so skipping is exact for trilinear samples), parents hold the min/max of their 8 children,
 * stored level by level in Morton order so each parent's children are contiguous.
 *
 * Two timestamps, as in VTK's space-leaping filter: Update() rebuilds only when the input's
 * scalars (or LeafSize / Builder) changed; Classify() re-flags the nodes only when the opacity
 * function or the scalar range changed.
 *
 * Builders: BUILDER_REFERENCE (plain loops, the test oracle), BUILDER_CPU (Morton-order
 * parallel build with vtkSMPTools; identical results for any thread count) and BUILDER_GPU
 * (compute shaders in the OpenGL context of SetRenderWindow(); needs OpenGL 4.3; the levels
 * stay on the GPU in shader storage buffers and are read back only when a CPU query needs them).
 *
 * Supported scalars: one component of char, signed/unsigned char, short, unsigned short, int,
 * float or double; any dimensions >= 1. NaN and -Inf voxels count as the finite minimum of the
 * data and +Inf as its finite maximum, the values the slice mapper's volume texture holds.
 */

#ifndef vtkAccelVolumeMinMaxOctree_h
#define vtkAccelVolumeMinMaxOctree_h

#include "vtkObject.h"
#include "vtkRenderingAccelVolumeModule.h" // For export macro
#include "vtkTimeStamp.h"                  // For vtkTimeStamp

#include <memory> // For std::unique_ptr

class vtkImageData;
class vtkOpenGLRenderWindow;
class vtkTextureObject;
class vtkPiecewiseFunction;

class VTKRENDERINGACCELVOLUME_EXPORT vtkAccelVolumeMinMaxOctree : public vtkObject
{
public:
  static vtkAccelVolumeMinMaxOctree* New();
  vtkTypeMacro(vtkAccelVolumeMinMaxOctree, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum Builders
  {
    BUILDER_REFERENCE = 0,
    BUILDER_CPU = 1,
    BUILDER_GPU = 2
  };

  ///@{
  /** The volume (point scalars, one component). */
  void SetInputData(vtkImageData* image);
  vtkImageData* GetInput();
  ///@}

  ///@{
  /** Leaf block edge in voxels: a power of two in [2, 64] (default 8, as in the paper). */
  vtkSetMacro(LeafSize, int);
  vtkGetMacro(LeafSize, int);
  ///@}

  ///@{
  /**
   * Which builder Update() uses (default BUILDER_CPU). BUILDER_GPU falls back to BUILDER_CPU
   * (same octree, one warning per reason) when the window's context has no compute shaders
   * (OpenGL < 4.3, or ACCELVOLUME_DISABLE_COMPUTE=1 in the environment); it still needs
   * SetRenderWindow().
   */
  vtkSetClampMacro(Builder, int, BUILDER_REFERENCE, BUILDER_GPU);
  vtkGetMacro(Builder, int);
  ///@}

  /** The builder the last build used (-1 before any): BUILDER_CPU where BUILDER_GPU fell back. */
  vtkGetMacro(LastBuilder, int);

  ///@{
  /** Threads for BUILDER_CPU (0 = vtkSMPTools' default). Results never depend on it. */
  vtkSetClampMacro(NumberOfThreads, int, 0, 1024);
  vtkGetMacro(NumberOfThreads, int);
  ///@}

  /** OpenGL context for BUILDER_GPU (not reference counted: keep the window alive). */
  void SetRenderWindow(vtkOpenGLRenderWindow* window);

  /**
   * BUILDER_GPU: read the scalars from this 3D texture of the render window's context instead
   * of uploading them (default none). It must hold the input's scalars as the module's mappers
   * store them: 8/16-bit integers as unsigned normalised texels (signed ones offset), other
   * types normalised to their finite range; vtkAccelVolumeSliceMapper passes its resident volume
   * this way (SetOctreeBuilder), so a time-varying volume is uploaded once per step, for
   * rendering, and its octree built from that copy. Not reference counted: keep it alive, or
   * set nullptr.
   */
  void SetInputTexture(vtkTextureObject* texture);

  /**
   * Builds the octree if the input scalars, LeafSize or Builder changed since the last build.
   * Returns false (with a vtkErrorMacro) on bad input or when BUILDER_GPU has no window.
   * A build (not a reuse) fires StartEvent, ProgressEvent 0 and 1 and EndEvent.
   */
  bool Update();

  /**
   * Flags transparent nodes for the opacity function over the scalar range `range`
   * (normally the data range the mapper maps the transfer function over). Re-runs only when
   * the function, the range or the octree changed. Call after Update().
   */
  bool Classify(vtkPiecewiseFunction* opacity, const double range[2]);

  /** Build / classification cost of the last real build / classification, in seconds. */
  vtkGetMacro(LastBuildTime, double);
  vtkGetMacro(LastClassifyTime, double);

  /** Levels above the leaves (the root is at level GetDepth()), total nodes, leaf grid size. */
  int GetDepth();
  vtkIdType GetNumberOfNodes();
  void GetLeafGridSize(int size[3]);

  /** Min and max of a node (level 0 = leaves), by Morton index. False when out of range. */
  bool GetNodeRange(int level, vtkIdType mortonIndex, double range[2]);
  /** Whether a node is transparent under the last classification. */
  bool IsNodeTransparent(int level, vtkIdType mortonIndex);
  /** Fraction of leaves inside the volume that the last classification found transparent. */
  double GetTransparentLeafFraction();

  /**
   * Index-space distance query: the smallest t in [t0, t1] where origin + t * direction enters
   * a non-transparent leaf; t1 if none.
   */
  double NextNonEmpty(const double origin[3], const double direction[3], double t0, double t1);

  /**
   * For the GPU builder: the OpenGL buffer names holding each level's interleaved (min, max)
   * floats in Morton order (0 if not built on the GPU). Valid in the render window's context.
   */
  unsigned int GetGPULevelBuffer(int level);

  /** Core access for the module's mappers (not wrapped). */
  class vtkInternals;
#ifndef __VTK_WRAP__ // returns a private type: the Python wrapper cannot wrap it
  vtkInternals* GetInternals() { return this->Internals.get(); }
#endif

  /** Releases GPU buffers (call while the context is current, or before it goes away). */
  void ReleaseGraphicsResources();

protected:
  vtkAccelVolumeMinMaxOctree();
  ~vtkAccelVolumeMinMaxOctree() override;

  int LeafSize = 8;
  int Builder = BUILDER_CPU;
  int LastBuilder = -1;
  int NumberOfThreads = 0;
  double LastBuildTime = 0.0;
  double LastClassifyTime = 0.0;
  vtkTimeStamp BuildTime;
  vtkTimeStamp ClassifyTime;

private:
  vtkAccelVolumeMinMaxOctree(const vtkAccelVolumeMinMaxOctree&) = delete;
  void operator=(const vtkAccelVolumeMinMaxOctree&) = delete;

  std::unique_ptr<vtkInternals> Internals;
};

#endif
