// Render: builds the scene the options describe, renders and times it, and saves the last frame.
#ifndef accelvolume_cli_Render_h
#define accelvolume_cli_Render_h

#include "Options.h"
#include "TransferFunctions.h"

#include <vtkImageData.h>

#include <string>
#include <vector>

class vtkAccelVolumeMPIExchange;

namespace accelvolume::cli
{

// Catches VTK's error and warning output for the whole run (vtkOutputWindow and vtkLogger), so
// nothing reaches the terminal unasked and render failures become one error line.
class VTKMessages
{
public:
  VTKMessages();
  ~VTKMessages();
  VTKMessages(const VTKMessages&) = delete;
  VTKMessages& operator=(const VTKMessages&) = delete;

  // Re-installs the capture after code that swapped the output window or logger levels.
  void Install();
  // Throws CliError(ExitRuntime, context + ": " + first error) when an error arrived since the
  // last Clear(), then clears.
  void ThrowIfError(const std::string& context);
  // The first error since the last Clear() ("" when none), and clears it.
  std::string TakeError();
  void Clear();
  int GetNumberOfWarnings() const;
  std::string GetFirstWarning() const;

  struct State;

private:
  State* Data;
};

// --mapper raycast: the mapper's settings and what it did in the last frame.
struct RayCastResult
{
  LeapKind leap = LeapKind::Octree;
  bool cellLeap = true;
  int threads = 0; // 0 = vtkSMPTools' default
  int octreeLeafSize = 0;
  double imageSampleDistance = 1;
  long long rays = 0;
  long long samples = 0;
  long long leapedOctree = 0;
  long long leapedDistanceMap = 0;
  long long leapedCellTable = 0;
  long long transparentCellSamples = 0;
  long long terminatedRays = 0;
  long long octreeLeaps = 0;      // leaps taken (each skips >= 1 sample)
  long long distanceMapLeaps = 0;
  long long culledPixels = 0;
  long long packetRays = 0;        // cast sixteen at a time
  long long accelerationBytes = 0; // held by the octree, cell table / distance map, gradients
  double renderMs = 0;
  double castMs = 0;
  double prepareMs = 0;
  double firstPrepareMs = 0; // the warm-up frame, which builds the leaping structures
};

// --mapper shearwarp: the mapper's settings and what it did in the last frame (this rank).
struct ShearWarpResult
{
  bool runLengthEncoding = true;
  bool earlyRayTermination = true;
  bool balance = true;
  bool phongShading = false;
  bool warpOnGPU = true;
  int threads = 0; // as set (0 = all cores)
  int ranks = 1;
  double renderMs = 0;
  double encodeMs = 0;
  double firstEncodeMs = 0; // the warm-up frame, which classifies and encodes the volume
  double tableMs = 0;
  double compositeMs = 0;
  double gatherMs = 0;
  double warpMs = 0;
  double imbalance = 1;
  std::vector<double> bandMs; // compositing time of each band (threads x ranks)
  // Counters of the whole frame (summed over the ranks with --mpi); the encoding's are per rank
  // (every rank encodes the whole volume).
  long long voxels = 0;
  long long samples = 0;
  long long skippedPixels = 0;
  int principalAxis = -1;
  long long storedVoxels = 0;
  long long encodedBytes = 0;
};

// The slice mapper's last frame (--mapper slice, or smart when it chose slice); its slice count,
// passes and skipping fractions are RenderResult's own fields.
struct SliceResult
{
  double renderMs = 0;
  int proxyPolygons = 0;
  int boundaryFaces = 0;
  int bricks = 0;       // bricks of the volume's layout (1 when it fits one texture)
  int bricksDrawn = 0;  // bricks with geometry in the last frame
  int brickUploads = 0; // bricks uploaded in the last frame
  double uploadedBytes = 0;
  double residentBytes = 0; // volume texture bytes on the GPU after the last frame
};

// --mapper smart: what the last frame chose and why, and the smart mapper's own time.
struct SmartResult
{
  std::string mode = "none"; // slice, raycast or shearwarp
  std::string reason;
  double renderMs = 0;
};

struct RenderResult
{
  double firstFrameMs = 0;
  std::vector<double> frameMs; // the timed frames, in order
  std::string glRenderer = "unknown";
  std::string glBackend = "unknown";
  double window[2] = { 0, 1 }; // transfer-function window actually used
  double scalarRange[2] = { 0, 0 };
  double raysumUnit = 0;            // slice and raycast mappers' AdditiveUnitDistance
  double sampleDistance = 0;        // world distance between samples / slices actually used
  std::string sampleDistanceSource; // "min-spacing", "flag" or "slices"
  int slices = -1;                  // slice mapper's last slice count; -1 for other mappers
  int slabSamples = -1;             // slice mapper's samples per proxy fragment; -1 for others
  // Slice mapper, composite: what the accelerations did in the last frame (-1 = not used).
  int terminationPasses = -1;
  bool slicesGenerated = false; // slice mapper: the last frame's slices built on the GPU
  bool halfFloatTarget = false; // slice mapper: 16-bit float accumulation
  bool computeSlices = false;   // slice mapper: the last frame composited by the compute pass
  double transparentLeafFraction = -1;
  double proxyAreaFraction = 1;
  double cropPlanes[6] = { 0, 0, 0, 0, 0, 0 }; // world coordinates, when cropping
  AppliedTransferFunction transferFunction;    // shading and lighting actually set
  bool rayCastUsed = false;
  RayCastResult rayCast; // when rayCastUsed
  bool shearWarpUsed = false;
  ShearWarpResult shearWarp; // when shearWarpUsed
  bool sliceUsed = false;
  SliceResult slice; // when sliceUsed
  bool smartUsed = false;
  SmartResult smart; // when smartUsed
  double mapperRenderMs = 0; // the mapper's own time for the last frame (every mapper)
};

// Throws CliError(ExitUsage) when the crop box lies outside the volume or is inverted.
void CheckCrop(const Options& options, vtkImageData* image);

// Renders one warm-up frame and options.frames timed frames (a progress bar on stderr as
// options.progress says, fed by the mapper's ProgressEvent), writing options.outPath if set, with
// the transfer function tf (LoadTransferFunction). Throws CliError(ExitRuntime) when VTK reports an
// error while rendering or writing. mpi (--mpi, shear-warp only; its controller's ranks): every
// rank calls this with the same arguments; the ranks agree after every frame whether one of them
// failed (so none waits forever for a failed one), and only the caller passes outPath for rank 0.
// Test hook: ACCELVOLUME_FAULT (see FaultInjection in Render.cxx) makes one rank hang or die.
RenderResult RunRender(const Options& options, const TransferFunctionSpec& tf, vtkImageData* image,
  VTKMessages& messages, vtkAccelVolumeMPIExchange* mpi = nullptr);

// Throws CliError(code, message) on every rank when any rank passed a non-zero code: on the lowest
// failing rank its own message, on the others "rank N: <that rank's message>" (with --mpi only
// rank 0 prints). Without mpi: throws when code is non-zero. Every rank must call it (what names
// the exchange in timeout messages).
void ThrowIfAnyRankFailed(
  vtkAccelVolumeMPIExchange* mpi, int code, const std::string& message, const char* what);

} // namespace accelvolume::cli

#endif
