// ShearWarpEncodings: the run-length encodings of the classified volume, cached per principal
// axis and layout, built when the scalars, the transfer function or the shading inputs change.
#include "shearwarp/ShearWarpEngineInternals.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <new>
#include <stdexcept>

namespace accelvolume
{
namespace
{

// Lowest (MIP) / highest (MinIP) quantized scalar that may be visible: every value beyond it on
// the other side has zero opacity in the (linearly interpolated) table.
std::uint16_t VisibleThreshold(const std::vector<float>& rgba, bool maximum)
{
  const int n = static_cast<int>(rgba.size() / 4);
  if (maximum)
  {
    for (int e = 0; e < n; ++e)
    {
      if (rgba[4 * e + 3] > 0)
      {
        return static_cast<std::uint16_t>(std::floor(65535.0 * std::max(0, e - 1) / (n - 1)));
      }
    }
    return 65535;
  }
  for (int e = n - 1; e >= 0; --e)
  {
    if (rgba[4 * e + 3] > 0)
    {
      return static_cast<std::uint16_t>(std::ceil(65535.0 * std::min(n - 1, e + 1) / (n - 1)));
    }
  }
  return 0;
}

// What the composite encoding classifies with; false when the index-to-world map is singular.
bool MakeCompositeClassification(double rangeMin, double rangeMax, const RayCastTransfer& transfer,
  const RayCastLighting& lighting, const ShearWarpView& view,
  CompositeClassification& classification, std::string& error)
{
  classification.rangeMin = rangeMin;
  classification.rangeMax = rangeMax;
  classification.rgba = transfer.rgba;
  classification.gradientOpacity = transfer.gradientOpacity;
  classification.gradientOpacityMaximum = transfer.gradientOpacityMaximum;
  classification.normals = lighting.shade;
  std::copy(transfer.gradientAxisScale, transfer.gradientAxisScale + 3,
    classification.gradientAxisScale);
  return true;
}

} // namespace

ShearWarpRenderer::Internals::~Internals()
{
  this->backgroundCancelled = true;
  this->FinishBackgroundEncodings();
}

double ShearWarpRenderer::Internals::FinishBackgroundEncodings()
{
  if (!this->background.joinable())
  {
    return 0;
  }
  const Clock::time_point start = Clock::now();
  this->background.join();
  return Seconds(start);
}

void ShearWarpRenderer::Internals::StartBackgroundEncodings(
  int dense, int axis, const EncodingKey& key)
{
  if (this->background.joinable())
  {
    if (this->backgroundRunning)
    {
      return; // one job at a time; a later frame starts the next
    }
    this->background.join(); // finished: at once
  }
  std::vector<int> missing;
  for (int other = 0; other < 3; ++other)
  {
    if (other != axis && !(this->composite[dense][other].key == key))
    {
      missing.push_back(other);
    }
  }
  if (missing.empty())
  {
    return;
  }
  this->backgroundKey = key;
  this->backgroundCancelled = false;
  this->backgroundRunning = true;
  this->background = std::thread(
    [this, dense, axis, key, missing]()
    {
      const RunLengthVolume<ShadedVoxel>& from = this->composite[dense][axis].encoded;
      struct Finished
      {
        std::atomic<bool>& running;
        ~Finished() { running = false; }
      } finished{ this->backgroundRunning };
      for (int other : missing)
      {
        if (this->backgroundCancelled)
        {
          return;
        }
        EncodingSlot<ShadedVoxel> slot;
        std::string error;
        try
        {
          if (!TransposeEncoding(from, other, slot.encoded, error))
          {
            return; // the frame that needs it encodes it and reports the error
          }
        }
        catch (const std::bad_alloc&)
        {
          return; // no room for another axis now: encoded when a frame needs it
        }
        slot.key = key;
        const std::lock_guard<std::mutex> lock(this->slotsMutex);
        this->composite[dense][other] = std::move(slot);
      }
    });
}

void ShearWarpRenderer::Internals::DropStaleEncodings(
  std::uint64_t volumeVersion, std::uint64_t transferVersion)
{
  if (this->background.joinable() &&
    (this->backgroundKey.volumeVersion != volumeVersion ||
      this->backgroundKey.transferVersion != transferVersion))
  {
    this->FinishBackgroundEncodings(); // its encodings are stale too: dropped below
  }
  auto stale = [&](const EncodingKey& key)
  {
    return key.valid &&
      (key.volumeVersion != volumeVersion || key.transferVersion != transferVersion);
  };
  // A job still running has these versions: it reads no slot dropped here, but it may publish
  // into one while the keys are read.
  const std::lock_guard<std::mutex> lock(this->slotsMutex);
  for (int d = 0; d < 2; ++d)
  {
    for (int a = 0; a < 3; ++a)
    {
      if (stale(this->composite[d][a].key))
      {
        this->composite[d][a] = EncodingSlot<ShadedVoxel>();
      }
      if (stale(this->extreme[d][a].key))
      {
        this->extreme[d][a] = EncodingSlot<ScalarVoxel>();
      }
    }
  }
}

bool ShearWarpRenderer::Internals::UpdateCompositeEncoding(const VolumeView& volume,
  double rangeMin, double rangeMax, const RayCastTransfer& transfer,
  const RayCastLighting& lighting, const ShearWarpView& view, EncodingKey key, int axis, int dense,
  const ParallelFor& encodeParallel, Clock::time_point encodeStart, ShearWarpStats& stats,
  std::string& error)
{
  key.normals = lighting.shade;
  EncodingSlot<ShadedVoxel>& slot = this->composite[dense][axis];
  bool ready = false;
  {
    const std::lock_guard<std::mutex> lock(this->slotsMutex);
    ready = slot.key == key;
  }
  if (!ready && this->background.joinable())
  {
    // The job may be building this axis, and must not read a slot while it changes.
    stats.encodeSeconds = this->FinishBackgroundEncodings();
    ready = slot.key == key;
  }
  if (!ready)
  {
    CompositeClassification classification;
    if (!MakeCompositeClassification(
          rangeMin, rangeMax, transfer, lighting, view, classification, error))
    {
      return false;
    }
    slot = EncodingSlot<ShadedVoxel>();
    if (!EncodeComposite(
          volume, classification, axis, dense != 0, encodeParallel, slot.encoded, error))
    {
      return false;
    }
    if (!classification.normals)
    {
      AssignPalette(
        slot.encoded, encodeParallel); // none when too many distinct voxels: converted per voxel
    }
    slot.key = key;
    stats.encodeSeconds = Seconds(encodeStart);
  }
  this->compositeSlot = &slot;
  if (this->settings.backgroundEncodings)
  {
    this->StartBackgroundEncodings(dense, axis, key);
  }
  return true;
}

bool ShearWarpRenderer::Internals::UpdateExtremeEncoding(const VolumeView& volume, double rangeMin,
  double rangeMax, const RayCastTransfer& transfer, bool maximum, EncodingKey key, int axis,
  int dense, const ParallelFor& encodeParallel, Clock::time_point encodeStart,
  ShearWarpStats& stats, std::string& error)
{
  key.maximum = maximum;
  key.threshold = VisibleThreshold(transfer.rgba, maximum);
  EncodingSlot<ScalarVoxel>& slot = this->extreme[dense][axis];
  if (!(slot.key == key))
  {
    slot = EncodingSlot<ScalarVoxel>();
    if (!EncodeExtreme(volume, rangeMin, rangeMax, maximum, key.threshold, axis, dense != 0,
          encodeParallel, slot.encoded, error))
    {
      return false;
    }
    slot.key = key;
    float extreme = maximum ? 0.0f : 65535.0f;
    for (ScalarVoxel value : slot.encoded.voxels)
    {
      extreme = maximum ? std::max(extreme, float(value)) : std::min(extreme, float(value));
    }
    slot.saturation = extreme;
    stats.encodeSeconds = Seconds(encodeStart);
  }
  this->extremeSlot = &slot;
  this->transfer = transfer.rgba;
  return true;
}

} // namespace accelvolume
