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
 */

#ifndef vtkAccelVolumeMapper_h
#define vtkAccelVolumeMapper_h

#include "vtkRenderingAccelVolumeModule.h" // For export macro
#include "vtkTimeStamp.h"                  // For vtkTimeStamp
#include "vtkVolumeMapper.h"

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

  vtkTypeBool EarlyRayTermination = 1;
  double EarlyRayTerminationThreshold = 0.99;
  double LastRenderTime = 0.0;

private:
  vtkAccelVolumeMapper(const vtkAccelVolumeMapper&) = delete;
  void operator=(const vtkAccelVolumeMapper&) = delete;

  vtkTimeStamp MissingInputReportTime;
};

#endif
