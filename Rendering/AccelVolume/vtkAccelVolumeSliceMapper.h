/**
 * @class   vtkAccelVolumeSliceMapper
 * @brief   Slice-based OpenGL volume mapper: view-aligned proxy slices through a 3D texture,
 *          for composite (shaded direct volume rendering with early ray termination and
 *          empty-space skipping), maximum / minimum intensity projection, raysum (additive)
 *          and average, with cropping whose cut faces are re-rendered against aliasing.
 *
 * The volume is uploaded once as a 3D texture (trilinear or nearest sampling, as the volume
 * property says). Every frame the mapper draws planes of constant eye depth, clipped to the
 * (cropped, clipped) volume box, and accumulates one value per pixel in a float target with
 * max / min / additive blending; a resolve pass then colours that value the way
 * vtkGPUVolumeRayCastMapper does for the same blend mode and blends it over the scene:
 * - MAXIMUM / MINIMUM_INTENSITY_BLEND: colour and scalar opacity of the extreme value.
 * - ADDITIVE_BLEND (raysum): (1/unit) * integral of opacity(s) * s along the ray, s normalised
 *   to the data range, shown grey and clamped to [0, 1]. Samples are weighted by the ray
 *   length they stand for, so the result does not depend on the slice count; with the default
 *   unit (the smallest voxel spacing) it equals VTK's per-voxel-step sum.
 * - AVERAGE_INTENSITY_BLEND: ray-length-weighted mean of opacity(s) * s over samples inside
 *   AverageIPScalarRange, shown grey.
 * - COMPOSITE_BLEND: front-to-back (or back-to-front) compositing of colour and scalar
 *   opacity, opacity corrected for each ray's slice spacing against
 *   ScalarOpacityUnitDistance; gradient opacity; Phong shading with VTK's lights and the
 *   property's coefficients (gradients precomputed or by central differences); 2D transfer
 *   functions (TF_2D, value x gradient magnitude). Accelerations after the
 *   slice-based renderer of Lee 2005: early ray termination (a mark pass every N slices closes
 *   saturated pixels through the early depth test) and exact empty-space skipping, per
 *   fragment and with a min-max octree (slices clipped to the non-empty boxes, fragments in
 *   transparent leaves discarded before any shading).
 *
 * Cropping (VTK's region flags, any combination: each visible region is drawn as a convex
 * cell) and up to 8 clipping planes restrict the sampled region. With BoundaryRerendering on
 * (the default) the faces of each cell are drawn as extra textured polygons after the
 * slices (Hong, Kye and Shin 2007): for MIP / MinIP they
 * add the samples that coarse slices miss along oblique cut faces; for raysum / average each
 * face sample takes half of the gap to the nearest slice (trapezoid rule), so nothing is
 * counted twice and the integral stays exact for linear data.
 *
 * Opaque geometry already in the depth buffer hides what lies behind it.
 *
 * Large volumes: a volume with an axis longer than GL_MAX_3D_TEXTURE_SIZE (or
 * MaximumBrickSize), or larger than GPUMemoryBudget, is split into bricks that share one voxel
 * with each neighbour (so trilinear samples and central differences read the same texels as
 * in one texture: no seams). Each sample point is taken by exactly one brick; composite draws
 * the bricks in visibility order (front to back, or back to front), the other modes in any
 * order. Bricks the min-max octree finds transparent (composite) are never uploaded. Within a
 * budget, bricks stay resident once uploaded; beyond it, the bricks the budget cannot hold
 * stream through one texture every frame (see GetLastNumberOfBrickUploads).
 *
 * Limits: one-component scalars of type char, unsigned char, short, unsigned short, int,
 * float or double (int, float and double are sampled as 32-bit floats normalised to the
 * data range; NaN samples count as the minimum). Boundary re-rendering applies to the
 * projection modes, not to composite. Bricked volumes take gradients by central differences
 * (no precomputed gradient texture) and plain slices (SlabSamples is ignored).
 */

#ifndef vtkAccelVolumeSliceMapper_h
#define vtkAccelVolumeSliceMapper_h

#include "vtkRenderingAccelVolumeModule.h" // For export macro
#include "vtkAccelVolumeMapper.h"

#include <memory> // For std::unique_ptr

class vtkImageData;
class vtkOpenGLRenderWindow;
class vtkVolumeProperty;
class vtkRenderer;
class vtkVolume;
class vtkWindow;

class VTKRENDERINGACCELVOLUME_EXPORT vtkAccelVolumeSliceMapper : public vtkAccelVolumeMapper
{
public:
  static vtkAccelVolumeSliceMapper* New();
  vtkTypeMacro(vtkAccelVolumeSliceMapper, vtkAccelVolumeMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Distance between slices along the viewing direction, in world units, used when
   * AutoAdjustSampleDistances is off and NumberOfSlices is 0. Default 1.0, must be > 0.
   */
  vtkSetClampMacro(SampleDistance, double, 1.0e-6, VTK_DOUBLE_MAX);
  vtkGetMacro(SampleDistance, double);
  ///@}

  ///@{
  /**
   * When on (default), slices are one smallest voxel spacing apart, like VTK's GPU mapper,
   * and the spacing grows up to InteractiveSlowdownLimit times during interaction when the
   * last frame took longer than the time allotted to the volume.
   */
  vtkSetMacro(AutoAdjustSampleDistances, vtkTypeBool);
  vtkGetMacro(AutoAdjustSampleDistances, vtkTypeBool);
  vtkBooleanMacro(AutoAdjustSampleDistances, vtkTypeBool);
  ///@}

  ///@{
  /**
   * Explicit number of slices through the depth of the whole volume box (0 = use the
   * sample distance, the default). Overrides the sample distance when > 0.
   */
  vtkSetClampMacro(NumberOfSlices, int, 0, 1 << 16);
  vtkGetMacro(NumberOfSlices, int);
  ///@}

  ///@{
  /** Upper bound on slices per frame (default 4096): a tiny sample distance is widened. */
  vtkSetClampMacro(MaximumNumberOfSlices, int, 2, 1 << 16);
  vtkGetMacro(MaximumNumberOfSlices, int);
  ///@}

  ///@{
  /**
   * MIP / MinIP only: slice depths each proxy-slice fragment samples along its ray (default 1,
   * range 1..64). 1 is classic slicing, one polygon per sample plane. Larger values draw one
   * proxy polygon per group of planes, covering the group's projection, and take the same
   * samples in a loop, which cuts rasterisation and blending work at the price of a ray-box
   * test per fragment; the samples, and so the image, stay those of plain slicing. On software GL
   * the per-fragment test costs more than it saves, hence the default; GPUs with costly
   * blending may gain (the benchmark report has the figures).
   */
  vtkSetClampMacro(SlabSamples, int, 1, 64);
  vtkGetMacro(SlabSamples, int);
  ///@}

  ///@{
  /**
   * Composite only: early ray termination (EarlyRayTermination, default on, and
   * EarlyRayTerminationThreshold, default 0.99: vtkAccelVolumeMapper). Slices are drawn front
   * to back; every EarlyRayTerminationInterval slices (default 16, as in Lee 2005; the
   * benchmark report compares intervals) a cheap pass closes the pixels whose accumulated
   * opacity reached the threshold, so later slices generate no shaded fragments there. The image changes by at most the
   * remaining transparency (1 - threshold) at those pixels.
   */
  vtkSetClampMacro(EarlyRayTerminationInterval, int, 1, 4096);
  vtkGetMacro(EarlyRayTerminationInterval, int);
  /** Mark passes the last frame ran. */
  vtkGetMacro(LastNumberOfTerminationPasses, int);
  ///@}

  ///@{
  /**
   * Composite order (default on: front to back, which early ray termination needs). Off
   * draws back to front with "over" blending: the same image, without termination.
   */
  vtkSetMacro(FrontToBack, vtkTypeBool);
  vtkGetMacro(FrontToBack, vtkTypeBool);
  vtkBooleanMacro(FrontToBack, vtkTypeBool);
  ///@}

  ///@{
  /**
   * Composite shading / gradient opacity / 2D transfer functions: gradients precomputed into
   * a 4-channel 16-bit texture (the paper's way; 8 bytes per voxel, rebuilt when the data
   * change) instead of central differences on the fly (6 extra fetches per sample).
   * Default on: faster than central differences in the composite benchmark. Volumes whose
   * gradient texture would pass 1 GiB use central differences.
   */
  vtkSetMacro(PrecomputeGradients, vtkTypeBool);
  vtkGetMacro(PrecomputeGradients, vtkTypeBool);
  vtkBooleanMacro(PrecomputeGradients, vtkTypeBool);
  ///@}

  ///@{
  /**
   * Composite: offset each pixel's samples by up to half a slice along its ray (default off),
   * trading wood-grain rings for fine noise. Samples may then reach half a slice beyond a
   * crop or clip face.
   */
  vtkSetMacro(Jittering, vtkTypeBool);
  vtkGetMacro(Jittering, vtkTypeBool);
  vtkBooleanMacro(Jittering, vtkTypeBool);
  ///@}

  enum EmptySpaceSkippingModes
  {
    SKIP_NONE = 0,
    SKIP_FRAGMENT = 1, ///< transparent samples skip gradient and lighting
    SKIP_OCTREE = 2,   ///< fragments in transparent min-max octree leaves skip everything
    SKIP_BOTH = 3
  };

  ///@{
  /**
   * Composite only: empty-space skipping (default SKIP_BOTH). Exact: skipped samples have
   * opacity 0 under the scalar opacity function. SKIP_OCTREE builds a
   * vtkAccelVolumeMinMaxOctree (OctreeLeafSize^3 leaves, default 8) when the scalars change
   * and re-classifies it when the transfer function changes.
   */
  vtkSetClampMacro(EmptySpaceSkipping, int, SKIP_NONE, SKIP_BOTH);
  vtkGetMacro(EmptySpaceSkipping, int);
  vtkSetClampMacro(OctreeLeafSize, int, 2, 64);
  vtkGetMacro(OctreeLeafSize, int);
  /** Fraction of octree leaves found transparent in the last frame (-1 when unused). */
  vtkGetMacro(LastTransparentLeafFraction, double);
  /** Composite: fraction of the slice area kept by the octree culling in the last frame. */
  vtkGetMacro(LastProxyAreaFraction, double);
  ///@}

  ///@{
  /**
   * GPU memory the volume's bricks may hold at once, in bytes (default 0: no budget, as much as
   * the volume needs). A volume larger than the budget is cut into bricks of at most 1/8 of it;
   * 7/8 stay resident and the rest are streamed each frame. Transfer tables, the octree's leaf
   * texture, the float target and a precomputed gradient texture (one-brick volumes only) are
   * not counted. A budget smaller than a 16^3-cell brick is an error.
   */
  vtkSetClampMacro(GPUMemoryBudget, vtkIdType, 0, VTK_ID_MAX);
  vtkGetMacro(GPUMemoryBudget, vtkIdType);
  ///@}

  ///@{
  /**
   * Largest brick texture per axis (default 0: GL_MAX_3D_TEXTURE_SIZE). Smaller values force
   * bricking, e.g. to test it or to make octree brick culling finer; values below 4 are errors.
   */
  vtkSetClampMacro(MaximumBrickSize, int, 0, 1 << 16);
  vtkGetMacro(MaximumBrickSize, int);
  ///@}

  ///@{
  /**
   * Last frame: bricks of the layout, bricks drawn (others were culled as empty or lay outside
   * the crop), bricks uploaded and their bytes, and the bytes resident after the frame.
   */
  vtkGetMacro(LastNumberOfBricks, int);
  vtkGetMacro(LastNumberOfBricksDrawn, int);
  vtkGetMacro(LastNumberOfBrickUploads, int);
  vtkGetMacro(LastUploadedBytes, vtkIdType);
  vtkGetMacro(LastResidentBytes, vtkIdType);
  ///@}

  ///@{
  /**
   * Re-render the faces of the cropped / clipped volume after the slices (default on).
   */
  vtkSetMacro(BoundaryRerendering, vtkTypeBool);
  vtkGetMacro(BoundaryRerendering, vtkTypeBool);
  vtkBooleanMacro(BoundaryRerendering, vtkTypeBool);
  ///@}

  ///@{
  /**
   * World length that counts as one unit of the raysum (ADDITIVE_BLEND):
   * result = integral(opacity(s) * s dl) / unit. 0 (default) = the smallest voxel spacing.
   */
  vtkSetClampMacro(AdditiveUnitDistance, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(AdditiveUnitDistance, double);
  ///@}

  /**
   * Last frame: slice spacing (world units), sample planes (slab polygons times SlabSamples
   * when slabs are used), proxy polygons drawn for them, and boundary faces drawn.
   */
  vtkGetMacro(LastSliceSpacing, double);
  vtkGetMacro(LastNumberOfSlices, int);
  vtkGetMacro(LastNumberOfProxyPolygons, int);
  vtkGetMacro(LastNumberOfBoundaryFaces, int);
  // GetLastRenderTime (vtkAccelVolumeMapper) includes the GPU work: Render() waits for it.
  /** GL_RENDERER of the context that rendered last. */
  const char* GetOpenGLRenderer();

  /**
   * Renders the volume. Called by vtkVolume; not for direct use.
   */
  void Render(vtkRenderer* renderer, vtkVolume* volume) override;

  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  vtkAccelVolumeSliceMapper();
  ~vtkAccelVolumeSliceMapper() override;

  double SampleDistance = 1.0;
  vtkTypeBool AutoAdjustSampleDistances = 1;
  int NumberOfSlices = 0;
  int MaximumNumberOfSlices = 4096;
  vtkTypeBool BoundaryRerendering = 1;
  int SlabSamples = 1;
  int EarlyRayTerminationInterval = 16;
  int LastNumberOfTerminationPasses = 0;
  int EmptySpaceSkipping = SKIP_BOTH;
  vtkTypeBool FrontToBack = 1;
  vtkTypeBool PrecomputeGradients = 1;
  vtkTypeBool Jittering = 0;
  int OctreeLeafSize = 8;
  double LastTransparentLeafFraction = -1.0;
  double LastProxyAreaFraction = 1.0;
  double AdditiveUnitDistance = 0.0;
  double InteractiveSlowdownLimit = 4.0;

  vtkIdType GPUMemoryBudget = 0;
  int MaximumBrickSize = 0;
  int LastNumberOfBricks = 0;
  int LastNumberOfBricksDrawn = 0;
  int LastNumberOfBrickUploads = 0;
  vtkIdType LastUploadedBytes = 0;
  vtkIdType LastResidentBytes = 0;
  double LastSliceSpacing = 0.0;
  int LastNumberOfSlices = 0;
  int LastNumberOfProxyPolygons = 0;
  int LastNumberOfBoundaryFaces = 0;

private:
  vtkAccelVolumeSliceMapper(const vtkAccelVolumeSliceMapper&) = delete;
  void operator=(const vtkAccelVolumeSliceMapper&) = delete;

  bool ValidateInput(vtkImageData* input, vtkVolume* volume);
  // Builds / classifies the octree and uploads its leaf transparency; false if unavailable.
  bool UpdateEmptyLeaves(vtkOpenGLRenderWindow* window, vtkImageData* input,
    vtkVolumeProperty* property, const double range[2]);

  class vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
};

#endif
