/**
 * @class   vtkAccelVolumeShearWarpMapper
 * @brief   CPU shear-warp volume renderer (Lacroute & Levoy 1994) with run-length encoded
 *          volumes, skip links over opaque pixels and a load-balanced sheared-space partition
 *          on threads and MPI ranks (Kim 1998).
 *
 * The parallel view is factorized into a shear of the volume slices along the principal
 * viewing axis and a 2D warp. The volume is classified with the transfer function and
 * run-length encoded per scanline for the principal axis (only voxels that can contribute are
 * stored; encodings are kept until the scalars or the transfer function change, one per axis).
 * Slices are composited front to back into an intermediate image, walking runs of
 * non-transparent voxels and runs of unsaturated pixels (skip links) together, then the
 * intermediate image is warped bilinearly into the final image, shown in the VTK scene as a
 * textured quad.
 *
 * Blend modes: composite (colour, scalar and gradient opacity, Phong shading with VTK's lights
 * through a per-frame table over quantized normals, or per voxel), maximum and minimum
 * intensity. MIP / MinIP store only voxels on the visible side of the transfer function's
 * first (last) non-zero opacity, with their in-slice neighbours, and skip pixels that already
 * hold the volume's extreme: both exact.
 *
 * Differences from the ray casters (the bound the tests state): colours are classified per
 * voxel and then resampled (pre-classification), resampling is bilinear within slices with
 * one sample per slice, and the final image is a bilinear warp of an image with one pixel per
 * voxel. Parallel projection only (a perspective camera is an error); cropping, clipping planes
 * and opaque geometry in the scene are not applied (a warning says so).
 *
 * Parallel work: the intermediate image's scanlines are split into contiguous bands (planes
 * parallel to the rays), balanced with the per-scanline times of the previous frame; workers
 * never share a pixel and the image never depends on the thread or rank count. With a
 * multi-process controller (SetController) every rank must render the same scene in lockstep
 * (SPMD); each composites its band with its threads, rank 0 gathers the bands, warps and
 * shows the image. The ranks agree on every frame's status first (a rank that cannot render
 * makes every rank fail the frame, and rank 0's error names it), and every wait for another
 * rank is bounded (CommunicationTimeout): a rank that hangs or dies ends the job instead of
 * blocking the others forever.
 */
#ifndef vtkAccelVolumeShearWarpMapper_h
#define vtkAccelVolumeShearWarpMapper_h

#include "vtkRenderingAccelVolumeModule.h" // For export macro
#include "vtkAccelVolumeMapper.h"

#include <memory> // For std::unique_ptr

class vtkMultiProcessController;
class vtkRenderer;
class vtkVolume;
class vtkWindow;

class VTKRENDERINGACCELVOLUME_EXPORT vtkAccelVolumeShearWarpMapper : public vtkAccelVolumeMapper
{
public:
  static vtkAccelVolumeShearWarpMapper* New();
  vtkTypeMacro(vtkAccelVolumeShearWarpMapper, vtkAccelVolumeMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum ShadingModes
  {
    SHADING_LOOKUP_TABLE = 0, // Lacroute: a table over quantized normals, rebuilt per frame
    SHADING_PHONG = 1         // Phong evaluated per voxel
  };

  ///@{
  /**
   * Run-length encoding (default on). Off: every voxel is stored and composited, and no pixel
   * is skipped (the unaccelerated baseline; the image equals the encoded one exactly when early
   * termination is off).
   */
  vtkSetMacro(RunLengthEncoding, vtkTypeBool);
  vtkGetMacro(RunLengthEncoding, vtkTypeBool);
  vtkBooleanMacro(RunLengthEncoding, vtkTypeBool);
  ///@}

  // Termination (EarlyRayTermination, vtkAccelVolumeMapper; default on) is shear-warp's skip
  // links over saturated pixels: composite pixels whose opacity reaches
  // EarlyRayTerminationThreshold (default 0.99, in [0.5, 1]), MIP / MinIP pixels that hold the
  // volume's extreme.

  ///@{
  /** Shading evaluation (default SHADING_LOOKUP_TABLE). */
  vtkSetClampMacro(ShadingMode, int, SHADING_LOOKUP_TABLE, SHADING_PHONG);
  vtkGetMacro(ShadingMode, int);
  ///@}

  ///@{
  /**
   * Threads per process (0 = all cores, the default; more than the cores are capped). The
   * image does not depend on it.
   */
  vtkSetClampMacro(NumberOfThreads, int, 0, 1024);
  vtkGetMacro(NumberOfThreads, int);
  ///@}

  ///@{
  /**
   * Balance the scanline bands with the previous frame's per-scanline times (default on); off:
   * bands of equal scanline counts.
   */
  vtkSetMacro(LoadBalancing, vtkTypeBool);
  vtkGetMacro(LoadBalancing, vtkTypeBool);
  vtkBooleanMacro(LoadBalancing, vtkTypeBool);
  ///@}

  ///@{
  /**
   * Warp the intermediate image into the view while drawing it, on the GPU (default on): only
   * the intermediate image (one pixel per voxel) is uploaded and the texture unit resamples it
   * bilinearly. Off: the CPU warps into an image of the viewport's size, which is uploaded
   * (LastWarpTime measures it). Intermediate images past the texture size limit are warped on
   * the CPU either way. The two differ by the texture unit's filtering precision.
   */
  vtkSetMacro(WarpOnGPU, vtkTypeBool);
  vtkGetMacro(WarpOnGPU, vtkTypeBool);
  vtkBooleanMacro(WarpOnGPU, vtkTypeBool);
  ///@}

  ///@{
  /**
   * Composite blending: once a frame has the encoding of its principal axis, build the other two
   * axes' encodings in a background thread, from that one (the stored voxels re-sorted, nothing
   * classified again), so that a view turning across an axis does not stall on the encoding
   * (default on). All three encodings are then held. Off: each axis is encoded when a frame first
   * needs it, and only those are held.
   */
  vtkSetMacro(BackgroundEncoding, vtkTypeBool);
  vtkGetMacro(BackgroundEncoding, vtkTypeBool);
  vtkBooleanMacro(BackgroundEncoding, vtkTypeBool);
  ///@}

  /**
   * Waits until the background encodings the last frame started are built (benchmarks and
   * tools: a frame that needs one waits by itself).
   */
  void FinishBackgroundEncoding();

  ///@{
  /**
   * Multi-process controller (default none: this process renders alone). With more than one
   * process every rank must call Render for the same scene; rank 0 shows the image.
   */
  void SetController(vtkMultiProcessController* controller);
  vtkGetObjectMacro(Controller, vtkMultiProcessController);
  ///@}

  ///@{
  /**
   * With several ranks: the longest one rank waits for another in one exchange of a frame, in
   * seconds (default 60; 0 = wait forever). Rank 0 waits at most this long for the other ranks'
   * frame status, band rows and timings; the others wait up to twice as long for rank 0 (which
   * may itself be waiting for a hung rank, and then names it). When a wait runs out the job is
   * ended through the communication abort function (SetCommunicationAbortFunction): a rank
   * blocked in MPI cannot go on. It must exceed the longest time one rank may still work while
   * another waits (the ranks' difference in encoding and compositing time).
   */
  vtkSetClampMacro(CommunicationTimeout, double, 0.0, 1.0e6);
  vtkGetMacro(CommunicationTimeout, double);
  ///@}

  /**
   * Process-wide: ends the job when a wait of CommunicationTimeout ran out. Called on a watchdog
   * thread (the rendering thread is blocked in the controller) with a one-line message naming
   * the rank waited for; an MPI application passes a function that prints it and calls
   * MPI_Abort. If it returns, or none is set (the default), the message goes to stderr and the
   * process exits with status 1, which makes mpiexec end the other ranks.
   */
  static void SetCommunicationAbortFunction(void (*function)(const char* message));

  ///@{
  /** Last frame, wall-clock seconds (GetLastRenderTime: the whole Render()): classification and encoding (0 when
   * reused), the per-frame tables, compositing (all bands; not the image parts drawn meanwhile),
   * gathering bands from other ranks,
   * the warp. */
  vtkGetMacro(LastEncodeTime, double);
  vtkGetMacro(LastTableTime, double);
  vtkGetMacro(LastCompositeTime, double);
  vtkGetMacro(LastGatherTime, double);
  vtkGetMacro(LastWarpTime, double);
  ///@}

  ///@{
  /** Last frame's load imbalance: the busiest thread's compositing time over the mean per thread
   * (MPI: the slowest band over the mean band; 1 = even). */
  vtkGetMacro(LastImbalance, double);
  /** Bands of the last frame (one process: 4 per thread with several threads, taken dynamically;
   * MPI: one per thread of every rank) and their compositing seconds. */
  vtkGetMacro(LastNumberOfBands, int);
  /** Threads of this process that composited the last frame's bands: at most NumberOfThreads
   * when that is set. */
  vtkGetMacro(LastNumberOfWorkers, int);
  /** Parts the last frame's image was drawn in: several when one thread composites a frame of
   * one process that the GPU warps (each part drawn while the next rows composite, so the GL
   * driver works meanwhile), else 1; 0 when nothing was drawn. */
  vtkGetMacro(LastNumberOfImageParts, int);
  /** Seconds of the last frame spent drawing image parts while compositing (in GetLastRenderTime,
   * not in GetLastCompositeTime). */
  vtkGetMacro(LastImagePartsTime, double);
  double GetLastBandTime(int band) const;
  /** Scanlines of the last frame's intermediate image and the compositing seconds of each (this
   * rank's, the rest 0): what balances the next frame's bands (and models other core counts). */
  int GetLastNumberOfScanlines() const;
  double GetLastScanlineTime(int scanline) const;
  ///@}

  ///@{
  /** Last frame's counters (this rank): voxels read, pixels composited, pixel visits skipped
   * by skip links; the principal axis; voxels stored in its encoding; bytes of all encodings. */
  vtkGetMacro(LastNumberOfVoxels, vtkTypeInt64);
  vtkGetMacro(LastNumberOfSamples, vtkTypeInt64);
  vtkGetMacro(LastNumberOfSkippedPixels, vtkTypeInt64);
  vtkGetMacro(LastPrincipalAxis, int);
  vtkGetMacro(LastNumberOfStoredVoxels, vtkTypeInt64);
  vtkGetMacro(EncodedBytes, vtkTypeInt64);
  ///@}

  void Render(vtkRenderer* renderer, vtkVolume* volume) override;
  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  vtkAccelVolumeShearWarpMapper();
  ~vtkAccelVolumeShearWarpMapper() override;

  vtkTypeBool RunLengthEncoding = 1;
  int ShadingMode = SHADING_LOOKUP_TABLE;
  int NumberOfThreads = 0;
  vtkTypeBool LoadBalancing = 1;
  vtkTypeBool WarpOnGPU = 1;
  vtkTypeBool BackgroundEncoding = 1;
  vtkMultiProcessController* Controller = nullptr;
  double CommunicationTimeout = 60;

  double LastEncodeTime = 0;
  double LastTableTime = 0;
  double LastCompositeTime = 0;
  double LastGatherTime = 0;
  double LastWarpTime = 0;
  double LastImbalance = 1;
  int LastNumberOfBands = 0;
  int LastNumberOfWorkers = 0;
  int LastNumberOfImageParts = 0;
  double LastImagePartsTime = 0;
  vtkTypeInt64 LastNumberOfVoxels = 0;
  vtkTypeInt64 LastNumberOfSamples = 0;
  vtkTypeInt64 LastNumberOfSkippedPixels = 0;
  int LastPrincipalAxis = -1;
  vtkTypeInt64 LastNumberOfStoredVoxels = 0;
  vtkTypeInt64 EncodedBytes = 0;

private:
  vtkAccelVolumeShearWarpMapper(const vtkAccelVolumeShearWarpMapper&) = delete;
  void operator=(const vtkAccelVolumeShearWarpMapper&) = delete;

  class vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
};

#endif
