/**
 * @class   vtkAccelVolumeRayCastMapper
 * @brief   CPU volume ray caster with exact empty-space leaping (min-max octree with a
 *          distance template, or a distance map) and semi-transparent cell leaping through a
 *          modified Marching Cubes table (Lim, Kim and Shin 2009).
 *
 * For users without a GPU: rays are cast on the CPU (vtkSMPTools over fixed 16x16 pixel
 * tiles, so the image never depends on the thread count) and the image is shown in the VTK
 * scene as a textured quad, stopped by the opaque geometry already drawn (the depth buffer is
 * read back when the renderer has visible actors).
 *
 * Blend modes: composite (colour, scalar opacity, gradient opacity, Phong shading with VTK's
 * lights), maximum / minimum intensity, additive (raysum), average, slice (the property's
 * vtkPlane: one classified, optionally shaded sample where each ray meets it) and isosurface
 * (the property's iso-values: every crossing between two samples adds the tables' colour and
 * opacity at that value, shaded, front to back, as VTK's GPU mapper), with the transfer
 * function semantics of vtkAccelVolumeSliceMapper (1024-entry tables over the data range,
 * opacity corrected from ScalarOpacityUnitDistance to the sample distance), VTK cropping
 * (every region flag pattern) and any number of clipping planes, parallel and perspective
 * cameras, trilinear or nearest interpolation, scalars of any integer or floating type.
 *
 * 2-4 scalar components render in every blend mode as vtkGPUVolumeRayCastMapper renders
 * them (and vtkAccelVolumeSliceMapper): independent
 * components each classified by their own colour, opacity and gradient-opacity functions over
 * their own range, lit with their own coefficients and combined with the component weights;
 * dependent 2 components (colour of component 0, opacity of component 1) and RGBA (colour as is,
 * 8/16-bit integers normalised to their type, opacity of component 3). The octree and the
 * distance map classify each component (a node or cell is empty when every component of
 * positive weight, or the dependent opacity component, is transparent there); cell leaping does
 * not apply to them, their gradients are taken on the fly. ISOSURFACE_BLEND draws the
 * iso-surfaces of the independent component of the largest weight (the first of equals, as VTK;
 * normalised to its own range, where VTK 9.1 takes component 0's) or of dependent component 0;
 * SLICE_BLEND classifies the plane's sample as composite does, without opacity correction
 * (VTK 9.1's shader fails to compile for independent slices).
 *
 * Samples sit at the middle of each step of the ray inside the volume (the midpoint rule of
 * the ray integral); VTK's fixed-point mapper starts at the entry point, which differs visibly
 * only when the sample distance is a large part of the volume.
 *
 * Rays sample at a fixed world distance: SampleDistance, or InteractiveSampleDistance when
 * AutoAdjustSampleDistances is on and the renderer asks for an interactive frame (allocated
 * time < 1 s). The image has one ray per ImageSampleDistance x ImageSampleDistance pixels;
 * with AutoAdjustSampleDistances on, interactive frames adapt it between
 * MinimumImageSampleDistance and MaximumImageSampleDistance to meet the allocated time, like
 * vtkFixedPointVolumeRayCastMapper.
 *
 * Every acceleration is exact: the image is identical with and without it (early ray
 * termination changes a pixel by at most 1 - EarlyRayTerminationThreshold, identically with
 * and without leaping):
 * - LEAP_OCTREE: a min-max octree (OctreeLeafSize^3 leaves, built in parallel in Morton order
 *   when the scalars change, classified when the transfer function changes). Composite and
 *   additive rays leap over transparent nodes; MIP / MinIP rays leap over nodes whose range
 *   cannot beat the ray's current extreme (multi-component: every component's own octree). The step count out of a node comes from a per-tile
 *   distance template instead of a ray-box intersection.
 * - LEAP_DISTANCE_MAP: per cell, the chessboard distance to the nearest cell that may be
 *   opaque (rebuilt when the transfer function changes); composite and additive only.
 * - CellLeaping (off by default, see SetCellLeaping): in a semi-transparent cell (some corners
 * transparent, some not) the cell's Marching Cubes case says which edge interpolations bound the
 * opaque part; a sample outside it is transparent and is not resampled (composite and additive,
 * trilinear only). Average intensity counts transparent samples, so it never leaps.
 */

#ifndef vtkAccelVolumeRayCastMapper_h
#define vtkAccelVolumeRayCastMapper_h

#include "vtkRenderingAccelVolumeModule.h" // For export macro
#include "vtkAccelVolumeMapper.h"

#include <memory> // For std::unique_ptr

class vtkImageData;
class vtkRenderer;
class vtkVolume;
class vtkWindow;

class VTKRENDERINGACCELVOLUME_EXPORT vtkAccelVolumeRayCastMapper : public vtkAccelVolumeMapper
{
public:
  static vtkAccelVolumeRayCastMapper* New();
  vtkTypeMacro(vtkAccelVolumeRayCastMapper, vtkAccelVolumeMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum LeapModes
  {
    LEAP_NONE = 0,
    LEAP_OCTREE = 1,
    LEAP_DISTANCE_MAP = 2
  };

  ///@{
  /**
   * Empty-space leaping (default LEAP_DISTANCE_MAP: the fastest frames; its rebuild after a
   * transfer-function change scans every cell, while LEAP_OCTREE only re-classifies its nodes,
   * which suits interactive transfer-function editing better; the benchmark report has both).
   */
  vtkSetClampMacro(LeapMode, int, LEAP_NONE, LEAP_DISTANCE_MAP);
  vtkGetMacro(LeapMode, int);
  ///@}

  ///@{
  /**
   * Semi-transparent cell leaping through the modified Marching Cubes table (default off).
   * Exact. Measured on 2-core EPYC, 512^2, six volumes x two transfer functions
   * (accelvolume_benchmark_raycast, four runs): +15..54% without empty-space leaping, but
   * -15..+6% on top of the distance map and -16..+17% on top of the octree, as those leave few
   * semi-transparent samples and the test costs about what it saves; hence off by default.
   */
  vtkSetMacro(CellLeaping, vtkTypeBool);
  vtkGetMacro(CellLeaping, vtkTypeBool);
  vtkBooleanMacro(CellLeaping, vtkTypeBool);
  ///@}

  ///@{
  /** Octree leaf edge in voxels, a power of two in [2, 64] (default 4). */
  vtkSetClampMacro(OctreeLeafSize, int, 2, 64);
  vtkGetMacro(OctreeLeafSize, int);
  ///@}

  ///@{
  /** Distance between samples along a ray in world units (default 1.0). */
  vtkSetClampMacro(SampleDistance, double, 1.0e-6, VTK_DOUBLE_MAX);
  vtkGetMacro(SampleDistance, double);
  vtkSetClampMacro(InteractiveSampleDistance, double, 1.0e-6, VTK_DOUBLE_MAX);
  vtkGetMacro(InteractiveSampleDistance, double);
  ///@}

  ///@{
  /**
   * As vtkFixedPointVolumeRayCastMapper (default off): sample at
   * vtkVolumeMapper::SpacingAdjustedSampleDistance (half the mean voxel spacing, less for small
   * volumes), still and interactive frames alike, instead of (Interactive)SampleDistance.
   */
  vtkSetClampMacro(LockSampleDistanceToInputSpacing, vtkTypeBool, 0, 1);
  vtkGetMacro(LockSampleDistanceToInputSpacing, vtkTypeBool);
  vtkBooleanMacro(LockSampleDistanceToInputSpacing, vtkTypeBool);
  ///@}

  ///@{
  /**
   * As vtkFixedPointVolumeRayCastMapper (default on): opaque geometry drawn before the volume
   * stops the rays. Off ignores the scene's depth.
   */
  vtkSetClampMacro(IntermixIntersectingGeometry, vtkTypeBool, 0, 1);
  vtkGetMacro(IntermixIntersectingGeometry, vtkTypeBool);
  vtkBooleanMacro(IntermixIntersectingGeometry, vtkTypeBool);
  ///@}

  ///@{
  /** Pixels per ray along each image axis (default 1). */
  vtkSetClampMacro(ImageSampleDistance, double, 1.0, 32.0);
  vtkGetMacro(ImageSampleDistance, double);
  vtkSetClampMacro(MinimumImageSampleDistance, double, 1.0, 32.0);
  vtkGetMacro(MinimumImageSampleDistance, double);
  vtkSetClampMacro(MaximumImageSampleDistance, double, 1.0, 32.0);
  vtkGetMacro(MaximumImageSampleDistance, double);
  ///@}

  ///@{
  /**
   * Interactive frames (allocated render time < 1 s) use InteractiveSampleDistance and adapt
   * the image sample distance to the allocated time (default on, like VTK's CPU mapper).
   * Still frames always use SampleDistance and ImageSampleDistance.
   */
  vtkSetMacro(AutoAdjustSampleDistances, vtkTypeBool);
  vtkGetMacro(AutoAdjustSampleDistances, vtkTypeBool);
  vtkBooleanMacro(AutoAdjustSampleDistances, vtkTypeBool);
  ///@}

  ///@{
  /**
   * Threads for the tiles and the frame's preparation: 0 = vtkSMPTools' default (all cores);
   * N > 0 = exactly N workers (capped at the machine's cores). The image does not depend on it.
   */
  vtkSetClampMacro(NumberOfThreads, int, 0, 1024);
  vtkGetMacro(NumberOfThreads, int);
  ///@}

  ///@{
  /**
   * ADDITIVE_BLEND (raysum): the ray-length integral of opacity(s) * s over a unit length: 0
   * (the default) = the property's ScalarOpacityUnitDistance, as VTK's GPU mapper (its
   * per-sample sum scales each opacity by sample distance / unit distance); > 0: that length.
   */
  vtkSetClampMacro(AdditiveUnitDistance, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(AdditiveUnitDistance, double);
  ///@}

  ///@{
  /**
   * As vtkGPUVolumeRayCastMapper and vtkAccelVolumeSliceMapper (VTK's fixed-point mapper has no
   * mask): a mask image with the volume's dimensions, its type (BinaryMaskType, or
   * LabelMapMaskType: the default) and the label blend factor (default 1), each read at the
   * voxel nearest to a sample. Binary (nonzero = inside): samples outside are skipped in every
   * blend mode, and cells all outside are empty space for the distance map (exact: a mask only
   * removes samples). Label map (composite, one component): a voxel with label L > 0 takes the
   * colour and opacity of the property's SetLabelColor(L) / SetLabelScalarOpacity(L) (the
   * property's own functions where a label has none), mixed with the unlabelled classification
   * by MaskBlendFactor (0: no effect); leaping is off then, since labels may make transparent
   * values visible. Ghost arrays (blanked points, ghost cells) hide samples as in the slice
   * mapper (intersected with a binary mask; a label map takes precedence). ISOSURFACE_BLEND
   * crosses no iso-value across a hidden sample.
   */
  void SetMaskInput(vtkImageData* mask);
  vtkGetObjectMacro(MaskInput, vtkImageData);
  enum MaskTypes
  {
    BinaryMaskType = 0,
    LabelMapMaskType = 1
  };
  vtkSetClampMacro(MaskType, int, BinaryMaskType, LabelMapMaskType);
  vtkGetMacro(MaskType, int);
  void SetMaskTypeToBinary() { this->SetMaskType(BinaryMaskType); }
  void SetMaskTypeToLabelMap() { this->SetMaskType(LabelMapMaskType); }
  vtkSetClampMacro(MaskBlendFactor, float, 0.0f, 1.0f);
  vtkGetMacro(MaskBlendFactor, float);
  ///@}

  ///@{
  /** Last frame: rays that met the volume, samples interpolated, and samples leaped. */
  vtkGetMacro(LastNumberOfRays, vtkTypeInt64);
  vtkGetMacro(LastNumberOfSamples, vtkTypeInt64);
  vtkGetMacro(LastSamplesLeapedByOctree, vtkTypeInt64);
  vtkGetMacro(LastSamplesLeapedByDistanceMap, vtkTypeInt64);
  vtkGetMacro(LastSamplesLeapedByCellTable, vtkTypeInt64);
  vtkGetMacro(LastSamplesInTransparentCells, vtkTypeInt64);
  vtkGetMacro(LastNumberOfTerminatedRays, vtkTypeInt64);
  /** Last frame: leaps taken over octree nodes / by the distance map (each skips >= 1 sample). */
  vtkGetMacro(LastNumberOfOctreeLeaps, vtkTypeInt64);
  vtkGetMacro(LastNumberOfDistanceMapLeaps, vtkTypeInt64);
  /** Last frame: pixels left empty without a ray, their rays unable to meet a non-empty cell
   * (the screen footprint of the non-empty cells; composite with distance-map leaping). */
  vtkGetMacro(LastNumberOfCulledPixels, vtkTypeInt64);
  /** Last frame: rays cast sixteen at a time, one per SIMD lane (composite with distance-map
   * leaping on CPUs with AVX-512; the other rays take the one-ray paths, same image). */
  vtkGetMacro(LastNumberOfPacketRays, vtkTypeInt64);
  /** Bytes the acceleration structures (octree, cell table / distance map, gradients) hold. */
  vtkGetMacro(AccelerationBytes, vtkTypeInt64);
  /** Wall-clock seconds: the ray casting alone, the structure rebuild (GetLastRenderTime: the
   * whole Render()). Termination: vtkAccelVolumeMapper (composite rays stop at the threshold). */
  vtkGetMacro(LastCastTime, double);
  vtkGetMacro(LastPrepareTime, double);
  /** Image sample distance and sample distance the last frame used. */
  vtkGetMacro(LastImageSampleDistance, double);
  vtkGetMacro(LastSampleDistance, double);
  ///@}

  /**
   * Renders the volume. Called by vtkVolume; not for direct use.
   */
  void Render(vtkRenderer* renderer, vtkVolume* volume) override;

  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  vtkAccelVolumeRayCastMapper();
  ~vtkAccelVolumeRayCastMapper() override;

  vtkTypeBool LockSampleDistanceToInputSpacing = 0;
  vtkTypeBool IntermixIntersectingGeometry = 1;
  int LeapMode = LEAP_DISTANCE_MAP;
  vtkTypeBool CellLeaping = 0;
  int OctreeLeafSize = 4;
  double SampleDistance = 1.0;
  double InteractiveSampleDistance = 2.0;
  double ImageSampleDistance = 1.0;
  double MinimumImageSampleDistance = 1.0;
  double MaximumImageSampleDistance = 10.0;
  vtkTypeBool AutoAdjustSampleDistances = 1;
  int NumberOfThreads = 0;
  double AdditiveUnitDistance = 0.0;
  vtkImageData* MaskInput = nullptr;
  int MaskType = LabelMapMaskType;
  float MaskBlendFactor = 1.0f;

  vtkTypeInt64 LastNumberOfRays = 0;
  vtkTypeInt64 LastNumberOfSamples = 0;
  vtkTypeInt64 LastSamplesLeapedByOctree = 0;
  vtkTypeInt64 LastSamplesLeapedByDistanceMap = 0;
  vtkTypeInt64 LastSamplesLeapedByCellTable = 0;
  vtkTypeInt64 LastSamplesInTransparentCells = 0;
  vtkTypeInt64 LastNumberOfTerminatedRays = 0;
  vtkTypeInt64 LastNumberOfOctreeLeaps = 0;
  vtkTypeInt64 LastNumberOfDistanceMapLeaps = 0;
  vtkTypeInt64 LastNumberOfCulledPixels = 0;
  vtkTypeInt64 AccelerationBytes = 0;
  double LastCastTime = 0.0;
  double LastPrepareTime = 0.0;
  double LastImageSampleDistance = 1.0;
  double LastSampleDistance = 1.0;
  vtkTypeInt64 LastNumberOfPacketRays = 0;

private:
  vtkAccelVolumeRayCastMapper(const vtkAccelVolumeRayCastMapper&) = delete;
  void operator=(const vtkAccelVolumeRayCastMapper&) = delete;

  class vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
};

#endif
