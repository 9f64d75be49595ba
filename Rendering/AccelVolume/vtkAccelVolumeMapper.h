/**
 * @class   vtkAccelVolumeMapper
 * @brief   Abstract base of AccelVolume's volume mappers: what every one of them shares.
 *
 * vtkAccelVolumeSliceMapper, vtkAccelVolumeRayCastMapper, vtkAccelVolumeShearWarpMapper and
 * vtkAccelVolumeSmartMapper derive from it, so code that holds a vtkAccelVolumeMapper can set
 * early ray termination and read the last frame's time whatever the mapper is:
 * - Early ray termination ("termination"): stop a composite ray once its accumulated opacity
 *   reaches EarlyRayTerminationThreshold. The slice mapper closes such pixels every
 *   EarlyRayTerminationInterval slices (Lee 2005), the ray caster stops the ray, shear-warp
 *   jumps over saturated pixels with skip links (Lacroute and Levoy 1994; Kim 1998), and the
 *   smart mapper forwards both settings to the mapper it picks. A terminated pixel differs from
 *   the unterminated one by at most 1 - EarlyRayTerminationThreshold.
 * - LastRenderTime: wall-clock seconds of the last Render().
 * - The input is optional, so a missing input gets one clear error (from GetBounds, once per
 *   change of the mapper) instead of VTK's pipeline error.
 * - Inputs as VTK's mappers take them: vtkImageData or a vtkRectilinearGrid (unevenly spaced
 *   ones with point scalars are resampled trilinearly onto a regular grid),
 *   point or cell scalars (cell scalars are drawn as VTK's GPU mapper draws them: one sample
 *   per cell centre, so the picture ends half a cell inside the point bounds), of any integer
 *   or floating type but bit (unsigned int and 64-bit integers are sampled as 32-bit floats, as
 *   VTK's GPU mapper does).
 * - VTK's shared mapper API: IsRenderSupported, FinalColorWindow / FinalColorLevel.
 */

#ifndef vtkAccelVolumeMapper_h
#define vtkAccelVolumeMapper_h

#include "vtkRenderingAccelVolumeModule.h" // For export macro
#include "vtkTimeStamp.h"                  // For vtkTimeStamp
#include "vtkVolumeMapper.h"

#include <memory> // For std::unique_ptr
#include <set>    // For std::set
#include <string> // For std::string

class vtkAccelVolumeInputAdapter;
class vtkImageData;
class vtkRenderWindow;
class vtkVolumeProperty;

class VTKRENDERINGACCELVOLUME_EXPORT vtkAccelVolumeMapper : public vtkVolumeMapper
{
public:
  vtkAbstractTypeMacro(vtkAccelVolumeMapper, vtkVolumeMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Composite: early ray termination (default on) and its opacity threshold (default 0.99,
   * clamped to [0.5, 1]). What terminating means for each mapper: see the class documentation.
   */
  vtkSetMacro(EarlyRayTermination, vtkTypeBool);
  vtkGetMacro(EarlyRayTermination, vtkTypeBool);
  vtkBooleanMacro(EarlyRayTermination, vtkTypeBool);
  vtkSetClampMacro(EarlyRayTerminationThreshold, double, 0.5, 1.0);
  vtkGetMacro(EarlyRayTerminationThreshold, double);
  ///@}

  /**
   * As VTK's mappers: 1 when this mapper can render into `window` (null: any window) with
   * `property` (null: any), else 0. The CPU mappers need an OpenGL window to show their image;
   * the slice mapper also needs OpenGL 3.2 with 3D textures, which every window VTK 9.1 can
   * open has.
   */
  virtual int IsRenderSupported(vtkRenderWindow* window, vtkVolumeProperty* property);

  ///@{
  /**
   * Window / level applied to the final colours, as VTK's mappers do (defaults 1 and 0.5: no
   * change): colour' = colour / window + (0.5 - level / window) * alpha (premultiplied).
   */
  vtkSetMacro(FinalColorWindow, float);
  vtkGetMacro(FinalColorWindow, float);
  vtkSetMacro(FinalColorLevel, float);
  vtkGetMacro(FinalColorLevel, float);
  ///@}

  /** Wall-clock seconds of the last Render() (0 before the first). */
  vtkGetMacro(LastRenderTime, double);

  /** Bounds of the input; a missing input is reported here (once per change of the mapper). */
  double* GetBounds() VTK_SIZEHINT(6) override;
  using vtkVolumeMapper::GetBounds;

protected:
  vtkAccelVolumeMapper();
  ~vtkAccelVolumeMapper() override;

  /** The input is optional so a missing input gets this mapper's own clear error. */
  int FillInputPortInformation(int port, vtkInformation* info) override;

  // The scale and bias FinalColorWindow / FinalColorLevel apply (a window of 0 counts as tiny).
  void GetFinalColorScaleAndBias(float& scale, float& bias) const;

  // Warns once per member (for this mapper's life) that a VTK setting does not apply here.
  void WarnNotApplicable(const char* member, const char* why);
  // True when the image's ghost array hides points (vtkUniformGrid blanking); cached per array.
  bool HasHiddenPoints(vtkImageData* image);

  vtkTypeBool EarlyRayTermination = 1;
  double EarlyRayTerminationThreshold = 0.99;
  double LastRenderTime = 0.0;
  float FinalColorWindow = 1.0f;
  float FinalColorLevel = 0.5f;
  // Converts cell scalars, other integer types and rectilinear grids for the engines.
  std::unique_ptr<vtkAccelVolumeInputAdapter> InputAdapter;

private:
  vtkAccelVolumeMapper(const vtkAccelVolumeMapper&) = delete;
  void operator=(const vtkAccelVolumeMapper&) = delete;

  vtkTimeStamp MissingInputReportTime;
  std::set<std::string> WarnedNotApplicable;
  void* HiddenPointsArray = nullptr;
  vtkMTimeType HiddenPointsTime = 0;
  bool HiddenPoints = false;
};

#endif
