// ShearWarpEngineInternals: the shear-warp renderer's private state (its encodings cached per
// axis, the frame's tables and image) shared by ShearWarpEngine.cxx and ShearWarpEncodings.cxx.
// Not installed.
#ifndef accelvolume_ShearWarpEngineInternals_h
#define accelvolume_ShearWarpEngineInternals_h

#include "shearwarp/RunLengthVolume.h"
#include "shearwarp/ShearWarpCompositor.h"
#include "shearwarp/ShearWarpEngine.h"

#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <thread>
#include <vector>

namespace accelvolume
{
namespace detail
{
using Clock = std::chrono::steady_clock;

inline double Seconds(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// What an encoding was built from; any change rebuilds it.
struct EncodingKey
{
  std::uint64_t volumeVersion = 0, transferVersion = 0;
  bool normals = false;
  bool maximum = false;
  std::uint16_t threshold = 0;
  bool valid = false;
  bool operator==(const EncodingKey& o) const
  {
    return this->valid && o.valid && this->volumeVersion == o.volumeVersion &&
      this->transferVersion == o.transferVersion && this->normals == o.normals &&
      this->maximum == o.maximum && this->threshold == o.threshold;
  }
};

template <typename Voxel>
struct EncodingSlot
{
  RunLengthVolume<Voxel> encoded;
  EncodingKey key;
  float saturation = 0; // MIP / MinIP: the stored voxels' extreme
  std::vector<std::uint32_t> rowVoxels; // per scanline (j, k), for cost estimates
};

} // namespace detail

// The .cxx files that share this state use these unqualified.
using detail::Clock;
using detail::EncodingKey;
using detail::EncodingSlot;
using detail::Seconds;

struct ShearWarpRenderer::Internals
{
  detail::EncodingSlot<ShadedVoxel> composite[2][3]; // [dense][axis]
  detail::EncodingSlot<ScalarVoxel> extreme[2][3];

  // Composite encodings of the other two axes, built in the background from the frame's
  // (TransposeEncoding) so that a view crossing an axis finds its encoding ready. The job only
  // reads the encoding it started from and publishes each new one into an empty slot under
  // slotsMutex; the frame thread waits for the job (joins it) before it changes or drops any
  // composite slot, and reads a slot the job may publish into only under the mutex.
  std::thread background;
  std::atomic<bool> backgroundCancelled{ false };
  std::atomic<bool> backgroundRunning{ false }; // false once the job has returned
  detail::EncodingKey backgroundKey;
  mutable std::mutex slotsMutex;

  ~Internals();
  // Waits for the background job, if any; returns the seconds waited.
  double FinishBackgroundEncodings();
  // Starts the job for the composite slots of `dense` still missing `key`, from slot `axis`.
  void StartBackgroundEncodings(int dense, int axis, const detail::EncodingKey& key);

  // The frame.
  ShearWarpFactorization factorization;
  ShearWarpSettings settings;
  CompositeTables tables;
  detail::EncodingSlot<ShadedVoxel>* compositeSlot = nullptr;
  detail::EncodingSlot<ScalarVoxel>* extremeSlot = nullptr;
  std::vector<float> transfer; // RGBA table for MIP / MinIP classification
  std::vector<float> intermediate;
  // settings.displayPixels: the intermediate image converted by the band workers.
  std::vector<std::uint16_t> displayPixels;
  std::vector<int> displayRowFirst, displayRowLast;
  bool displayReady = false;
  std::vector<double> scanlineSeconds;
  int imageSize[2] = { 0, 0 };
  double opacityRatio = -1; // ray length between slices / opacity unit distance of tables.opacity
  std::atomic<std::uint64_t> voxels{ 0 }, samples{ 0 }, terminatedPixelVisits{ 0 };

  // Balancing: the costs of the last frame, for its principal axis.
  std::vector<double> costs;
  int costAxis = -1;

  ProgressFunction progress;
  ShearWarpRenderer::RowsReadyFunction rowsReady;

  std::vector<double> EstimateCosts();
  void ClassifyExtremeRow(const float* values, float* rgba) const;

  // Steps of BeginFrameReporting, in order.
  // Encodings built from other scalars or another transfer function are dropped right away.
  void DropStaleEncodings(std::uint64_t volumeVersion, std::uint64_t transferVersion);
  // The (cached) encoding of this frame's axis and layout: composite or MIP / MinIP.
  bool UpdateCompositeEncoding(const VolumeView& volume, double rangeMin, double rangeMax,
    const RayCastTransfer& transfer, const RayCastLighting& lighting, const ShearWarpView& view,
    detail::EncodingKey key, int axis, int dense, const ParallelFor& encodeParallel,
    detail::Clock::time_point encodeStart, ShearWarpStats& stats, std::string& error);
  bool UpdateExtremeEncoding(const VolumeView& volume, double rangeMin, double rangeMax,
    const RayCastTransfer& transfer, bool maximum, detail::EncodingKey key, int axis, int dense,
    const ParallelFor& encodeParallel, detail::Clock::time_point encodeStart, ShearWarpStats& stats,
    std::string& error);
  // Per-frame tables: opacity for this view's ray length between slices, and shading.
  void UpdateTables(const RayCastTransfer& transfer, const RayCastLighting& lighting,
    const ShearWarpView& view, const ShearWarpSettings& settings, const ParallelFor& parallel);
  // Sizes the intermediate image and clears the counters; fills the frame's stats.
  void StartFrame(int axis, ShearWarpStats& stats);
  // Sizes the display pixels for this frame's intermediate image (Render, displayPixels) and
  // zeroes their padding row; ConvertRowsForDisplay converts rows [v0, v1), composited
  // already, and writes their padding column.
  void PrepareDisplayPixels();
  void ConvertRowsForDisplay(int v0, int v1);
};

} // namespace accelvolume

#endif
