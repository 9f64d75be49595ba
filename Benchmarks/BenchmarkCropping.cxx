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
//   (ref) 8x slices with re-rendering on: the "truth" the aliasing error is measured against.
// Timing: a warm-up frame, then N frames each turning the camera 1 degree in azimuth; each
// frame is Render() plus a 1x1 read-back (so the GPU work is included). Median reported.
// Error: grey-level differences (0..255) from the reference at two fixed views (see the
// printed description of the masks).
// Options: BenchmarkCroppingOptions.{h,cxx}; table and JSON: BenchmarkCroppingReport.{h,cxx}.
#include "BenchmarkCommon.h"
#include "BenchmarkCroppingOptions.h"
#include "BenchmarkCroppingReport.h"
#include "BenchmarkImageMetrics.h"
#include "VolumeIO.h"

#include "vtkAccelVolumeHeadlessRenderWindow.h"
#include "vtkAccelVolumeSliceMapper.h"

#include <vtkCamera.h>
#include <vtkColorTransferFunction.h>
#include <vtkGPUVolumeRayCastMapper.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkPiecewiseFunction.h>
#include <vtkPointData.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkVolume.h>
#include <vtkVolumeProperty.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <regex>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace accelvolume::benchmark;

namespace
{
struct DatasetWindow
{
  double Low;
  double High;
};

// Transfer-function windows chosen per dataset (grey ramp, linear opacity ramp over the window).
bool KnownWindow(const std::string& name, DatasetWindow& window)
{
  if (name == "cthead")
  {
    window = { 300.0, 2000.0 }; // 16-bit CT, range 0..3272: soft tissue faint, bone bright
    return true;
  }
  if (name == "cta_avm")
  {
    window = { 30.0, 255.0 }; // 8-bit CTA, range 0..255: contrast-filled vessels
    return true;
  }
  return false;
}

std::vector<Config> MakeConfigs()
{
  return {
    { "a", "slice 1x (auto), re-render off", false, false, true, 1.0, false },
    { "b", "slice 1x (auto), re-render ON", false, true, true, 1.0, false },
    { "c", "slice 1.5x, re-render off", false, false, false, 1.5, false },
    { "d", "slice 2x, re-render off", false, false, false, 2.0, false },
    { "e", "vtkGPUVolumeRayCastMapper 1x", true, false, false, 1.0, false },
    { "ref", "slice 8x + re-render (reference)", false, true, false, 8.0, true },
  };
}

bool RunDataset(const Options& options, const std::string& name, bool saveImages,
  vtkAccelVolumeHeadlessRenderWindow* window, DatasetResult& result)
{
  const auto datasetStart = Clock::now();
  result.Name = name;
  result.File = FindDatasetFile(options.DataDir, name);
  if (result.File.empty())
  {
    std::cerr << "dataset " << name << ": no file " << name << "_<X>x<Y>x<Z>_<type>.raw[.gz] in "
              << options.DataDir << "\n";
    return false;
  }
  accelvolume::cli::VolumeRequest request;
  request.inputPath = result.File;
  std::string error;
  const auto loadStart = Clock::now();
  vtkSmartPointer<vtkImageData> image = accelvolume::cli::LoadVolume(request, error);
  result.LoadSeconds = SecondsSince(loadStart);
  if (!image)
  {
    std::cerr << "dataset " << name << ": " << error << "\n";
    return false;
  }
  result.Description = accelvolume::cli::DescribeVolume(image);
  image->GetSpacing(result.Spacing);
  result.MinSpacing = std::min({ result.Spacing[0], result.Spacing[1], result.Spacing[2] });
  double range[2];
  image->GetPointData()->GetScalars()->GetRange(range);
  DatasetWindow tf;
  if (options.HaveWindow)
  {
    tf = { options.Window[0], options.Window[1] };
  }
  else if (!KnownWindow(name, tf))
  {
    tf = { range[0] + 0.1 * (range[1] - range[0]), range[1] };
  }
  result.Window[0] = tf.Low;
  result.Window[1] = tf.High;

  double bounds[6];
  image->GetBounds(bounds);
  double cropBounds[6];
  for (int axis = 0; axis < 3; ++axis)
  {
    const double length = bounds[2 * axis + 1] - bounds[2 * axis];
    cropBounds[2 * axis] = bounds[2 * axis] + options.CropLow * length;
    cropBounds[2 * axis + 1] = bounds[2 * axis] + options.CropHigh * length;
  }
  std::copy(cropBounds, cropBounds + 6, result.CropPlanes);

  std::cout << "\n=== " << name << ": " << fs::path(result.File).filename().string() << " ("
            << result.Description << ", spacing " << result.Spacing[0] << " " << result.Spacing[1]
            << " " << result.Spacing[2] << ", scalar range " << range[0] << ".." << range[1]
            << ", loaded in " << Num(result.LoadSeconds, 2) << " s)\n"
            << "    TF window " << tf.Low << ".." << tf.High
            << " (grey ramp, linear opacity ramp 0..1), crop box " << options.CropLow * 100 << "%.."
            << options.CropHigh * 100 << "% of each axis = [" << cropBounds[0] << ","
            << cropBounds[1] << "]x[" << cropBounds[2] << "," << cropBounds[3] << "]x["
            << cropBounds[4] << "," << cropBounds[5] << "]\n"
            << std::flush;

  // Scene: one renderer, two volumes sharing the property (one visible at a time).
  vtkNew<vtkColorTransferFunction> colours;
  colours->AddRGBPoint(tf.Low, 0, 0, 0);
  colours->AddRGBPoint(tf.High, 1, 1, 1);
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(tf.Low, 0.0);
  opacity->AddPoint(tf.High, 1.0);
  vtkNew<vtkVolumeProperty> property;
  property->SetColor(colours);
  property->SetScalarOpacity(opacity);
  property->SetInterpolationTypeToLinear();
  property->ShadeOff();

  vtkNew<vtkAccelVolumeSliceMapper> slice;
  slice->SetInputData(image);
  slice->SetBlendModeToMaximumIntensity();
  slice->SetCropping(1);
  slice->SetCroppingRegionPlanes(cropBounds);
  slice->SetCroppingRegionFlagsToSubVolume();
  slice->SetMaximumNumberOfSlices(1 << 16); // the 8x reference must not be widened
  vtkNew<vtkVolume> sliceVolume;
  sliceVolume->SetMapper(slice);
  sliceVolume->SetProperty(property);

  vtkNew<vtkGPUVolumeRayCastMapper> gpu;
  gpu->SetInputData(image);
  gpu->SetBlendModeToMaximumIntensity();
  gpu->SetCropping(1);
  gpu->SetCroppingRegionPlanes(cropBounds);
  gpu->SetCroppingRegionFlagsToSubVolume();
  gpu->SetAutoAdjustSampleDistances(0);
  gpu->SetSampleDistance(result.MinSpacing);
  gpu->SetImageSampleDistance(1.0);
  gpu->SetUseJittering(0);
  vtkNew<vtkVolume> gpuVolume;
  gpuVolume->SetMapper(gpu);
  gpuVolume->SetProperty(property);

  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(0, 0, 0);
  renderer->AddVolume(sliceVolume);
  renderer->AddVolume(gpuVolume);
  window->AddRenderer(renderer);

  // The fixed views: camera fitted to the crop box, turned so the cut faces are oblique.
  std::vector<vtkSmartPointer<vtkCamera>> viewCameras;
  for (const View& view : Views)
  {
    vtkCamera* camera = renderer->GetActiveCamera();
    camera->SetPosition(0, 0, 1);
    camera->SetFocalPoint(0, 0, 0);
    camera->SetViewUp(0, 1, 0);
    renderer->ResetCamera(cropBounds);
    camera->Azimuth(view.Azimuth);
    camera->Elevation(view.Elevation);
    camera->OrthogonalizeViewUp();
    renderer->ResetCamera(cropBounds);
    camera->Zoom(options.Zoom);
    auto saved = vtkSmartPointer<vtkCamera>::New();
    saved->DeepCopy(camera);
    viewCameras.push_back(saved);
  }
  auto setView = [&](size_t v)
  {
    renderer->GetActiveCamera()->DeepCopy(viewCameras[v]);
    renderer->ResetCameraClippingRange();
  };

  // Crop-box footprint and outline band per view.
  const int width = options.Width;
  const int height = options.Height;
  std::vector<std::vector<std::uint8_t>> hullMasks;
  std::vector<std::vector<std::uint8_t>> bandMasks;
  for (size_t v = 0; v < viewCameras.size(); ++v)
  {
    setView(v);
    std::vector<Point2> corners;
    for (int corner = 0; corner < 8; ++corner)
    {
      renderer->SetWorldPoint(cropBounds[corner & 1 ? 1 : 0], cropBounds[corner & 2 ? 3 : 2],
        cropBounds[corner & 4 ? 5 : 4], 1.0);
      renderer->WorldToDisplay();
      double display[3];
      renderer->GetDisplayPoint(display);
      corners.push_back({ display[0], display[1] });
    }
    const std::vector<Point2> hull = ConvexHull(corners);
    hullMasks.push_back(PolygonMask(hull, width, height));
    bandMasks.push_back(OutlineBandMask(hull, width, height, options.BandRadius));
  }

  const std::vector<Config> configs = MakeConfigs();
  const int cx = width / 2;
  const int cy = height / 2;
  vtkNew<vtkUnsignedCharArray> onePixel;
  auto apply = [&](const Config& cfg)
  {
    sliceVolume->SetVisibility(!cfg.Gpu);
    gpuVolume->SetVisibility(cfg.Gpu);
    if (!cfg.Gpu)
    {
      slice->SetBoundaryRerendering(cfg.Rerender);
      slice->SetAutoAdjustSampleDistances(cfg.AutoAdjust);
      slice->SetSampleDistance(result.MinSpacing / cfg.SliceFactor);
    }
  };
  auto renderAndWait = [&]()
  {
    window->Render();
    static_cast<vtkRenderWindow*>(window)->GetPixelData(cx, cy, cx, cy, 0, onePixel.Get());
  };
  for (const Config& cfg : configs)
  {
    ConfigResult r;
    r.Cfg = cfg;
    result.Results.push_back(std::move(r));
  }

  // Warm-up (texture upload, shader compilation) of every configuration except the reference,
  // which shares the slice mapper's texture and shaders with (a)..(d).
  setView(0);
  for (const Config& cfg : configs)
  {
    if (!cfg.Reference)
    {
      apply(cfg);
      renderAndWait();
    }
  }
  // Timed frames, interleaved: in round f every configuration renders the same camera (turned
  // f+1 degrees from view 1), so load changes on a shared machine hit all of them alike.
  const int referenceFrames = std::min(options.ReferenceFrames, options.Frames);
  for (int f = 0; f < options.Frames; ++f)
  {
    renderer->GetActiveCamera()->Azimuth(1.0);
    renderer->ResetCameraClippingRange();
    for (ConfigResult& r : result.Results)
    {
      if (r.Cfg.Reference && f >= referenceFrames)
      {
        continue;
      }
      apply(r.Cfg);
      const auto start = Clock::now();
      renderAndWait();
      const auto stop = Clock::now();
      r.FrameMs.push_back(std::chrono::duration<double, std::milli>(stop - start).count());
      if (!r.Cfg.Gpu)
      {
        r.MapperMs.push_back(1000.0 * slice->GetLastRenderTime());
      }
    }
  }
  // Fixed views for the error measurement.
  for (ConfigResult& r : result.Results)
  {
    apply(r.Cfg);
    for (size_t v = 0; v < viewCameras.size(); ++v)
    {
      setView(v);
      window->Render();
      r.Images.push_back(Capture(window, width, height));
      if (v == 0 && !r.Cfg.Gpu)
      {
        r.Slices = slice->GetLastNumberOfSlices();
        r.Faces = slice->GetLastNumberOfBoundaryFaces();
        r.SliceSpacing = slice->GetLastSliceSpacing();
      }
    }
    std::cout << "    " << std::left << std::setw(4) << r.Cfg.Id << std::setw(36) << r.Cfg.Label
              << std::right << " median " << std::setw(8) << Num(r.MedianMs(), 1) << " ms over "
              << r.FrameMs.size() << " frames";
    if (!r.Cfg.Gpu)
    {
      std::cout << "  (" << r.Slices << " slices, spacing " << Num(r.SliceSpacing, 4) << ", "
                << r.Faces << " faces)";
    }
    std::cout << "\n" << std::flush;
  }

  // Errors against the reference over the footprint (crop-box projection OR non-background
  // reference pixels), over the outline band, and over the cut-face pixels (where the
  // re-rendered faces change the 1x image by more than the threshold: there the boundary
  // layer holds the maximum).
  const ConfigResult* referencePtr = nullptr;
  const ConfigResult* plainPtr = nullptr;
  const ConfigResult* rerenderPtr = nullptr;
  for (const ConfigResult& r : result.Results)
  {
    referencePtr = r.Cfg.Reference ? &r : referencePtr;
    plainPtr = r.Cfg.Id == "a" ? &r : plainPtr;
    rerenderPtr = r.Cfg.Id == "b" ? &r : rerenderPtr;
  }
  const ConfigResult& reference = *referencePtr;
  for (size_t v = 0; v < viewCameras.size(); ++v)
  {
    const auto footprint =
      MaskOr(hullMasks[v], NonBackgroundMask(reference.Images[v], width, height));
    std::vector<std::uint8_t> faceMask(footprint.size(), 0);
    for (size_t p = 0; p < faceMask.size(); ++p)
    {
      const auto& ia = plainPtr->Images[v];
      const auto& ib = rerenderPtr->Images[v];
      const double grey = std::abs((ia[3 * p] + ia[3 * p + 1] + ia[3 * p + 2]) / 3.0 -
        (ib[3 * p] + ib[3 * p + 1] + ib[3 * p + 2]) / 3.0);
      faceMask[p] = grey > options.AboveThreshold ? 1 : 0;
    }
    result.FootprintPixels.push_back(std::count(footprint.begin(), footprint.end(), 1));
    result.BandPixels.push_back(std::count(bandMasks[v].begin(), bandMasks[v].end(), 1));
    result.FacePixels.push_back(std::count(faceMask.begin(), faceMask.end(), 1));
    for (ConfigResult& r : result.Results)
    {
      r.Footprint.push_back(
        CompareImages(reference.Images[v], r.Images[v], footprint, options.AboveThreshold));
      r.Band.push_back(
        CompareImages(reference.Images[v], r.Images[v], bandMasks[v], options.AboveThreshold));
      r.Face.push_back(
        CompareImages(reference.Images[v], r.Images[v], faceMask, options.AboveThreshold));
      r.FootprintAll.Add(r.Footprint.back());
      r.BandAll.Add(r.Band.back());
      r.FaceAll.Add(r.Face.back());
    }
  }

  if (saveImages)
  {
    std::error_code ec;
    fs::create_directories(options.Images, ec);
    for (const ConfigResult& r : result.Results)
    {
      for (size_t v = 0; v < viewCameras.size(); ++v)
      {
        const std::string stem = options.Images + "/" + name + "_" + Views[v].Name + "_" + r.Cfg.Id;
        bool ok = WritePng(stem + ".png", r.Images[v], width, height);
        if (!r.Cfg.Reference)
        {
          ok = WritePng(stem + "_diff_x8.png",
                 DifferenceImage(reference.Images[v], r.Images[v], 8.0), width, height) &&
            ok;
        }
        if (!ok)
        {
          std::cerr << "could not write " << stem << ".png\n";
        }
      }
    }
    std::cout
      << "    images written to " << options.Images << "/" << name
      << "_<view>_<config>.png (+ _diff_x8.png: |config - ref| x8, red = darker than ref)\n";
  }

  window->RemoveRenderer(renderer);
  result.TotalSeconds = SecondsSince(datasetStart);
  return true;
}

} // namespace

int main(int argc, char* argv[])
{
  Options options;
  if (!ParseArguments(argc, argv, options))
  {
    return 2;
  }
  int backend = 0;
  if (const int exitCode = ResolveHeadlessBackend(options.GL, backend))
  {
    return exitCode;
  }

  vtkNew<vtkAccelVolumeHeadlessRenderWindow> window;
  StartHeadlessWindow(window, backend, options.Width, options.Height);
  const std::string rendererName = window->GetOpenGLRendererString();
  const std::string backendName =
    vtkAccelVolumeHeadlessRenderWindow::GetBackendName(window->GetActiveBackend());

  std::cout
    << "accelvolume_benchmark_cropping: Hong, Kye and Shin 2007 Table 2 (MIP of a cropped volume, "
       "boundary re-rendering vs more slices)\n"
    << "settings: " << options.Width << "x" << options.Height << ", MultiSamples 0, GL "
    << backendName << " (" << rendererName << "), " << options.Frames
    << " timed frames per config (reference: " << std::min(options.ReferenceFrames, options.Frames)
    << "), after one warm-up frame per config; frames interleaved across configs, camera "
       "turned 1 deg azimuth per round; time = Render() + 1x1 read-back, median;\n"
       "  'time x' = median over rounds of (config / (a)) in the same round (robust to load "
       "from other processes)\n"
    << "views: " << Views[0].Name << " (timed sequence starts here) and " << Views[1].Name
    << "; camera fitted to the crop box, zoom " << options.Zoom << "\n"
    << "data: " << options.DataDir << "\n"
    << "error: grey levels (0..255) against ref = slice mapper, 8x slices, re-rendering on.\n"
       "  RMS / max over the footprint = pixels inside the projected crop box OR non-black "
       "in ref;\n"
       "  band = pixels within "
    << options.BandRadius
    << " px of the projected crop-box outline (where slices clipped to the box leave "
       "staircase edges);\n"
       "  cut-face = pixels where re-rendering the faces changes the 1x image ((a) vs (b)) by > "
    << options.AboveThreshold
    << " grey levels: the boundary layer holds the maximum there;\n"
       "  >2lv% = share of footprint pixels off by more than "
    << options.AboveThreshold << " grey levels; 'x' columns are ratios to config (a).\n"
    << std::flush;

  std::vector<DatasetResult> datasets;
  bool ok = true;
  const auto start = Clock::now();
  CaseProgress progress(
    "accelvolume_benchmark_cropping", static_cast<int>(options.Datasets.size()));
  for (size_t i = 0; i < options.Datasets.size(); ++i)
  {
    progress.Begin(options.Datasets[i]);
    DatasetResult result;
    if (RunDataset(options, options.Datasets[i], i == 0 && !options.Images.empty(), window, result))
    {
      datasets.push_back(std::move(result));
    }
    else
    {
      ok = false;
    }
  }
  for (const DatasetResult& d : datasets)
  {
    PrintTable(d);
  }
  std::cout << "\npaper Table 2 (Radeon 9800 Pro, 256x256x240 Big Head, fps): re-render 256 slices "
               "149.83, plain 256 150.81, 400 97.24, 512 73.85\n";
  WriteJson(options, rendererName, backendName, datasets);
  std::cout << "results written to " << options.Json << "; total " << Num(SecondsSince(start), 1)
            << " s\n";
  return ok && !datasets.empty() ? 0 : 1;
}
