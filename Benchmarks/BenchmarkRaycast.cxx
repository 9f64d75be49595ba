// accelvolume_benchmark_raycast: Table 2 of Lim, Kim and Shin 2009 (semi-transparent cell leaping through a
// modified Marching Cubes table) and beyond, on real volumes.
// Lim, Kim and Shin 2009 casts rays on the CPU (perspective, 512^2 images) with distance-map or min-max
// octree leaping, and reports 16.8-24.1 % more speed when semi-transparent cells are leaped as
// well, with pixel-identical images. This program measures vtkAccelVolumeRayCastMapper in every
// leap mode (none / distance map / octree) with cell leaping off and on, against VTK's
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
// Options: BenchmarkRaycastOptions.{h,cxx}; tables and JSON: BenchmarkRaycastReport.{h,cxx}.
#include "BenchmarkCommon.h"
#include "BenchmarkImageMetrics.h"
#include "BenchmarkRaycastOptions.h"
#include "BenchmarkRaycastReport.h"
#include "Options.h"
#include "TransferFunctions.h"
#include "VolumeIO.h"

#include "vtkAccelVolumeHeadlessRenderWindow.h"
#include "vtkAccelVolumeRayCastMapper.h"

#include <vtkCamera.h>
#include <vtkDataArray.h>
#include <vtkFixedPointVolumeRayCastMapper.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkVolume.h>
#include <vtkVolumeProperty.h>

#include <sys/resource.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>
#include <thread>
#include <vector>

using namespace accelvolume::benchmark;
using namespace accelvolume::benchmark::raycast;

namespace
{
// Grey-level error of `image` against `reference` over the pixels non-black in either.
ErrorStats AgainstReference(
  const std::vector<std::uint8_t>& reference, const std::vector<std::uint8_t>& image, int size)
{
  return CompareImages(reference, image,
    MaskOr(NonBackgroundMask(reference, size, size), NonBackgroundMask(image, size, size)), 2.0);
}

// Pixels whose bytes differ at all, and the largest byte difference.
void ByteDifferences(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b,
  long long& pixels, int& largest)
{
  pixels = 0;
  largest = 0;
  for (size_t p = 0; p + 2 < a.size() && p + 2 < b.size(); p += 3)
  {
    int differs = 0;
    for (size_t channel = p; channel < p + 3; ++channel)
    {
      differs = std::max(differs, std::abs(int(a[channel]) - int(b[channel])));
    }
    pixels += differs > 0;
    largest = std::max(largest, differs);
  }
}

// Loads and describes one volume (a line on stdout); false, after saying why, when it can't.
bool LoadDataset(const Options& options, const std::string& name, DatasetInfo& info,
  vtkSmartPointer<vtkImageData>& image)
{
  info.Name = name;
  info.File = FindDatasetFile(options.DataDir, name);
  std::string error = "no file " + name + "_<X>x<Y>x<Z>_<type>.raw[.gz] in " + options.DataDir;
  if (!info.File.empty())
  {
    accelvolume::cli::VolumeRequest request;
    request.inputPath = info.File; // the spacing comes from datasets.json beside the file
    const auto start = Clock::now();
    image = accelvolume::cli::LoadVolume(request, error);
    info.LoadSeconds = SecondsSince(start);
  }
  if (!image)
  {
    std::cerr << "dataset " << name << ": " << error << "\n";
    return false;
  }
  info.Description = accelvolume::cli::DescribeVolume(image);
  image->GetSpacing(info.Spacing);
  info.MinSpacing = *std::min_element(info.Spacing, info.Spacing + 3);
  image->GetPointData()->GetScalars()->GetRange(info.Range);
  std::cout << "=== " << name << ": " << info.Description << ", spacing " << info.Spacing[0] << " "
            << info.Spacing[1] << " " << info.Spacing[2] << ", range " << info.Range[0] << ".."
            << info.Range[1] << " (loaded in " << Num(info.LoadSeconds, 2) << " s)\n"
            << std::flush;
  return true;
}

// User + system CPU time of the whole process (every thread) in milliseconds.
double ProcessCpuMs()
{
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return 1000.0 * (usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
    (usage.ru_utime.tv_usec + usage.ru_stime.tv_usec) / 1000.0;
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
// fixed oblique view; perspective.
void SetFixedView(vtkRenderer* renderer, vtkImageData* image, const Options& options)
{
  double bounds[6];
  image->GetBounds(bounds);
  const double centre[3] = { (bounds[0] + bounds[1]) / 2, (bounds[2] + bounds[3]) / 2,
    (bounds[4] + bounds[5]) / 2 };
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->ParallelProjectionOff();
  camera->SetFocalPoint(centre);
  camera->SetPosition(centre[0], centre[1], centre[2] - 1);
  camera->SetViewUp(0, 1, 0);
  renderer->ResetCamera();
  camera->Azimuth(options.Azimuth);
  camera->Elevation(options.Elevation);
  camera->OrthogonalizeViewUp();
  renderer->ResetCameraClippingRange();
}

// One volume x transfer function: fresh mappers (so every case pays its own first frame), the
// prepare frames, the image checks at the fixed view and the timed rounds.
CaseResult RunCase(const Options& options, const DatasetInfo& info, vtkImageData* image,
  const std::string& tf, vtkAccelVolumeHeadlessRenderWindow* window)
{
  const auto caseStart = Clock::now();
  const int size = options.Size;
  CaseResult c;
  c.Dataset = info.Name;
  c.Tf = tf;
  c.Size = size;
  c.Frames = options.Frames;
  c.SampleDistance = options.SampleFactor * info.MinSpacing;
  c.ReferenceSampleDistance = c.SampleDistance / options.ReferenceFactor;

  vtkNew<vtkVolumeProperty> property;
  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(0, 0, 0);
  std::vector<vtkSmartPointer<vtkVolume>> volumes;
  std::vector<vtkAccelVolumeRayCastMapper*> ours; // nullptr for VTK's mapper
  auto addVolume = [&](vtkVolumeMapper* mapper)
  {
    mapper->SetInputData(image);
    mapper->SetBlendModeToComposite();
    auto volume = vtkSmartPointer<vtkVolume>::New();
    volume->SetMapper(mapper);
    volume->SetProperty(property);
    renderer->AddVolume(volume);
    volumes.push_back(volume);
    ours.push_back(vtkAccelVolumeRayCastMapper::SafeDownCast(mapper));
  };
  for (const Config& cfg : MakeConfigs())
  {
    c.Results.push_back({ cfg });
    if (cfg.Vtk)
    {
      addVolume(VtkMapper(c.SampleDistance, options.Threads));
    }
    else
    {
      addVolume(OurMapper(c.SampleDistance, options.Threads, cfg.Leap, cfg.Cell));
    }
  }
  const size_t reference = volumes.size(); // the fine reference, last
  addVolume(OurMapper(
    c.ReferenceSampleDistance, options.Threads, vtkAccelVolumeRayCastMapper::LEAP_NONE, false));
  window->AddRenderer(renderer);

  vtkNew<vtkUnsignedCharArray> onePixel;
  double lastCores = 0; // CPU time / wall time of the last render(): the cores it kept busy
  // Shows volume k alone and renders it; wall milliseconds of Render() + a 1x1 read-back.
  auto render = [&](size_t k)
  {
    for (size_t j = 0; j < volumes.size(); ++j)
    {
      volumes[j]->SetVisibility(j == k);
    }
    const double cpuStart = ProcessCpuMs();
    const auto start = Clock::now();
    window->Render();
    static_cast<vtkRenderWindow*>(window)->GetPixelData(
      size / 2, size / 2, size / 2, size / 2, 0, onePixel.Get());
    const double wall = MsSince(start);
    lastCores = SafeRatio(ProcessCpuMs() - cpuStart, wall);
    return wall;
  };

  // The CLI's `render --blend composite --tf <tf> --shade on|off`, window = the data range.
  accelvolume::cli::Options cli;
  cli.blend = accelvolume::cli::BlendKind::Composite;
  cli.haveShade = true;
  cli.shade = options.Shade;
  cli.transferFunction = tf;
  const auto spec = accelvolume::cli::LoadTransferFunction(cli);
  const double low = info.Range[0];
  const double high = info.Range[1] > low ? info.Range[1] : low + 1;
  const double wider[2] = { low, high + 0.02 * (high - low) };
  const double tfWindow[2] = { low, high };

  SetFixedView(renderer, image, options);
  accelvolume::cli::ApplyTransferFunction(spec, cli, wider, property);
  for (size_t k = 0; k < c.Results.size(); ++k)
  {
    c.Results[k].FirstFrameMs = render(k);
    c.Results[k].FirstPrepareMs = ours[k] ? 1000.0 * ours[k]->GetLastPrepareTime() : std::nan("");
  }
  accelvolume::cli::ApplyTransferFunction(spec, cli, tfWindow, property);
  std::vector<std::vector<std::uint8_t>> images;
  for (size_t k = 0; k < c.Results.size(); ++k)
  {
    c.Results[k].TfFrameMs = render(k);
    c.Results[k].TfPrepareMs = ours[k] ? 1000.0 * ours[k]->GetLastPrepareTime() : std::nan("");
    images.push_back(Capture(window, size, size));
  }
  c.ReferenceMs = render(reference);
  const std::vector<std::uint8_t> referenceImage = Capture(window, size, size);

  for (size_t k = 0; k < c.Results.size(); ++k)
  {
    if (ours[k])
    {
      ByteDifferences(
        images[0], images[k], c.Results[k].DifferingPixels, c.Results[k].MaxDifference);
    }
  }
  auto indexOf = [&](const char* id) { return static_cast<size_t>(c.Find(id) - c.Results.data()); };
  const size_t ourDefault = indexOf("dmap_off"); // the mapper's default configuration
  const size_t vtk = indexOf("vtk_fixed");
  c.OursVsReference = AgainstReference(referenceImage, images[ourDefault], size);
  c.VtkVsReference = AgainstReference(referenceImage, images[vtk], size);
  c.OursVsVtk = AgainstReference(images[vtk], images[ourDefault], size);
  if (!options.Images.empty())
  {
    std::error_code ec;
    std::filesystem::create_directories(options.Images, ec);
    const std::string stem = options.Images + "/" + info.Name + "_" + tf + "_";
    WritePng(stem + "dmap_off.png", images[ourDefault], size, size);
    WritePng(stem + "vtk_fixed.png", images[vtk], size, size);
    WritePng(stem + "reference.png", referenceImage, size, size);
  }

  const double perFrame = 1.0 / options.Frames;
  for (int f = 0; f < options.Frames; ++f)
  {
    renderer->GetActiveCamera()->Azimuth(options.Turn);
    renderer->ResetCameraClippingRange();
    for (size_t k = 0; k < c.Results.size(); ++k)
    {
      ConfigResult& r = c.Results[k];
      r.FrameMs.push_back(render(k));
      r.Cores.push_back(lastCores);
      if (vtkAccelVolumeRayCastMapper* m = ours[k])
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
  window->RemoveRenderer(renderer);
  c.Seconds = SecondsSince(caseStart);
  return c;
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
  StartHeadlessWindow(window, backend, options.Size, options.Size);
  MachineInfo machine;
  machine.Cpu = ReadCpuModel();
  machine.HardwareThreads = static_cast<int>(std::thread::hardware_concurrency());
  machine.GlRenderer = window->GetOpenGLRendererString();
  machine.GlBackend =
    vtkAccelVolumeHeadlessRenderWindow::GetBackendName(window->GetActiveBackend());

  std::cout << "accelvolume_benchmark_raycast: Lim, Kim and Shin 2009 Table 2 (CPU ray casting: empty-space "
               "leaping with / without semi-transparent cell leaping) and vtkFixedPoint\n"
            << "machine: " << (machine.Cpu.empty() ? "CPU unknown" : machine.Cpu) << ", "
            << machine.HardwareThreads << " hardware threads; GL " << machine.GlBackend << " ("
            << machine.GlRenderer << ")\n"
            << "settings: " << options.Size << "x" << options.Size << " perspective, composite, "
            << "shading " << (options.Shade ? "on" : "off")
            << " (tf presets of `accelvolume render --tf` over the data range), sample distance = "
            << options.SampleFactor << " x smallest voxel spacing, ImageSampleDistance 1, "
            << "AutoAdjust off, early ray termination on, " << options.Threads
            << " threads for every mapper;\n  view azimuth " << options.Azimuth << " elevation "
            << options.Elevation << ", camera turned " << options.Turn << " deg per round; "
            << options.Frames
            << " timed frames per config after the prepare / warm-up frames, interleaved; "
               "time = Render() + 1x1 read-back, median\n"
            << "data: " << options.DataDir << "\n"
            << std::flush;

  const auto start = Clock::now();
  std::vector<DatasetInfo> datasets;
  std::vector<CaseResult> cases;
  bool ok = true;
  const int tfCount = static_cast<int>(options.TransferFunctions.size());
  CaseProgress progress(
    "accelvolume_benchmark_raycast", static_cast<int>(options.Datasets.size()) * tfCount);
  for (const std::string& name : options.Datasets)
  {
    DatasetInfo info;
    vtkSmartPointer<vtkImageData> image;
    if (!LoadDataset(options, name, info, image))
    {
      ok = false;
      progress.Skip(tfCount);
      continue;
    }
    for (const std::string& tf : options.TransferFunctions)
    {
      progress.Begin(name + " " + tf);
      cases.push_back(RunCase(options, info, image, tf, window));
      const CaseResult& c = cases.back();
      std::cout << "--- " << name << " " << tf << ": sample distance " << c.SampleDistance << ", "
                << c.Frames << " frames (" << Num(c.Seconds, 1) << " s)\n";
      PrintCase(c);
    }
    datasets.push_back(info);
  }
  if (!cases.empty())
  {
    PrintSummary(cases);
  }
  const double total = SecondsSince(start);
  WriteJson(options, machine, datasets, cases, total);
  std::cout << "results written to " << options.Json << "; total " << Num(total, 1) << " s\n";
  const bool identical =
    std::all_of(cases.begin(), cases.end(), [](const CaseResult& c) { return c.Identical(); });
  if (!identical)
  {
    std::cout << "FAILED: our leaping configurations gave different images\n";
    return 3;
  }
  return ok && !cases.empty() ? 0 : 1;
}
