/**
 * @class   vtkAccelVolumeRepresentation
 * @brief   ParaView volume representation of image data that renders with AccelVolume's
 *          mappers (slice-based OpenGL, CPU ray casting, CPU shear-warp, or the smart choice).
 *
 * Everything but the mapper is ParaView's vtkImageVolumeRepresentation: the data delivery,
 * the colour array selection, the colour transfer function (LookupTable) and scalar opacity
 * function, ScalarOpacityUnitDistance, interpolation, shading coefficients, cropping and the
 * outline LOD. The volume's mapper is one vtkAccelVolumeSmartMapper whose RequestedRenderMode
 * is the MapperType, so a mapper that cannot render the scene (shear-warp with a perspective
 * camera, raysum / average blending, cropping) falls back to another with a warning and the
 * information properties say which one rendered.
 *
 * Limits (those of the mappers): one-component scalars of image data (no rectilinear grids,
 * partitioned data, separate opacity arrays, 2D transfer functions or isosurface / slice blend
 * modes). In parallel (pvserver with several ranks) each rank renders its piece and ParaView
 * composites them, as with the Volume representation.
 */
#ifndef vtkAccelVolumeRepresentation_h
#define vtkAccelVolumeRepresentation_h

#include "vtkImageVolumeRepresentation.h"
#include "vtkNew.h"                                // For vtkNew
#include "vtkRenderingAccelVolumeParaViewModule.h" // For export macro
#include "vtkWrappingHints.h"                      // For VTK_WRAPEXCLUDE

class vtkAccelVolumeSmartMapper;

class VTKRENDERINGACCELVOLUMEPARAVIEW_EXPORT vtkAccelVolumeRepresentation
  : public vtkImageVolumeRepresentation
{
public:
  static vtkAccelVolumeRepresentation* New();
  vtkTypeMacro(vtkAccelVolumeRepresentation, vtkImageVolumeRepresentation);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /** Values of MapperType: those of vtkAccelVolumeSmartMapper::RenderModes. */
  enum MapperTypes
  {
    MAPPER_SMART = 0,     // vtkAccelVolumeSmartMapper::DEFAULT_RENDER
    MAPPER_SLICE = 2,     // SLICE_RENDER (VTK's GPURenderMode)
    MAPPER_RAYCAST = 1,   // RAYCAST_RENDER (VTK's RayCastRenderMode)
    MAPPER_SHEARWARP = 6  // SHEARWARP_RENDER
  };

  ///@{
  /** The mapper that renders (default MAPPER_SMART; other values fall back to it). */
  void SetMapperType(int type);
  int GetMapperType() const { return this->MapperType; }
  ///@}

  ///@{
  /** Composite blending: early ray termination in all three mappers (default on). */
  void SetEarlyRayTermination(bool enable);
  bool GetEarlyRayTermination() const { return this->EarlyRayTermination; }
  ///@}

  ///@{
  /**
   * Slice mapper: empty-space skipping, a vtkAccelVolumeSliceMapper::EmptySpaceSkippingModes
   * value (default SKIP_BOTH = 3, range 0..3).
   */
  void SetEmptySpaceSkipping(int mode);
  int GetEmptySpaceSkipping() const { return this->EmptySpaceSkipping; }
  ///@}

  ///@{
  /** Slice mapper: re-render the faces of cropped regions (default on). */
  void SetBoundaryRerendering(bool enable);
  bool GetBoundaryRerendering() const { return this->BoundaryRerendering; }
  ///@}

  ///@{
  /** Ray cast and shear-warp mappers: threads (default 0 = vtkSMPTools' default). */
  void SetNumberOfThreads(int threads);
  int GetNumberOfThreads() const { return this->NumberOfThreads; }
  ///@}

  ///@{
  /**
   * Slice and ray cast mappers: distance between samples along the view direction in world
   * units (default 0 = automatic: the smallest voxel spacing, as ParaView's GPU ray caster
   * takes it). Shear-warp always takes one sample per slice.
   */
  void SetSampleDistance(double distance);
  double GetSampleDistance() const { return this->SampleDistance; }
  ///@}

  ///@{
  /**
   * What the last render did: the vtkAccelVolumeSmartMapper::RenderModes value of the mapper
   * that rendered (-1 before any render), why it was chosen, its time in seconds, and its
   * work (slices drawn by the slice mapper, samples taken by the ray cast and shear-warp
   * mappers; 0 before any render).
   */
  int GetLastRenderMode();
  const char* GetLastChoiceReason();
  double GetLastRenderTime();
  double GetLastRenderWork();
  ///@}

  /** The mapper of the volume, for settings not exposed as properties (C++ only). */
  VTK_WRAPEXCLUDE vtkAccelVolumeSmartMapper* GetAccelVolumeMapper();

protected:
  vtkAccelVolumeRepresentation();
  ~vtkAccelVolumeRepresentation() override;

  /** Also pushes the automatic sample distance, which depends on the data's spacing. */
  void UpdateMapperParameters() override;

  vtkNew<vtkAccelVolumeSmartMapper> Mapper;
  int MapperType = MAPPER_SMART;
  bool EarlyRayTermination = true;
  int EmptySpaceSkipping = 3;
  bool BoundaryRerendering = true;
  int NumberOfThreads = 0;
  double SampleDistance = 0.0;

private:
  vtkAccelVolumeRepresentation(const vtkAccelVolumeRepresentation&) = delete;
  void operator=(const vtkAccelVolumeRepresentation&) = delete;
};

#endif
