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
 * - ADDITIVE_BLEND (raysum): (1/unit) * the integral of opacity(s) * s along the ray, s
 *   normalised to the data range, shown grey and clamped to [0, 1], unit = the property's
 *   ScalarOpacityUnitDistance as VTK (or AdditiveUnitDistance). Samples are weighted by the ray
 *   length they stand for, so the result does not depend on the slice count.
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
 * Compute slices (SliceCompositing, default AUTO): where the frame allows it (composite, MIP,
 * MinIP; one brick, one cropping region, one component, no mask), the same slices' samples are
 * composited per pixel in one compute pass instead of rasterised and blended, each ray stopping
 * at the termination threshold and leaping over transparent octree leaves; the image is the
 * rasterised one up to rounding and the termination bound.
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
 * Drop-in for vtkGPUVolumeRayCastMapper (docs/drop-in.md): its API members, VTK's light model
 * and gradient units, masks (binary and label map), ghost arrays and blanking, RenderToImage,
 * picking, multisampled windows, ISOSURFACE_BLEND (the property's iso-values, drawn by the
 * composite passes), SLICE_BLEND (the property's vtkPlane, drawn as a cut face), the depth pass
 * (UseDepthPass) and 2-4 component scalars (independent with per-component functions, weights
 * and gradient opacities, or dependent luminance-alpha / RGBA; composite, MIP, MinIP, raysum and
 * average as VTK's GPU mapper combines them, iso-surfaces of the independent component of the
 * largest weight or of dependent component 0, slice planes classified as composite samples
 * without opacity correction; one brick; octree skipping by the opacity component of dependent
 * ones and by every weighted component of independent ones). Where VTK 9.1's
 * shader slips we differ on purpose: independent MinIP keeps each component's minimum (VTK's
 * its maximum, with alpha 0) and luminance-alpha MIP / MinIP the sample whose alpha is extreme
 * (VTK's the ray's first sample).
 *
 * Limits: scalars of any integer or floating type but bit (int, unsigned int, 64-bit integers,
 * float and double are sampled as 32-bit floats normalised to the data range; NaN samples
 * count as the minimum). Boundary re-rendering applies to the projection modes, not to
 * composite. Bricked volumes take gradients by central differences (no precomputed gradient
 * texture) and plain slices (SlabSamples is ignored). With depth peeling of volumes the volume
 * is drawn once, before the translucent layers (VTK interleaves them). Multi-component scalars
 * past GL_MAX_3D_TEXTURE_SIZE are not bricked (a clear error).
 */

#ifndef vtkAccelVolumeSliceMapper_h
#define vtkAccelVolumeSliceMapper_h

#include "vtkRenderingAccelVolumeModule.h" // For export macro
#include "vtkAccelVolumeMapper.h"

#include <memory> // For std::unique_ptr
#include <string> // For std::string

class vtkContourValues;
class vtkDataArray;
class vtkImageData;
class vtkOpenGLRenderWindow;
class vtkRenderWindow;
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
   * MIP, MinIP and composite: slice depths each proxy-slice fragment samples along its ray
   * (default 1, range 1..64). 1 is classic slicing, one polygon per sample plane. Larger values
   * draw one proxy polygon per group of planes, covering the group's projection, and take the
   * same samples in a loop (composite: composited front to back in registers, one blend per
   * slab; early termination every EarlyRayTerminationInterval planes, in whole slabs), which
   * cuts rasterisation and blending work at the price of a ray-box test per fragment; the
   * samples stay those of plain slicing, so the image changes only by rounding. Composite slabs
   * need one cropping region and single-component scalars without a mask, depth pass or depth
   * image (plain slices otherwise); they are drawn from CPU polygons, not generated on the GPU
   * (SetGPUSliceGeneration). Bricked volumes take plain slices. The benchmark report has the
   * figures per renderer.
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

  ///@{
  /** vtkGPUVolumeRayCastMapper's name for Jittering (both names set the same flag). */
  void SetUseJittering(vtkTypeBool use) { this->SetJittering(use); }
  vtkTypeBool GetUseJittering() { return this->GetJittering(); }
  void UseJitteringOn() { this->SetJittering(1); }
  void UseJitteringOff() { this->SetJittering(0); }
  ///@}

  ///@{
  /**
   * As vtkGPUVolumeRayCastMapper: with AutoAdjustSampleDistances off, sample at
   * vtkVolumeMapper::SpacingAdjustedSampleDistance (half the mean voxel spacing, less for small
   * volumes) instead of SampleDistance (default off).
   */
  vtkSetClampMacro(LockSampleDistanceToInputSpacing, vtkTypeBool, 0, 1);
  vtkGetMacro(LockSampleDistanceToInputSpacing, vtkTypeBool);
  vtkBooleanMacro(LockSampleDistanceToInputSpacing, vtkTypeBool);
  ///@}

  ///@{
  /**
   * As vtkGPUVolumeRayCastMapper: pixels per ray along each image axis (default 1, clamped to
   * [0.1, 100]; values below 1 render at full resolution). Above 1 the slices are drawn into a
   * target that many times smaller and resolved to colours there, then magnified bilinearly
   * over the scene. Minimum / MaximumImageSampleDistance bound it (defaults 1 and 10); they are
   * kept for VTK's API (interactive frames adapt the slice spacing, not the image size).
   */
  vtkSetClampMacro(ImageSampleDistance, float, 0.1f, 100.0f);
  vtkGetMacro(ImageSampleDistance, float);
  vtkSetClampMacro(MinimumImageSampleDistance, float, 0.1f, 100.0f);
  vtkGetMacro(MinimumImageSampleDistance, float);
  vtkSetClampMacro(MaximumImageSampleDistance, float, 0.1f, 100.0f);
  vtkGetMacro(MaximumImageSampleDistance, float);
  ///@}

  ///@{
  /**
   * As vtkGPUVolumeRayCastMapper: GPU memory for the volume, MaxMemoryInBytes *
   * MaxMemoryFraction (defaults 0 = no limit, and 0.75). Setting either sets GPUMemoryBudget to
   * their product; GPUMemoryBudget is the one limit the mapper applies.
   */
  void SetMaxMemoryInBytes(vtkIdType bytes);
  vtkGetMacro(MaxMemoryInBytes, vtkIdType);
  void SetMaxMemoryFraction(float fraction);
  vtkGetMacro(MaxMemoryFraction, float);
  ///@}

  /**
   * As vtkGPUVolumeRayCastMapper: split the volume into x * y * z blocks rendered one after
   * another, mapped onto this mapper's bricking (MaximumBrickSize per axis becomes the block
   * size plus the shared voxel). 1 1 1 (the default) turns it off.
   */
  void SetPartitions(unsigned short x, unsigned short y, unsigned short z);
  const unsigned short* GetPartitions() { return this->Partitions; }

  ///@{
  /** As vtkGPUVolumeRayCastMapper (default true): StartEvent / ProgressEvent / EndEvent. */
  vtkSetMacro(ReportProgress, bool);
  vtkGetMacro(ReportProgress, bool);
  ///@}

  ///@{
  /**
   * As vtkGPUVolumeRayCastMapper: a mask image with the volume's dimensions, its type
   * (BinaryMaskType, or LabelMapMaskType: the default) and the label blend factor (default 1),
   * each sampled at the voxel nearest to a sample. Binary (nonzero = inside): samples outside
   * are skipped in every blend mode; exact with the accelerations (a mask only removes
   * samples). Label map (composite): a voxel with label L > 0 takes the colour and opacity of
   * the property's SetLabelColor(L) / SetLabelScalarOpacity(L) (the property's own functions
   * where a label has none), mixed with the unlabelled classification by MaskBlendFactor
   * (0: the mask has no effect); octree and per-fragment skipping are off then, since labels
   * may make transparent voxels visible.
   */
  void SetMaskInput(vtkImageData* mask);
  vtkGetObjectMacro(MaskInput, vtkImageData);
  enum MaskTypes
  {
    BinaryMaskType = 0,
    LabelMapMaskType = 1
  };
  vtkSetMacro(MaskType, int);
  vtkGetMacro(MaskType, int);
  void SetMaskTypeToBinary() { this->SetMaskType(BinaryMaskType); }
  void SetMaskTypeToLabelMap() { this->SetMaskType(LabelMapMaskType); }
  vtkSetClampMacro(MaskBlendFactor, float, 0.0f, 1.0f);
  vtkGetMacro(MaskBlendFactor, float);
  ///@}

  ///@{
  /**
   * As vtkGPUVolumeRayCastMapper's render-to-image mode (default off): the volume is not
   * drawn into the scene; GetColorImage gives the last frame's premultiplied RGBA (unsigned
   * char, viewport size) and GetDepthImage the window depth of the nearest contributing sample
   * per pixel (1 where none), as float or scaled to DepthImageScalarType (unsigned char /
   * short). Opaque geometry already drawn still stops the rays. With ClampDepthToBackface,
   * pixels whose ray crosses the volume but meets no contributing sample take the depth where
   * the ray enters the volume box (and clip planes): what vtkGPUVolumeRayCastMapper 9.1 writes
   * under that name; the image sample distance is 1 in this mode.
   */
  vtkSetMacro(RenderToImage, vtkTypeBool);
  vtkGetMacro(RenderToImage, vtkTypeBool);
  vtkBooleanMacro(RenderToImage, vtkTypeBool);
  vtkSetMacro(DepthImageScalarType, int);
  vtkGetMacro(DepthImageScalarType, int);
  void SetDepthImageScalarTypeToUnsignedChar() { this->SetDepthImageScalarType(VTK_UNSIGNED_CHAR); }
  void SetDepthImageScalarTypeToUnsignedShort()
  {
    this->SetDepthImageScalarType(VTK_UNSIGNED_SHORT);
  }
  void SetDepthImageScalarTypeToFloat() { this->SetDepthImageScalarType(VTK_FLOAT); }
  vtkSetMacro(ClampDepthToBackface, vtkTypeBool);
  vtkGetMacro(ClampDepthToBackface, vtkTypeBool);
  vtkBooleanMacro(ClampDepthToBackface, vtkTypeBool);
  void GetDepthImage(vtkImageData* image);
  void GetColorImage(vtkImageData* image);
  ///@}

  ///@{
  /**
   * vtkGPUVolumeRayCastMapper's depth pass (default off; composite blending; multi-component
   * scalars: the contour of component 0, as vtkContourFilter's): rays start where they first cross one of the DepthPassContourValues and pixels
   * whose ray crosses none draw nothing, as VTK's. VTK renders the contour's polygons
   * (vtkContourFilter) for that depth; here the crossing is found along the ray between
   * successive slices (linear between the two samples), so the start differs from VTK's by
   * less than a voxel where marching cubes and trilinear interpolation disagree. Octree
   * skipping stays on when every contour value has a non-zero opacity (else the contour may
   * lie in transparent space and it is off). With no contour value it warns once and the
   * volume is drawn without it.
   */
  vtkSetClampMacro(UseDepthPass, vtkTypeBool, 0, 1);
  vtkGetMacro(UseDepthPass, vtkTypeBool);
  vtkBooleanMacro(UseDepthPass, vtkTypeBool);
  vtkContourValues* GetDepthPassContourValues();
  ///@}

  /** Transfer-function ranges, as vtkGPUVolumeRayCastMapper::TFRangeType. */
  enum TFRangeType
  {
    SCALAR = 0, ///< the tables span the data range (the only one this mapper applies)
    NATIVE = 1  ///< the functions' own range: warns once, the data range is used
  };
  ///@{
  /** As vtkGPUVolumeRayCastMapper (default SCALAR). */
  vtkSetMacro(ColorRangeType, int);
  vtkGetMacro(ColorRangeType, int);
  vtkSetMacro(ScalarOpacityRangeType, int);
  vtkGetMacro(ScalarOpacityRangeType, int);
  vtkSetMacro(GradientOpacityRangeType, int);
  vtkGetMacro(GradientOpacityRangeType, int);
  ///@}

  ///@{
  /**
   * As vtkGPUVolumeRayCastMapper: the array for the 2D transfer function's y axis (default
   * none: the gradient magnitude). Another array warns once and the gradient magnitude is used.
   */
  vtkSetStringMacro(Transfer2DYAxisArray);
  vtkGetStringMacro(Transfer2DYAxisArray);
  ///@}

  /** As vtkGPUVolumeRayCastMapper: the input is never resampled, so 1 1 1. */
  void GetReductionRatio(double ratio[3]);

  int IsRenderSupported(vtkRenderWindow* window, vtkVolumeProperty* property) override;

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
  /**
   * Which vtkAccelVolumeMinMaxOctree builder builds the skipping octree when the scalars change
   * (default BUILDER_CPU, all threads). BUILDER_GPU builds it with compute shaders from the
   * mapper's resident volume texture (one brick, one component: no second upload; otherwise
   * the builder uploads the scalars itself); compute slices then classify it on the GPU too,
   * straight into the skipping textures (nothing read back but the count of transparent
   * leaves), while rasterised slices read the levels back for the CPU classification and the
   * slice culling. Without compute shaders it falls back to the CPU builder (the same octree).
   */
  vtkSetClampMacro(OctreeBuilder, int, 1, 2);
  vtkGetMacro(OctreeBuilder, int);
  /** The builder of the skipping octree the last frame used (-1: no octree). */
  vtkGetMacro(LastOctreeBuilder, int);
  /** Fraction of octree leaves found transparent in the last frame (-1 when unused). */
  vtkGetMacro(LastTransparentLeafFraction, double);
  /**
   * Composite: fraction of the slice area kept by the octree culling in the last frame (with
   * slices generated on the GPU it is computed when asked, from the last frame's view).
   */
  double GetLastProxyAreaFraction();
  ///@}

  ///@{
  /**
   * Composite: generate the proxy slices in the vertex stage (default on): one instanced draw
   * per batch of slices, the CPU sending only each slice's depth and its octree-culled box, so
   * a frame's CPU cost does not grow with the slice polygons. Used for an unbricked volume
   * without cropping or clip planes; otherwise (and when off) the CPU clips the slice polygons.
   * Both sample the same points (the fragment stage places samples from the slice depth).
   */
  vtkSetMacro(GPUSliceGeneration, vtkTypeBool);
  vtkGetMacro(GPUSliceGeneration, vtkTypeBool);
  vtkBooleanMacro(GPUSliceGeneration, vtkTypeBool);
  ///@}

  ///@{
  /**
   * Accumulate into a half-float (16-bit) target instead of 32-bit float (default off): half
   * the bytes read and written by every slice's blend, which is what framebuffer blending
   * costs on GPUs with few blending units, at the precision of an 11-bit mantissa. Composite,
   * MIP and MinIP only: raysum and average sums grow past 1 and keep the 32-bit target. The
   * difference from the 32-bit target is tested (TestAccelVolumeHalfFloatTarget: at most one
   * level of 255 on its scenes; real semi-transparent volumes reach about 3 levels, see
   * docs/benchmarks/slice-gpu.md); off by default until a GPU measurement says it pays.
   */
  vtkSetMacro(HalfFloatTarget, vtkTypeBool);
  vtkGetMacro(HalfFloatTarget, vtkTypeBool);
  vtkBooleanMacro(HalfFloatTarget, vtkTypeBool);
  /** Whether the last frame's slices were generated on the GPU. */
  vtkGetMacro(LastSlicesGenerated, bool);
  ///@}

  enum SliceCompositingModes
  {
    SLICE_COMPOSITING_AUTO = 0,   ///< compute where the frame allows it and the context has it
    SLICE_COMPOSITING_RASTER = 1, ///< proxy slices rasterised and blended into the target
    SLICE_COMPOSITING_COMPUTE = 2 ///< compute slices where the frame allows it
  };

  ///@{
  /**
   * How the slices' samples are composited (default SLICE_COMPOSITING_AUTO). RASTER draws the
   * proxy slices (or slabs) and blends each into the float target. COMPUTE takes the same
   * samples (the same slice planes and sample points, the same classification and shading) in
   * one compute pass, one invocation per pixel compositing front to back in registers: no
   * rasterisation and no framebuffer blending (on compute-class GPUs such as NVIDIA's H100 and
   * H200 only a few units rasterise and blend, while compute shaders use the whole chip), each
   * ray stopping at EarlyRayTerminationThreshold and leaping over transparent octree leaves.
   * Compute slices need OpenGL 4.3 and serve composite (without iso-surfaces, slice planes or
   * the depth pass), MIP and MinIP of single-component scalars in one brick, without a mask or
   * ghost array, with at most one cropping region and no RenderToImage; other frames are
   * rasterised. The image equals the rasterised one up to rounding (composite without
   * termination), or within the termination bound (the rays stop exactly at the threshold
   * instead of at the next mark pass). With PrecomputeGradients, compute rays read the scalar
   * from the gradient texture's 16-bit copy (one fetch per sample instead of two): exact for
   * 8-bit data, within 1/131070 of the scalar range otherwise. AUTO takes compute slices where
   * they apply.
   * GetLastSliceCompositing says which ran.
   */
  vtkSetClampMacro(SliceCompositing, int, SLICE_COMPOSITING_AUTO, SLICE_COMPOSITING_COMPUTE);
  vtkGetMacro(SliceCompositing, int);
  void SetSliceCompositingToAuto() { this->SetSliceCompositing(SLICE_COMPOSITING_AUTO); }
  void SetSliceCompositingToRaster() { this->SetSliceCompositing(SLICE_COMPOSITING_RASTER); }
  void SetSliceCompositingToCompute() { this->SetSliceCompositing(SLICE_COMPOSITING_COMPUTE); }
  /** SLICE_COMPOSITING_RASTER or _COMPUTE: how the last frame was composited. */
  vtkGetMacro(LastSliceCompositing, int);
  ///@}

  ///@{
  /**
   * Count the volume samples each frame takes (compute slices only; default off). Counting
   * reads a counter back, which waits for the GPU: for benchmarks, not for interaction.
   * GetLastNumberOfSamples: the last frame's count, -1 when not counted.
   */
  vtkSetMacro(CountSamples, bool);
  vtkGetMacro(CountSamples, bool);
  vtkGetMacro(LastNumberOfSamples, vtkIdType);
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
   * ADDITIVE_BLEND (raysum): the ray-length integral of opacity(s) * s divided by a unit
   * length. 0 (the default): the property's ScalarOpacityUnitDistance, which is what
   * vtkGPUVolumeRayCastMapper's per-sample sum amounts to (it scales each sample's opacity by
   * sample distance / unit distance). > 0: that world length. Samples are weighted by the ray
   * length they stand for, so the result does not depend on the slice spacing; cut faces
   * re-rendered with BoundaryRerendering keep the integral exact for linear data.
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
  /**
   * GetLastRenderTime (vtkAccelVolumeMapper): the CPU time of the last Render(), or the GPU time
   * of the latest frame that GL timer queries have returned (a frame or two back) when that is
   * longer; Render() never waits for the GPU. GetLastGPUTime: that GPU time in seconds, -1
   * until a query has returned or without timer queries.
   */
  vtkGetMacro(LastGPUTime, double);
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
  int OctreeBuilder = 1; // vtkAccelVolumeMinMaxOctree::BUILDER_CPU
  int LastOctreeBuilder = -1;
  double LastTransparentLeafFraction = -1.0;
  double LastProxyAreaFraction = 1.0;
  vtkTypeBool GPUSliceGeneration = 1;
  vtkTypeBool HalfFloatTarget = 0;
  double LastGPUTime = -1.0;
  bool LastSlicesGenerated = false;
  int SliceCompositing = SLICE_COMPOSITING_AUTO;
  int LastSliceCompositing = SLICE_COMPOSITING_RASTER;
  bool CountSamples = false;
  vtkIdType LastNumberOfSamples = -1;
  double AdditiveUnitDistance = 0.0;
  double InteractiveSlowdownLimit = 4.0;

  vtkTypeBool LockSampleDistanceToInputSpacing = 0;
  float ImageSampleDistance = 1.0f;
  float MinimumImageSampleDistance = 1.0f;
  float MaximumImageSampleDistance = 10.0f;
  vtkIdType MaxMemoryInBytes = 0;
  float MaxMemoryFraction = 0.75f;
  unsigned short Partitions[3] = { 1, 1, 1 };
  bool ReportProgress = true;
  vtkImageData* MaskInput = nullptr;
  int MaskType = LabelMapMaskType;
  float MaskBlendFactor = 1.0f;
  vtkTypeBool RenderToImage = 0;
  int DepthImageScalarType = VTK_FLOAT;
  vtkTypeBool ClampDepthToBackface = 0;
  vtkTypeBool UseDepthPass = 0;
  vtkContourValues* DepthPassContourValues = nullptr;
  int ColorRangeType = SCALAR;
  int ScalarOpacityRangeType = SCALAR;
  int GradientOpacityRangeType = SCALAR;
  char* Transfer2DYAxisArray = nullptr;

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

  bool ValidateInput(vtkImageData* input, vtkDataArray* scalars, const std::string& inputError,
    vtkVolume* volume);
  // Warns once for each VTK setting in use that this mapper does not apply.
  void WarnUnappliedSettings();
  // UseDepthPass applies: composite, at least one contour value.
  bool UsesDepthPass() const;
  // A label-map mask that changes composite colours (then no opacity-based skipping applies).
  bool UsesLabelMap() const;

  class vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
};

#endif
