/**
 * @class   vtkAccelVolumeSmartMapper
 * @brief   Volume mapper that renders with the best of AccelVolume's three mappers for the
 *          context (like VTK's vtkSmartVolumeMapper) and says which it chose and why.
 *
 * It owns one vtkAccelVolumeSliceMapper (OpenGL), one vtkAccelVolumeRayCastMapper (CPU) and
 * one vtkAccelVolumeShearWarpMapper (CPU, parallel projection) and, on every Render, forwards
 * its input connection and vtkVolumeMapper settings (blend mode, cropping flag, region planes
 * and flags, clipping planes, AverageIPScalarRange, scalar mode and array selection) to the
 * one it picks, then lets that one render (the input connection only for that render).
 * Mapper-specific settings (sample distances, leaping, threads, ...) are reached through
 * GetSliceMapper(), GetRayCastMapper() and GetShearWarpMapper(); their defaults are the
 * mappers' own.
 *
 * The choice (RequestedRenderMode DEFAULT_RENDER):
 *
 * | context                                                               | mapper     |
 * |-----------------------------------------------------------------------|------------|
 * | OpenGL window with 3D textures, every axis <= GL_MAX_3D_TEXTURE_SIZE, |            |
 * | hardware GL (GL_RENDERER not llvmpipe / softpipe / swrast)            | slice      |
 * | otherwise, if parallel projection, composite / MIP / MinIP, no        |            |
 * | cropping, no clipping planes and an interactive frame                 |            |
 * | (allocated render time < 1 / InteractiveUpdateRate seconds)           | shear-warp |
 * | otherwise (perspective, raysum / average, cropping, clipping,         |            |
 * | still frames)                                                         | ray cast   |
 *
 * Why (the matrix of Benchmarks/mapper_choice.py, docs/benchmarks/mapper-choice.md: the three
 * mappers on the same volumes, transfer functions, views and threads): on software GL the slice
 * mapper's work runs on the same CPU cores as everything else, and the CPU mappers were faster
 * in every measured case: shear-warp on every parallel view, the ray caster (distance-map
 * leaping) on every perspective one. Shear-warp is therefore the interactive CPU path, but it
 * pre-classifies voxels,
 * resamples bilinearly with one sample per slice and warps the image, ignores cropping,
 * clipping planes and scene geometry, and cannot do perspective, raysum or average; the ray
 * caster is exact with every feature, so it renders still frames and everything shear-warp
 * cannot. With a hardware GPU the slice mapper has every feature and was the fastest where
 * measured (an NVIDIA H200, rasterised slices, against the ray caster on 16 threads); its compute
 * slices run on every shader core of such a GPU (the matrix's GPU column is measured by
 * scripts/bench-device.sh when a GPU is at hand).
 * (Opaque geometry in the scene is not detected: a scene that needs it to hide the volume in
 * interactive parallel frames should request RAYCAST_RENDER.)
 *
 * A requested mode (SLICE_RENDER, RAYCAST_RENDER, SHEARWARP_RENDER) is honoured unless that
 * mapper cannot render the scene: shear-warp with a perspective camera, raysum / average
 * blending, cropping or clipping planes; slice without an OpenGL window with 3D textures large
 * enough for the volume. Then the automatic choice among the others is used, a warning is
 * issued (once per distinct reason) and the reason says so.
 *
 * GetLastRenderMode() and GetLastChoiceReason() describe the last Render. Errors and warnings
 * of the mapper used are re-issued by this mapper (vtkErrorMacro / vtkWarningMacro), prefixed
 * with its name. Each Render fires StartEvent, the chosen mapper's ProgressEvent values as this
 * mapper's own (ending at 1) and EndEvent, all on the calling thread.
 */
#ifndef vtkAccelVolumeSmartMapper_h
#define vtkAccelVolumeSmartMapper_h

#include "vtkAccelVolumeRayCastMapper.h"   // For vtkNew member
#include "vtkAccelVolumeShearWarpMapper.h" // For vtkNew member
#include "vtkAccelVolumeSliceMapper.h"     // For vtkNew member
#include "vtkCallbackCommand.h"            // For vtkNew member
#include "vtkNew.h"                        // For vtkNew
#include "vtkSmartPointer.h"                // For vtkSmartPointer
#include "vtkRenderingAccelVolumeModule.h" // For export macro
#include "vtkAccelVolumeMapper.h"

#include <string> // For std::string

class vtkDataSet;
class vtkObject;
class vtkRenderer;
class vtkVolume;
class vtkWindow;

class VTKRENDERINGACCELVOLUME_EXPORT vtkAccelVolumeSmartMapper : public vtkAccelVolumeMapper
{
public:
  static vtkAccelVolumeSmartMapper* New();
  vtkTypeMacro(vtkAccelVolumeSmartMapper, vtkAccelVolumeMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Render modes, with vtkSmartVolumeMapper's values: DefaultRenderMode (0), RayCastRenderMode
   * (1: our ray caster), GPURenderMode (2: our slice mapper), OSPRayRenderMode (3: not
   * available, warns once and chooses automatically), UndefinedRenderMode (4),
   * InvalidRenderMode (5); then SHEARWARP_RENDER (6), which VTK lacks.
   */
  enum RenderModes
  {
    DEFAULT_RENDER = 0,   // automatic choice
    RAYCAST_RENDER = 1,   // vtkAccelVolumeRayCastMapper
    SLICE_RENDER = 2,     // vtkAccelVolumeSliceMapper
    OSPRAY_RENDER = 3,    // VTK's OSPRay mode: not available here
    UNDEFINED_RENDER = 4, // GetLastRenderMode before any render, or when none could run
    INVALID_RENDER = 5,
    SHEARWARP_RENDER = 6, // vtkAccelVolumeShearWarpMapper
    DefaultRenderMode = DEFAULT_RENDER,
    RayCastRenderMode = RAYCAST_RENDER,
    GPURenderMode = SLICE_RENDER,
    OSPRayRenderMode = OSPRAY_RENDER,
    UndefinedRenderMode = UNDEFINED_RENDER,
    InvalidRenderMode = INVALID_RENDER
  };

  ///@{
  /**
   * The mapper to use (default DEFAULT_RENDER: automatic, see the class documentation). Values
   * other than those of RenderModes (and INVALID_RENDER, UNDEFINED_RENDER) are an error.
   */
  void SetRequestedRenderMode(int mode);
  vtkGetMacro(RequestedRenderMode, int);
  void SetRequestedRenderModeToDefault() { this->SetRequestedRenderMode(DEFAULT_RENDER); }
  void SetRequestedRenderModeToSlice() { this->SetRequestedRenderMode(SLICE_RENDER); }
  void SetRequestedRenderModeToRayCast() { this->SetRequestedRenderMode(RAYCAST_RENDER); }
  void SetRequestedRenderModeToShearWarp() { this->SetRequestedRenderMode(SHEARWARP_RENDER); }
  /** vtkSmartVolumeMapper's names: GPU is the slice mapper. */
  void SetRequestedRenderModeToGPU() { this->SetRequestedRenderMode(SLICE_RENDER); }
  void SetRequestedRenderModeToOSPRay() { this->SetRequestedRenderMode(OSPRAY_RENDER); }
  ///@}

  ///@{
  /**
   * As vtkSmartVolumeMapper: the sample distance forwarded to the slice and ray cast mappers
   * (default -1: locked to the input spacing), AutoAdjustSampleDistances (default on) for the
   * owned mappers when InteractiveAdjustSampleDistances is off; with it on (the default) they
   * auto-adjust exactly in interactive frames (desired update rate >= InteractiveUpdateRate).
   * An explicit SampleDistance is used as given (VTK's still frames replace it by half the mean
   * spacing). Differs on purpose: while all three keep their defaults, the owned mappers keep
   * their own sample distances (one voxel spacing, auto-adjusted: the picture VTK's half-spacing
   * gives, within the opacity correction, at half the samples).
   */
  vtkSetMacro(SampleDistance, float);
  vtkGetMacro(SampleDistance, float);
  vtkSetClampMacro(AutoAdjustSampleDistances, vtkTypeBool, 0, 1);
  vtkGetMacro(AutoAdjustSampleDistances, vtkTypeBool);
  vtkBooleanMacro(AutoAdjustSampleDistances, vtkTypeBool);
  vtkSetClampMacro(InteractiveAdjustSampleDistances, vtkTypeBool, 0, 1);
  vtkGetMacro(InteractiveAdjustSampleDistances, vtkTypeBool);
  vtkBooleanMacro(InteractiveAdjustSampleDistances, vtkTypeBool);
  ///@}

  /** As vtkSmartVolumeMapper::VectorModeType. */
  enum VectorModeType
  {
    DISABLED = -1,
    MAGNITUDE = 0,
    COMPONENT = 1
  };
  ///@{
  /**
   * As vtkSmartVolumeMapper: how multi-component scalars are reduced to one (default
   * DISABLED). MAGNITUDE renders the Euclidean norm of the components (as a float array),
   * COMPONENT renders VectorComponent (0..3) with the property's first transfer functions.
   */
  void SetVectorMode(int mode);
  vtkGetMacro(VectorMode, int);
  vtkSetClampMacro(VectorComponent, int, 0, 3);
  vtkGetMacro(VectorComponent, int);
  ///@}

  ///@{
  /**
   * As vtkSmartVolumeMapper: the GPU memory limit (forwarded to the slice mapper's
   * SetMaxMemoryInBytes / SetMaxMemoryFraction; defaults 0 = no limit, and 0.75) and the
   * interpolation of VTK's low-resolution resampling, which this mapper never does (stored
   * only).
   */
  vtkSetMacro(MaxMemoryInBytes, vtkIdType);
  vtkGetMacro(MaxMemoryInBytes, vtkIdType);
  vtkSetClampMacro(MaxMemoryFraction, float, 0.1f, 1.0f);
  vtkGetMacro(MaxMemoryFraction, float);
  vtkSetClampMacro(InterpolationMode, int, 0, 2);
  vtkGetMacro(InterpolationMode, int);
  void SetInterpolationModeToNearestNeighbor() { this->SetInterpolationMode(0); }
  void SetInterpolationModeToLinear() { this->SetInterpolationMode(1); }
  void SetInterpolationModeToCubic() { this->SetInterpolationMode(2); }
  ///@}

  /** vtkSmartVolumeMapper's name for GetLastRenderMode. */
  int GetLastUsedRenderMode() { return this->LastRenderMode; }

  ///@{
  /**
   * Frames per second above which a frame counts as interactive (default 1.0, > 0): a frame
   * whose allocated render time is below 1 / InteractiveUpdateRate seconds may use the
   * shear-warp mapper on software GL.
   */
  vtkSetClampMacro(InteractiveUpdateRate, double, 1.0e-6, VTK_DOUBLE_MAX);
  vtkGetMacro(InteractiveUpdateRate, double);
  ///@}

  /** The mode the last Render used (UNDEFINED_RENDER before any). */
  vtkGetMacro(LastRenderMode, int);
  // GetLastRenderTime (vtkAccelVolumeMapper): the choice and the chosen mapper's render. That
  // mapper's own time and acceleration counters: GetLastRenderMode() says which of
  // GetSliceMapper(), GetRayCastMapper() or GetShearWarpMapper() to ask.
  /** Why the last Render chose its mode (never empty). */
  const char* GetLastChoiceReason() const { return this->LastChoiceReason.c_str(); }
  /** "Default", "Slice", "RayCast", "ShearWarp", "OSPRay" or "Undefined". */
  static const char* GetRenderModeAsString(int mode);

  ///@{
  /** The owned mappers, for their own settings (the forwarded ones are overwritten). */
  vtkAccelVolumeSliceMapper* GetSliceMapper() { return this->SliceMapper; }
  vtkAccelVolumeRayCastMapper* GetRayCastMapper() { return this->RayCastMapper; }
  vtkAccelVolumeShearWarpMapper* GetShearWarpMapper() { return this->ShearWarpMapper; }
  ///@}

  void Render(vtkRenderer* renderer, vtkVolume* volume) override;
  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  vtkAccelVolumeSmartMapper();
  ~vtkAccelVolumeSmartMapper() override;

  // Picks the mode for this frame and fills LastChoiceReason.
  int ChooseMode(vtkRenderer* renderer, vtkVolume* volume, const int dims[3]);
  // Copies the input connection, the vtkVolumeMapper settings and the termination settings
  // (vtkAccelVolumeMapper) to the mapper.
  void Forward(vtkAccelVolumeMapper* mapper);
  // Re-issues an owned mapper's error or warning on this mapper.
  static void Relay(vtkObject* caller, unsigned long event, void* client, void* data);

  // The input the chosen mapper renders: the smart mapper's, or its VectorMode reduction.
  void ConnectInput(vtkAccelVolumeMapper* mapper);
  // Forwards the sample-distance settings as vtkSmartVolumeMapper does.
  void ForwardSampleDistances(vtkRenderer* renderer, vtkAccelVolumeMapper* mapper);

  int RequestedRenderMode = DEFAULT_RENDER;
  double InteractiveUpdateRate = 1.0;
  float SampleDistance = -1.0f;
  vtkTypeBool AutoAdjustSampleDistances = 1;
  vtkTypeBool InteractiveAdjustSampleDistances = 1;
  int VectorMode = DISABLED;
  int VectorComponent = 0;
  vtkIdType MaxMemoryInBytes = 0;
  float MaxMemoryFraction = 0.75f;
  int InterpolationMode = 2;
  vtkSmartPointer<vtkDataSet> Reduced; // VectorMode's one-component copy of the input
  vtkMTimeType ReducedTime = 0;
  int ReducedMode = DISABLED;
  int ReducedComponent = 0;
  int LastRenderMode = UNDEFINED_RENDER;
  std::string LastChoiceReason = "not rendered yet";
  std::string LastWarning;

  vtkNew<vtkAccelVolumeSliceMapper> SliceMapper;
  vtkNew<vtkAccelVolumeRayCastMapper> RayCastMapper;
  vtkNew<vtkAccelVolumeShearWarpMapper> ShearWarpMapper;
  vtkNew<vtkCallbackCommand> Relayer;

private:
  vtkAccelVolumeSmartMapper(const vtkAccelVolumeSmartMapper&) = delete;
  void operator=(const vtkAccelVolumeSmartMapper&) = delete;
};

#endif
