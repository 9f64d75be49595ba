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
 * Why (measured in docs/benchmarks-summary.md): on software GL the slice mapper's fragment work
 * runs on the same CPU cores as everything else, and the CPU paths are faster there: the ray
 * caster with distance-map leaping for shaded perspective composite, shear-warp faster still
 * for interactive frames. Shear-warp is therefore the interactive CPU path, but it pre-classifies voxels,
 * resamples bilinearly with one sample per slice and warps the image, ignores cropping,
 * clipping planes and scene geometry, and cannot do perspective, raysum or average; the ray
 * caster is exact with every feature, so it renders still frames and everything shear-warp
 * cannot. With a hardware GPU the slice mapper has every feature and is the fastest.
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
#include "vtkRenderingAccelVolumeModule.h" // For export macro
#include "vtkAccelVolumeMapper.h"

#include <string> // For std::string

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

  enum RenderModes
  {
    UNDEFINED_RENDER = -1, // GetLastRenderMode before any render, or when none could run
    DEFAULT_RENDER = 0,    // automatic choice
    SLICE_RENDER = 1,      // vtkAccelVolumeSliceMapper
    RAYCAST_RENDER = 2,    // vtkAccelVolumeRayCastMapper
    SHEARWARP_RENDER = 3   // vtkAccelVolumeShearWarpMapper
  };

  ///@{
  /** The mapper to use (default DEFAULT_RENDER: automatic, see the class documentation). */
  vtkSetClampMacro(RequestedRenderMode, int, DEFAULT_RENDER, SHEARWARP_RENDER);
  vtkGetMacro(RequestedRenderMode, int);
  void SetRequestedRenderModeToDefault() { this->SetRequestedRenderMode(DEFAULT_RENDER); }
  void SetRequestedRenderModeToSlice() { this->SetRequestedRenderMode(SLICE_RENDER); }
  void SetRequestedRenderModeToRayCast() { this->SetRequestedRenderMode(RAYCAST_RENDER); }
  void SetRequestedRenderModeToShearWarp() { this->SetRequestedRenderMode(SHEARWARP_RENDER); }
  ///@}

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
  /** "Default", "Slice", "RayCast", "ShearWarp" or "Undefined". */
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

  int RequestedRenderMode = DEFAULT_RENDER;
  double InteractiveUpdateRate = 1.0;
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
