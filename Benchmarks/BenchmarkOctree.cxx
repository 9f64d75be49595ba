// accelvolume_benchmark_octree: min-max octree build times of Lim and Shin 2009 on
// real volumes and a time-varying phantom, against a one-thread streaming read of the volume.
//
// Per dataset: builds with the reference builder (plain loops), the Morton-order CPU builder
// on 1 thread and on all threads, and the GPU compute builder (OpenGL >= 4.3 in a headless
// window); each build is forced by marking the scalars modified (as a new time step would);
// median of --repeat. The read floor sums every byte as 64-bit words on one thread. Re-
// classification alternates two opacity ramps. The time-varying phantom (Lim and Shin 2009's
// motivation) also times frames of data update + CPU rebuild + slice-mapper MIP render.
// JSON: octree.json of the report (scripts/bench_report/octree.py renders it).
#include "BenchmarkHarness.h"
#include "VolumeIO.h"

#include "vtkAccelVolumeHeadlessRenderWindow.h"
#include "vtkAccelVolumeMinMaxOctree.h"
#include "vtkAccelVolumeSliceMapper.h"

#include <vtkColorTransferFunction.h>
#include <vtkDataArray.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkOpenGLState.h>
#include <vtkPiecewiseFunction.h>
#include <vtkPointData.h>
#include <vtkRenderer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkTextureObject.h>
#include <vtkVolume.h>
#include <vtkVolumeProperty.h>
#include <vtk_glew.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <iostream>

namespace fs = std::filesystem;

namespace accelvolume::benchmark
{
namespace
{

struct BuildResult
{
  std::string Builder;     // reference | cpu | gpu
  int Threads = 0;         // 0 for gpu
  bool AllThreads = false; // the cpu build on every thread
  std::vector<double> Ms;
  bool ReducedRepeats = false;
};

// Per frame of the time-varying phantom (generation is the data source, outside the frame).
struct FrameResult
{
  std::vector<double> GenerateMs, CopyMs, RebuildMs, RenderMs, FrameMs;
};

struct DatasetResult
{
  std::string Name;
  std::string File; // empty for the phantom
  std::string Description;
  std::size_t Bytes = 0;
  double Range[2] = { 0, 0 };
  double LoadSeconds = 0;
  std::vector<double> ReadFloorMs;
  std::vector<BuildResult> Builds; // reference, cpu 1 thread, cpu all, gpu (if available)
  long long Nodes = 0;
  int Depth = 0;
  std::vector<double> ClassifyMs;
  double TransparentLeafFraction = 0;
  FrameResult Frames; // only for the phantom
};

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

// NAME_*.raw[.gz] in the data folder ("" if absent): a looser match than FindDatasetFile(),
// which also requires the _<X>x<Y>x<Z>_<type> part.
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
// The image's 8/16-bit unsigned scalars as a one-channel normalised 3D texture.
bool MakeResidentTexture(
  vtkAccelVolumeHeadlessRenderWindow* window, vtkImageData* image, vtkTextureObject* texture)
{
  int dims[3];
  image->GetDimensions(dims);
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  window->MakeCurrent();
  texture->SetContext(window);
  window->GetState()->vtkglPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  const bool ok = texture->Create3DFromRaw(
    dims[0], dims[1], dims[2], 1, scalars->GetDataType(), scalars->GetVoidPointer(0));
  texture->SetMinificationFilter(vtkTextureObject::Nearest);
  texture->SetMagnificationFilter(vtkTextureObject::Nearest);
  return ok;
}

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
  result.ReducedRepeats = count < repeat;
  return true;
}

const BuildResult* Find(const DatasetResult& d, const std::string& builder)
{
  for (const BuildResult& b : d.Builds)
  {
    if (b.Builder == builder)
    {
      return &b;
    }
  }
  return nullptr;
}

Json DatasetJson(const DatasetResult& d)
{
  const double floor = Median(d.ReadFloorMs);
  const BuildResult* reference = Find(d, "reference");
  Json out = { { "name", d.Name }, { "file", StringOrNull(d.File) }, { "volume", d.Description },
    { "bytes", d.Bytes }, { "load_s", Round(d.LoadSeconds, 3) },
    { "read_floor_ms", Round(floor, 4) }, { "nodes", d.Nodes }, { "depth", d.Depth },
    { "classify_ms",
      { { "median", Round(Median(d.ClassifyMs), 5) }, { "all", RoundAll(d.ClassifyMs, 4) } } },
    { "transparent_leaf_fraction", Round(d.TransparentLeafFraction, 5) },
    { "builds", Json::array() } };
  for (const BuildResult& r : d.Builds)
  {
    const double ms = Median(r.Ms);
    out["builds"].push_back({ { "builder", r.Builder }, { "threads", r.Threads },
      { "median_ms", Round(ms, 4) }, { "ms", RoundAll(r.Ms, 4) },
      { "reduced_repeats", r.ReducedRepeats }, { "gb_per_s", Round(d.Bytes / ms / 1e6, 4) },
      { "x_reference", Round(reference ? SafeRatio(Median(reference->Ms), ms) : NAN, 4) },
      { "x_floor", Round(SafeRatio(ms, floor), 4) } });
  }
  if (!d.Frames.FrameMs.empty())
  {
    const FrameResult& f = d.Frames;
    out["frames"] = { { "generate_ms", RoundAll(f.GenerateMs, 4) },
      { "copy_ms", RoundAll(f.CopyMs, 4) }, { "rebuild_ms", RoundAll(f.RebuildMs, 4) },
      { "render_ms", RoundAll(f.RenderMs, 4) }, { "frame_ms", RoundAll(f.FrameMs, 4) },
      { "rebuild_percent_of_frame", Round(100 * Median(f.RebuildMs) / Median(f.FrameMs), 3) } };
  }
  return out;
}

class OctreeBenchmark : public Benchmark
{
public:
  const char* Name() const override { return "accelvolume_benchmark_octree"; }
  const char* Description() const override
  {
    return "Lim and Shin 2009: min-max octree build times (reference, CPU, GPU) against a "
           "one-thread read of the volume, re-classification, time-varying rebuilds";
  }
  const char* DefaultJson() const override { return "benchmark_octree.json"; }

  void AddOptions(CLI::App& app) override
  {
    AddList(app, "--datasets", this->Datasets,
      "file-name prefixes in the data folder, 'vessels' = time-varying phantom");
    app
      .add_option("--repeat", this->Repeat,
        "builds per builder, median reported (builds over "
        "2 s get fewer)")
      ->check(CLI::Range(1, 1 << 20));
    app.add_option("--leaf", this->Leaf, "leaf edge, power of two 2..64")
      ->check(CLI::IsMember({ 2, 4, 8, 16, 32, 64 }));
    app.add_option("--frames", this->Frames, "time-varying phantom frames")
      ->check(CLI::Range(1, 1 << 20));
    app.add_option("--phantom-size", this->PhantomSize, "its edge in voxels")
      ->check(CLI::Range(1, 1 << 20));
  }

  void Resolve(const CLI::App&, const MachineInfo&) override
  {
    if (this->Datasets.empty())
    {
      throw CLI::ValidationError("--datasets", "needs at least one name");
    }
  }

  int Run(Harness& harness, Json& result) override;

private:
  std::vector<std::string> Datasets = { "cta_avm", "aneurism", "engine", "ct_chest_lidc0314",
    "vessels" };
  int Repeat = 5;
  int Leaf = 8;
  int Frames = 5;
  int PhantomSize = 256;
  int AllThreads = 1; // vtkSMPTools' thread count at start-up
  bool GPUAvailable = false;
  vtkAccelVolumeHeadlessRenderWindow* Window = nullptr;

  bool RunDataset(const std::string& name, vtkImageData* image, DatasetResult& d);
  void Classify(vtkAccelVolumeMinMaxOctree* octree, DatasetResult& d);
  void RunTimeVarying(DatasetResult& d);
};

bool OctreeBenchmark::RunDataset(const std::string& name, vtkImageData* image, DatasetResult& d)
{
  d.Name = name;
  d.Description = accelvolume::cli::DescribeVolume(image);
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  d.Bytes = static_cast<std::size_t>(scalars->GetNumberOfValues()) * scalars->GetDataTypeSize();
  scalars->GetRange(d.Range, 0);
  for (int k = 0; k < this->Repeat; ++k)
  {
    d.ReadFloorMs.push_back(ReadFloorMs(scalars->GetVoidPointer(0), d.Bytes));
  }

  vtkNew<vtkAccelVolumeMinMaxOctree> octree;
  octree->SetInputData(image);
  octree->SetLeafSize(this->Leaf);
  octree->SetRenderWindow(this->Window);
  struct Config
  {
    const char* Builder;
    int Id;
    int Threads; // 0 = all
  };
  const Config configs[] = { { "reference", vtkAccelVolumeMinMaxOctree::BUILDER_REFERENCE, 1 },
    { "cpu", vtkAccelVolumeMinMaxOctree::BUILDER_CPU, 1 },
    { "cpu", vtkAccelVolumeMinMaxOctree::BUILDER_CPU, 0 },
    { "gpu", vtkAccelVolumeMinMaxOctree::BUILDER_GPU, 0 },
    { "gpu_texture", vtkAccelVolumeMinMaxOctree::BUILDER_GPU, 0 } };
  // "gpu_texture": the GPU builder reading a texture that already holds the scalars, as the
  // slice mapper's resident volume does (8/16-bit unsigned data: normalised texels).
  vtkNew<vtkTextureObject> resident;
  const int type = scalars->GetDataType();
  const bool residentUsable = this->GPUAvailable &&
    (type == VTK_UNSIGNED_CHAR || type == VTK_UNSIGNED_SHORT) &&
    MakeResidentTexture(this->Window, image, resident);
  for (const Config& config : configs)
  {
    const bool gpu = config.Id == vtkAccelVolumeMinMaxOctree::BUILDER_GPU;
    const bool fromTexture = std::string(config.Builder) == "gpu_texture";
    if ((gpu && !this->GPUAvailable) || (fromTexture && !residentUsable))
    {
      continue;
    }
    octree->SetInputTexture(fromTexture ? resident.GetPointer() : nullptr);
    BuildResult build;
    build.Builder = config.Builder;
    // "All threads" is the count measured at start-up, set explicitly: in VTK 9.1 (TBB) a
    // LocalScope of 1 thread does not restore the default afterwards, so 0 would stay at 1.
    const int threads = config.Threads > 0 ? config.Threads : this->AllThreads;
    build.Threads = gpu ? 0 : threads;
    build.AllThreads = config.Id == vtkAccelVolumeMinMaxOctree::BUILDER_CPU && config.Threads == 0;
    octree->SetBuilder(config.Id);
    octree->SetNumberOfThreads(threads);
    if (!TimeBuilds(octree, image, this->Repeat, build))
    {
      std::cerr << name << ": " << config.Builder << " build failed\n";
      return false;
    }
    d.Builds.push_back(build);
    d.Nodes = octree->GetNumberOfNodes();
    d.Depth = octree->GetDepth();
  }
  octree->SetInputTexture(nullptr);
  this->Classify(octree, d);
  this->Window->MakeCurrent();
  octree->ReleaseGraphicsResources();
  resident->ReleaseGraphicsResources(this->Window);
  return true;
}

// Re-classification on the last CPU-resident octree: rebuild with all threads first so the
// GPU read-back is not part of it; every call gets a modified function, so it really runs.
void OctreeBenchmark::Classify(vtkAccelVolumeMinMaxOctree* octree, DatasetResult& d)
{
  octree->SetBuilder(vtkAccelVolumeMinMaxOctree::BUILDER_CPU);
  octree->SetNumberOfThreads(this->AllThreads);
  octree->Update();
  vtkNew<vtkPiecewiseFunction> opacity;
  const double low = d.Range[0] + 0.1 * (d.Range[1] - d.Range[0]);
  const double alternate = low + 0.5 * (d.Range[1] - low);
  SetRamp(opacity, low, d.Range);
  octree->Classify(opacity, d.Range);
  d.TransparentLeafFraction = octree->GetTransparentLeafFraction();
  for (int k = 0; k < std::max(this->Repeat, 5); ++k)
  {
    SetRamp(opacity, k % 2 == 0 ? alternate : low, d.Range);
    const auto start = Clock::now();
    octree->Classify(opacity, d.Range);
    d.ClassifyMs.push_back(MsSince(start));
  }
}

// Lim and Shin 2009's case: the volume changes every frame, so the octree is rebuilt before each
// render.
void OctreeBenchmark::RunTimeVarying(DatasetResult& d)
{
  const int dims[3] = { this->PhantomSize, this->PhantomSize, this->PhantomSize };
  accelvolume::PhantomVolume phantom;
  std::string error;
  auto start = Clock::now();
  accelvolume::GeneratePhantom("vessels", dims, 0.0, phantom, error);
  vtkSmartPointer<vtkImageData> image = accelvolume::cli::PhantomToImage(phantom);
  const double generateMs = MsSince(start);
  if (!this->RunDataset("vessels (t)", image, d))
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
  this->Window->AddRenderer(renderer);
  renderer->ResetCamera();
  vtkNew<vtkUnsignedCharArray> pixel;
  auto render = [&]()
  {
    this->Window->Render();
    this->Window->GetPixelData(0, 0, 0, 0, 0, pixel, 0); // waits for the GPU
  };
  render(); // warm-up: texture and shader creation

  vtkNew<vtkAccelVolumeMinMaxOctree> octree;
  octree->SetInputData(image);
  octree->SetLeafSize(this->Leaf);
  octree->SetNumberOfThreads(this->AllThreads);
  octree->Update();
  auto* values = vtkFloatArray::SafeDownCast(image->GetPointData()->GetScalars());
  for (int f = 1; f <= this->Frames; ++f)
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
  this->Window->RemoveRenderer(renderer);
}

int OctreeBenchmark::Run(Harness& harness, Json& result)
{
  const MachineInfo& machine = harness.Machine;
  this->Window = harness.Window();
  this->AllThreads = machine.SMPThreads;
  this->GPUAvailable = machine.GLMajor * 10 + machine.GLMinor >= 43;
  const std::string gpuNote =
    this->GPUAvailable ? "" : "OpenGL " + machine.GLVersion + " < 4.3 (no compute shaders)";

  result = { { "benchmark", this->Name() }, { "leaf", this->Leaf }, { "repeat", this->Repeat },
    { "threads", machine.SMPThreads }, { "smp_backend", machine.SMPBackend },
    { "gl_backend", machine.GLBackend }, { "gl_renderer", machine.GLRenderer },
    { "gl_version", machine.GLVersion }, { "gpu_note", StringOrNull(gpuNote) },
    { "datasets", Json::array() } };
  bool ok = true;
  CaseProgress progress(this->Name(), static_cast<int>(this->Datasets.size()));
  for (const std::string& name : this->Datasets)
  {
    progress.Begin(name);
    DatasetResult d;
    if (name == "vessels")
    {
      this->RunTimeVarying(d);
    }
    else
    {
      d.File = FindPrefixedRawFile(harness.Options.DataDir, name);
      if (d.File.empty())
      {
        std::cerr << name << ": no file " << name << "_<X>x<Y>x<Z>_<type>.raw[.gz] in "
                  << harness.Options.DataDir << "\n";
        ok = false;
        continue;
      }
      accelvolume::cli::VolumeRequest request;
      request.inputPath = d.File;
      std::string error;
      const auto loadStart = Clock::now();
      vtkSmartPointer<vtkImageData> image = accelvolume::cli::LoadVolume(request, error);
      d.LoadSeconds = SecondsSince(loadStart);
      if (!image || !this->RunDataset(name, image, d))
      {
        std::cerr << name << ": " << (image ? "benchmark failed" : error) << "\n";
        d.Builds.clear();
      }
    }
    if (d.Builds.empty())
    {
      ok = false;
      continue;
    }
    result["datasets"].push_back(DatasetJson(d));
  }
  return ok && !result["datasets"].empty() ? 0 : 1;
}

} // namespace

std::unique_ptr<Benchmark> MakeBenchmark()
{
  return std::make_unique<OctreeBenchmark>();
}

} // namespace accelvolume::benchmark
