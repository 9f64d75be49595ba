// accelvolume_benchmark_composite: Table V-3 of Lee 2005 (ERT and ESS) on real volumes.
// Lee 2005 accelerates slice-based composite rendering with early ray termination and
// empty-space skipping; this program measures both, alone and together, and goes beyond the
// paper with octree skipping and a comparison against VTK's GPU ray caster.
//
// For each volume x transfer function (the `accelvolume render --tf` presets tf1 and tf2, over
// the data range, shading on) x square image size: frame time of vtkAccelVolumeSliceMapper
// with ERT / ESS switched on one at a time and together, and of vtkGPUVolumeRayCastMapper with
// the same transfer function and sample distance (the smallest voxel spacing). Timing: one
// warm-up frame per configuration, then N rounds, each turning the camera 1 degree in azimuth
// and rendering every configuration (interleaved, so load from other processes hits all alike);
// a frame is Render() plus a 1x1 read-back so the GPU work is included. Image check: grey-level
// RMS of ERT+both against base (should be ~0: both are exact up to the 0.99 threshold) and
// against VTK's image, at the fixed oblique view. Work per frame (issue 17): one untimed frame
// per configuration counted by GL queries (fragment-shader invocations, fragments reaching
// blending) and VTK's pixels x samples per ray; the CPU cost under Mesa's no-op driver from
// `accelvolume render` children with GALLIUM_NOOP=1 (--noop-frames; 0 skips it).
// JSON: composite.json of the report (scripts/bench_report/composite.py renders it).
#include "BenchmarkHarness.h"
#include "BenchmarkImageMetrics.h"
#include "CompositeCounts.h"
#include "Options.h"
#include "TransferFunctions.h"

#include "vtkAccelVolumeHeadlessRenderWindow.h"
#include "vtkAccelVolumeSliceMapper.h"

#include <vtkCamera.h>
#include <vtkGPUVolumeRayCastMapper.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkRenderer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkVolume.h>
#include <vtkVolumeProperty.h>

#include <filesystem>
#include <iostream>

namespace fs = std::filesystem;

namespace accelvolume::benchmark
{
namespace
{

// One rendering configuration: a column of Table V-3.
struct Config
{
  std::string Id;
  std::string Label;
  bool Vtk = false; // vtkGPUVolumeRayCastMapper instead of the slice mapper
  bool Ert = false;
  int Ess = 0;            // vtkAccelVolumeSliceMapper::SKIP_*: 0 none, 1 fragment, 2 octree, 3 both
  bool GpuSlices = true;  // proxy slices generated in the vertex stage (else CPU polygons)
  bool HalfFloat = false; // 16-bit float accumulation target
  int SlabSamples = 1;    // slice depths composited per fragment (one blend per slab)
  int Compositing = 0;    // vtkAccelVolumeSliceMapper::SLICE_COMPOSITING_* (0: the default)
  bool CentralDifferences = false; // gradients on the fly instead of the precomputed texture
};

constexpr int Raster = vtkAccelVolumeSliceMapper::SLICE_COMPOSITING_RASTER;

// The columns of one blend mode: composite has Table V-3's accelerations (with the default
// compositing: compute slices where they apply) and the rasterised variants; MIP and MinIP
// the default against the rasterised slices and slabs.
const std::vector<Config>& Configs(const std::string& blend)
{
  static const std::vector<Config> composite = {
    { "base", "ERT off, ESS none", false, false, 0 },
    { "ert", "ERT on, ESS none", false, true, 0 },
    { "ess_fragment", "ERT off, ESS fragment", false, false, 1 },
    { "ess_octree", "ERT off, ESS octree", false, false, 2 },
    { "ert_both", "ERT on, ESS both (default)", false, true, 3 },
    { "raster_base", "raster slices, ERT off, ESS none", false, false, 0, true, false, 1, Raster },
    { "raster", "raster slices, ERT on, ESS both", false, true, 3, true, false, 1, Raster },
    { "cpu_slices", "raster, ERT on, ESS both, CPU slice polygons", false, true, 3, false, false,
      1, Raster },
    { "half_float", "raster, ERT on, ESS both, RGBA16F target", false, true, 3, true, true, 1,
      Raster },
    { "slab4", "raster, ERT on, ESS both, 4-sample composite slabs", false, true, 3, false,
      false, 4, Raster },
    { "slab8", "raster, ERT on, ESS both, 8-sample composite slabs", false, true, 3, false,
      false, 8, Raster },
    { "central", "ERT on, ESS both, gradients by central differences", false, true, 3, true,
      false, 1, 0, true },
    { "vtk", "vtkGPUVolumeRayCastMapper", true, false, 0 },
  };
  static const std::vector<Config> extreme = {
    { "ert_both", "default", false, true, 3 },
    { "raster", "raster slices", false, true, 3, true, false, 1, Raster },
    { "slab4", "raster, 4-sample slabs", false, true, 3, true, false, 4, Raster },
    { "slab8", "raster, 8-sample slabs", false, true, 3, true, false, 8, Raster },
    { "vtk", "vtkGPUVolumeRayCastMapper", true, false, 0 },
  };
  return blend == "composite" ? composite : extreme;
}

struct ConfigResult
{
  Config Cfg;
  std::vector<double> FrameMs;  // Render() + 1x1 read-back
  std::vector<double> MapperMs; // slice mapper's GetLastRenderTime (it waits for the GPU)
  int TerminationPasses = 0;
  bool ComputeSlices = false; // the frames were composited by the compute pass
  double TransparentLeafFraction = -1;
  int Slices = 0;
  FrameCounts Counts;   // one untimed frame at the fixed view
  long long ComputeSamples = -1; // compute slices: samples the counted frame took
  RaySamples RayWork;   // VTK: pixels x samples per ray at the fixed view
  double NoOpMs = -1;   // CPU cost per frame under GALLIUM_NOOP=1 (child process), -1 = not run
  ErrorStats VsDefault; // slabs: grey-level difference from the default's image (fixed view)
  double Fps() const { return this->FrameMs.empty() ? std::nan("") : 1000.0 / Median(FrameMs); }
  // Median over the interleaved rounds of (other's frame / this frame of the same round): the
  // speed-up over `other`, robust to load from other processes on a shared machine.
  double PairedSpeedUp(const ConfigResult& other) const
  {
    std::vector<double> ratios;
    for (size_t f = 0; f < this->FrameMs.size() && f < other.FrameMs.size(); ++f)
    {
      ratios.push_back(other.FrameMs[f] / this->FrameMs[f]);
    }
    return Median(ratios);
  }
};

// One volume x transfer function x image size.
struct CaseResult
{
  std::string Dataset, Tf;
  int Size = 0;
  int Frames = 0;
  double Seconds = 0;
  std::vector<ConfigResult> Results; // in Configs() order
  // Grey-level (0..255) differences at the fixed view over pixels non-black in either image.
  ErrorStats ErtBothVsBase, OursVsVtk, HalfVsFull, OursVsRaster;
  const ConfigResult& Find(const std::string& id) const
  {
    for (const ConfigResult& r : this->Results)
    {
      if (r.Cfg.Id == id)
      {
        return r;
      }
    }
    return this->Results.front();
  }
  // The fastest slice-mapper configuration.
  const ConfigResult& Best() const
  {
    const ConfigResult* best = &this->Results.front();
    for (const ConfigResult& r : this->Results)
    {
      if (!r.Cfg.Vtk && Median(r.FrameMs) < Median(best->FrameMs))
      {
        best = &r;
      }
    }
    return *best;
  }
};

Json CaseJson(const CaseResult& c)
{
  const ConfigResult& base = c.Find("base");
  Json out = { { "dataset", c.Dataset }, { "tf", c.Tf }, { "size", c.Size }, { "frames", c.Frames },
    { "seconds", Round(c.Seconds, 2) },
    { "best_over_vtk", Round(c.Best().Fps() / c.Find("vtk").Fps(), 3) },
    { "rms_ert_both_vs_base", Round(c.ErtBothVsBase.Rms(), 3) },
    { "max_ert_both_vs_base", Round(c.ErtBothVsBase.Max, 1) },
    { "rms_ours_vs_vtk", Round(c.OursVsVtk.Rms(), 3) },
    { "max_ours_vs_vtk", Round(c.OursVsVtk.Max, 1) },
    { "rms_half_vs_full", Round(c.HalfVsFull.Rms(), 3) },
    { "max_half_vs_full", Round(c.HalfVsFull.Max, 1) },
    { "rms_ours_vs_raster", Round(c.OursVsRaster.Rms(), 3) },
    { "max_ours_vs_raster", Round(c.OursVsRaster.Max, 1) }, { "compared_pixels", c.OursVsVtk.Pixels },
    { "configs", Json::array() } };
  const double oursNoOp = c.Find("ert_both").NoOpMs;
  const double vtkNoOp = c.Find("vtk").NoOpMs;
  out["noop_ours_over_vtk"] =
    oursNoOp > 0 && vtkNoOp > 0 ? Json(Round(oursNoOp / vtkNoOp, 3)) : Json();
  for (const ConfigResult& r : c.Results)
  {
    Json config = { { "id", r.Cfg.Id }, { "label", r.Cfg.Label },
      { "median_ms", Round(Median(r.FrameMs), 2) }, { "fps", Round(r.Fps(), 3) },
      { "speedup_over_base", Round(r.PairedSpeedUp(base), 3) } };
    if (!r.Cfg.Vtk)
    {
      config["mapper_median_ms"] = Round(Median(r.MapperMs), 2);
      config["slices"] = r.Slices;
      config["termination_passes"] = r.TerminationPasses;
      config["transparent_leaf_fraction"] = Round(r.TransparentLeafFraction, 4);
      config["compositing"] = r.ComputeSlices ? "compute" : "raster";
      // One fragment = one volume sample; each one that passes is blended into the RGBA32F
      // accumulation target (16 bytes read, 16 written).
      config["fragments_shaded"] = r.Counts.FragmentsShaded;
      // A slab fragment fetches up to SlabSamples samples (fewer at the region's edges).
      config["samples_fetched"] =
        r.Counts.FragmentsShaded < 0 ? -1 : r.Counts.FragmentsShaded * r.Cfg.SlabSamples;
      config["fragments_blended"] = r.Counts.SamplesPassed;
      const long long texelBytes = r.Cfg.HalfFloat ? 8 : 16;
      config["bytes_blended"] =
        r.Counts.SamplesPassed < 0 ? -1 : 2 * texelBytes * r.Counts.SamplesPassed;
      if (r.ComputeSlices)
      {
        // No fragments and no blending: the counted samples, one store per pixel.
        config["samples_fetched"] = r.ComputeSamples;
        config["bytes_blended"] = 0;
      }
      if (r.Cfg.SlabSamples > 1)
      {
        config["rms_vs_default"] = Round(r.VsDefault.Rms(), 3);
        config["max_vs_default"] = Round(r.VsDefault.Max, 1);
      }
    }
    else
    {
      // One fragment per covered pixel, its whole ray of samples, one RGBA8 blend.
      config["fragments_shaded"] = r.Counts.FragmentsShaded;
      config["ray_pixels"] = r.RayWork.Pixels;
      config["samples_fetched"] = r.RayWork.Samples;
      config["fragments_blended"] = r.Counts.SamplesPassed;
      config["bytes_blended"] = 8 * r.RayWork.Pixels;
    }
    config["noop_ms"] = r.NoOpMs > 0 ? Json(Round(r.NoOpMs, 4)) : Json();
    config["frame_ms"] = RoundAll(r.FrameMs, 2);
    out["configs"].push_back(config);
  }
  return out;
}

// The two mappers of one volume in one renderer, and the timed rounds over them.
class Scene
{
public:
  Scene(vtkImageData* image, const DatasetInfo& info, vtkAccelVolumeHeadlessRenderWindow* window,
    int blendMode)
    : Window(window)
  {
    this->Slice->SetInputData(image);
    this->Slice->SetBlendMode(blendMode);
    this->Slice->SetAutoAdjustSampleDistances(0);
    this->Slice->SetSampleDistance(info.MinSpacing);
    this->SliceVolume->SetMapper(this->Slice);
    this->SliceVolume->SetProperty(this->Property);
    this->Gpu->SetInputData(image);
    this->Gpu->SetBlendMode(blendMode);
    this->Gpu->SetAutoAdjustSampleDistances(0);
    this->Gpu->SetSampleDistance(static_cast<float>(info.MinSpacing));
    this->Gpu->SetImageSampleDistance(1.0f);
    this->Gpu->SetUseJittering(0);
    this->GpuVolume->SetMapper(this->Gpu);
    this->GpuVolume->SetProperty(this->Property);
    this->Renderer->SetBackground(0, 0, 0);
    this->Renderer->AddVolume(this->SliceVolume);
    this->Renderer->AddVolume(this->GpuVolume);
    this->Window->AddRenderer(this->Renderer);
    image->GetBounds(this->Bounds);
  }
  ~Scene() { this->Window->RemoveRenderer(this->Renderer); }

  // The CLI's camera: front view along +z at the centre, then azimuth / elevation.
  void SetView(double azimuth, double elevation)
  {
    const double* b = this->Bounds;
    vtkCamera* camera = this->Renderer->GetActiveCamera();
    camera->SetFocalPoint((b[0] + b[1]) / 2, (b[2] + b[3]) / 2, (b[4] + b[5]) / 2);
    camera->SetPosition((b[0] + b[1]) / 2, (b[2] + b[3]) / 2, (b[4] + b[5]) / 2 - 1);
    camera->SetViewUp(0, 1, 0);
    this->Renderer->ResetCamera();
    camera->Azimuth(azimuth);
    camera->Elevation(elevation);
    camera->OrthogonalizeViewUp();
    this->Renderer->ResetCameraClippingRange();
  }

  void Turn(double degrees)
  {
    this->Renderer->GetActiveCamera()->Azimuth(degrees);
    this->Renderer->ResetCameraClippingRange();
  }

  void Apply(const Config& cfg)
  {
    this->SliceVolume->SetVisibility(!cfg.Vtk);
    this->GpuVolume->SetVisibility(cfg.Vtk);
    if (!cfg.Vtk)
    {
      this->Slice->SetEarlyRayTermination(cfg.Ert);
      this->Slice->SetEmptySpaceSkipping(cfg.Ess);
      this->Slice->SetGPUSliceGeneration(cfg.GpuSlices);
      this->Slice->SetHalfFloatTarget(cfg.HalfFloat);
      this->Slice->SetSlabSamples(cfg.SlabSamples);
      this->Slice->SetSliceCompositing(cfg.Compositing);
      this->Slice->SetPrecomputeGradients(!cfg.CentralDifferences);
    }
  }

  // Counts of one frame of `r`'s configuration at the current view.
  void CountWork(ConfigResult& r, int size, double sampleDistance)
  {
    this->Apply(r.Cfg);
    this->Slice->SetCountSamples(true);
    r.Counts = CountFrame(this->Window);
    this->Slice->SetCountSamples(false);
    r.ComputeSamples = r.Cfg.Vtk ? -1 : this->Slice->GetLastNumberOfSamples();
    if (r.Cfg.Vtk)
    {
      r.RayWork = CountRaySamples(this->Renderer, this->Bounds, size, sampleDistance);
    }
  }

  void RenderAndWait(int size)
  {
    this->Window->Render();
    static_cast<vtkRenderWindow*>(this->Window)
      ->GetPixelData(size / 2, size / 2, size / 2, size / 2, 0, this->OnePixel.Get());
  }

  // One timed frame of `r`'s configuration.
  void TimeFrame(ConfigResult& r, int size)
  {
    this->Apply(r.Cfg);
    const auto start = Clock::now();
    this->RenderAndWait(size);
    r.FrameMs.push_back(MsSince(start));
    if (!r.Cfg.Vtk)
    {
      r.MapperMs.push_back(1000.0 * this->Slice->GetLastRenderTime());
      r.TerminationPasses = this->Slice->GetLastNumberOfTerminationPasses();
      r.TransparentLeafFraction = this->Slice->GetLastTransparentLeafFraction();
      r.Slices = this->Slice->GetLastNumberOfSlices();
      r.ComputeSlices = this->Slice->GetLastSliceCompositing() ==
        vtkAccelVolumeSliceMapper::SLICE_COMPOSITING_COMPUTE;
    }
  }

  vtkNew<vtkVolumeProperty> Property;

private:
  vtkAccelVolumeHeadlessRenderWindow* Window;
  vtkNew<vtkAccelVolumeSliceMapper> Slice;
  vtkNew<vtkVolume> SliceVolume;
  vtkNew<vtkGPUVolumeRayCastMapper> Gpu;
  vtkNew<vtkVolume> GpuVolume;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkUnsignedCharArray> OnePixel;
  double Bounds[6] = { 0, 1, 0, 1, 0, 1 };
};

class CompositeBenchmark : public Benchmark
{
public:
  const char* Name() const override { return "accelvolume_benchmark_composite"; }
  const char* Description() const override
  {
    return "Lee 2005 Table V-3: slice-based composite rendering with early ray termination and "
           "empty-space skipping, against vtkGPUVolumeRayCastMapper";
  }
  const char* DefaultJson() const override { return "benchmark_composite.json"; }
  int InitialSize() const override { return this->Sizes.front(); }

  void AddOptions(CLI::App& app) override
  {
    AddList(app, "--datasets", this->Datasets,
      "dataset names: NAME_<X>x<Y>x<Z>_<type>.raw[.gz] in the data folder");
    AddList(app, "--tfs", this->Tfs,
      "transfer-function presets of `accelvolume render --tf` (tf1, tf2), or ramp (its default)");
    AddList(app, "--sizes", this->Sizes, "square image sizes (16..4096)");
    app.add_option("--blend", this->Blend, "composite (Table V-3's columns), mip or minip")
      ->check(CLI::IsMember({ "composite", "mip", "minip" }));
    app.add_option("--frames", this->Frames, "timed frames per configuration")
      ->check(CLI::PositiveNumber);
    app
      .add_option(
        "--large-frames", this->LargeFrames, "timed frames at sizes above 256 (0 = --frames)")
      ->check(CLI::NonNegativeNumber);
    app.add_option("--view", this->View, "camera azimuth / elevation in degrees")
      ->expected(2)
      ->type_name("AZ EL");
    app
      .add_option("--noop-frames", this->NoOpFrames,
        "frames per configuration of the no-op-driver CPU column (accelvolume render on EGL "
        "with GALLIUM_NOOP=1; 0 = skip)")
      ->check(CLI::NonNegativeNumber);
    app
      .add_option("--images", this->Images,
        "save PNGs of the quality-check view (base, "
        "ERT+both, VTK)")
      ->type_name("DIR");
  }

  void Resolve(const CLI::App&, const MachineInfo&) override
  {
    // "ramp": the CLI's default grey ramp (opaque from the window's bottom for MinIP).
    std::vector<std::string> presets;
    for (const std::string& tf : this->Tfs)
    {
      if (tf != "ramp")
      {
        presets.push_back(tf);
      }
    }
    if (presets.size() != this->Tfs.size() && presets.empty())
    {
      presets.push_back("tf1"); // only ramps: nothing more to check
    }
    CheckTransferFunctions(presets, "--tfs");
    bool sizes = !this->Sizes.empty();
    for (int size : this->Sizes)
    {
      sizes = sizes && size >= 16 && size <= 4096;
    }
    if (!sizes || this->Datasets.empty())
    {
      throw CLI::ValidationError("--sizes/--datasets", "sizes 16..4096, at least one dataset");
    }
  }

  int Run(Harness& harness, Json& result) override;

private:
  std::vector<std::string> Datasets = { "engine", "cthead", "bonsai_hazeremoved" };
  std::vector<std::string> Tfs = { "tf1", "tf2" };
  std::vector<int> Sizes = { 256, 512 };
  std::string Blend = "composite";
  int Frames = 5;
  // Timed frames at sizes above 256: a shaded 512^2 frame takes 0.5-1 s on llvmpipe.
  int LargeFrames = 3;
  std::vector<double> View = { 30.0, 20.0 };
  std::string Images;
  int NoOpFrames = 100;

  int FramesFor(int size) const
  {
    return size > 256 && this->LargeFrames > 0 ? this->LargeFrames : this->Frames;
  }
  int BlendMode() const
  {
    return this->Blend == "mip" ? vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND
      : this->Blend == "minip"  ? vtkVolumeMapper::MINIMUM_INTENSITY_BLEND
                                : vtkVolumeMapper::COMPOSITE_BLEND;
  }
  CaseResult RunCase(Scene& scene, vtkAccelVolumeHeadlessRenderWindow* window,
    const DatasetInfo& info, const std::string& tf, int size) const;
  void RunNoOp(CaseResult& c, const DatasetInfo& info) const;
};

// The same case through the CLI under the no-op driver, one child per configuration.
void CompositeBenchmark::RunNoOp(CaseResult& c, const DatasetInfo& info) const
{
  const std::string cli = FindCli();
  if (this->NoOpFrames <= 0 || cli.empty())
  {
    return;
  }
  const auto number = [](double v) { return std::to_string(v); };
  for (ConfigResult& r : c.Results)
  {
    std::vector<std::string> args = { "--input", info.File, "--spacing", number(info.Spacing[0]),
      number(info.Spacing[1]), number(info.Spacing[2]), "--blend", this->Blend, "--shade",
      "on", "--sample-distance", number(info.MinSpacing), "--size",
      std::to_string(c.Size), std::to_string(c.Size), "--azimuth", number(this->View[0]),
      "--elevation", number(this->View[1]) };
    const std::vector<std::string> mapper = r.Cfg.Vtk
      ? std::vector<std::string>{ "--mapper", "vtk-gpu" }
      : std::vector<std::string>{ "--mapper", "slice", "--ert", r.Cfg.Ert ? "on" : "off", "--ess",
          std::vector<std::string>{ "none", "fragment", "octree", "both" }[r.Cfg.Ess],
          "--gpu-slices", r.Cfg.GpuSlices ? "on" : "off", "--half-float",
          r.Cfg.HalfFloat ? "on" : "off", "--slab-samples", std::to_string(r.Cfg.SlabSamples),
          "--compositing", r.Cfg.Compositing == Raster ? "raster" : "auto", "--gradients",
          r.Cfg.CentralDifferences ? "on-the-fly" : "texture" };
    args.insert(args.end(), mapper.begin(), mapper.end());
    if (c.Tf != "ramp")
    {
      args.push_back("--tf");
      args.push_back(c.Tf);
    }
    r.NoOpMs = NoOpMsPerFrame(cli, args, this->NoOpFrames);
  }
}

CaseResult CompositeBenchmark::RunCase(Scene& scene, vtkAccelVolumeHeadlessRenderWindow* window,
  const DatasetInfo& info, const std::string& tf, int size) const
{
  const auto caseStart = Clock::now();
  window->SetSize(size, size);
  CaseResult c;
  c.Dataset = info.Name;
  c.Tf = tf;
  c.Size = size;
  c.Frames = this->FramesFor(size);
  for (const Config& cfg : Configs(this->Blend))
  {
    c.Results.emplace_back();
    c.Results.back().Cfg = cfg;
  }
  // Warm-up (texture upload, octree build / classification, shader compilation) and the
  // quality-check images, both at the fixed view.
  scene.SetView(this->View[0], this->View[1]);
  std::vector<std::uint8_t> baseImage, bothImage, vtkImage, halfImage, rasterImage;
  std::vector<std::vector<std::uint8_t>> slabImages; // in Configs() order
  for (ConfigResult& r : c.Results)
  {
    scene.Apply(r.Cfg);
    scene.RenderAndWait(size);
    if (r.Cfg.SlabSamples > 1)
    {
      window->Render();
      slabImages.push_back(Capture(window, size, size));
    }
    else if (r.Cfg.Id == "base" || r.Cfg.Id == "ert_both" || r.Cfg.Vtk || r.Cfg.HalfFloat ||
      r.Cfg.Id == "raster")
    {
      window->Render(); // a second frame: the first may include one-time work
      auto& target = r.Cfg.Id == "base" ? baseImage
        : r.Cfg.Id == "raster"          ? rasterImage
        : r.Cfg.Vtk                     ? vtkImage
        : r.Cfg.HalfFloat               ? halfImage
                                        : bothImage;
      target = Capture(window, size, size);
    }
  }
  for (ConfigResult& r : c.Results)
  {
    scene.CountWork(r, size, info.MinSpacing);
  }
  const auto compare = [size](const std::vector<std::uint8_t>& reference,
                         const std::vector<std::uint8_t>& image)
  {
    return reference.empty() || image.empty() ? ErrorStats()
                                              : CompareVisible(reference, image, size, size);
  };
  c.ErtBothVsBase = compare(baseImage, bothImage);
  c.OursVsVtk = compare(vtkImage, bothImage);
  c.HalfVsFull = compare(rasterImage, halfImage);
  c.OursVsRaster = compare(rasterImage, bothImage);
  size_t slab = 0;
  for (ConfigResult& r : c.Results)
  {
    if (r.Cfg.SlabSamples > 1)
    {
      r.VsDefault = compare(bothImage, slabImages[slab++]);
    }
  }
  if (!this->Images.empty())
  {
    std::error_code ec;
    fs::create_directories(this->Images, ec);
    const std::string stem =
      this->Images + "/" + info.Name + "_" + tf + "_" + std::to_string(size) + "_";
    WritePng(stem + "base.png", baseImage, size, size);
    WritePng(stem + "ert_both.png", bothImage, size, size);
    WritePng(stem + "vtk.png", vtkImage, size, size);
  }
  for (int f = 0; f < c.Frames; ++f)
  {
    scene.Turn(1.0);
    for (ConfigResult& r : c.Results)
    {
      scene.TimeFrame(r, size);
    }
  }
  this->RunNoOp(c, info);
  c.Seconds = SecondsSince(caseStart);
  return c;
}

int CompositeBenchmark::Run(Harness& harness, Json& result)
{
  result = { { "benchmark", "composite (Lee 2005 Table V-3)" }, { "blend", this->Blend },
    { "gl_backend", harness.Machine.GLBackend }, { "gl_renderer", harness.Machine.GLRenderer },
    { "frames", this->Frames }, { "large_frames", this->LargeFrames },
    { "view",
      { { "azimuth", Round(this->View[0], 2) }, { "elevation", Round(this->View[1], 2) } } },
    { "total_seconds", 0 }, { "datasets", Json::array() }, { "cases", Json::array() } };
  bool ok = true;
  // A progress step per dataset (its transfer functions and sizes run inside).
  CaseProgress progress(this->Name(), static_cast<int>(this->Datasets.size()));
  for (const std::string& name : this->Datasets)
  {
    progress.Begin(name);
    DatasetInfo info;
    vtkSmartPointer<vtkImageData> image = LoadDataset(harness.Options.DataDir, name, info);
    if (!image)
    {
      ok = false;
      continue;
    }
    Scene scene(image, info, harness.Window(), this->BlendMode());
    // The CLI's settings for `render --blend composite --tf tfN --shade on` (window = data range).
    accelvolume::cli::Options cli;
    cli.blend = this->Blend == "mip" ? accelvolume::cli::BlendKind::MIP
      : this->Blend == "minip"       ? accelvolume::cli::BlendKind::MinIP
                                     : accelvolume::cli::BlendKind::Composite;
    cli.haveShade = true;
    cli.shade = true;
    const double tfWindow[2] = { info.Range[0],
      info.Range[1] > info.Range[0] ? info.Range[1] : info.Range[0] + 1 };
    for (const std::string& tf : this->Tfs)
    {
      cli.transferFunction = tf == "ramp" ? "" : tf;
      accelvolume::cli::ApplyTransferFunction(
        accelvolume::cli::LoadTransferFunction(cli), cli, tfWindow, scene.Property);
      for (int size : this->Sizes)
      {
        result["cases"].push_back(CaseJson(this->RunCase(scene, harness.Window(), info, tf, size)));
      }
    }
    result["datasets"].push_back(DatasetJson(info, true));
  }
  result["total_seconds"] = Round(harness.Seconds(), 2);
  return ok && !result["cases"].empty() ? 0 : 1;
}

} // namespace

std::unique_ptr<Benchmark> MakeBenchmark()
{
  return std::make_unique<CompositeBenchmark>();
}

} // namespace accelvolume::benchmark
