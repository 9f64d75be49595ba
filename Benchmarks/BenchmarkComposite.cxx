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
// against VTK's image, at the fixed oblique view.
// Options: BenchmarkCompositeOptions.{h,cxx}; table and JSON: BenchmarkCompositeReport.{h,cxx}.
#include "BenchmarkCommon.h"
#include "BenchmarkCompositeOptions.h"
#include "BenchmarkCompositeReport.h"
#include "BenchmarkImageMetrics.h"
#include "Options.h"
#include "TransferFunctions.h"
#include "VolumeIO.h"

#include "vtkAccelVolumeHeadlessRenderWindow.h"
#include "vtkAccelVolumeSliceMapper.h"

#include <vtkCamera.h>
#include <vtkDataArray.h>
#include <vtkGPUVolumeRayCastMapper.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkPointData.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkVolume.h>
#include <vtkVolumeProperty.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <regex>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace accelvolume::benchmark;
using namespace accelvolume::benchmark::composite;

namespace
{
// Grey-level differences over the pixels that are non-black in either image (the black
// background would dilute the RMS by the empty share of the window).
ErrorStats Compare(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b, int size)
{
  const auto mask = MaskOr(NonBackgroundMask(a, size, size), NonBackgroundMask(b, size, size));
  return CompareImages(a, b, mask, 2.0);
}

bool LoadDataset(const Options& options, const std::string& name, DatasetInfo& info,
  vtkSmartPointer<vtkImageData>& image)
{
  info.Name = name;
  info.File = FindDatasetFile(options.DataDir, name);
  if (info.File.empty())
  {
    std::cerr << "dataset " << name << ": no file " << name << "_<X>x<Y>x<Z>_<type>.raw[.gz] in "
              << options.DataDir << "\n";
    return false;
  }
  accelvolume::cli::VolumeRequest request;
  request.inputPath = info.File; // spacing comes from datasets.json next to the file
  std::string error;
  const auto start = Clock::now();
  image = accelvolume::cli::LoadVolume(request, error);
  info.LoadSeconds = SecondsSince(start);
  if (!image)
  {
    std::cerr << "dataset " << name << ": " << error << "\n";
    return false;
  }
  info.Description = accelvolume::cli::DescribeVolume(image);
  image->GetSpacing(info.Spacing);
  info.MinSpacing = std::min({ info.Spacing[0], info.Spacing[1], info.Spacing[2] });
  image->GetPointData()->GetScalars()->GetRange(info.Range);
  return true;
}

// All cases (transfer functions x sizes) of one volume; one renderer holds both mappers.
void RunDataset(const Options& options, const DatasetInfo& info, vtkImageData* image,
  vtkAccelVolumeHeadlessRenderWindow* window, std::vector<CaseResult>& cases)
{
  vtkNew<vtkVolumeProperty> property;
  vtkNew<vtkAccelVolumeSliceMapper> slice;
  slice->SetInputData(image);
  slice->SetBlendModeToComposite();
  slice->SetAutoAdjustSampleDistances(0);
  slice->SetSampleDistance(info.MinSpacing);
  vtkNew<vtkVolume> sliceVolume;
  sliceVolume->SetMapper(slice);
  sliceVolume->SetProperty(property);

  vtkNew<vtkGPUVolumeRayCastMapper> gpu;
  gpu->SetInputData(image);
  gpu->SetBlendModeToComposite();
  gpu->SetAutoAdjustSampleDistances(0);
  gpu->SetSampleDistance(static_cast<float>(info.MinSpacing));
  gpu->SetImageSampleDistance(1.0f);
  gpu->SetUseJittering(0);
  vtkNew<vtkVolume> gpuVolume;
  gpuVolume->SetMapper(gpu);
  gpuVolume->SetProperty(property);

  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(0, 0, 0);
  renderer->AddVolume(sliceVolume);
  renderer->AddVolume(gpuVolume);
  window->AddRenderer(renderer);

  // The CLI's camera: front view along +z at the centre, then azimuth / elevation.
  double bounds[6];
  image->GetBounds(bounds);
  auto setView = [&]()
  {
    vtkCamera* camera = renderer->GetActiveCamera();
    camera->SetFocalPoint(
      (bounds[0] + bounds[1]) / 2, (bounds[2] + bounds[3]) / 2, (bounds[4] + bounds[5]) / 2);
    camera->SetPosition(
      (bounds[0] + bounds[1]) / 2, (bounds[2] + bounds[3]) / 2, (bounds[4] + bounds[5]) / 2 - 1);
    camera->SetViewUp(0, 1, 0);
    renderer->ResetCamera();
    camera->Azimuth(options.Azimuth);
    camera->Elevation(options.Elevation);
    camera->OrthogonalizeViewUp();
    renderer->ResetCameraClippingRange();
  };

  // The CLI's settings for `render --blend composite --tf tfN --shade on` (window = data range).
  accelvolume::cli::Options cli;
  cli.blend = accelvolume::cli::BlendKind::Composite;
  cli.haveShade = true;
  cli.shade = true;
  const double tfWindow[2] = { info.Range[0],
    info.Range[1] > info.Range[0] ? info.Range[1] : info.Range[0] + 1 };

  const std::vector<Config> configs = MakeConfigs();
  vtkNew<vtkUnsignedCharArray> onePixel;
  auto apply = [&](const Config& cfg)
  {
    sliceVolume->SetVisibility(!cfg.Vtk);
    gpuVolume->SetVisibility(cfg.Vtk);
    if (!cfg.Vtk)
    {
      slice->SetEarlyRayTermination(cfg.Ert);
      slice->SetEmptySpaceSkipping(cfg.Ess);
    }
  };
  for (const std::string& tf : options.TransferFunctions)
  {
    cli.transferFunction = tf;
    accelvolume::cli::ApplyTransferFunction(
      accelvolume::cli::LoadTransferFunction(cli), cli, tfWindow, property);
    for (int size : options.Sizes)
    {
      const auto caseStart = Clock::now();
      window->SetSize(size, size);
      CaseResult c;
      c.Dataset = info.Name;
      c.Tf = tf;
      c.Size = size;
      c.Frames = options.FramesFor(size);
      for (const Config& cfg : configs)
      {
        c.Results.push_back({ cfg });
      }
      auto renderAndWait = [&]()
      {
        window->Render();
        static_cast<vtkRenderWindow*>(window)->GetPixelData(
          size / 2, size / 2, size / 2, size / 2, 0, onePixel.Get());
      };

      // Warm-up (texture upload, octree build / classification, shader compilation) and the
      // quality-check images, both at the fixed view.
      setView();
      std::vector<std::uint8_t> baseImage, bothImage, vtkImage;
      for (ConfigResult& r : c.Results)
      {
        apply(r.Cfg);
        renderAndWait();
        if (r.Cfg.Id == "base" || r.Cfg.Id == "ert_both" || r.Cfg.Vtk)
        {
          window->Render(); // a second frame: the first may include one-time work
          auto& target = r.Cfg.Id == "base" ? baseImage : r.Cfg.Vtk ? vtkImage : bothImage;
          target = Capture(window, size, size);
        }
      }
      c.ErtBothVsBase = Compare(baseImage, bothImage, size);
      c.OursVsVtk = Compare(vtkImage, bothImage, size);
      if (!options.Images.empty())
      {
        std::error_code ec;
        fs::create_directories(options.Images, ec);
        const std::string stem =
          options.Images + "/" + info.Name + "_" + tf + "_" + std::to_string(size) + "_";
        WritePng(stem + "base.png", baseImage, size, size);
        WritePng(stem + "ert_both.png", bothImage, size, size);
        WritePng(stem + "vtk.png", vtkImage, size, size);
      }

      for (int f = 0; f < c.Frames; ++f)
      {
        renderer->GetActiveCamera()->Azimuth(1.0);
        renderer->ResetCameraClippingRange();
        for (ConfigResult& r : c.Results)
        {
          apply(r.Cfg);
          const auto start = Clock::now();
          renderAndWait();
          r.FrameMs.push_back(
            std::chrono::duration<double, std::milli>(Clock::now() - start).count());
          if (!r.Cfg.Vtk)
          {
            r.MapperMs.push_back(1000.0 * slice->GetLastRenderTime());
            r.TerminationPasses = slice->GetLastNumberOfTerminationPasses();
            r.TransparentLeafFraction = slice->GetLastTransparentLeafFraction();
            r.Slices = slice->GetLastNumberOfSlices();
          }
        }
      }
      c.Seconds = SecondsSince(caseStart);
      const ConfigResult* base = c.Find("base");
      std::cout << "  " << std::left << std::setw(20) << info.Name << std::setw(4) << tf
                << std::right << std::setw(5) << size << "  " << c.Frames << " frames, ms:";
      for (const ConfigResult& r : c.Results)
      {
        std::cout << " " << r.Cfg.Id << " " << Num(r.MedianMs(), 0);
      }
      std::cout << "  (ERT passes " << c.Find("ert_both")->TerminationPasses << ", slices "
                << base->Slices << ", " << Num(c.Seconds, 1) << " s)\n"
                << std::flush;
      cases.push_back(std::move(c));
    }
  }
  window->RemoveRenderer(renderer);
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
  StartHeadlessWindow(window, backend, options.Sizes.front(), options.Sizes.front());
  const std::string rendererName = window->GetOpenGLRendererString();
  const std::string backendName =
    vtkAccelVolumeHeadlessRenderWindow::GetBackendName(window->GetActiveBackend());

  std::cout << "accelvolume_benchmark_composite: Lee 2005 Table V-3 (slice-based composite "
               "rendering: early ray termination, empty-space skipping)\n"
            << "settings: GL " << backendName << " (" << rendererName
            << "), MultiSamples 0, shading on (tf presets of `accelvolume render --tf` over the "
               "data range), sample distance = smallest voxel spacing, AutoAdjust off;\n"
            << "  view azimuth " << options.Azimuth << " elevation " << options.Elevation
            << ", camera turned 1 deg per round; " << options.Frames << " timed frames per config";
  if (options.LargeFrames > 0 && options.LargeFrames != options.Frames)
  {
    std::cout << " (" << options.LargeFrames
              << " at sizes above 256, to keep the run short: --large-frames)";
  }
  std::cout << " after one warm-up frame; frames interleaved across configs; time = Render() + "
               "1x1 read-back, median\n"
            << "data: " << options.DataDir << "\n"
            << std::flush;

  const auto start = Clock::now();
  std::vector<DatasetInfo> datasets;
  std::vector<CaseResult> cases;
  bool ok = true;
  // A case per dataset here (its transfer functions and sizes run inside RunDataset).
  CaseProgress progress(
    "accelvolume_benchmark_composite", static_cast<int>(options.Datasets.size()));
  for (const std::string& name : options.Datasets)
  {
    progress.Begin(name);
    DatasetInfo info;
    vtkSmartPointer<vtkImageData> image;
    if (!LoadDataset(options, name, info, image))
    {
      ok = false;
      continue;
    }
    std::cout << "=== " << name << ": " << info.Description << ", spacing " << info.Spacing[0]
              << " " << info.Spacing[1] << " " << info.Spacing[2] << ", range " << info.Range[0]
              << ".." << info.Range[1] << " (loaded in " << Num(info.LoadSeconds, 2) << " s)\n"
              << std::flush;
    RunDataset(options, info, image, window, cases);
    datasets.push_back(info);
  }
  if (!cases.empty())
  {
    PrintTable(datasets, cases);
  }
  const double total = SecondsSince(start);
  WriteJson(options, rendererName, backendName, datasets, cases, total);
  std::cout << "results written to " << options.Json << "; total " << Num(total, 1) << " s\n";
  return ok && !cases.empty() ? 0 : 1;
}
