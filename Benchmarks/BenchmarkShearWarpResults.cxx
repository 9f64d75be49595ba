// Configurations, per-case results and their JSON of accelvolume_benchmark_shearwarp (see
// BenchmarkShearWarpResults.h).
#include "BenchmarkShearWarpResults.h"

#include "shearwarp/ShearWarpEngine.h" // BandsPerWorker
#include "shearwarp/ShearWarpPartition.h"

#include <algorithm>
#include <numeric>

namespace accelvolume::benchmark::shearwarp
{
namespace
{
Json ErrorsJson(const ErrorStats& e)
{
  return { { "rms", Round(e.Rms(), 3) }, { "max", Round(e.Max, 1) }, { "pixels", e.Pixels } };
}

// true / false against the target, null when the value is unknown.
Json Met(double value, bool met)
{
  return std::isfinite(value) ? Json(met) : Json(nullptr);
}

// The numbers of a JSON list (NaN for null).
std::vector<double> Numbers(const Json& object, const char* key)
{
  std::vector<double> values;
  const auto found = object.find(key);
  if (found != object.end() && found->is_array())
  {
    for (const Json& item : *found)
    {
      values.push_back(item.is_number() ? item.get<double>() : std::nan(""));
    }
  }
  return values;
}

double Number(const Json& object, const char* key)
{
  const auto found = object.find(key);
  return found != object.end() && found->is_number() ? found->get<double>() : std::nan("");
}
} // namespace

std::vector<Config> MakeConfigs(bool shade)
{
  std::vector<Config> configs = {
    { "dense", "(1) no RLE", 1, false, false, false, false },
    { "rle", "(2) RLE+ERT, equal", 2, true, true, false, false },
    { "balanced", "(3) RLE+ERT+balance", 3, true, true, true, false },
  };
  if (shade)
  {
    configs.push_back({ "phong", "(3) Phong per voxel", 3, true, true, true, true });
  }
  return configs;
}

double RunResult::MeanImbalance() const
{
  if (this->Imbalance.empty())
  {
    return std::nan("");
  }
  return std::accumulate(this->Imbalance.begin(), this->Imbalance.end(), 0.0) /
    static_cast<double>(this->Imbalance.size());
}

double PairedRatio(const std::vector<double>& a, const std::vector<double>& b)
{
  std::vector<double> ratios;
  for (size_t f = 0; f < a.size() && f < b.size(); ++f)
  {
    if (b[f] > 0 && std::isfinite(a[f]))
    {
      ratios.push_back(a[f] / b[f]);
    }
  }
  return ratios.empty() ? std::nan("") : Median(ratios);
}

std::string CaseKey(const std::string& dataset, const std::string& tf, bool shade, int size)
{
  return dataset + "/" + tf + "/" + (shade ? "shaded" : "unshaded") + "/" + std::to_string(size);
}

std::string CaseResult::Key() const
{
  return CaseKey(this->Dataset, this->Tf, this->Shade, this->Size);
}

const RunResult* CaseResult::Find(const std::string& id, int threads) const
{
  for (const RunResult& r : this->Runs)
  {
    if (r.Cfg.Id == id && r.Threads == threads)
    {
      return &r;
    }
  }
  return nullptr;
}

const RunResult* CaseResult::FindMpi(int ranks) const
{
  for (const RunResult& r : this->Mpi)
  {
    if (r.Ranks == ranks)
    {
      return &r;
    }
  }
  return nullptr;
}

double CaseResult::Efficiency(const std::string& id) const
{
  const RunResult* one = this->Find(id, 1);
  const RunResult* all = this->Find(id, this->Threads);
  if (!one || !all || this->Threads < 2)
  {
    return std::nan("");
  }
  return PairedRatio(one->RenderMs, all->RenderMs) / this->Threads;
}

double CaseResult::MpiEfficiency() const
{
  const RunResult* one = this->FindMpi(1);
  const RunResult* most = nullptr;
  for (const RunResult& r : this->Mpi)
  {
    most = r.Ranks > 1 && (!most || r.Ranks > most->Ranks) ? &r : most;
  }
  if (!one || !most)
  {
    return std::nan("");
  }
  return SafeRatio(one->MedianMs(), most->Ranks * most->MedianMs());
}

double CaseResult::ModelImbalance(int parts, int bandsPerWorker) const
{
  const RunResult* one = this->Find("balanced", 1);
  if (!one || one->ScanlineMs.size() < 2)
  {
    return std::nan("");
  }
  std::vector<double> imbalances;
  for (std::size_t f = 1; f < one->ScanlineMs.size(); ++f)
  {
    const std::vector<double>& now = one->ScanlineMs[f];
    const int bands = parts * bandsPerWorker;
    const std::vector<int> bounds = accelvolume::BalanceBands(
      accelvolume::ResampleCosts(one->ScanlineMs[f - 1], static_cast<int>(now.size())), bands);
    std::vector<double> load(static_cast<std::size_t>(parts), 0.0);
    for (int b = 0; b < bands; ++b)
    {
      double cost = 0;
      for (int v = bounds[b]; v < bounds[b + 1]; ++v)
      {
        cost += now[v];
      }
      *std::min_element(load.begin(), load.end()) += cost; // the first core free takes it
    }
    imbalances.push_back(accelvolume::Imbalance(load));
  }
  return Median(imbalances);
}

double CaseResult::ModelSpeedup(int parts, int bandsPerWorker) const
{
  const RunResult* one = this->Find("balanced", 1);
  const double imbalance = this->ModelImbalance(parts, bandsPerWorker);
  if (!one || !std::isfinite(imbalance))
  {
    return std::nan("");
  }
  const double total = one->MedianMs();
  const double composite = Median(one->CompositeMs);
  const double tables = Median(one->TableMs); // built in parallel too, evenly
  // Several threads draw the image at once after compositing, not in parts meanwhile: the
  // parts' drawing is not serial work of theirs (their one draw is in what remains).
  const double imageParts = one->ImagePartsMs.empty() ? 0.0 : Median(one->ImagePartsMs);
  return SafeRatio(total,
    total - composite - tables - imageParts + (composite * imbalance + tables) / parts);
}

double CaseResult::VolPackRatio(bool wholeFrame, int threads) const
{
  const RunResult* ours = this->Find("balanced", threads);
  return this->VolPack.Ran && ours
    ? PairedRatio(this->VolPack.RenderMs, wholeFrame ? ours->WallMs : ours->EngineMs)
    : std::nan("");
}

bool CaseResult::ChecksOk() const
{
  return std::all_of(this->Checks.begin(), this->Checks.end(),
           [](const ImageCheck& c) { return c.Ok(); }) &&
    std::all_of(this->Runs.begin(), this->Runs.end(),
      [](const RunResult& r)
      {
        return std::all_of(r.Workers.begin(), r.Workers.end(),
          [&](double workers) { return workers <= r.Threads; });
      });
}

Json RunJson(const RunResult& r)
{
  const Config& g = r.Cfg;
  return { { "id", g.Id }, { "label", g.Label }, { "experiment", g.Experiment }, { "rle", g.Rle },
    { "ert", g.Ert }, { "balance", g.Balance }, { "phong", g.Phong }, { "threads", r.Threads },
    { "ranks", r.Ranks }, { "median_ms", Round(r.MedianMs(), 3) },
    { "median_engine_ms", Round(r.MedianEngineMs(), 3) },
    { "median_wall_ms", Round(Median(r.WallMs), 3) },
    { "median_composite_ms", Round(Median(r.CompositeMs), 3) },
    { "median_warp_ms", Round(Median(r.WarpMs), 3) },
    { "median_table_ms", Round(Median(r.TableMs), 3) },
    { "median_gather_ms", Round(Median(r.GatherMs), 3) },
    { "mean_imbalance", Round(r.MeanImbalance(), 4) },
    { "median_cores", Round(Median(r.Cores), 2) }, { "first_frame_ms", Round(r.FirstFrameMs, 2) },
    { "encode_ms", Round(r.EncodeMs, 2) }, { "stored_voxels", r.StoredVoxels },
    { "encoded_bytes", r.EncodedBytes }, { "principal_axis", r.Axis }, { "bands", r.Bands },
    { "voxels_per_frame", Round(r.Voxels, 0) }, { "samples_per_frame", Round(r.Samples, 0) },
    { "skipped_pixels_per_frame", Round(r.SkippedPixels, 0) },
    { "render_ms", RoundAll(r.RenderMs, 3) }, { "engine_ms", RoundAll(r.EngineMs, 3) },
    { "wall_ms", RoundAll(r.WallMs, 3) }, { "composite_ms", RoundAll(r.CompositeMs, 3) },
    { "warp_ms", RoundAll(r.WarpMs, 3) }, { "table_ms", RoundAll(r.TableMs, 3) },
    { "image_parts_ms", RoundAll(r.ImagePartsMs, 3) },
    { "gather_ms", RoundAll(r.GatherMs, 3) }, { "imbalance", RoundAll(r.Imbalance, 3) },
    { "cores", RoundAll(r.Cores, 3) }, { "workers", r.Workers },
    { "last_band_ms", RoundAll(r.BandMs, 3) } };
}

bool ReadRunJson(const Json& v, RunResult& r)
{
  if (!v.is_object() || !v.contains("id") || !v["id"].is_string())
  {
    return false;
  }
  r.Cfg.Id = v["id"].get<std::string>();
  r.Cfg.Label = v.value("label", r.Cfg.Id);
  r.Cfg.Experiment = static_cast<int>(Number(v, "experiment"));
  r.Cfg.Rle = v.value("rle", false);
  r.Cfg.Ert = v.value("ert", false);
  r.Cfg.Balance = v.value("balance", false);
  r.Cfg.Phong = v.value("phong", false);
  r.Threads = static_cast<int>(Number(v, "threads"));
  r.Ranks = static_cast<int>(Number(v, "ranks"));
  r.FirstFrameMs = Number(v, "first_frame_ms");
  r.EncodeMs = Number(v, "encode_ms");
  r.StoredVoxels = static_cast<long long>(Number(v, "stored_voxels"));
  r.EncodedBytes = static_cast<long long>(Number(v, "encoded_bytes"));
  r.Axis = static_cast<int>(Number(v, "principal_axis"));
  r.Bands = static_cast<int>(Number(v, "bands"));
  r.Voxels = Number(v, "voxels_per_frame");
  r.Samples = Number(v, "samples_per_frame");
  r.SkippedPixels = Number(v, "skipped_pixels_per_frame");
  r.RenderMs = Numbers(v, "render_ms");
  r.EngineMs = Numbers(v, "engine_ms");
  r.WallMs = Numbers(v, "wall_ms");
  r.CompositeMs = Numbers(v, "composite_ms");
  r.WarpMs = Numbers(v, "warp_ms");
  r.TableMs = Numbers(v, "table_ms");
  r.ImagePartsMs = Numbers(v, "image_parts_ms");
  r.GatherMs = Numbers(v, "gather_ms");
  r.Imbalance = Numbers(v, "imbalance");
  r.Cores = Numbers(v, "cores");
  r.Workers = Numbers(v, "workers");
  r.BandMs = Numbers(v, "last_band_ms");
  return !r.RenderMs.empty();
}

Json ScalingModelJson(const CaseResult& c)
{
  Json model = Json::object();
  for (int parts : { 2, 4, 8, 16, 32 })
  {
    model[std::to_string(parts)] = { { "imbalance", Round(c.ModelImbalance(parts, 1), 4) },
      { "speedup", Round(c.ModelSpeedup(parts, 1), 3) },
      { "dynamic_imbalance", Round(c.ModelImbalance(parts, accelvolume::BandsPerWorker), 4) },
      { "dynamic_speedup", Round(c.ModelSpeedup(parts, accelvolume::BandsPerWorker), 3) } };
  }
  return model;
}

Json CaseJson(const CaseResult& c)
{
  const RunResult* all = c.Find("balanced", c.Threads);
  const double ratio = c.VolPackRatio(true);
  const double engineRatio = c.VolPackRatio(false);
  const double efficiency = c.Efficiency("balanced");
  const double imbalance = all && c.Threads > 1 ? all->MeanImbalance() : std::nan("");
  const double mpi = c.MpiEfficiency();
  Json checks = Json::array();
  for (const ImageCheck& x : c.Checks)
  {
    checks.push_back({ { "a", x.A }, { "b", x.B }, { "bound", x.Bound },
      { "differing_pixels", x.DifferingPixels }, { "max_difference", x.MaxDifference } });
  }
  const VolPackResult& v = c.VolPack;
  Json volpack = { { "ran", v.Ran }, { "note", v.Note }, { "mode", v.Grey ? "grey" : "rgb" },
    { "classify_ms", Round(v.ClassifyMs, 2) }, { "median_ms", Round(v.MedianMs(), 3) },
    { "axis", v.Axis }, { "opacity_exponent", Round(v.OpacityExponent, 4) },
    { "vs_ours", ErrorsJson(v.VsOurs) }, { "vs_ours_rgb", ErrorsJson(v.VsOursRgb) },
    { "render_ms", RoundAll(v.RenderMs, 3) } };
  Json runs = Json::array(), mpiRuns = Json::array();
  for (const RunResult& r : c.Runs)
  {
    runs.push_back(RunJson(r));
  }
  for (const RunResult& r : c.Mpi)
  {
    mpiRuns.push_back(RunJson(r));
  }
  return { { "key", c.Key() }, { "dataset", c.Dataset }, { "tf", c.Tf }, { "shade", c.Shade },
    { "size", c.Size }, { "frames", c.Frames }, { "threads", c.Threads },
    { "total_voxels", c.TotalVoxels }, { "seconds", Round(c.Seconds, 2) },
    { "volpack_ratio", Round(ratio, 3) }, { "volpack_ratio_engine", Round(engineRatio, 3) },
    { "volpack_ratio_all_threads", Round(c.VolPackRatio(true, c.Threads), 3) },
    { "volpack_ratio_engine_all_threads", Round(c.VolPackRatio(false, c.Threads), 3) },
    { "efficiency", Round(efficiency, 4) }, { "scaling_model", ScalingModelJson(c) },
    { "efficiency_rle", Round(c.Efficiency("rle"), 4) },
    { "efficiency_dense", Round(c.Efficiency("dense"), 4) }, { "imbalance", Round(imbalance, 4) },
    { "mpi_efficiency", Round(mpi, 4) },
    { "targets_met",
      { { "volpack", Met(ratio, ratio >= VolPackTarget) },
        { "efficiency", Met(efficiency, efficiency >= EfficiencyTarget) },
        { "imbalance", Met(imbalance, imbalance <= ImbalanceTarget) },
        { "mpi_efficiency", Met(mpi, mpi >= EfficiencyTarget) } } },
    { "checks_ok", c.ChecksOk() }, { "checks", checks },
    { "phong_vs_table", ErrorsJson(c.PhongVsTable) }, { "volpack", volpack }, { "runs", runs },
    { "mpi_note", c.MpiNote }, { "mpi", mpiRuns } };
}

Json DatasetJson(const DatasetInfo& d)
{
  return { { "name", d.Name }, { "file", d.File }, { "volume", d.Description },
    { "spacing", { d.Spacing[0], d.Spacing[1], d.Spacing[2] } },
    { "range", { d.Range[0], d.Range[1] } }, { "load_seconds", Round(d.LoadSeconds, 3) } };
}

} // namespace accelvolume::benchmark::shearwarp
