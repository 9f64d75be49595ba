// accelvolume_benchmark_raycast: Table 2 of Lim, Kim and Shin 2009 (semi-transparent cell leaping
// through a modified Marching Cubes table) and beyond, on real volumes. Lim, Kim and Shin 2009
// casts rays on the CPU (perspective, 512^2 images) with distance-map or min-max octree leaping,
// and reports 16.8-24.1 % more speed when semi-transparent cells are leaped as well, with
// pixel-identical images. This program measures vtkAccelVolumeRayCastMapper in every leap mode
// (none / distance map / octree) with cell leaping off and on, against VTK's
// vtkFixedPointVolumeRayCastMapper.
//
// Per volume x transfer function: perspective camera, composite blend, square image (512^2),
// sample distance = the smallest voxel spacing (x --sample-factor), ImageSampleDistance 1,
// AutoAdjustSampleDistances off, early ray termination on (both mappers' defaults), the same
// number of threads for every mapper. vtkFixedPoint gets the same property, sample distance
// (also as InteractiveSampleDistance), ImageSampleDistance 1 and LockSampleDistanceToInputSpacing
// off. Every mapper is a fresh object in one renderer, shown one at a time.
// - Prepare: each mapper's first frame (structures from the scalars, then classification) is
//   rendered under the transfer function over a window 2 % wider; the next frame, under the real
//   one, is the first after a transfer-function change (classification only). Both are reported
//   (wall time and GetLastPrepareTime) and excluded from the timed frames; the second is also
//   the warm-up frame and gives the images at the fixed view.
// - Timing: N rounds, each turning the camera 3 degrees in azimuth and rendering every
//   configuration (interleaved, so load from other processes hits all alike); a frame is
//   Render() plus a 1x1 read-back; the table gives the median, and the median of the process
//   CPU time / wall time ("cores": how many cores the frame kept busy, a check on the thread
//   count and on load from other processes).
// - Images at the fixed view: our six configurations must be byte-identical (exit code 3 when
//   not); quality is the grey-level RMS, over pixels non-black in either image, of ours (the
//   default: distance map, cell leaping off) and of vtkFixedPoint against a fine reference: ours
//   with leap none, cell leaping off, at 1/4 of the sample distance (--reference-factor).
//
// Transfer functions: the presets of `accelvolume render --tf` (TransferFunctions.cxx) laid over
// each volume's data range, shading on. tf2 (default first) is the paper's kind of rendering
// (Figure 7: skin / bone-like surfaces): transparent below 30 % of the range, a 2 %-wide ramp
// to opaque above. tf1 is semi-transparent: transparent below 10 %, then a ramp to opacity 0.35
// at the maximum. Both leave every object's boundary in semi-transparent cells (some corners
// transparent, some not), which is what cell leaping accelerates; neither makes the whole volume
// transparent or opaque on the six default volumes (71-99 % of their voxels lie below 10 % of
// the range, datasets.json "empty_fraction").
// JSON: raycast.json of the report (scripts/bench_report/raycast.py renders it, Table 2 included).
#include "BenchmarkHarness.h"
#include "BenchmarkImageMetrics.h"
#include "Options.h"
#include "TransferFunctions.h"

#include "vtkAccelVolumeHeadlessRenderWindow.h"
#include "vtkAccelVolumeRayCastMapper.h"

#include <vtkCamera.h>
#include <vtkFixedPointVolumeRayCastMapper.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkRenderer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkVolume.h>
#include <vtkVolumeProperty.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>

namespace accelvolume::benchmark
{
namespace
{

// Targets: ours (the default: distance map, cell leaping off) at least this much faster than
// vtkFixedPointVolumeRayCastMapper in every case at an RMS no larger than its (and
// MedianSpeedUpTarget over the cases), and cell leaping worth this many percent on top of the
// distance map (the paper: 16.8-24.1 % on top of its leaping).
constexpr double SpeedUpTarget = 2.5;
constexpr double MedianSpeedUpTarget = 3.0;
constexpr double CellGainTarget = 15.0;

// One row of the table: our mapper in one leap mode with cell leaping off / on, or VTK's.
struct Config
{
  std::string Id;
  std::string Label;
  bool Vtk = false; // vtkFixedPointVolumeRayCastMapper
  int Leap = 0;     // vtkAccelVolumeRayCastMapper::LEAP_*
  bool Cell = false;
};

const std::vector<Config>& Configs()
{
  using Mapper = vtkAccelVolumeRayCastMapper;
  static const std::vector<Config> configs = {
    { "none_off", "none, cell off", false, Mapper::LEAP_NONE, false },
    { "none_cell", "none, cell on", false, Mapper::LEAP_NONE, true },
    { "dmap_off", "dist. map, cell off", false, Mapper::LEAP_DISTANCE_MAP, false },
    { "dmap_cell", "dist. map, cell on", false, Mapper::LEAP_DISTANCE_MAP, true },
    { "octree_off", "octree, cell off", false, Mapper::LEAP_OCTREE, false },
    { "octree_cell", "octree, cell on", false, Mapper::LEAP_OCTREE, true },
    { "vtk_fixed", "vtkFixedPoint", true, 0, false },
  };
  return configs;
}

// Our mapper's counters, as per-frame means over the timed rounds.
struct Counters
{
  double Rays = 0;
  double Samples = 0;     // interpolated
  double LeapedSpace = 0; // skipped by the octree or the distance map
  double LeapedCell = 0;  // semi-transparent cells: skipped by the modified MC table
  double EmptyCell = 0;   // all-transparent cells met by the cell table
  double Terminated = 0;  // rays closed by early ray termination
};

struct ConfigResult
{
  Config Cfg;
  std::vector<double> FrameMs; // Render() + 1x1 read-back, one per timed round
  std::vector<double> CastMs;  // ours: GetLastCastTime (ray casting alone)
  std::vector<double> Cores;   // process CPU time / wall time of each timed frame
  Counters Count;              // ours
  // First frame of the mapper (structures built from the scalars, then classified) and first
  // frame after a transfer-function change (classification only): wall time and, for ours,
  // GetLastPrepareTime. Excluded from FrameMs.
  double FirstFrameMs = std::nan("");
  double FirstPrepareMs = std::nan("");
  double TfFrameMs = std::nan("");
  double TfPrepareMs = std::nan("");
  // Ours at the fixed view against ours with leap none and cell leaping off (same samples).
  long long DifferingPixels = 0;
  int MaxDifference = 0; // bytes
  double MedianMs() const { return Median(this->FrameMs); }
};

// One volume x transfer function.
struct CaseResult
{
  std::string Dataset;
  std::string Tf;
  bool Parallel = false; // projection
  int Threads = 1;       // of every mapper
  std::vector<std::uint8_t> DefaultImage; // ours (dmap_off) at the fixed view
  bool SameAcrossThreads = true; // DefaultImage equals the other thread counts' (same projection)
  int Size = 0;
  int Frames = 0;
  double SampleDistance = 1;
  double ReferenceSampleDistance = 0.25;
  double ReferenceMs = 0; // the one frame of the fine reference
  double Seconds = 0;
  std::vector<ConfigResult> Results; // in Configs() order
  // Grey-level (0..255) differences at the fixed view against the fine reference, over pixels
  // non-black in either image.
  ErrorStats OursVsReference; // distance map, cell leaping off (the default)
  ErrorStats VtkVsReference;
  ErrorStats OursVsVtk; // for information: includes VTK's own shading and table quantisation

  // Configurations not run (--configs) are not found: their ratios are NaN.
  std::size_t IndexOf(const std::string& id) const
  {
    for (std::size_t k = 0; k < this->Results.size(); ++k)
    {
      if (this->Results[k].Cfg.Id == id)
      {
        return k;
      }
    }
    return this->Results.size();
  }
  double MedianMs(const std::string& id) const
  {
    const std::size_t k = this->IndexOf(id);
    return k < this->Results.size() ? this->Results[k].MedianMs() : std::nan("");
  }
  bool Identical() const
  {
    return std::all_of(this->Results.begin(), this->Results.end(),
      [](const ConfigResult& r) { return r.Cfg.Vtk || r.DifferingPixels == 0; });
  }
  // (t_off - t_on) / t_off * 100 of the leap mode's two rows ("none", "dmap", "octree").
  double CellGain(const std::string& leap) const
  {
    const double off = this->MedianMs(leap + "_off");
    const double on = this->MedianMs(leap + "_cell");
    return off > 0 ? (off - on) / off * 100.0 : std::nan("");
  }
  double SpeedUpOverVtk(const ConfigResult& ours) const
  {
    return SafeRatio(this->MedianMs("vtk_fixed"), ours.MedianMs());
  }
  double DefaultSpeedUp() const { return SafeRatio(this->MedianMs("vtk_fixed"), this->MedianMs("dmap_off")); }
  bool SpeedTargetMet() const
  {
    return this->DefaultSpeedUp() >= SpeedUpTarget &&
      this->OursVsReference.Rms() <= this->VtkVsReference.Rms();
  }
};

Json ErrorsJson(const ErrorStats& e)
{
  return { { "rms", Round(e.Rms(), 3) }, { "max", Round(e.Max, 1) }, { "pixels", e.Pixels } };
}

Json ConfigJson(const CaseResult& c, const ConfigResult& r)
{
  const double baseMs = c.MedianMs("none_off");
  Json out = { { "id", r.Cfg.Id }, { "label", r.Cfg.Label },
    { "median_ms", Round(r.MedianMs(), 2) },
    { "speedup_over_none_off", Round(SafeRatio(baseMs, r.MedianMs()), 3) },
    { "speedup_over_vtk", Round(c.SpeedUpOverVtk(r), 3) },
    { "first_frame_ms", Round(r.FirstFrameMs, 1) }, { "tf_change_frame_ms", Round(r.TfFrameMs, 1) },
    { "median_cores", Round(Median(r.Cores), 2) } };
  if (!r.Cfg.Vtk)
  {
    const Counters& n = r.Count;
    out["first_prepare_ms"] = Round(r.FirstPrepareMs, 2);
    out["tf_change_prepare_ms"] = Round(r.TfPrepareMs, 2);
    out["median_cast_ms"] = Round(Median(r.CastMs), 2);
    out["differing_pixels"] = r.DifferingPixels;
    out["max_difference"] = r.MaxDifference;
    out["per_frame"] = { { "rays", Round(n.Rays, 0) }, { "samples", Round(n.Samples, 0) },
      { "leaped_space", Round(n.LeapedSpace, 0) }, { "leaped_cell_table", Round(n.LeapedCell, 0) },
      { "in_transparent_cells", Round(n.EmptyCell, 0) },
      { "terminated_rays", Round(n.Terminated, 0) } };
  }
  out["frame_ms"] = RoundAll(r.FrameMs, 2);
  return out;
}

Json CaseJson(const CaseResult& c)
{
  Json out = { { "dataset", c.Dataset }, { "tf", c.Tf },
    { "projection", c.Parallel ? "parallel" : "perspective" }, { "threads", c.Threads },
    { "size", c.Size }, { "frames", c.Frames }, { "speedup_over_vtk", Round(c.DefaultSpeedUp(), 3) },
    { "identical_across_threads", c.SameAcrossThreads },
    { "sample_distance", c.SampleDistance },
    { "reference_sample_distance", c.ReferenceSampleDistance },
    { "reference_ms", Round(c.ReferenceMs, 1) }, { "seconds", Round(c.Seconds, 2) },
    { "identical", c.Identical() }, { "ours_vs_reference", ErrorsJson(c.OursVsReference) },
    { "vtk_vs_reference", ErrorsJson(c.VtkVsReference) },
    { "ours_vs_vtk", ErrorsJson(c.OursVsVtk) },
    { "cell_gain_percent",
      { { "none", Round(c.CellGain("none"), 2) }, { "dmap", Round(c.CellGain("dmap"), 2) },
        { "octree", Round(c.CellGain("octree"), 2) } } },
    { "targets_met",
      { { "speed", c.SpeedTargetMet() }, { "cell_dmap", c.CellGain("dmap") >= CellGainTarget },
        { "cell_octree", c.CellGain("octree") >= CellGainTarget } } },
    { "configs", Json::array() } };
  for (const ConfigResult& r : c.Results)
  {
    out["configs"].push_back(ConfigJson(c, r));
  }
  return out;
}

vtkSmartPointer<vtkAccelVolumeRayCastMapper> OurMapper(
  double sampleDistance, int threads, int leap, bool cell)
{
  auto mapper = vtkSmartPointer<vtkAccelVolumeRayCastMapper>::New();
  mapper->SetAutoAdjustSampleDistances(0);
  mapper->SetSampleDistance(sampleDistance);
  mapper->SetInteractiveSampleDistance(sampleDistance);
  mapper->SetImageSampleDistance(1.0);
  mapper->SetNumberOfThreads(threads);
  mapper->SetLeapMode(leap);
  mapper->SetCellLeaping(cell);
  return mapper;
}

vtkSmartPointer<vtkFixedPointVolumeRayCastMapper> VtkMapper(double sampleDistance, int threads)
{
  auto mapper = vtkSmartPointer<vtkFixedPointVolumeRayCastMapper>::New();
  mapper->SetAutoAdjustSampleDistances(0);
  mapper->SetLockSampleDistanceToInputSpacing(0);
  mapper->SetSampleDistance(static_cast<float>(sampleDistance));
  mapper->SetInteractiveSampleDistance(static_cast<float>(sampleDistance));
  mapper->SetImageSampleDistance(1.0f);
  mapper->SetNumberOfThreads(threads);
  return mapper;
}

// The CLI's camera (looking along +z at the centre, the volume filling the view), turned to the
// fixed oblique view.
void SetFixedView(
  vtkRenderer* renderer, vtkImageData* image, double azimuth, double elevation, bool parallel)
{
  double bounds[6];
  image->GetBounds(bounds);
  const double centre[3] = { (bounds[0] + bounds[1]) / 2, (bounds[2] + bounds[3]) / 2,
    (bounds[4] + bounds[5]) / 2 };
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetParallelProjection(parallel ? 1 : 0);
  camera->SetFocalPoint(centre);
  camera->SetPosition(centre[0], centre[1], centre[2] - 1);
  camera->SetViewUp(0, 1, 0);
  renderer->ResetCamera();
  camera->Azimuth(azimuth);
  camera->Elevation(elevation);
  camera->OrthogonalizeViewUp();
  renderer->ResetCameraClippingRange();
}

// Every configuration's mapper (and the fine reference, last) in one renderer, shown one at a
// time.
class Scene
{
public:
  Scene(vtkImageData* image, vtkAccelVolumeHeadlessRenderWindow* window, int size)
    : Image(image)
    , Window(window)
    , Size(size)
  {
    this->Renderer->SetBackground(0, 0, 0);
    this->Window->AddRenderer(this->Renderer);
  }
  ~Scene() { this->Window->RemoveRenderer(this->Renderer); }

  void Add(vtkVolumeMapper* mapper)
  {
    mapper->SetInputData(this->Image);
    mapper->SetBlendModeToComposite();
    auto volume = vtkSmartPointer<vtkVolume>::New();
    volume->SetMapper(mapper);
    volume->SetProperty(this->Property);
    this->Renderer->AddVolume(volume);
    this->Volumes.push_back(volume);
    this->Ours.push_back(vtkAccelVolumeRayCastMapper::SafeDownCast(mapper));
  }

  // Shows volume k alone and renders it; wall milliseconds of Render() + a 1x1 read-back.
  double Render(std::size_t k)
  {
    for (std::size_t j = 0; j < this->Volumes.size(); ++j)
    {
      this->Volumes[j]->SetVisibility(j == k);
    }
    const int s = this->Size;
    const double cpuStart = ProcessCpuMs();
    const auto start = Clock::now();
    this->Window->Render();
    static_cast<vtkRenderWindow*>(this->Window)
      ->GetPixelData(s / 2, s / 2, s / 2, s / 2, 0, this->OnePixel.Get());
    const double wall = MsSince(start);
    this->LastCores = SafeRatio(ProcessCpuMs() - cpuStart, wall);
    return wall;
  }

  std::vector<std::uint8_t> Capture() { return benchmark::Capture(Window, Size, Size); }
  // 1000 x GetLastPrepareTime of our mapper k; NaN for VTK's.
  double PrepareMs(std::size_t k) const
  {
    return this->Ours[k] ? 1000.0 * this->Ours[k]->GetLastPrepareTime() : std::nan("");
  }

  vtkNew<vtkVolumeProperty> Property;
  vtkNew<vtkRenderer> Renderer;
  std::vector<vtkAccelVolumeRayCastMapper*> Ours; // nullptr for VTK's mapper
  double LastCores = 0; // CPU time / wall time of the last Render(): the cores it kept busy

private:
  vtkImageData* Image;
  vtkAccelVolumeHeadlessRenderWindow* Window;
  int Size;
  std::vector<vtkSmartPointer<vtkVolume>> Volumes;
  vtkNew<vtkUnsignedCharArray> OnePixel;
};

// The table of the issue: per case ours (default) vs vtkFixedPoint, the cell-leaping gain on top
// of the distance map and the image errors; then the medians and the targets.
void PrintSummary(const std::vector<CaseResult>& cases, Json& result)
{
  std::printf("%-20s %-4s %-11s %4s %9s %9s %8s %10s %15s %9s\n", "volume", "tf", "projection",
    "thr", "ours ms", "VTK ms", "x VTK", "cell gain", "RMS ours/VTK", "identical");
  std::vector<double> ratios, gains;
  int met = 0;
  for (const CaseResult& c : cases)
  {
    const double ratio = c.DefaultSpeedUp();
    ratios.push_back(ratio);
    const double gain = c.CellGain("dmap");
    if (!std::isnan(gain))
    {
      gains.push_back(gain);
    }
    met += c.SpeedTargetMet() ? 1 : 0;
    std::printf("%-20s %-4s %-11s %4d %9.1f %9.1f %7.2fx %9.1f%% %7.2f/%-7.2f %9s\n",
      c.Dataset.c_str(), c.Tf.c_str(), c.Parallel ? "parallel" : "perspective", c.Threads,
      c.MedianMs("dmap_off"), c.MedianMs("vtk_fixed"), ratio, gain, c.OursVsReference.Rms(),
      c.VtkVsReference.Rms(), c.Identical() && c.SameAcrossThreads ? "yes" : "NO");
  }
  const double median = ratios.empty() ? std::nan("") : Median(ratios);
  const double lowest = ratios.empty() ? std::nan("") : *std::min_element(ratios.begin(), ratios.end());
  const double medianGain = gains.empty() ? std::nan("") : Median(gains);
  std::printf("ours vs vtkFixedPoint: median %.2fx, lowest %.2fx over %zu cases; >= %.1fx at <= "
              "its RMS in %d / %zu (target: all, median >= %.1fx); cell leaping on top of the "
              "distance map: median %.1f%% (target >= %.0f%%)\n",
    median, lowest, ratios.size(), SpeedUpTarget, met, ratios.size(), MedianSpeedUpTarget,
    medianGain, CellGainTarget);
  result["summary"] = { { "median_speedup_over_vtk", Round(median, 3) },
    { "lowest_speedup_over_vtk", Round(lowest, 3) }, { "cases", ratios.size() },
    { "cases_meeting_speed_target", met }, { "median_cell_gain_over_dmap_percent", Round(medianGain, 2) } };
}

class RaycastBenchmark : public Benchmark
{
public:
  const char* Name() const override { return "accelvolume_benchmark_raycast"; }
  const char* Description() const override
  {
    return "Lim, Kim and Shin 2009 Table 2: CPU ray casting with distance-map / octree leaping, "
           "with and without semi-transparent cell leaping, against vtkFixedPoint. Exit code: 0 "
           "ok, 1 a dataset or backend missing, 2 bad options, 3 our six leaping configurations "
           "gave different images";
  }
  const char* DefaultJson() const override { return "accelvolume_benchmark_raycast.json"; }
  int InitialSize() const override { return this->Size; }

  void AddOptions(CLI::App& app) override
  {
    this->DatasetsOption = AddList(app, "--datasets", this->Datasets,
      "dataset names: NAME_<X>x<Y>x<Z>_<type>.raw[.gz] in the data folder");
    this->TfsOption =
      AddList(app, "--tfs", this->Tfs, "transfer-function presets of `accelvolume render --tf`");
    this->SizeOption = app.add_option("--size", this->Size, "square image size in pixels")
                         ->check(CLI::Range(16, 4096));
    this->FramesOption = app.add_option("--frames", this->Frames, "timed frames per configuration")
                           ->check(CLI::PositiveNumber);
    AddList(app, "--threads", this->ThreadCounts,
      "thread counts every case runs at, each for every mapper (0: hardware threads)");
    AddList(app, "--projections", this->Projections, "perspective and / or parallel");
    AddList(app, "--configs", this->ConfigIds,
      "our configurations (none|dmap|octree _off|_cell); dmap_off and vtk_fixed always run");
    app
      .add_option(
        "--sample-factor", this->SampleFactor, "sample distance = F x smallest voxel spacing")
      ->check(CLI::PositiveNumber);
    app
      .add_option("--reference-factor", this->ReferenceFactor,
        "the quality reference samples K times more densely")
      ->check(CLI::PositiveNumber);
    app.add_option("--view", this->View, "initial camera azimuth / elevation in degrees")
      ->expected(2)
      ->type_name("AZ EL");
    app.add_option("--turn", this->Turn, "azimuth turn per timed round in degrees");
    AddOnOff(app, "--shade", this->Shade, "Phong shading");
    app.add_flag(
      "--quick", this->Quick, "smoke run: size 128, 2 frames, engine, tf2 (unless given)");
    app.add_option("--images", this->Images, "save PNGs of the fixed view (ours, VTK, reference)")
      ->type_name("DIR");
  }

  void Resolve(const CLI::App&, const MachineInfo& machine) override
  {
    if (this->Quick)
    {
      this->Size = this->SizeOption->count() ? this->Size : 128;
      this->Frames = this->FramesOption->count() ? this->Frames : 2;
      if (!this->DatasetsOption->count())
      {
        this->Datasets = { "engine" };
      }
      if (!this->TfsOption->count())
      {
        this->Tfs = { "tf2" };
      }
    }
    for (int& threads : this->ThreadCounts)
    {
      if (threads < 0 || threads > 1024)
      {
        throw CLI::ValidationError("--threads", "each count must be in 0..1024");
      }
      threads = threads > 0 ? threads : machine.HardwareThreads;
    }
    std::sort(this->ThreadCounts.begin(), this->ThreadCounts.end());
    this->ThreadCounts.erase(
      std::unique(this->ThreadCounts.begin(), this->ThreadCounts.end()), this->ThreadCounts.end());
    for (const std::string& projection : this->Projections)
    {
      if (projection != "perspective" && projection != "parallel")
      {
        throw CLI::ValidationError("--projections", "perspective or parallel, not " + projection);
      }
    }
    for (const std::string& id : this->ConfigIds)
    {
      const auto& all = Configs();
      if (std::none_of(all.begin(), all.end(), [&](const Config& c) { return c.Id == id; }))
      {
        throw CLI::ValidationError("--configs", "unknown configuration " + id);
      }
    }
    if (this->ThreadCounts.empty() || this->Projections.empty())
    {
      throw CLI::ValidationError("--threads / --projections", "need at least one value");
    }
    CheckTransferFunctions(this->Tfs, "--tfs");
    if (this->Datasets.empty())
    {
      throw CLI::ValidationError("--datasets", "needs at least one name");
    }
  }

  int Run(Harness& harness, Json& result) override;

private:
  std::vector<std::string> Datasets = { "cthead", "aneurism", "cta_avm", "boston_teapot", "engine",
    "bonsai_hazeremoved" };
  std::vector<std::string> Tfs = { "tf2", "tf1" };
  int Size = 512;
  int Frames = 10;
  std::vector<int> ThreadCounts = { 1, 0 }; // 0: the hardware threads
  std::vector<std::string> Projections = { "perspective", "parallel" };
  std::vector<std::string> ConfigIds = { "none_off", "none_cell", "dmap_off", "dmap_cell",
    "octree_off", "octree_cell" };
  double SampleFactor = 1; // sample distance = factor x the smallest voxel spacing
  int ReferenceFactor = 4; // the fine reference samples this many times more densely
  std::vector<double> View = { 30.0, 20.0 }; // fixed initial view
  double Turn = 3.0;                         // azimuth degrees per timed round
  bool Shade = true;
  bool Quick = false;
  std::string Images;
  CLI::Option* DatasetsOption = nullptr;
  CLI::Option* TfsOption = nullptr;
  CLI::Option* SizeOption = nullptr;
  CLI::Option* FramesOption = nullptr;

  CaseResult RunCase(const DatasetInfo& info, vtkImageData* image, const std::string& tf,
    vtkAccelVolumeHeadlessRenderWindow* window, bool parallel, int threads) const;
  bool Runs(const Config& cfg) const
  {
    return cfg.Vtk || cfg.Id == "dmap_off" ||
      std::find(this->ConfigIds.begin(), this->ConfigIds.end(), cfg.Id) != this->ConfigIds.end();
  }
  void CheckImages(
    CaseResult& c, Scene& scene, std::size_t reference, const std::string& stem) const;
  void TimeRounds(CaseResult& c, Scene& scene) const;
  Json SettingsJson() const;
};

// The prepare frames and the image checks at the fixed view.
void RaycastBenchmark::CheckImages(
  CaseResult& c, Scene& scene, std::size_t reference, const std::string& stem) const
{
  std::vector<std::vector<std::uint8_t>> images;
  for (std::size_t k = 0; k < c.Results.size(); ++k)
  {
    c.Results[k].TfFrameMs = scene.Render(k);
    c.Results[k].TfPrepareMs = scene.PrepareMs(k);
    images.push_back(scene.Capture());
  }
  c.ReferenceMs = scene.Render(reference);
  const std::vector<std::uint8_t> referenceImage = scene.Capture();
  for (std::size_t k = 0; k < c.Results.size(); ++k)
  {
    if (scene.Ours[k])
    {
      const ByteDifferences d = CompareBytes(images[0], images[k]);
      c.Results[k].DifferingPixels = d.Pixels;
      c.Results[k].MaxDifference = d.Max;
    }
  }
  const std::size_t ourDefault = c.IndexOf("dmap_off"); // the mapper's default configuration
  const std::size_t vtk = c.IndexOf("vtk_fixed");
  c.DefaultImage = images[ourDefault];
  c.OursVsReference = CompareVisible(referenceImage, images[ourDefault], this->Size, this->Size);
  c.VtkVsReference = CompareVisible(referenceImage, images[vtk], this->Size, this->Size);
  c.OursVsVtk = CompareVisible(images[vtk], images[ourDefault], this->Size, this->Size);
  if (!this->Images.empty())
  {
    std::error_code ec;
    std::filesystem::create_directories(this->Images, ec);
    WritePng(stem + "dmap_off.png", images[ourDefault], this->Size, this->Size);
    WritePng(stem + "vtk_fixed.png", images[vtk], this->Size, this->Size);
    WritePng(stem + "reference.png", referenceImage, this->Size, this->Size);
  }
}

void RaycastBenchmark::TimeRounds(CaseResult& c, Scene& scene) const
{
  const double perFrame = 1.0 / this->Frames;
  for (int f = 0; f < this->Frames; ++f)
  {
    scene.Renderer->GetActiveCamera()->Azimuth(this->Turn);
    scene.Renderer->ResetCameraClippingRange();
    for (std::size_t k = 0; k < c.Results.size(); ++k)
    {
      ConfigResult& r = c.Results[k];
      r.FrameMs.push_back(scene.Render(k));
      r.Cores.push_back(scene.LastCores);
      if (vtkAccelVolumeRayCastMapper* m = scene.Ours[k])
      {
        r.CastMs.push_back(1000.0 * m->GetLastCastTime());
        r.Count.Rays += perFrame * m->GetLastNumberOfRays();
        r.Count.Samples += perFrame * m->GetLastNumberOfSamples();
        r.Count.LeapedSpace +=
          perFrame * (m->GetLastSamplesLeapedByOctree() + m->GetLastSamplesLeapedByDistanceMap());
        r.Count.LeapedCell += perFrame * m->GetLastSamplesLeapedByCellTable();
        r.Count.EmptyCell += perFrame * m->GetLastSamplesInTransparentCells();
        r.Count.Terminated += perFrame * m->GetLastNumberOfTerminatedRays();
      }
    }
  }
}

// One volume x transfer function: fresh mappers (so every case pays its own first frame), the
// prepare frames, the image checks at the fixed view and the timed rounds.
CaseResult RaycastBenchmark::RunCase(const DatasetInfo& info, vtkImageData* image,
  const std::string& tf, vtkAccelVolumeHeadlessRenderWindow* window, bool parallel,
  int threads) const
{
  const auto caseStart = Clock::now();
  CaseResult c;
  c.Dataset = info.Name;
  c.Tf = tf;
  c.Parallel = parallel;
  c.Threads = threads;
  c.Size = this->Size;
  c.Frames = this->Frames;
  c.SampleDistance = this->SampleFactor * info.MinSpacing;
  c.ReferenceSampleDistance = c.SampleDistance / this->ReferenceFactor;

  Scene scene(image, window, this->Size);
  for (const Config& cfg : Configs())
  {
    if (!this->Runs(cfg))
    {
      continue;
    }
    c.Results.emplace_back();
    c.Results.back().Cfg = cfg;
    if (cfg.Vtk)
    {
      scene.Add(VtkMapper(c.SampleDistance, threads));
    }
    else
    {
      scene.Add(OurMapper(c.SampleDistance, threads, cfg.Leap, cfg.Cell));
    }
  }
  const std::size_t reference = c.Results.size(); // the fine reference, last
  scene.Add(OurMapper(
    c.ReferenceSampleDistance, threads, vtkAccelVolumeRayCastMapper::LEAP_NONE, false));

  // The CLI's `render --blend composite --tf <tf> --shade on|off`, window = the data range.
  accelvolume::cli::Options cli;
  cli.blend = accelvolume::cli::BlendKind::Composite;
  cli.haveShade = true;
  cli.shade = this->Shade;
  cli.transferFunction = tf;
  const auto spec = accelvolume::cli::LoadTransferFunction(cli);
  const double low = info.Range[0];
  const double high = info.Range[1] > low ? info.Range[1] : low + 1;
  const double wider[2] = { low, high + 0.02 * (high - low) };
  const double tfWindow[2] = { low, high };

  SetFixedView(scene.Renderer, image, this->View[0], this->View[1], parallel);
  accelvolume::cli::ApplyTransferFunction(spec, cli, wider, scene.Property);
  for (std::size_t k = 0; k < c.Results.size(); ++k)
  {
    c.Results[k].FirstFrameMs = scene.Render(k);
    c.Results[k].FirstPrepareMs = scene.PrepareMs(k);
  }
  accelvolume::cli::ApplyTransferFunction(spec, cli, tfWindow, scene.Property);
  this->CheckImages(c, scene, reference,
    this->Images + "/" + info.Name + "_" + tf + (parallel ? "_parallel_" : "_perspective_") +
      std::to_string(threads) + "t_");
  this->TimeRounds(c, scene);
  c.Seconds = SecondsSince(caseStart);
  return c;
}

Json RaycastBenchmark::SettingsJson() const
{
  return { { "size", this->Size }, { "frames", this->Frames }, { "threads", this->ThreadCounts },
    { "sample_factor", this->SampleFactor }, { "reference_factor", this->ReferenceFactor },
    { "view",
      { { "azimuth", Round(this->View[0], 2) }, { "elevation", Round(this->View[1], 2) } } },
    { "turn_degrees", Round(this->Turn, 2) }, { "shade", this->Shade },
    { "projections", this->Projections }, { "blend", "composite" }, { "image_sample_distance", 1 },
    { "auto_adjust_sample_distances", false }, { "early_ray_termination", true },
    { "quick", this->Quick }, { "speedup_target", SpeedUpTarget },
    { "median_speedup_target", MedianSpeedUpTarget },
    { "cell_gain_target_percent", CellGainTarget } };
}

int RaycastBenchmark::Run(Harness& harness, Json& result)
{
  const MachineInfo& machine = harness.Machine;
  result = { { "benchmark",
               "raycast (Lim, Kim and Shin 2009 Table 2: semi-transparent cell leaping)" },
    { "machine",
      { { "cpu", machine.Cpu }, { "hardware_threads", machine.HardwareThreads },
        { "gl_backend", machine.GLBackend }, { "gl_renderer", machine.GLRenderer } } },
    { "settings", this->SettingsJson() }, { "total_seconds", 0 }, { "datasets", Json::array() },
    { "cases", Json::array() } };
  bool ok = true, identical = true;
  const int runs = static_cast<int>(this->Projections.size() * this->ThreadCounts.size());
  const int tfCount = static_cast<int>(this->Tfs.size()) * runs;
  CaseProgress progress(this->Name(), static_cast<int>(this->Datasets.size()) * tfCount);
  std::vector<CaseResult> all;
  for (const std::string& name : this->Datasets)
  {
    DatasetInfo info;
    vtkSmartPointer<vtkImageData> image = LoadDataset(harness.Options.DataDir, name, info);
    if (!image)
    {
      ok = false;
      progress.Skip(tfCount);
      continue;
    }
    for (const std::string& tf : this->Tfs)
    {
      for (const std::string& projection : this->Projections)
      {
        const std::size_t first = all.size();
        for (const int threads : this->ThreadCounts)
        {
          progress.Begin(name + " " + tf + " " + projection + " " + std::to_string(threads) + "t");
          all.push_back(
            this->RunCase(info, image, tf, harness.Window(), projection == "parallel", threads));
          CaseResult& c = all.back();
          c.SameAcrossThreads = c.DefaultImage == all[first].DefaultImage;
          all[first].SameAcrossThreads = all[first].SameAcrossThreads && c.SameAcrossThreads;
          identical = identical && c.Identical() && c.SameAcrossThreads;
        }
      }
    }
    result["datasets"].push_back(DatasetJson(info, false));
  }
  for (CaseResult& c : all)
  {
    c.DefaultImage.clear();
    result["cases"].push_back(CaseJson(c));
  }
  PrintSummary(all, result);
  result["total_seconds"] = Round(harness.Seconds(), 2);
  if (!identical)
  {
    std::cout << "FAILED: our leaping configurations or thread counts gave different images\n";
    return 3;
  }
  return ok && !result["cases"].empty() ? 0 : 1;
}

} // namespace

std::unique_ptr<Benchmark> MakeBenchmark()
{
  return std::make_unique<RaycastBenchmark>();
}

} // namespace accelvolume::benchmark
