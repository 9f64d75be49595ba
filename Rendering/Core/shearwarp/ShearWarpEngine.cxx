// Shear-warp frames: encodings cached per axis, per-frame tables, banded compositing, warp.
#include "shearwarp/ShearWarpEngine.h"

#include "common/Unorm16.h"
#include "shearwarp/ShearWarpEngineInternals.h"

#include "shearwarp/RunLengthVolume.h"
#include "shearwarp/ShearWarpCompositor.h"
#include "shearwarp/ShearWarpPartition.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <thread>
#include <utility>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace accelvolume
{
namespace
{

template <typename Voxel>
const std::vector<std::uint32_t>& RowVoxels(EncodingSlot<Voxel>& slot)
{
  if (slot.rowVoxels.empty())
  {
    const auto& e = slot.encoded;
    slot.rowVoxels.resize(e.rowStart.size() - 1);
    for (std::size_t r = 0; r + 1 < e.rowStart.size(); ++r)
    {
      std::uint32_t count = 0;
      for (std::uint64_t q = e.rowStart[r]; q < e.rowStart[r + 1]; ++q)
      {
        count += e.runs[q].end - e.runs[q].begin;
      }
      slot.rowVoxels[r] = count;
    }
  }
  return slot.rowVoxels;
}

// The arguments BeginFrameReporting refuses before it factorizes the view.
bool CheckFrameArguments(const VolumeView& volume, double rangeMin, double rangeMax,
  const RayCastTransfer& transfer, const ShearWarpView& view, const ShearWarpSettings& settings,
  std::string& error)
{
  if (!volume.data || volume.dims[0] < 1 || volume.dims[1] < 1 || volume.dims[2] < 1)
  {
    error = "shear-warp: the volume is empty";
    return false;
  }
  if (view.width < 1 || view.height < 1)
  {
    error = "shear-warp: the image has no pixels";
    return false;
  }
  if (transfer.rgba.size() < 8 || transfer.rgba.size() % 4 != 0)
  {
    error = "shear-warp: the transfer function table needs at least 2 RGBA entries";
    return false;
  }
  if (!std::isfinite(rangeMin) || !std::isfinite(rangeMax) || settings.bands < 1 ||
    !(transfer.opacityUnitDistance > 0))
  {
    error = "shear-warp: bad scalar range, band count or opacity unit distance";
    return false;
  }
  if (settings.blend == Blend::Additive || settings.blend == Blend::Average ||
    settings.blend == Blend::Slice || settings.blend == Blend::Isosurface)
  {
    error = "shear-warp: additive, average, slice and isosurface blending are not supported";
    return false;
  }
  return true;
}

// The shading part of the per-frame tables: lighting coefficients, lights and normal matrix.
void SetShading(
  const RayCastLighting& lighting, const ShearWarpSettings& settings, CompositeTables& t)
{
  t.shade = lighting.shade;
  t.phong = settings.shading == ShearWarpShading::Phong;
  t.lighting = lighting.model;
  // Positional lights at the volume's centre: the shading table is per normal, not per voxel.
  for (int r = 0; r < 3; ++r)
  {
    t.lightingPoint[r] = static_cast<float>(lighting.centre[r]);
  }
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      t.normalMatrix[r][c] = static_cast<float>(lighting.normalMatrix[r][c]);
    }
  }
}
}

std::vector<double> ShearWarpRenderer::Internals::EstimateCosts()
{
  const ShearWarpFactorization& f = this->factorization;
  const std::vector<std::uint32_t>& rows =
    this->compositeSlot ? RowVoxels(*this->compositeSlot) : RowVoxels(*this->extremeSlot);
  const int height = f.intermediateSize[1];
  std::vector<double> cost(static_cast<std::size_t>(height), 0.0);
  const int nj = f.sliceDims[1];
  for (int k = 0; k < f.sliceDims[2]; ++k)
  {
    double offset[2];
    f.SliceOffset(k, offset);
    const int shift = static_cast<int>(std::floor(offset[1]));
    for (int j = 0; j < nj; ++j)
    {
      // Scanline j serves intermediate rows j + shift (as row 1) and j + shift + 1 (as row 0).
      const double c = 1.0 + rows[static_cast<std::size_t>(j) + static_cast<std::size_t>(nj) * k];
      cost[j + shift] += c;
      if (j + shift + 1 < height)
      {
        cost[j + shift + 1] += c;
      }
    }
  }
  return cost;
}

void ShearWarpRenderer::Internals::ClassifyExtremeRow(const float* values, float* rgba) const
{
  const int width = this->factorization.intermediateSize[0];
  const int n = static_cast<int>(this->transfer.size() / 4);
  const float scale = static_cast<float>(n - 1) / 65535.0f;
  for (int u = 0; u < width; ++u)
  {
    float* out = rgba + 4 * static_cast<std::size_t>(u);
    const float value = values[u];
    if (!std::isfinite(value))
    {
      out[0] = out[1] = out[2] = out[3] = 0;
      continue;
    }
    const float x = std::min(std::max(value * scale, 0.0f), static_cast<float>(n - 1));
    const int e = std::min(static_cast<int>(x), n - 2);
    const float t = x - static_cast<float>(e);
    const float* lo = &this->transfer[4 * static_cast<std::size_t>(e)];
    const float opacity = lo[3] + (lo[7] - lo[3]) * t;
    for (int c = 0; c < 3; ++c)
    {
      out[c] = (lo[c] + (lo[c + 4] - lo[c]) * t) * opacity;
    }
    out[3] = opacity;
  }
}

int DistinctWorkers(std::vector<std::thread::id> bandWorker)
{
  std::sort(bandWorker.begin(), bandWorker.end());
  return static_cast<int>(std::unique(bandWorker.begin(), bandWorker.end()) - bandWorker.begin());
}

namespace
{
// The busiest worker's compositing time over the mean per worker (`workers` of them; one that
// took no band counts as idle): the imbalance of the frame, whatever the band count.
double WorkerImbalance(const std::vector<double>& bandSeconds,
  const std::vector<std::thread::id>& bandWorker, int workers)
{
  std::vector<std::pair<std::thread::id, double>> busy;
  double total = 0;
  for (std::size_t b = 0; b < bandSeconds.size(); ++b)
  {
    total += bandSeconds[b];
    auto it = std::find_if(busy.begin(), busy.end(),
      [&](const std::pair<std::thread::id, double>& w) { return w.first == bandWorker[b]; });
    if (it == busy.end())
    {
      busy.emplace_back(bandWorker[b], bandSeconds[b]);
    }
    else
    {
      it->second += bandSeconds[b];
    }
  }
  double slowest = 0;
  for (const auto& w : busy)
  {
    slowest = std::max(slowest, w.second);
  }
  return total > 0 ? slowest / (total / std::max<int>(workers, static_cast<int>(busy.size())))
                   : 1.0;
}
}

ShearWarpRenderer::ShearWarpRenderer()
  : Impl(new Internals)
{
}

ShearWarpRenderer::~ShearWarpRenderer() = default;

void ShearWarpRenderer::SetProgressFunction(ProgressFunction report)
{
  this->Impl->progress = std::move(report);
}

void ShearWarpRenderer::SetRowsReadyFunction(RowsReadyFunction ready)
{
  this->Impl->rowsReady = std::move(ready);
}

bool ShearWarpRenderer::BeginFrame(const VolumeView& volume, double rangeMin, double rangeMax,
  std::uint64_t volumeVersion, const RayCastTransfer& transfer, std::uint64_t transferVersion,
  const RayCastLighting& lighting, const ShearWarpView& view, const ShearWarpSettings& settings,
  const ParallelFor& parallel, ShearWarpStats& stats, std::string& error)
{
  return this->BeginFrameReporting(volume, rangeMin, rangeMax, volumeVersion, transfer,
    transferVersion, lighting, view, settings, parallel, this->Impl->progress, stats, error);
}

void ShearWarpRenderer::Internals::UpdateTables(const RayCastTransfer& transfer,
  const RayCastLighting& lighting, const ShearWarpView& view, const ShearWarpSettings& settings,
  const ParallelFor& parallel)
{
  const ShearWarpFactorization& f = this->factorization;
  CompositeTables& t = this->tables;
  t.earlyTermination = settings.earlyTermination;
  t.terminationLinks = settings.earlyTermination;
  t.terminationThreshold = static_cast<float>(settings.terminationThreshold);
  if (settings.blend != Blend::Composite)
  {
    return;
  }
  double world[3];
  for (int r = 0; r < 3; ++r)
  {
    world[r] = view.indexToWorld[r][0] * f.rayStep[0] + view.indexToWorld[r][1] * f.rayStep[1] +
      view.indexToWorld[r][2] * f.rayStep[2];
  }
  const double ratio = std::sqrt(world[0] * world[0] + world[1] * world[1] + world[2] * world[2]) /
    transfer.opacityUnitDistance;
  if (ratio != this->opacityRatio || t.opacity.size() != OpacityLevels + 1)
  {
    t.opacity.resize(OpacityLevels + 1);
    // In parallel, like the shading table: a turning view changes the ray length every frame,
    // and serial work here caps the speed-up of every core count.
    parallel(OpacityLevels + 1,
      [&](std::size_t begin, std::size_t end)
      {
        for (std::size_t q = begin; q < end; ++q)
        {
          t.opacity[q] = static_cast<float>(1.0 - std::pow(1.0 - q / double(OpacityLevels), ratio));
        }
      });
    this->opacityRatio = ratio;
  }
  SetShading(lighting, settings, t);
  if (t.shade && !t.phong)
  {
    BuildShadingTable(t, parallel);
  }
  // Every frame, like the opacity table it depends on: one conversion per distinct voxel.
  if (this->compositeSlot)
  {
    BuildPaletteColours(this->compositeSlot->encoded.palette, t, parallel);
  }
  else
  {
    t.paletteColours.clear();
  }
}

void ShearWarpRenderer::Internals::StartFrame(int axis, ShearWarpStats& stats)
{
  const ShearWarpFactorization& f = this->factorization;
  const std::size_t pixels = static_cast<std::size_t>(f.intermediateSize[0]) *
    static_cast<std::size_t>(f.intermediateSize[1]);
  // Resized only: each band clears its own rows (in parallel) before compositing them.
  this->intermediate.resize(4 * pixels);
  this->displayReady = false;
  this->scanlineSeconds.assign(static_cast<std::size_t>(f.intermediateSize[1]), 0.0);
  this->voxels = 0;
  this->samples = 0;
  this->terminatedPixelVisits = 0;
  stats.principalAxis = axis;
  stats.intermediateSize[0] = f.intermediateSize[0];
  stats.intermediateSize[1] = f.intermediateSize[1];
  if (this->compositeSlot)
  {
    stats.storedVoxels = this->compositeSlot->encoded.StoredVoxels();
    stats.runs = this->compositeSlot->encoded.runs.size();
  }
  else
  {
    stats.storedVoxels = this->extremeSlot->encoded.voxels.size();
    stats.runs = this->extremeSlot->encoded.runs.size();
  }
}

void ShearWarpRenderer::Internals::PrepareDisplayPixels()
{
  const std::size_t paddedWidth = static_cast<std::size_t>(this->factorization.intermediateSize[0]) + 1;
  const std::size_t rows = static_cast<std::size_t>(this->factorization.intermediateSize[1]);
  this->displayPixels.resize(4 * paddedWidth * (rows + 1));
  // The padding row; each band writes its rows' padding column.
  std::fill(this->displayPixels.end() - static_cast<std::ptrdiff_t>(4 * paddedWidth),
    this->displayPixels.end(), std::uint16_t(0));
  this->displayRowFirst.resize(rows);
  this->displayRowLast.resize(rows);
}

void ShearWarpRenderer::Internals::ConvertRowsForDisplay(int v0, int v1)
{
  ConvertRowsPadded(this->intermediate.data(), this->factorization.intermediateSize[0], v0, v1,
    this->displayPixels.data(), this->displayRowFirst.data(), this->displayRowLast.data());
}

bool ShearWarpRenderer::BeginFrameReporting(const VolumeView& volume, double rangeMin,
  double rangeMax, std::uint64_t volumeVersion, const RayCastTransfer& transfer,
  std::uint64_t transferVersion, const RayCastLighting& lighting, const ShearWarpView& view,
  const ShearWarpSettings& settings, const ParallelFor& parallel,
  const ProgressFunction& encodeProgress, ShearWarpStats& stats, std::string& error)
{
  Internals& impl = *this->Impl;
  stats = ShearWarpStats();
  impl.compositeSlot = nullptr;
  impl.extremeSlot = nullptr;
  if (!CheckFrameArguments(volume, rangeMin, rangeMax, transfer, view, settings, error) ||
    !FactorizeShearWarp(view.voxelToImage, volume.dims, impl.factorization, error))
  {
    return false;
  }
  const ShearWarpFactorization& f = impl.factorization;
  impl.settings = settings;
  impl.imageSize[0] = view.width;
  impl.imageSize[1] = view.height;
  const int axis = f.axes[2];
  const int dense = settings.runLengthEncoding ? 0 : 1;
  const bool composite = settings.blend == Blend::Composite;
  const bool maximum = settings.blend == Blend::Maximum;

  impl.DropStaleEncodings(volumeVersion, transferVersion);

  EncodingKey key;
  key.valid = true;
  key.volumeVersion = volumeVersion;
  key.transferVersion = transferVersion;
  const Clock::time_point encodeStart = Clock::now();
  // With progress: the slices as they are encoded, reported by this thread.
  const ParallelFor encodeParallel = ReportingParallelFor(parallel, encodeProgress);
  const bool encoded = composite
    ? impl.UpdateCompositeEncoding(volume, rangeMin, rangeMax, transfer, lighting, view, key, axis,
        dense, encodeParallel, encodeStart, stats, error)
    : impl.UpdateExtremeEncoding(volume, rangeMin, rangeMax, transfer, maximum, key, axis, dense,
        encodeParallel, encodeStart, stats, error);
  if (!encoded)
  {
    return false;
  }

  const Clock::time_point tableStart = Clock::now();
  impl.UpdateTables(transfer, lighting, view, settings, parallel);
  stats.tableSeconds = Seconds(tableStart);

  impl.StartFrame(axis, stats);
  stats.encodedBytes = this->GetEncodedBytes();
  return true;
}

std::vector<int> ShearWarpRenderer::Bands(int parts, bool balance) const
{
  Internals& impl = *this->Impl;
  const int height = impl.factorization.intermediateSize[1];
  if (!balance || parts <= 1)
  {
    return EqualBands(height, parts);
  }
  if (impl.costAxis == impl.factorization.axes[2] && !impl.costs.empty())
  {
    const bool same = static_cast<int>(impl.costs.size()) == height;
    return BalanceBands(same ? impl.costs : ResampleCosts(impl.costs, height), parts);
  }
  // No measured frame for this axis yet: stored voxels per scanline stand in for time.
  return BalanceBands(impl.EstimateCosts(), parts);
}

void ShearWarpRenderer::CompositeRows(int v0, int v1)
{
  Internals& impl = *this->Impl;
  const ShearWarpFactorization& f = impl.factorization;
  const int width = f.intermediateSize[0];
  v0 = std::max(v0, 0);
  v1 = std::min(v1, f.intermediateSize[1]);
  if (v1 <= v0)
  {
    return;
  }
  const Clock::time_point start = Clock::now();
  ScanlineWorkspace workspace;
  ScanlineCounters counters;
  std::vector<double> work(static_cast<std::size_t>(v1 - v0), 0.0);
  float* rows = impl.intermediate.data() + 4 * static_cast<std::size_t>(width) * v0;
  std::fill(rows, rows + 4 * static_cast<std::size_t>(width) * (v1 - v0), 0.0f);
  if (impl.compositeSlot)
  {
    CompositeBand(
      impl.compositeSlot->encoded, f, impl.tables, v0, v1, rows, workspace, counters, work.data());
  }
  else
  {
    const bool maximum = impl.settings.blend == Blend::Maximum;
    std::vector<float> values(static_cast<std::size_t>(width) * (v1 - v0),
      maximum ? -std::numeric_limits<float>::infinity() : std::numeric_limits<float>::infinity());
    ExtremeBand(impl.extremeSlot->encoded, f, maximum, impl.extremeSlot->saturation,
      impl.settings.earlyTermination, v0, v1, values.data(), workspace, counters, work.data());
    for (int v = v0; v < v1; ++v)
    {
      impl.ClassifyExtremeRow(values.data() + static_cast<std::size_t>(width) * (v - v0),
        rows + 4 * static_cast<std::size_t>(width) * (v - v0));
    }
  }
  // The band's time, shared out over its scanlines by the work each took.
  const double seconds = Seconds(start);
  double total = 0;
  for (double w : work)
  {
    total += w;
  }
  for (int v = v0; v < v1; ++v)
  {
    impl.scanlineSeconds[v] =
      total > 0 ? seconds * work[v - v0] / total : seconds / static_cast<double>(v1 - v0);
  }
  impl.voxels += counters.voxels;
  impl.samples += counters.samples;
  impl.terminatedPixelVisits += counters.terminatedPixelVisits;
}

void ShearWarpRenderer::Warp(
  const ParallelFor& parallel, std::vector<float>& rgba, int rectangle[4])
{
  Internals& impl = *this->Impl;
  const ShearWarpFactorization& f = impl.factorization;
  const int width = impl.imageSize[0];
  const int height = impl.imageSize[1];
  // Every pixel is written below (zero outside the warped image), so no clearing pass first.
  rgba.resize(4 * static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  const int iw = f.intermediateSize[0];
  const int ih = f.intermediateSize[1];
  WarpedRectangle(f, width, height, rectangle);
  if (rectangle[1] < rectangle[0] || rectangle[3] < rectangle[2])
  {
    std::fill(rgba.begin(), rgba.end(), 0.0f);
    return;
  }
  const float* image = impl.intermediate.data();
  const double(*m)[3] = f.inverseWarp;
  const int x0 = rectangle[0];
  const int x1 = rectangle[1];
  // Every row, so that the rows outside the rectangle are cleared in parallel too.
  parallel(static_cast<std::size_t>(height),
    [&](std::size_t begin, std::size_t end)
    {
      for (std::size_t row = begin; row < end; ++row)
      {
        const int y = static_cast<int>(row);
        float* out = rgba.data() + 4 * (static_cast<std::size_t>(y) * width);
        if (y < rectangle[2] || y > rectangle[3])
        {
          std::fill(out, out + 4 * static_cast<std::size_t>(width), 0.0f);
          continue;
        }
        // (u, v) of pixel x's centre is (uStart + x du, vStart + x dv): linear along the row.
        const double uStart = m[0][0] * 0.5 + m[0][1] * (y + 0.5) + m[0][2];
        const double vStart = m[1][0] * 0.5 + m[1][1] * (y + 0.5) + m[1][2];
        const double du = m[0][0];
        const double dv = m[1][0];
        // Only x with u in (-1, iw) and v in (-1, ih) meet the intermediate image.
        double lowX = x0;
        double highX = x1;
        auto clip = [&](double start, double step, double limit)
        {
          if (step == 0)
          {
            if (!(start > -1.0 && start < limit))
            {
              highX = lowX - 1;
            }
            return;
          }
          double a = (-1.0 - start) / step;
          double b = (limit - start) / step;
          if (a > b)
          {
            std::swap(a, b);
          }
          lowX = std::max(lowX, std::floor(a));
          highX = std::min(highX, std::ceil(b));
        };
        clip(uStart, du, iw);
        clip(vStart, dv, ih);
        if (!(lowX <= highX)) // also keeps huge bounds (a nearly constant u) from the casts
        {
          std::fill(out, out + 4 * static_cast<std::size_t>(width), 0.0f);
          continue;
        }
        const int first = static_cast<int>(lowX);
        const int last = static_cast<int>(highX);
        std::fill(out, out + 4 * static_cast<std::size_t>(first), 0.0f);
        std::fill(out + 4 * static_cast<std::size_t>(last + 1),
          out + 4 * static_cast<std::size_t>(width), 0.0f);
        for (int x = first; x <= last; ++x)
        {
          // Shifted by one so the truncation is a floor (u, v > -1 here).
          const double u = uStart + du * x + 1.0;
          const double v = vStart + dv * x + 1.0;
          const int u1 = static_cast<int>(u);
          const int v1 = static_cast<int>(v);
          const int u0 = u1 - 1;
          const int v0 = v1 - 1;
          const float a = static_cast<float>(u - u1);
          const float b = static_cast<float>(v - v1);
          float* pixel = out + 4 * static_cast<std::size_t>(x);
          if (u0 >= 0 && v0 >= 0 && u0 + 1 < iw && v0 + 1 < ih)
          {
            const float* p00 = image + 4 * (static_cast<std::size_t>(v0) * iw + u0);
            const float* p10 = p00 + 4 * static_cast<std::size_t>(iw);
#if defined(__SSE2__)
            const __m128 wa = _mm_set1_ps(a);
            const __m128 bottom0 = _mm_loadu_ps(p00);
            const __m128 top0 = _mm_loadu_ps(p10);
            const __m128 bottom =
              _mm_add_ps(bottom0, _mm_mul_ps(wa, _mm_sub_ps(_mm_loadu_ps(p00 + 4), bottom0)));
            const __m128 top =
              _mm_add_ps(top0, _mm_mul_ps(wa, _mm_sub_ps(_mm_loadu_ps(p10 + 4), top0)));
            _mm_storeu_ps(
              pixel, _mm_add_ps(bottom, _mm_mul_ps(_mm_set1_ps(b), _mm_sub_ps(top, bottom))));
#else
            for (int c = 0; c < 4; ++c)
            {
              const float bottom = p00[c] + a * (p00[c + 4] - p00[c]);
              const float top = p10[c] + a * (p10[c + 4] - p10[c]);
              pixel[c] = bottom + b * (top - bottom);
            }
#endif
            continue;
          }
          // The image's one-pixel fringe: taps outside it are transparent.
          pixel[0] = pixel[1] = pixel[2] = pixel[3] = 0.0f;
          const float weights[4] = { (1 - a) * (1 - b), a * (1 - b), (1 - a) * b, a * b };
          for (int q = 0; q < 4; ++q)
          {
            const int uu = u0 + (q & 1);
            const int vv = v0 + (q >> 1);
            if (uu < 0 || vv < 0 || uu >= iw || vv >= ih)
            {
              continue;
            }
            const float* source = image + 4 * (static_cast<std::size_t>(vv) * iw + uu);
            for (int c = 0; c < 4; ++c)
            {
              pixel[c] += weights[q] * source[c];
            }
          }
        }
      }
    });
}

bool ShearWarpRenderer::Render(const VolumeView& volume, double rangeMin, double rangeMax,
  std::uint64_t volumeVersion, const RayCastTransfer& transfer, std::uint64_t transferVersion,
  const RayCastLighting& lighting, const ShearWarpView& view, const ShearWarpSettings& settings,
  const ParallelFor& parallel, std::vector<float>& rgba, int rectangle[4], ShearWarpStats& stats,
  std::string& error)
{
  // Shares of the frame's progress: the encoding (when this frame encodes), then compositing.
  constexpr double EncodeShare = 0.8;
  constexpr double CompositeEnd = 0.95;
  const ProgressFunction& progress = this->Impl->progress;
  if (!this->BeginFrameReporting(volume, rangeMin, rangeMax, volumeVersion, transfer,
        transferVersion, lighting, view, settings, parallel,
        ProgressRange(progress, 0.0, EncodeShare), stats, error))
  {
    return false;
  }
  const Clock::time_point compositeStart = Clock::now();
  // More bands than workers, taken dynamically (the ParallelFor hands out one band at a time):
  // a band that the previous frame's costs misjudged delays its worker by a fraction of a
  // worker's share, not by the whole error.
  // Bands are also kept small enough that their intermediate pixels, swept once per slice,
  // stay in a core's cache (a band composites every slice before the next band starts).
  const int workers = std::max(settings.bands, 1);
  const ShearWarpFactorization& f = this->Impl->factorization;
  const std::size_t pixelBytes = settings.blend == Blend::Composite ? 4 * sizeof(float) : sizeof(float);
  const std::size_t imageBytes = pixelBytes * static_cast<std::size_t>(f.intermediateSize[0]) *
    static_cast<std::size_t>(std::max(f.intermediateSize[1], 0));
  const int cacheParts = static_cast<int>(std::min<std::size_t>(
    (imageBytes + BandCacheBytes - 1) / BandCacheBytes, std::max(f.intermediateSize[1], 1)));
  const int parts = std::max(workers > 1 ? workers * BandsPerWorker : 1, cacheParts);
  const std::vector<int> bounds = this->Bands(parts, settings.balance);
  const int bands = static_cast<int>(bounds.size()) - 1;
  stats.bandSeconds.assign(static_cast<std::size_t>(bands), 0.0);
  std::vector<std::thread::id> bandWorker(static_cast<std::size_t>(bands));
  Internals& impl = *this->Impl;
  const bool display = settings.displayPixels && !settings.warp;
  if (display)
  {
    impl.PrepareDisplayPixels();
  }
  const auto compositeBands = [&](std::size_t begin, std::size_t end)
  {
    for (std::size_t b = begin; b < end; ++b)
    {
      const Clock::time_point start = Clock::now();
      this->CompositeRows(bounds[b], bounds[b + 1]);
      if (display)
      {
        impl.ConvertRowsForDisplay(
          std::max(bounds[b], 0), std::min(bounds[b + 1], f.intermediateSize[1]));
      }
      stats.bandSeconds[b] = Seconds(start);
      bandWorker[b] = std::this_thread::get_id();
    }
  };
  if (display && workers == 1 && impl.rowsReady)
  {
    // One worker: the bands in order here, each shown by the caller while the next composites.
    impl.displayReady = true;
    const ShearWarpDisplayPixels pixels = this->GetDisplayPixels();
    for (int b = 0; b < bands; ++b)
    {
      compositeBands(static_cast<std::size_t>(b), static_cast<std::size_t>(b) + 1);
      const Clock::time_point shown = Clock::now();
      impl.rowsReady(pixels, std::clamp(bounds[b + 1], 0, f.intermediateSize[1]));
      stats.rowsShownSeconds += Seconds(shown);
    }
  }
  else
  {
    parallel(static_cast<std::size_t>(bands), compositeBands);
  }
  stats.compositeSeconds = Seconds(compositeStart) - stats.rowsShownSeconds;
  impl.displayReady = display;
  stats.bandBounds = bounds;
  stats.imbalance = WorkerImbalance(stats.bandSeconds, bandWorker, workers);
  stats.workers = DistinctWorkers(bandWorker);
  this->SetScanlineCosts(this->Impl->scanlineSeconds);
  this->GetCounters(stats);
  if (progress)
  {
    progress(CompositeEnd);
  }
  if (settings.warp)
  {
    const Clock::time_point warpStart = Clock::now();
    this->Warp(parallel, rgba, rectangle);
    stats.warpSeconds = Seconds(warpStart);
  }
  else
  {
    WarpedRectangle(this->Impl->factorization, view.width, view.height, rectangle);
  }
  if (progress)
  {
    progress(1.0);
  }
  return true;
}

void WarpedRectangle(const ShearWarpFactorization& f, int width, int height, int rectangle[4])
{
  const int iw = f.intermediateSize[0];
  const int ih = f.intermediateSize[1];
  double lower[2] = { std::numeric_limits<double>::infinity(),
    std::numeric_limits<double>::infinity() };
  double upper[2] = { -lower[0], -lower[1] };
  for (int corner = 0; corner < 4; ++corner)
  {
    const double u = (corner & 1) ? iw : -1.0;
    const double v = (corner & 2) ? ih : -1.0;
    for (int r = 0; r < 2; ++r)
    {
      const double x = f.warp[r][0] * u + f.warp[r][1] * v + f.warp[r][2];
      lower[r] = std::min(lower[r], x);
      upper[r] = std::max(upper[r], x);
    }
  }
  rectangle[0] = static_cast<int>(std::max(0.0, std::floor(lower[0])));
  rectangle[1] = static_cast<int>(std::min(width - 1.0, std::ceil(upper[0])));
  rectangle[2] = static_cast<int>(std::max(0.0, std::floor(lower[1])));
  rectangle[3] = static_cast<int>(std::min(height - 1.0, std::ceil(upper[1])));
  if (rectangle[1] < rectangle[0] || rectangle[3] < rectangle[2])
  {
    rectangle[0] = rectangle[2] = 0;
    rectangle[1] = rectangle[3] = -1;
  }
}

void ParallelVoxelToImage(const double indexToWorld[3][4], const double worldToView[4][4],
  double parallelScale, int width, int height, double voxelToImage[3][4])
{
  // View coordinates: x right, y up, the camera looking down -z; a parallel projection shows
  // [-scale * aspect, scale * aspect] x [-scale, scale].
  const double aspect = static_cast<double>(width) / height;
  const double scale[3] = { width / (2.0 * parallelScale * aspect), height / (2.0 * parallelScale),
    -1.0 };
  const double offset[3] = { width / 2.0, height / 2.0, 0.0 };
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      double value = c == 3 ? worldToView[r][3] : 0.0;
      for (int q = 0; q < 3; ++q)
      {
        value += worldToView[r][q] * indexToWorld[q][c];
      }
      voxelToImage[r][c] = scale[r] * value + (c == 3 ? offset[r] : 0.0);
    }
  }
}

const ShearWarpFactorization& ShearWarpRenderer::GetFactorization() const
{
  return this->Impl->factorization;
}

float* ShearWarpRenderer::GetIntermediateImage()
{
  return this->Impl->intermediate.data();
}

ShearWarpDisplayPixels ShearWarpRenderer::GetDisplayPixels() const
{
  const Internals& impl = *this->Impl;
  ShearWarpDisplayPixels pixels;
  if (impl.displayReady)
  {
    pixels.rgba = impl.displayPixels.data();
    pixels.width = impl.factorization.intermediateSize[0] + 1;
    pixels.height = impl.factorization.intermediateSize[1] + 1;
    pixels.rowFirst = impl.displayRowFirst.data();
    pixels.rowLast = impl.displayRowLast.data();
  }
  return pixels;
}

const std::vector<double>& ShearWarpRenderer::GetScanlineSeconds() const
{
  return this->Impl->scanlineSeconds;
}

void ShearWarpRenderer::SetScanlineCosts(const std::vector<double>& seconds)
{
  this->Impl->costs = seconds;
  this->Impl->costAxis = this->Impl->factorization.axes[2];
}

void ShearWarpRenderer::GetCounters(ShearWarpStats& stats) const
{
  stats.voxels = this->Impl->voxels;
  stats.samples = this->Impl->samples;
  stats.terminatedPixelVisits = this->Impl->terminatedPixelVisits;
}

void ShearWarpRenderer::FinishBackgroundEncodings()
{
  this->Impl->FinishBackgroundEncodings();
}

std::size_t ShearWarpRenderer::GetEncodedBytes() const
{
  const std::lock_guard<std::mutex> lock(this->Impl->slotsMutex); // background publications
  std::size_t bytes = 0;
  for (int d = 0; d < 2; ++d)
  {
    for (int a = 0; a < 3; ++a)
    {
      bytes += this->Impl->composite[d][a].encoded.Bytes();
      bytes += this->Impl->extreme[d][a].encoded.Bytes();
    }
  }
  return bytes;
}

}
