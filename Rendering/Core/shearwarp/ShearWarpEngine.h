// ShearWarpEngine: Lacroute's shear-warp volume renderer behind vtkAccelVolumeShearWarpMapper
// (plain C++, no VTK).
//
// A frame: factorize the parallel view (ShearWarpFactorization); classify and run-length encode
// the volume for the principal axis (kept until the scalars or the transfer function change:
// one encoding per axis, built when first needed); composite the sheared slices front to back
// into the intermediate image, scanline band by band; warp it bilinearly into the final image.
// Composite colours are classified before resampling (pre-classification, as Lacroute): each
// voxel's opacity is corrected for the ray length between slices and its colour is shaded by a
// per-frame table over quantized normals (or by Phong per voxel), then resampled bilinearly in
// the slice. MIP / MinIP resample the quantized scalars and classify the extreme.
//
// Bands are contiguous runs of intermediate scanlines (planes parallel to the rays): workers never
// share a pixel, and bands are balanced with the per-scanline times of the previous frame. The
// image never depends on the band count or the worker count. The phases are public so that MPI
// ranks can each composite their bands and gather them (vtkAccelVolumeShearWarpMapper).
#ifndef accelvolume_ShearWarpEngine_h
#define accelvolume_ShearWarpEngine_h

#include "common/Blend.h"
#include "common/ParallelFor.h"
#include "common/VolumeView.h"
#include "common/Progress.h"
#include "raycast/RayCastEngine.h" // RayCastTransfer, RayCastLighting
#include "shearwarp/ShearWarpFactorization.h"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <thread>
#include <vector>

namespace accelvolume
{

enum class ShearWarpShading
{
  LookupTable, // Lacroute: one table per frame over the quantized normals
  Phong        // Phong per voxel from the decoded normal
};

// Bands per worker when compositing on several: handed out one at a time (dynamic scheduling
// on top of the balanced partition).
inline constexpr int BandsPerWorker = 4;
// The most intermediate-image bytes per band: a band's pixels stay in a core's L2 cache while
// every slice sweeps them.
inline constexpr std::size_t BandCacheBytes = 256 * 1024;

struct ShearWarpSettings
{
  Blend blend = Blend::Composite;
  bool runLengthEncoding = true; // false: dense volume, every voxel and pixel visited
  bool earlyTermination = true;  // skip links over saturated pixels (composite, MIP, MinIP)
  double terminationThreshold = 0.99;
  ShearWarpShading shading = ShearWarpShading::LookupTable;
  int bands = 1;        // workers compositing in parallel (>= 1); more bands when > 1
  bool balance = true;  // bands from the previous frame's per-scanline times; else equal sizes
  // false: Render stops after compositing and leaves the warp to the caller (the mapper draws
  // the intermediate image through the warp on the GPU); rgba is then left as it was.
  bool warp = true;
  // With warp false: each band worker also converts the rows it composited into the display
  // pixels (GetDisplayPixels) while they are still in its cache, so that showing the image
  // needs no serial pass over it. Render only (BeginFrame / CompositeRows leave them unset).
  bool displayPixels = false;
  // Composite: after a frame encodes (or reuses) its axis's encoding, a background thread
  // builds the other two axes' from it (re-sorting the stored voxels, no classification), so
  // that a view crossing an axis does not stall; all three are then held. false: each axis is
  // encoded when a frame first needs it.
  bool backgroundEncodings = true;
};

struct ShearWarpView
{
  int width = 0, height = 0;
  // Voxel index -> continuous image coordinates (x, y from the bottom-left corner, pixel (a, b)
  // covering [a, a + 1) x [b, b + 1); z: depth away from the viewer), row-major 3x4. Parallel.
  double voxelToImage[3][4] = {};
  // Linear part of voxel index -> world, row-major (ray length between slices in world units).
  double indexToWorld[3][3] = { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } };
};

struct ShearWarpStats
{
  int principalAxis = -1;
  int intermediateSize[2] = { 0, 0 };
  double encodeSeconds = 0;    // classification + run-length encoding done this frame
  double tableSeconds = 0;     // opacity correction and shading tables
  double compositeSeconds = 0; // all bands (wall clock; with their display pixels)
  double rowsShownSeconds = 0; // in the rows-ready function, not in compositeSeconds
  double warpSeconds = 0;
  std::vector<double> bandSeconds; // per band
  std::vector<int> bandBounds;     // bands + 1 scanline boundaries
  double imbalance = 1;            // busiest worker / mean worker compositing time
  int workers = 0;                 // threads that composited bands (this process)
  std::uint64_t voxels = 0, samples = 0, terminatedPixelVisits = 0;
  std::size_t encodedBytes = 0;   // all encodings held
  std::uint64_t storedVoxels = 0; // voxels in the current axis's encoding
  std::uint64_t runs = 0;
};

// The intermediate image as 16-bit normalised RGBA for display (common/Unorm16.h's values):
// (size[0] + 1) x (size[1] + 1) pixels, the last column and row zero (a bilinear lookup past
// the image reads zero), and each intermediate row's first and last pixel that is not zero
// (first > last: none).
struct ShearWarpDisplayPixels
{
  const std::uint16_t* rgba = nullptr; // null: not converted this frame
  int width = 0, height = 0;           // the padded size
  const int* rowFirst = nullptr;
  const int* rowLast = nullptr;
};

class ShearWarpRenderer
{
public:
  ShearWarpRenderer();
  ~ShearWarpRenderer();
  ShearWarpRenderer(const ShearWarpRenderer&) = delete;
  ShearWarpRenderer& operator=(const ShearWarpRenderer&) = delete;

  // Renders premultiplied RGBA (4 floats per pixel, x + y * width, rows from the bottom) and the
  // rectangle [x0, x1] x [y0, y1] outside which every pixel is transparent (x1 < x0: none).
  // volumeVersion / transferVersion identify the scalars and the transfer function: encodings
  // are rebuilt only when they change. False with error on bad arguments.
  bool Render(const VolumeView& volume, double rangeMin, double rangeMax,
    std::uint64_t volumeVersion, const RayCastTransfer& transfer, std::uint64_t transferVersion,
    const RayCastLighting& lighting, const ShearWarpView& view, const ShearWarpSettings& settings,
    const ParallelFor& parallel, std::vector<float>& rgba, int rectangle[4], ShearWarpStats& stats,
    std::string& error);

  // Progress of every later frame, reported from the thread that calls Render / BeginFrame.
  // Render reports the whole frame: classification and encoding (when the frame needs them) up
  // to 0.8 as the slices finish (ReportingParallelFor: no extra barrier); compositing 0.95; the
  // warp 1. BeginFrame reports its encoding alone, 0 to 1, and nothing when it reuses an
  // encoding. The image does not depend on it. Empty (the default): none.
  void SetProgressFunction(ProgressFunction report);

  // Rows shown while the frame composites: with one worker (settings.bands 1) and display
  // pixels (displayPixels, no warp), Render composites its bands in order on the calling
  // thread and calls this after each band with the intermediate rows [0, rowsReady) composited
  // and converted (`pixels` as GetDisplayPixels, its rows from rowsReady on not yet written),
  // so that a caller can draw them while the next band composites. Empty (the default): none.
  using RowsReadyFunction = std::function<void(const ShearWarpDisplayPixels& pixels, int rowsReady)>;
  void SetRowsReadyFunction(RowsReadyFunction ready);

  // The phases of Render, for distributed compositing:
  // BeginFrame factorizes, encodes when needed, builds the tables and clears the intermediate
  // image; Bands partitions its scanlines (balanced with the last costs given or measured);
  // CompositeRows composites scanlines [v0, v1) (concurrent calls on disjoint ranges are safe)
  // and records their times; Warp resamples the intermediate image into the final image.
  bool BeginFrame(const VolumeView& volume, double rangeMin, double rangeMax,
    std::uint64_t volumeVersion, const RayCastTransfer& transfer, std::uint64_t transferVersion,
    const RayCastLighting& lighting, const ShearWarpView& view, const ShearWarpSettings& settings,
    const ParallelFor& parallel, ShearWarpStats& stats, std::string& error);
  std::vector<int> Bands(int parts, bool balance) const;
  void CompositeRows(int v0, int v1);
  void Warp(const ParallelFor& parallel, std::vector<float>& rgba, int rectangle[4]);

  const ShearWarpFactorization& GetFactorization() const;
  // Intermediate image: intermediateSize[0] * intermediateSize[1] premultiplied RGBA pixels.
  // A scanline is defined once CompositeRows has composited it this frame (or a caller has
  // written it, e.g. rows received from other MPI ranks); Warp reads every scanline.
  float* GetIntermediateImage();
  // The last Render's display pixels when its settings asked for them (displayPixels, no
  // warp); rgba is null otherwise and after BeginFrame.
  ShearWarpDisplayPixels GetDisplayPixels() const;
  // Seconds per intermediate scanline of the last CompositeRows calls (0 where not composited):
  // each call's time shared out over its scanlines by the clock ticks each took.
  const std::vector<double>& GetScanlineSeconds() const;
  // Costs used to balance the next frame (e.g. the sum of every rank's scanline seconds).
  void SetScanlineCosts(const std::vector<double>& seconds);
  // Counters of the CompositeRows calls since BeginFrame.
  void GetCounters(ShearWarpStats& stats) const;
  std::size_t GetEncodedBytes() const;
  // Waits until the background encodings started by the last frame are built (benchmarks and
  // tools; a frame that needs one waits by itself).
  void FinishBackgroundEncodings();

  struct Internals;

private:
  // BeginFrame, reporting the encoding (when it encodes) through encodeProgress.
  bool BeginFrameReporting(const VolumeView& volume, double rangeMin, double rangeMax,
    std::uint64_t volumeVersion, const RayCastTransfer& transfer, std::uint64_t transferVersion,
    const RayCastLighting& lighting, const ShearWarpView& view, const ShearWarpSettings& settings,
    const ParallelFor& parallel, const ProgressFunction& encodeProgress, ShearWarpStats& stats,
    std::string& error);

  std::unique_ptr<Internals> Impl;
};

// The final pixels [x0, x1] x [y0, y1] the intermediate image (with its one-pixel bilinear
// fringe) can reach in a width x height image (x1 < x0 or y1 < y0: none).
void WarpedRectangle(const ShearWarpFactorization& f, int width, int height, int rectangle[4]);

// The distinct threads among the workers that composited a frame's bands (ShearWarpStats::
// workers; the mapper's MPI bands count theirs the same way).
int DistinctWorkers(std::vector<std::thread::id> bandWorker);

// Voxel index -> image map for a VTK-style parallel camera (tests, benchmarks and tools):
// indexToWorld (row-major 3x4), the camera's world -> view matrix (row-major 4x4), its parallel
// scale (half the viewport height in world units) and the image size.
void ParallelVoxelToImage(const double indexToWorld[3][4], const double worldToView[4][4],
  double parallelScale, int width, int height, double voxelToImage[3][4]);

}

#endif
