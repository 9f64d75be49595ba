// accelvolume_benchmark_cropping: replicates Table 2 of Hong, Kye and Shin 2007 ("GPU MIP
// with clipping-plane re-rendering") on real volumes.
//
// For each dataset: MIP of a cropped sub-volume (20%..80% of every axis by default) seen
// obliquely, rendered headless, with
//   (a) vtkAccelVolumeSliceMapper, 1 slice per smallest voxel spacing, re-rendering off;
//   (b) the same with boundary re-rendering on (the paper's method);
//   (c) 1.5x slices, re-rendering off;
//   (d) 2x slices, re-rendering off;
//   (e) vtkGPUVolumeRayCastMapper, same cropping, sample distance = smallest spacing;
//   (b_raster) (b) with rasterised proxy slices and cut faces (the default composites the
//       slices in a compute pass where it can);
//   (ref) 8x slices with re-rendering on: the "truth" the aliasing error is measured against.
// Work per frame (issue 17): one untimed frame per configuration at view 1, counted by GL
// queries (fragment-shader invocations, fragments blended) or the compute slices' sample
// counter, and VTK's pixels x samples per ray through the crop box; the CPU cost under Mesa's
// no-op driver from `accelvolume render` children with GALLIUM_NOOP=1 (--noop-frames; 0 skips it;
// the CLI's camera is fitted to the whole volume, turned as view 1).
// Timing: a warm-up frame, then N frames each turning the camera 1 degree in azimuth; each
// frame is Render() plus a 1x1 read-back (so the GPU work is included). Median reported.
// Error: grey-level differences (0..255) from the reference at two fixed views (see the
// printed description of the masks).
// JSON: cropping.json of the report (scripts/bench_report/cropping.py renders it).
#include "BenchmarkHarness.h"
#include "BenchmarkImageMetrics.h"
#include "CompositeCounts.h"

#include "vtkAccelVolumeHeadlessRenderWindow.h"
#include "vtkAccelVolumeSliceMapper.h"

#include <vtkCamera.h>
#include <vtkColorTransferFunction.h>
#include <vtkGPUVolumeRayCastMapper.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPiecewiseFunction.h>
#include <vtkRenderer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkVolume.h>
#include <vtkVolumeProperty.h>

#include <algorithm>
#include <filesystem>
#include <iostream>

namespace fs = std::filesystem;

namespace accelvolume::benchmark
{
namespace
{

struct View
{
  const char* Name;
  double Azimuth;
  double Elevation;
};
// The error is measured at these two views; the timed sequence starts at the first.
constexpr View Views[] = { { "view1_az30_el25", 30.0, 25.0 }, { "view2_az-55_el40", -55.0, 40.0 } };
constexpr std::size_t ViewCount = sizeof(Views) / sizeof(Views[0]);

// One rendering configuration: a row of the table.
struct Config
{
  std::string Id;
  std::string Label;
  bool Gpu = false;
  bool Rerender = false;
  bool AutoAdjust = false;
  double SliceFactor = 1.0; // slices per smallest voxel spacing
  bool Reference = false;
  int Compositing = 0; // vtkAccelVolumeSliceMapper::SLICE_COMPOSITING_* (0: the default)
};

const std::vector<Config>& Configs()
{
  constexpr int Raster = vtkAccelVolumeSliceMapper::SLICE_COMPOSITING_RASTER;
  static const std::vector<Config> configs = {
    { "a", "slice 1x (auto), re-render off", false, false, true, 1.0, false },
    { "b", "slice 1x (auto), re-render ON", false, true, true, 1.0, false },
    { "c", "slice 1.5x, re-render off", false, false, false, 1.5, false },
    { "d", "slice 2x, re-render off", false, false, false, 2.0, false },
    { "e", "vtkGPUVolumeRayCastMapper 1x", true, false, false, 1.0, false },
    { "b_raster", "slice 1x (auto), re-render ON, raster slices", false, true, true, 1.0, false,
      Raster },
    { "ref", "slice 8x + re-render (reference)", false, true, false, 8.0, true },
  };
  return configs;
}

struct ConfigResult
{
  Config Cfg;
  std::vector<double> FrameMs;  // Render() + 1x1 read-back
  std::vector<double> MapperMs; // slice mapper's own GetLastRenderTime (it waits for the GPU)
  int Slices = 0;
  int Faces = 0;
  double SliceSpacing = 0;
  std::vector<std::vector<std::uint8_t>> Images; // per view, RGB, bottom row first
  std::vector<ErrorStats> Footprint, Band, Face; // per view
  ErrorStats FootprintAll, BandAll, FaceAll;
  bool ComputeSlices = false;    // composited by the compute pass
  FrameCounts Counts;            // one untimed frame at view 1
  long long ComputeSamples = -1; // compute slices: samples taken
  RaySamples RayWork;            // VTK: pixels x samples per ray through the crop box
  double NoOpMs = -1;            // CPU cost per frame under GALLIUM_NOOP=1, -1 = not run
  double MedianMs() const { return Median(this->FrameMs); }
  double MinMs() const
  {
    return this->FrameMs.empty() ? 0.0
                                 : *std::min_element(this->FrameMs.begin(), this->FrameMs.end());
  }
  // Median over the interleaved rounds of (this frame / the other's frame of the same round):
  // robust to load changes on a shared machine.
  double PairedRatio(const ConfigResult& other) const
  {
    std::vector<double> ratios;
    for (size_t f = 0; f < this->FrameMs.size() && f < other.FrameMs.size(); ++f)
    {
      ratios.push_back(this->FrameMs[f] / other.FrameMs[f]);
    }
    return Median(ratios);
  }
};

struct DatasetResult
{
  DatasetInfo Info;
  double Window[2] = { 0, 1 };
  double CropPlanes[6] = { 0, 0, 0, 0, 0, 0 };
  double TotalSeconds = 0;
  std::vector<long long> FootprintPixels, BandPixels, FacePixels; // per view
  std::vector<ConfigResult> Results;                              // in Configs() order
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
};

// Settings of the run (the options).
struct Settings
{
  std::vector<std::string> Datasets = { "cthead", "cta_avm" };
  std::vector<int> Size = { 512, 512 };
  int Frames = 10;
  int ReferenceFrames = 3;
  std::string Images;
  std::vector<double> Crop = { 0.2, 0.8 };
  double BandRadius = 2.5;     // pixels either side of the projected crop-box outline
  double AboveThreshold = 2.0; // grey levels: "visibly different" pixel
  double Zoom = 1.0;           // after fitting the camera to the crop box
  std::vector<double> Window;  // --window LOW HIGH overrides the per-dataset window
  int NoOpFrames = 100;        // frames per configuration of the no-op-driver column (0: skip)
};

// Transfer-function windows chosen per dataset (grey ramp, linear opacity ramp over the window).
void ChooseWindow(const Settings& s, const std::string& name, const double range[2], double w[2])
{
  if (s.Window.size() == 2)
  {
    w[0] = s.Window[0];
    w[1] = s.Window[1];
  }
  else if (name == "cthead")
  {
    w[0] = 300.0; // 16-bit CT, range 0..3272: soft tissue faint, bone bright
    w[1] = 2000.0;
  }
  else if (name == "cta_avm")
  {
    w[0] = 30.0; // 8-bit CTA, range 0..255: contrast-filled vessels
    w[1] = 255.0;
  }
  else
  {
    w[0] = range[0] + 0.1 * (range[1] - range[0]);
    w[1] = range[1];
  }
}

Json ConfigJson(const DatasetResult& d, const ConfigResult& r)
{
  const ConfigResult& base = d.Find("a");
  Json out = { { "id", r.Cfg.Id }, { "label", r.Cfg.Label },
    { "mapper", r.Cfg.Gpu ? "vtkGPUVolumeRayCastMapper" : "vtkAccelVolumeSliceMapper" },
    { "boundary_rerendering", r.Cfg.Rerender }, { "slice_factor", r.Cfg.SliceFactor },
    { "auto_adjust", r.Cfg.AutoAdjust } };
  if (!r.Cfg.Gpu)
  {
    out["slices"] = r.Slices;
    out["boundary_faces"] = r.Faces;
    out["slice_spacing"] = Round(r.SliceSpacing, 5);
  }
  out["median_ms"] = Round(r.MedianMs(), 3);
  out["fps"] = Round(1000.0 / r.MedianMs(), 3);
  out["min_ms"] = Round(r.MinMs(), 3);
  out["time_ratio_vs_a"] = Round(r.PairedRatio(base), 4);
  out["median_ratio_vs_a"] = Round(r.MedianMs() / base.MedianMs(), 4);
  if (!r.Cfg.Gpu)
  {
    out["median_mapper_ms"] = Round(Median(r.MapperMs), 3);
    out["compositing"] = r.ComputeSlices ? "compute" : "raster";
    // Rasterised: one fragment per sample, each blended into the float target (one channel
    // for MIP: 4 bytes read and written); compute: the counted samples, no blending.
    out["fragments_shaded"] = r.Counts.FragmentsShaded;
    out["fragments_blended"] = r.Counts.SamplesPassed;
    out["samples_fetched"] = r.ComputeSlices ? r.ComputeSamples : r.Counts.FragmentsShaded;
    out["bytes_blended"] =
      r.ComputeSlices ? 0 : (r.Counts.SamplesPassed < 0 ? -1 : 8 * r.Counts.SamplesPassed);
  }
  else
  {
    out["fragments_shaded"] = r.Counts.FragmentsShaded;
    out["ray_pixels"] = r.RayWork.Pixels;
    out["samples_fetched"] = r.RayWork.Samples;
    out["bytes_blended"] = 8 * r.RayWork.Pixels;
  }
  out["noop_ms"] = r.NoOpMs > 0 ? Json(Round(r.NoOpMs, 4)) : Json();
  out["frame_ms"] = RoundAll(r.FrameMs, 2);
  auto error = [&](const char* key, const ErrorStats& all, const ErrorStats& baseAll)
  {
    out[std::string(key) + "rms_error"] = Round(all.Rms(), 4);
    out[std::string(key) + "max_error"] = Round(all.Max, 2);
    out[std::string(key) + "error_ratio_vs_a"] = Round(SafeRatio(all.Rms(), baseAll.Rms()), 4);
    if (std::string(key).empty())
    {
      out["above_threshold_fraction"] = Round(all.AboveFraction(), 5);
    }
  };
  error("", r.FootprintAll, base.FootprintAll);
  error("band_", r.BandAll, base.BandAll);
  error("cut_face_", r.FaceAll, base.FaceAll);
  out["per_view"] = Json::array();
  for (std::size_t v = 0; v < r.Footprint.size(); ++v)
  {
    out["per_view"].push_back(
      { { "view", Views[v].Name }, { "rms_error", Round(r.Footprint[v].Rms(), 4) },
        { "max_error", Round(r.Footprint[v].Max, 2) },
        { "above_threshold_fraction", Round(r.Footprint[v].AboveFraction(), 5) },
        { "band_rms_error", Round(r.Band[v].Rms(), 4) },
        { "band_max_error", Round(r.Band[v].Max, 2) },
        { "cut_face_rms_error", Round(r.Face[v].Rms(), 4) } });
  }
  return out;
}

Json DatasetResultJson(const DatasetResult& d)
{
  const ConfigResult& base = d.Find("a");
  const ConfigResult& rerender = d.Find("b");
  const ConfigResult& doubled = d.Find("d");
  Json planes = Json::array();
  for (double plane : d.CropPlanes)
  {
    planes.push_back(Round(plane, 4));
  }
  Json out = { { "name", d.Info.Name }, { "file", d.Info.File }, { "volume", d.Info.Description },
    { "spacing", { d.Info.Spacing[0], d.Info.Spacing[1], d.Info.Spacing[2] } },
    { "tf_window", { d.Window[0], d.Window[1] } }, { "crop_planes", planes },
    { "cut_face_pixels", d.FacePixels }, { "footprint_pixels", d.FootprintPixels },
    { "band_pixels", d.BandPixels }, { "seconds", Round(d.TotalSeconds, 2) },
    { "rerender_overhead_percent", Round(100.0 * (rerender.PairedRatio(base) - 1.0), 2) },
    { "rerender_beats_2x_in_band", rerender.BandAll.Rms() < doubled.BandAll.Rms() },
    { "rerender_beats_2x_on_cut_faces", rerender.FaceAll.Rms() < doubled.FaceAll.Rms() },
    { "rerender_beats_2x_in_footprint", rerender.FootprintAll.Rms() < doubled.FootprintAll.Rms() },
    { "configs", Json::array() } };
  for (const ConfigResult& r : d.Results)
  {
    out["configs"].push_back(ConfigJson(d, r));
  }
  return out;
}

// One dataset's scene: a renderer with the slice mapper and VTK's GPU ray caster sharing one
// property (one visible at a time), cropped to the sub-volume, and the fixed views.
class Scene
{
public:
  Scene(const Settings& settings, vtkImageData* image, DatasetResult& result,
    vtkAccelVolumeHeadlessRenderWindow* window);
  ~Scene() { this->Window->RemoveRenderer(this->Renderer); }
  void Time();
  void CountWork();
  void RunNoOp(int frames);
  void CaptureViews();
  void MeasureErrors();
  void SaveImages(const std::string& folder) const;

private:
  const Settings& S;
  DatasetResult& Result;
  vtkAccelVolumeHeadlessRenderWindow* Window;
  int Width, Height;
  vtkNew<vtkVolumeProperty> Property;
  vtkNew<vtkAccelVolumeSliceMapper> Slice;
  vtkNew<vtkVolume> SliceVolume;
  vtkNew<vtkGPUVolumeRayCastMapper> Gpu;
  vtkNew<vtkVolume> GpuVolume;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkUnsignedCharArray> OnePixel;
  std::vector<vtkSmartPointer<vtkCamera>> Cameras; // per view
  std::vector<std::vector<std::uint8_t>> HullMasks, BandMasks;

  void SetUpMappers(vtkImageData* image);
  void SetUpViews();
  void SetView(std::size_t v)
  {
    this->Renderer->GetActiveCamera()->DeepCopy(this->Cameras[v]);
    this->Renderer->ResetCameraClippingRange();
  }
  void Apply(const Config& cfg)
  {
    this->SliceVolume->SetVisibility(!cfg.Gpu);
    this->GpuVolume->SetVisibility(cfg.Gpu);
    if (!cfg.Gpu)
    {
      this->Slice->SetBoundaryRerendering(cfg.Rerender);
      this->Slice->SetAutoAdjustSampleDistances(cfg.AutoAdjust);
      this->Slice->SetSampleDistance(this->Result.Info.MinSpacing / cfg.SliceFactor);
      this->Slice->SetSliceCompositing(cfg.Compositing);
    }
  }
  void RenderAndWait()
  {
    this->Window->Render();
    const int cx = this->Width / 2, cy = this->Height / 2;
    static_cast<vtkRenderWindow*>(this->Window)
      ->GetPixelData(cx, cy, cx, cy, 0, this->OnePixel.Get());
  }
};

Scene::Scene(const Settings& settings, vtkImageData* image, DatasetResult& result,
  vtkAccelVolumeHeadlessRenderWindow* window)
  : S(settings)
  , Result(result)
  , Window(window)
  , Width(settings.Size[0])
  , Height(settings.Size[1])
{
  const double* w = result.Window;
  vtkNew<vtkColorTransferFunction> colours;
  colours->AddRGBPoint(w[0], 0, 0, 0);
  colours->AddRGBPoint(w[1], 1, 1, 1);
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(w[0], 0.0);
  opacity->AddPoint(w[1], 1.0);
  this->Property->SetColor(colours);
  this->Property->SetScalarOpacity(opacity);
  this->Property->SetInterpolationTypeToLinear();
  this->Property->ShadeOff();
  this->SetUpMappers(image);
  this->Renderer->SetBackground(0, 0, 0);
  this->Renderer->AddVolume(this->SliceVolume);
  this->Renderer->AddVolume(this->GpuVolume);
  this->Window->AddRenderer(this->Renderer);
  this->SetUpViews();
  for (const Config& cfg : Configs())
  {
    ConfigResult r;
    r.Cfg = cfg;
    this->Result.Results.push_back(std::move(r));
  }
}

void Scene::SetUpMappers(vtkImageData* image)
{
  double* crop = this->Result.CropPlanes;
  this->Slice->SetInputData(image);
  this->Slice->SetBlendModeToMaximumIntensity();
  this->Slice->SetCropping(1);
  this->Slice->SetCroppingRegionPlanes(crop);
  this->Slice->SetCroppingRegionFlagsToSubVolume();
  this->Slice->SetMaximumNumberOfSlices(1 << 16); // the 8x reference must not be widened
  this->SliceVolume->SetMapper(this->Slice);
  this->SliceVolume->SetProperty(this->Property);
  this->Gpu->SetInputData(image);
  this->Gpu->SetBlendModeToMaximumIntensity();
  this->Gpu->SetCropping(1);
  this->Gpu->SetCroppingRegionPlanes(crop);
  this->Gpu->SetCroppingRegionFlagsToSubVolume();
  this->Gpu->SetAutoAdjustSampleDistances(0);
  this->Gpu->SetSampleDistance(this->Result.Info.MinSpacing);
  this->Gpu->SetImageSampleDistance(1.0);
  this->Gpu->SetUseJittering(0);
  this->GpuVolume->SetMapper(this->Gpu);
  this->GpuVolume->SetProperty(this->Property);
}

// The fixed views (camera fitted to the crop box, turned so the cut faces are oblique), and the
// crop-box footprint and outline band of each.
void Scene::SetUpViews()
{
  double* crop = this->Result.CropPlanes;
  for (const View& view : Views)
  {
    vtkCamera* camera = this->Renderer->GetActiveCamera();
    camera->SetPosition(0, 0, 1);
    camera->SetFocalPoint(0, 0, 0);
    camera->SetViewUp(0, 1, 0);
    this->Renderer->ResetCamera(crop);
    camera->Azimuth(view.Azimuth);
    camera->Elevation(view.Elevation);
    camera->OrthogonalizeViewUp();
    this->Renderer->ResetCamera(crop);
    camera->Zoom(this->S.Zoom);
    auto saved = vtkSmartPointer<vtkCamera>::New();
    saved->DeepCopy(camera);
    this->Cameras.push_back(saved);
  }
  for (std::size_t v = 0; v < this->Cameras.size(); ++v)
  {
    this->SetView(v);
    std::vector<Point2> corners;
    for (int corner = 0; corner < 8; ++corner)
    {
      this->Renderer->SetWorldPoint(
        crop[corner & 1 ? 1 : 0], crop[corner & 2 ? 3 : 2], crop[corner & 4 ? 5 : 4], 1.0);
      this->Renderer->WorldToDisplay();
      double display[3];
      this->Renderer->GetDisplayPoint(display);
      corners.push_back({ display[0], display[1] });
    }
    const std::vector<Point2> hull = ConvexHull(corners);
    this->HullMasks.push_back(PolygonMask(hull, this->Width, this->Height));
    this->BandMasks.push_back(OutlineBandMask(hull, this->Width, this->Height, this->S.BandRadius));
  }
}

// Warm-up, then timed frames interleaved: in round f every configuration renders the same
// camera (turned f+1 degrees from view 1), so load changes on a shared machine hit all alike.
void Scene::Time()
{
  // Warm-up (texture upload, shader compilation) of every configuration except the reference,
  // which shares the slice mapper's texture and shaders with (a)..(d).
  this->SetView(0);
  for (const Config& cfg : Configs())
  {
    if (!cfg.Reference)
    {
      this->Apply(cfg);
      this->RenderAndWait();
    }
  }
  const int referenceFrames = std::min(this->S.ReferenceFrames, this->S.Frames);
  for (int f = 0; f < this->S.Frames; ++f)
  {
    this->Renderer->GetActiveCamera()->Azimuth(1.0);
    this->Renderer->ResetCameraClippingRange();
    for (ConfigResult& r : this->Result.Results)
    {
      if (r.Cfg.Reference && f >= referenceFrames)
      {
        continue;
      }
      this->Apply(r.Cfg);
      const auto start = Clock::now();
      this->RenderAndWait();
      r.FrameMs.push_back(MsSince(start));
      if (!r.Cfg.Gpu)
      {
        r.MapperMs.push_back(1000.0 * this->Slice->GetLastRenderTime());
      }
    }
  }
}

// Work of one untimed frame per configuration at view 1.
void Scene::CountWork()
{
  this->SetView(0);
  for (ConfigResult& r : this->Result.Results)
  {
    this->Apply(r.Cfg);
    this->Slice->SetCountSamples(!r.Cfg.Gpu);
    r.Counts = CountFrame(this->Window);
    this->Slice->SetCountSamples(false);
    if (r.Cfg.Gpu)
    {
      r.RayWork = CountRaySamples(
        this->Renderer, this->Result.CropPlanes, this->Width, this->Result.Info.MinSpacing);
    }
    else
    {
      r.ComputeSlices = this->Slice->GetLastSliceCompositing() ==
        vtkAccelVolumeSliceMapper::SLICE_COMPOSITING_COMPUTE;
      r.ComputeSamples = this->Slice->GetLastNumberOfSamples();
    }
  }
}

// The CPU cost of each configuration under the no-op driver, through the CLI (view 1's angles).
void Scene::RunNoOp(int frames)
{
  const std::string cli = FindCli();
  if (frames <= 0 || cli.empty())
  {
    return;
  }
  const DatasetInfo& info = this->Result.Info;
  const auto number = [](double v) { return std::to_string(v); };
  for (ConfigResult& r : this->Result.Results)
  {
    if (r.Cfg.Reference)
    {
      continue;
    }
    // The CLI crops in voxel indices (the raw volumes sit at the origin).
    double c[6];
    for (int i = 0; i < 6; ++i)
    {
      c[i] = this->Result.CropPlanes[i] / info.Spacing[i / 2];
    }
    std::vector<std::string> args = { "--input", info.File, "--spacing", number(info.Spacing[0]),
      number(info.Spacing[1]), number(info.Spacing[2]), "--blend", "mip", "--window",
      number(this->Result.Window[0]), number(this->Result.Window[1]), "--crop", number(c[0]),
      number(c[1]), number(c[2]), number(c[3]), number(c[4]), number(c[5]), "--size",
      std::to_string(this->Width), std::to_string(this->Height), "--azimuth",
      number(Views[0].Azimuth), "--elevation", number(Views[0].Elevation),
      "--sample-distance", number(info.MinSpacing / r.Cfg.SliceFactor) };
    const std::vector<std::string> mapper = r.Cfg.Gpu
      ? std::vector<std::string>{ "--mapper", "vtk-gpu" }
      : std::vector<std::string>{ "--mapper", "slice", "--boundary-rerender",
          r.Cfg.Rerender ? "on" : "off", "--compositing",
          r.Cfg.Compositing == vtkAccelVolumeSliceMapper::SLICE_COMPOSITING_RASTER ? "raster"
                                                                                   : "auto" };
    args.insert(args.end(), mapper.begin(), mapper.end());
    r.NoOpMs = NoOpMsPerFrame(cli, args, frames);
  }
}

// Every configuration at the fixed views, for the error measurement.
void Scene::CaptureViews()
{
  for (ConfigResult& r : this->Result.Results)
  {
    this->Apply(r.Cfg);
    for (std::size_t v = 0; v < this->Cameras.size(); ++v)
    {
      this->SetView(v);
      this->Window->Render();
      r.Images.push_back(Capture(this->Window, this->Width, this->Height));
      if (v == 0 && !r.Cfg.Gpu)
      {
        r.Slices = this->Slice->GetLastNumberOfSlices();
        r.Faces = this->Slice->GetLastNumberOfBoundaryFaces();
        r.SliceSpacing = this->Slice->GetLastSliceSpacing();
      }
    }
  }
}

// Errors against the reference over the footprint (crop-box projection OR non-background
// reference pixels), over the outline band, and over the cut-face pixels (where the re-rendered
// faces change the 1x image by more than the threshold: there the boundary layer holds the
// maximum).
void Scene::MeasureErrors()
{
  const ConfigResult& reference = this->Result.Find("ref");
  const ConfigResult& plain = this->Result.Find("a");
  const ConfigResult& rerender = this->Result.Find("b");
  const double threshold = this->S.AboveThreshold;
  for (std::size_t v = 0; v < this->Cameras.size(); ++v)
  {
    const auto footprint =
      MaskOr(this->HullMasks[v], NonBackgroundMask(reference.Images[v], this->Width, this->Height));
    std::vector<std::uint8_t> faceMask(footprint.size(), 0);
    const auto& ia = plain.Images[v];
    const auto& ib = rerender.Images[v];
    for (std::size_t p = 0; p < faceMask.size(); ++p)
    {
      const double grey = std::abs((ia[3 * p] + ia[3 * p + 1] + ia[3 * p + 2]) / 3.0 -
        (ib[3 * p] + ib[3 * p + 1] + ib[3 * p + 2]) / 3.0);
      faceMask[p] = grey > threshold ? 1 : 0;
    }
    const auto& band = this->BandMasks[v];
    this->Result.FootprintPixels.push_back(std::count(footprint.begin(), footprint.end(), 1));
    this->Result.BandPixels.push_back(std::count(band.begin(), band.end(), 1));
    this->Result.FacePixels.push_back(std::count(faceMask.begin(), faceMask.end(), 1));
    for (ConfigResult& r : this->Result.Results)
    {
      r.Footprint.push_back(CompareImages(reference.Images[v], r.Images[v], footprint, threshold));
      r.Band.push_back(CompareImages(reference.Images[v], r.Images[v], band, threshold));
      r.Face.push_back(CompareImages(reference.Images[v], r.Images[v], faceMask, threshold));
      r.FootprintAll.Add(r.Footprint.back());
      r.BandAll.Add(r.Band.back());
      r.FaceAll.Add(r.Face.back());
    }
  }
}

// <folder>/<dataset>_<view>_<config>.png, + _diff_x8.png: |config - ref| x8, red = darker.
void Scene::SaveImages(const std::string& folder) const
{
  std::error_code ec;
  fs::create_directories(folder, ec);
  const ConfigResult& reference = this->Result.Find("ref");
  for (const ConfigResult& r : this->Result.Results)
  {
    for (std::size_t v = 0; v < r.Images.size(); ++v)
    {
      const std::string stem =
        folder + "/" + this->Result.Info.Name + "_" + Views[v].Name + "_" + r.Cfg.Id;
      bool ok = WritePng(stem + ".png", r.Images[v], this->Width, this->Height);
      if (!r.Cfg.Reference)
      {
        ok = WritePng(stem + "_diff_x8.png", DifferenceImage(reference.Images[v], r.Images[v], 8.0),
               this->Width, this->Height) &&
          ok;
      }
      if (!ok)
      {
        std::cerr << "could not write " << stem << ".png\n";
      }
    }
  }
}

class CroppingBenchmark : public Benchmark
{
public:
  const char* Name() const override { return "accelvolume_benchmark_cropping"; }
  const char* Description() const override
  {
    return "Hong, Kye and Shin 2007 Table 2: MIP of a cropped volume, boundary re-rendering "
           "against more slices and vtkGPUVolumeRayCastMapper";
  }
  const char* DefaultJson() const override { return "benchmark_cropping.json"; }
  int InitialSize() const override { return this->S.Size[0]; }

  void AddOptions(CLI::App& app) override
  {
    AddList(app, "--datasets", this->S.Datasets,
      "dataset names: NAME_<X>x<Y>x<Z>_<type>.raw[.gz] in the data folder");
    app.add_option("--size", this->S.Size, "image size")->expected(2)->type_name("W H");
    app.add_option("--frames", this->S.Frames, "timed frames per configuration")
      ->check(CLI::PositiveNumber);
    app
      .add_option("--reference-frames", this->S.ReferenceFrames,
        "timed frames of the 8x "
        "reference")
      ->check(CLI::PositiveNumber);
    app
      .add_option("--images", this->S.Images,
        "save PNGs (and x8 difference images) of the "
        "first dataset")
      ->type_name("DIR");
    app.add_option("--crop", this->S.Crop, "crop box as fractions of every axis")
      ->expected(2)
      ->type_name("LOW HIGH");
    app.add_option("--band", this->S.BandRadius, "half-width in pixels of the outline band")
      ->check(CLI::PositiveNumber);
    app.add_option("--zoom", this->S.Zoom, "camera zoom after fitting the crop box")
      ->check(CLI::PositiveNumber);
    app
      .add_option("--noop-frames", this->S.NoOpFrames,
        "frames per configuration of the no-op-driver CPU column (accelvolume render on EGL "
        "with GALLIUM_NOOP=1; 0 = skip)")
      ->check(CLI::NonNegativeNumber);
    app
      .add_option("--window", this->S.Window,
        "transfer-function window for every dataset (default: per dataset)")
      ->expected(2)
      ->type_name("LOW HIGH");
  }

  void Resolve(const CLI::App&, const MachineInfo&) override
  {
    const Settings& s = this->S;
    if (s.Size[0] < 16 || s.Size[1] < 16 || s.Datasets.empty() ||
      !(s.Crop[0] >= 0 && s.Crop[0] < s.Crop[1] && s.Crop[1] <= 1) ||
      (s.Window.size() == 2 && !(s.Window[0] < s.Window[1])))
    {
      throw CLI::ValidationError("options",
        "invalid values (size >= 16, 0 <= crop low < high "
        "<= 1, window low < high, a dataset)");
    }
  }

  int Run(Harness& harness, Json& result) override;

private:
  Settings S;
  bool RunDataset(const std::string& dataDir, const std::string& name, bool saveImages,
    vtkAccelVolumeHeadlessRenderWindow* window, DatasetResult& result) const;
};

bool CroppingBenchmark::RunDataset(const std::string& dataDir, const std::string& name,
  bool saveImages, vtkAccelVolumeHeadlessRenderWindow* window, DatasetResult& result) const
{
  const auto datasetStart = Clock::now();
  vtkSmartPointer<vtkImageData> image = LoadDataset(dataDir, name, result.Info);
  if (!image)
  {
    return false;
  }
  ChooseWindow(this->S, name, result.Info.Range, result.Window);
  double bounds[6];
  image->GetBounds(bounds);
  for (int axis = 0; axis < 3; ++axis)
  {
    const double length = bounds[2 * axis + 1] - bounds[2 * axis];
    result.CropPlanes[2 * axis] = bounds[2 * axis] + this->S.Crop[0] * length;
    result.CropPlanes[2 * axis + 1] = bounds[2 * axis] + this->S.Crop[1] * length;
  }
  Scene scene(this->S, image, result, window);
  scene.Time();
  scene.CountWork();
  scene.RunNoOp(this->S.NoOpFrames);
  scene.CaptureViews();
  scene.MeasureErrors();
  if (saveImages)
  {
    scene.SaveImages(this->S.Images);
  }
  result.TotalSeconds = SecondsSince(datasetStart);
  return true;
}

int CroppingBenchmark::Run(Harness& harness, Json& result)
{
  const Settings& s = this->S;
  harness.Window()->SetSize(s.Size[0], s.Size[1]);
  Json views = Json::array();
  for (const View& view : Views)
  {
    views.push_back(
      { { "name", view.Name }, { "azimuth", view.Azimuth }, { "elevation", view.Elevation } });
  }
  result = { { "benchmark", "cropping (Hong, Kye and Shin 2007 Table 2)" },
    { "gl_backend", harness.Machine.GLBackend }, { "gl_renderer", harness.Machine.GLRenderer },
    { "size", s.Size }, { "frames", s.Frames }, { "reference_frames", s.ReferenceFrames },
    { "crop_fraction", s.Crop }, { "band_radius_px", s.BandRadius },
    { "above_threshold_grey_levels", s.AboveThreshold }, { "views", views },
    { "error_units", "grey levels 0..255 (mean of R,G,B) vs the 8x re-rendered slice reference" },
    { "paper_table2_fps",
      { { "rerender_256", 149.83 }, { "plain_256", 150.81 }, { "plain_400", 97.24 },
        { "plain_512", 73.85 } } },
    { "datasets", Json::array() } };
  bool ok = true;
  CaseProgress progress(this->Name(), static_cast<int>(s.Datasets.size()));
  for (std::size_t i = 0; i < s.Datasets.size(); ++i)
  {
    progress.Begin(s.Datasets[i]);
    DatasetResult d;
    if (this->RunDataset(
          harness.Options.DataDir, s.Datasets[i], i == 0 && !s.Images.empty(), harness.Window(), d))
    {
      result["datasets"].push_back(DatasetResultJson(d));
    }
    else
    {
      ok = false;
    }
  }
  return ok && !result["datasets"].empty() ? 0 : 1;
}

} // namespace

std::unique_ptr<Benchmark> MakeBenchmark()
{
  return std::make_unique<CroppingBenchmark>();
}

} // namespace accelvolume::benchmark
