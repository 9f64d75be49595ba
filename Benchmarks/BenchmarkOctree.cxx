// accelvolume_benchmark_octree: min-max octree build times of Lim and Shin 2009 on
// real volumes and a time-varying phantom, against a one-thread streaming read of the volume.
//
// Per dataset: builds with the reference builder (plain loops), the Morton-order CPU builder
// on 1 thread and on all threads, and the GPU compute builder (OpenGL >= 4.3 in a headless
// window); each build is forced by marking the scalars modified (as a new time step would);
// median of --repeat. The read floor sums every byte as 64-bit words on one thread. Re-
// classification alternates two opacity ramps. The time-varying phantom (Lim and Shin 2009's
// motivation) also times frames of data update + CPU rebuild + slice-mapper MIP render.
// Table and JSON: BenchmarkOctreeReport.{h,cxx}.
#include "BenchmarkOctreeReport.h"
#include "VolumeIO.h"

#include "vtkAccelVolumeHeadlessRenderWindow.h"
#include "vtkAccelVolumeMinMaxOctree.h"
#include "vtkAccelVolumeSliceMapper.h"

#include <vtkColorTransferFunction.h>
#include <vtkDataArray.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPiecewiseFunction.h>
#include <vtkPointData.h>
#include <vtkRenderer.h>
#include <vtkSMPTools.h>
#include <vtkSmartPointer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkVolume.h>
#include <vtkVolumeProperty.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <sstream>

namespace fs = std::filesystem;
using namespace accelvolume::benchmark;

namespace
{
// One thread streaming every byte once; the sum is published so the loop is not elided.
volatile std::uint64_t Sink = 0;
double ReadFloorMs(const void* data, std::size_t bytes)
{
  const auto start = Clock::now();
  const auto* p = static_cast<const unsigned char*>(data);
  std::uint64_t sum = 0;
  std::size_t i = 0;
  for (; i + 8 <= bytes; i += 8)
  {
    std::uint64_t word;
    std::memcpy(&word, p + i, 8);
    sum += word;
  }
  for (; i < bytes; ++i)
  {
    sum += p[i];
  }
  Sink = Sink + sum;
  return MsSince(start);
}

// NAME_*.raw[.gz] in the data folder ("" if absent): a looser match than the shared
// FindDatasetFile(), which also requires the _<X>x<Y>x<Z>_<type> part.
std::string FindPrefixedRawFile(const std::string& dir, const std::string& name)
{
  std::error_code ec;
  std::vector<std::string> matches;
  for (const auto& entry : fs::directory_iterator(dir, ec))
  {
    const std::string file = entry.path().filename().string();
    const bool raw = file.size() > 4 &&
      (file.compare(file.size() - 4, 4, ".raw") == 0 ||
        (file.size() > 7 && file.compare(file.size() - 7, 7, ".raw.gz") == 0));
    if (raw && file.compare(0, name.size() + 1, name + "_") == 0)
    {
      matches.push_back(entry.path().string());
    }
  }
  std::sort(matches.begin(), matches.end());
  return matches.empty() ? std::string() : matches.front();
}

// Opacity 0 up to `low`, then a ramp to 1 at the maximum (the CLI's --tf-low function).
void SetRamp(vtkPiecewiseFunction* opacity, double low, const double range[2])
{
  opacity->RemoveAllPoints();
  opacity->AddPoint(std::min(low, range[0]), 0.0);
  opacity->AddPoint(low, 0.0);
  opacity->AddPoint(std::max(range[1], low + 1e-6), 1.0);
}

// Times forced rebuilds; a build slower than 2 s cuts the repeats so the run stays short.
bool TimeBuilds(
  vtkAccelVolumeMinMaxOctree* octree, vtkImageData* image, int repeat, BuildResult& result)
{
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  int count = repeat;
  for (int k = 0; k < count; ++k)
  {
    scalars->Modified();
    image->Modified();
    const auto start = Clock::now();
    if (!octree->Update())
    {
      return false;
    }
    result.Ms.push_back(MsSince(start));
    if (k == 0 && result.Ms[0] > 2000.0)
    {
      count = std::max(1, std::min(repeat, static_cast<int>(8000.0 / result.Ms[0])));
    }
  }
  result.Repeats = count;
  result.ReducedRepeats = count < repeat;
  return true;
}

struct GPUState
{
  bool Available = false;
  std::string Why;
  std::string Renderer;
  std::string Version;
};

bool RunDataset(const Options& options, const std::string& name, vtkImageData* image,
  vtkAccelVolumeHeadlessRenderWindow* window, const GPUState& gpu, DatasetResult& d)
{
  d.Name = name;
  d.Description = accelvolume::cli::DescribeVolume(image);
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  d.Bytes = static_cast<std::size_t>(scalars->GetNumberOfValues()) * scalars->GetDataTypeSize();
  scalars->GetRange(d.Range, 0);
  for (int k = 0; k < options.Repeat; ++k)
  {
    d.ReadFloorMs.push_back(ReadFloorMs(scalars->GetVoidPointer(0), d.Bytes));
  }
  std::cout << "=== " << name << " (" << d.Description << ", " << Num(d.Bytes / 1e6, 1)
            << " MB): read floor " << Num(Median(d.ReadFloorMs), 2) << " ms\n"
            << std::flush;

  vtkNew<vtkAccelVolumeMinMaxOctree> octree;
  octree->SetInputData(image);
  octree->SetLeafSize(options.Leaf);
  octree->SetRenderWindow(window);
  struct Config
  {
    const char* Builder;
    int Id;
    int Threads; // 0 = all
  };
  const Config configs[] = { { "reference", vtkAccelVolumeMinMaxOctree::BUILDER_REFERENCE, 1 },
    { "cpu", vtkAccelVolumeMinMaxOctree::BUILDER_CPU, 1 },
    { "cpu", vtkAccelVolumeMinMaxOctree::BUILDER_CPU, 0 },
    { "gpu", vtkAccelVolumeMinMaxOctree::BUILDER_GPU, 0 } };
  for (const Config& config : configs)
  {
    if (config.Id == vtkAccelVolumeMinMaxOctree::BUILDER_GPU && !gpu.Available)
    {
      continue;
    }
    BuildResult build;
    build.Builder = config.Builder;
    // "All threads" is the count measured at start-up, set explicitly: in VTK 9.1 (TBB) a
    // LocalScope of 1 thread does not restore the default afterwards, so 0 would stay at 1.
    const int threads = config.Threads > 0 ? config.Threads : options.AllThreads;
    build.Threads = config.Id == vtkAccelVolumeMinMaxOctree::BUILDER_GPU ? 0 : threads;
    build.AllThreads = config.Id == vtkAccelVolumeMinMaxOctree::BUILDER_CPU && config.Threads == 0;
    octree->SetBuilder(config.Id);
    octree->SetNumberOfThreads(threads);
    if (!TimeBuilds(octree, image, options.Repeat, build))
    {
      std::cerr << name << ": " << config.Builder << " build failed\n";
      return false;
    }
    std::cout << "    " << config.Builder << ", threads " << build.Threads << ": "
              << Num(Median(build.Ms), 2) << " ms median of " << build.Ms.size()
              << (build.ReducedRepeats ? " (repeats reduced: > 2 s per build)" : "") << "\n"
              << std::flush;
    d.Builds.push_back(build);
    d.Nodes = octree->GetNumberOfNodes();
    d.Depth = octree->GetDepth();
  }

  // Re-classification on the last CPU-resident octree: rebuild with all threads first so the
  // GPU read-back is not part of it; every call gets a modified function, so it really runs.
  octree->SetBuilder(vtkAccelVolumeMinMaxOctree::BUILDER_CPU);
  octree->SetNumberOfThreads(options.AllThreads);
  octree->Update();
  vtkNew<vtkPiecewiseFunction> opacity;
  const double low = d.Range[0] + 0.1 * (d.Range[1] - d.Range[0]);
  const double alternate = low + 0.5 * (d.Range[1] - low);
  SetRamp(opacity, low, d.Range);
  octree->Classify(opacity, d.Range);
  d.TransparentLeafFraction = octree->GetTransparentLeafFraction();
  for (int k = 0; k < std::max(options.Repeat, 5); ++k)
  {
    SetRamp(opacity, k % 2 == 0 ? alternate : low, d.Range);
    const auto start = Clock::now();
    octree->Classify(opacity, d.Range);
    d.ClassifyMs.push_back(MsSince(start));
  }
  window->MakeCurrent();
  octree->ReleaseGraphicsResources();
  return true;
}

// Lim and Shin 2009's case: the volume changes every frame, so the octree is rebuilt before each render.
void RunTimeVarying(const Options& options, vtkAccelVolumeHeadlessRenderWindow* window,
  const GPUState& gpu, DatasetResult& d)
{
  const int dims[3] = { options.PhantomSize, options.PhantomSize, options.PhantomSize };
  accelvolume::PhantomVolume phantom;
  std::string error;
  auto start = Clock::now();
  accelvolume::GeneratePhantom("vessels", dims, 0.0, phantom, error);
  vtkSmartPointer<vtkImageData> image = accelvolume::cli::PhantomToImage(phantom);
  const double generateMs = MsSince(start);
  if (!RunDataset(options, "vessels (t)", image, window, gpu, d))
  {
    return;
  }
  d.Frames.GenerateMs.push_back(generateMs);

  vtkNew<vtkColorTransferFunction> colour;
  colour->AddRGBPoint(d.Range[0], 0, 0, 0);
  colour->AddRGBPoint(d.Range[1], 1, 1, 1);
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(d.Range[0], 0.0);
  opacity->AddPoint(d.Range[1], 1.0);
  vtkNew<vtkVolumeProperty> property;
  property->SetColor(colour);
  property->SetScalarOpacity(opacity);
  property->SetInterpolationTypeToLinear();
  vtkNew<vtkAccelVolumeSliceMapper> mapper;
  mapper->SetBlendModeToMaximumIntensity();
  mapper->SetInputData(image);
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  volume->SetProperty(property);
  vtkNew<vtkRenderer> renderer;
  renderer->AddVolume(volume);
  window->AddRenderer(renderer);
  renderer->ResetCamera();
  vtkNew<vtkUnsignedCharArray> pixel;
  auto render = [&]()
  {
    window->Render();
    window->GetPixelData(0, 0, 0, 0, 0, pixel, 0); // waits for the GPU
  };
  render(); // warm-up: texture and shader creation

  vtkNew<vtkAccelVolumeMinMaxOctree> octree;
  octree->SetInputData(image);
  octree->SetLeafSize(options.Leaf);
  octree->SetNumberOfThreads(options.AllThreads);
  octree->Update();
  auto* values = vtkFloatArray::SafeDownCast(image->GetPointData()->GetScalars());
  for (int f = 1; f <= options.Frames; ++f)
  {
    start = Clock::now();
    accelvolume::GeneratePhantom("vessels", dims, 0.05 * f, phantom, error);
    d.Frames.GenerateMs.push_back(MsSince(start));

    const auto frameStart = Clock::now();
    std::memcpy(values->GetPointer(0), phantom.values.data(), phantom.values.size() * 4);
    values->Modified();
    image->Modified();
    d.Frames.CopyMs.push_back(MsSince(frameStart));
    start = Clock::now();
    octree->Update();
    d.Frames.RebuildMs.push_back(MsSince(start));
    start = Clock::now();
    render();
    d.Frames.RenderMs.push_back(MsSince(start));
    d.Frames.FrameMs.push_back(MsSince(frameStart));
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
  const auto begin = Clock::now();
  const int backend = vtkAccelVolumeHeadlessRenderWindow::ParseBackendName(options.GL.c_str());
  if (backend < 0 || backend == vtkAccelVolumeHeadlessRenderWindow::BACKEND_X ||
    (backend != vtkAccelVolumeHeadlessRenderWindow::BACKEND_AUTOMATIC &&
      !vtkAccelVolumeHeadlessRenderWindow::IsBackendAvailable(backend)))
  {
    std::cerr << "--gl must be an available headless backend (egl, osmesa or auto)\n";
    return 2;
  }
  vtkNew<vtkAccelVolumeHeadlessRenderWindow> window;
  StartHeadlessWindow(window, backend, 512, 512);
  GPUState gpu;
  gpu.Renderer = window->GetOpenGLRendererString();
  int major = 0, minor = 0;
  window->GetOpenGLVersion(major, minor);
  gpu.Version = std::to_string(major) + "." + std::to_string(minor);
  gpu.Available = major * 10 + minor >= 43;
  gpu.Why = gpu.Available ? "" : "OpenGL " + gpu.Version + " < 4.3 (no compute shaders)";

  Machine machine;
  machine.Threads = vtkSMPTools::GetEstimatedNumberOfThreads();
  options.AllThreads = machine.Threads;
  machine.SMPBackend = vtkSMPTools::GetBackend() ? vtkSMPTools::GetBackend() : "unknown";
  machine.GLBackend =
    vtkAccelVolumeHeadlessRenderWindow::GetBackendName(window->GetActiveBackend());
  machine.GLRenderer = gpu.Renderer;
  machine.GLVersion = gpu.Version;
  machine.GPUNote = gpu.Why;
  std::cout << "accelvolume_benchmark_octree: Lim and Shin 2009 (min-max octree build), leaf "
            << options.Leaf << ", median of " << options.Repeat << "; " << machine.Threads
            << " threads (" << machine.SMPBackend << "), GL " << machine.GLBackend << " "
            << gpu.Version << " (" << gpu.Renderer << ")"
            << (gpu.Available ? "" : "; gpu builder skipped: " + gpu.Why) << "\n"
            << "data: " << options.DataDir << "\n"
            << std::flush;

  std::vector<DatasetResult> results;
  bool ok = true;
  CaseProgress progress(
    "accelvolume_benchmark_octree", static_cast<int>(options.Datasets.size()));
  for (const std::string& name : options.Datasets)
  {
    progress.Begin(name);
    DatasetResult d;
    if (name == "vessels")
    {
      RunTimeVarying(options, window, gpu, d);
      if (d.Builds.empty())
      {
        ok = false;
        continue;
      }
      results.push_back(std::move(d));
      continue;
    }
    d.File = FindPrefixedRawFile(options.DataDir, name);
    if (d.File.empty())
    {
      std::cerr << name << ": no file " << name << "_<X>x<Y>x<Z>_<type>.raw[.gz] in "
                << options.DataDir << "\n";
      ok = false;
      continue;
    }
    accelvolume::cli::VolumeRequest request;
    request.inputPath = d.File;
    std::string error;
    const auto loadStart = Clock::now();
    vtkSmartPointer<vtkImageData> image = accelvolume::cli::LoadVolume(request, error);
    d.LoadSeconds = MsSince(loadStart) / 1000.0;
    if (!image || !RunDataset(options, name, image, window, gpu, d))
    {
      std::cerr << name << ": " << (image ? "benchmark failed" : error) << "\n";
      ok = false;
      continue;
    }
    results.push_back(std::move(d));
  }
  PrintReport(machine, results);
  WriteJson(options, machine, results);
  std::cout << "results written to " << options.Json << "; total " << Num(MsSince(begin) / 1000, 1)
            << " s\n";
  return ok && !results.empty() ? 0 : 1;
}
