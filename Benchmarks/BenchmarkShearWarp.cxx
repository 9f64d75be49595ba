// accelvolume_benchmark_shearwarp: Tables 2-3 of Kim 1998 (parallel shear-warp with a
// run-length encoded volume, skip links and a load-balanced partition of the sheared volume) and
// beyond, on real volumes, in one run: threads, VolPack and MPI ranks.
// The paper renders a 128^3 MRI brain and a 256x256x226 CT head on a 4,096-PE MasPar MP-2 in
// three experiments, (1) a plain 3D array without balancing, (2) the run-length encoded volume,
// (3) RLE with its scanline partition balanced by the previous frame's times, each averaged over
// 90 frames turned 1 degree. This program measures vtkAccelVolumeShearWarpMapper likewise:
//   (1) RunLengthEncoding off, EarlyRayTermination off, LoadBalancing off;
//   (2) RunLengthEncoding on, EarlyRayTermination (skip links) on, LoadBalancing off (equal bands);
//   (3) as (2) with LoadBalancing on; and (3) with ShadingMode Phong per voxel (shaded cases);
// each on 1 thread and on all threads, as separate mappers (each balances with its own previous
// frame), plus VolPack (vpRenderClassifiedVolume, one thread, the volume quantized to 8 bits)
// and (3) on 1 and 2 MPI ranks of one thread each (this program re-launched under mpiexec).
//
// Per volume x transfer function x shading x image size: parallel camera fitted to the volume,
// turned to the fixed view (azimuth 30, elevation 20), composite blend. Every mapper's first frame
// (classification + encoding) is rendered at the fixed view, the images are checked there, then
// rounds of --run-length frames turning the camera by --turn degrees (1, as the paper) render
// every configuration and VolPack over the same views, each its frames in a row as a user's
// turning view does (the configurations alternate between rounds, so load from other processes
// hits all alike; --run-length 1 interleaves every frame, each then starting with the caches
// the other configurations left). ms/frame is the median
// of the mapper's GetLastRenderTime (its whole Render(), the draw calls included); "wall" is the
// window's whole Render() with one pixel read back (so the OpenGL work has finished): the frame
// as a user sees it, which the VolPack ratio uses (VolPack's time: its image in memory); "engine"
// is encode + tables + composite + gather + CPU warp (the default warp runs on the GPU while the
// image is drawn, so it counts in the wall time only), the second VolPack ratio. Speed-ups and
// efficiencies are medians of paired per-round ratios.
//
// Transfer functions: the presets of `accelvolume render --tf` over each volume's data range.
// tf2 (first) is the paper's kind of picture: opaque surfaces (transparent below 30 % of the
// range, opaque above 32 %: the skin / bone of the heads), where skip links matter; tf1 is
// translucent (transparent below 10 %, ramp to opacity 0.35), where runs of transparent voxels
// matter and few rays saturate. Shading: the presets' Phong (ambient 0.2, diffuse 0.7,
// specular 0.3, power 10) with VTK's headlight; VolPack gets the same tables at 256 entries
// (the RGB colour transfer function in VolPack's RGB mode, so both render the same coloured
// image with three colour channels; --volpack-grey: the mean of R, G, B in its luminance mode)
// and its opacity raised to spacing(principal axis) / unit distance.
// The harness (Harness/) parses the options and writes the JSON (shearwarp.json of the report,
// scripts/bench_report/shearwarp.py); the scene, frame records and VolPack:
// BenchmarkShearWarpScene.{h,cxx}; results and their JSON: BenchmarkShearWarpResults.{h,cxx}.
#include "BenchmarkHarness.h"
#include "BenchmarkImageMetrics.h"
#include "BenchmarkShearWarpResults.h"
#include "BenchmarkShearWarpScene.h"

#include "vtkAccelVolumeShearWarpMapper.h"

#include <vtkCommunicator.h>
#include <vtkImageData.h>
#include <vtkMPI.h> // MPI_Abort
#include <vtkMPIController.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <regex>
#include <sstream>

namespace fs = std::filesystem;

namespace accelvolume::benchmark::shearwarp
{
namespace
{
// The command-line arguments that make a worker render the same cases of `dataset` (everything
// but the output options), for the MPI re-launch.
std::vector<std::string> WorkerArguments(
  const Options& options, const std::string& dataset, const std::string& mpiDir)
{
  std::string tfs, sizes;
  for (const std::string& tf : options.TransferFunctions)
  {
    tfs += (tfs.empty() ? "" : ",") + tf;
  }
  for (int size : options.Sizes)
  {
    sizes += (sizes.empty() ? "" : ",") + std::to_string(size);
  }
  const std::string shade = options.Shades.size() == 2 ? "both" : options.Shades[0] ? "on" : "off";
  auto exact = [](double value)
  {
    std::ostringstream text;
    text.precision(17);
    text << value;
    return text.str();
  };
  return { "--mpi-worker", "--mpi-dir", mpiDir, "--data", options.DataDir, "--datasets", dataset,
    "--sizes", sizes, "--tfs", tfs, "--shade", shade, "--frames", std::to_string(options.Frames),
    "--view", exact(options.Azimuth), exact(options.Elevation), "--turn", exact(options.Turn),
    "--gl", options.GL };
}

// Byte differences of two images against a bound (0: identical).
ImageCheck Compare(
  const std::string& a, const std::string& b, const Image& x, const Image& y, int bound)
{
  const ByteDifferences d = CompareBytes(x, y);
  ImageCheck check;
  check.A = a;
  check.B = b;
  check.Bound = bound;
  check.DifferingPixels = d.Pixels;
  check.MaxDifference = d.Max;
  return check;
}

// Channel-level error (0..255) over the pixels non-black in either image: each of R, G, B of a
// pixel is a sample (RMS over the three channels), Max the largest channel difference.
ErrorStats RgbError(const Image& reference, const Image& image, int size)
{
  const std::vector<std::uint8_t> mask =
    MaskOr(NonBackgroundMask(reference, size, size), NonBackgroundMask(image, size, size));
  ErrorStats stats;
  for (size_t p = 0; p < mask.size() && 3 * p + 2 < reference.size() && 3 * p + 2 < image.size();
       ++p)
  {
    if (!mask[p])
    {
      continue;
    }
    double squared = 0, largest = 0;
    for (size_t c = 3 * p; c < 3 * p + 3; ++c)
    {
      const double d = std::abs(double(image[c]) - double(reference[c]));
      squared += d * d;
      largest = std::max(largest, d);
    }
    stats.SumSquared += squared / 3.0;
    stats.Max = std::max(stats.Max, largest);
    ++stats.Pixels;
    stats.Above += largest > 2.0;
  }
  return stats;
}

// Our configurations on 1 / all threads and VolPack: first frames and image checks at the fixed
// view, then the interleaved timed rounds. `ours` gets the (3) 1-thread image of the fixed view.
CaseResult RunCase(const Options& options, const DatasetInfo& info, vtkImageData* image,
  const std::string& tf, bool shade, int size, int backend, VolPackAnchor* volpack, Image& ours)
{
  const auto caseStart = Clock::now();
  CaseResult c;
  c.Dataset = info.Name;
  c.Tf = tf;
  c.Shade = shade;
  c.Size = size;
  c.Frames = options.Frames;
  c.Threads = options.Threads;
  c.TotalVoxels = static_cast<long long>(info.Dims[0]) * info.Dims[1] * info.Dims[2];
  Scene scene(info, backend, tf, shade, size);
  std::vector<int> threadCounts = { 1 };
  if (options.Threads > 1)
  {
    threadCounts.push_back(options.Threads);
  }
  for (const Config& cfg : MakeConfigs(shade))
  {
    for (int threads : threadCounts)
    {
      scene.Add(image, cfg, threads, nullptr);
      c.Runs.emplace_back();
      c.Runs.back().Cfg = cfg;
      c.Runs.back().Threads = threads;
    }
  }
  scene.FixedView(options.Azimuth, options.Elevation);
  std::vector<Image> images;
  for (size_t k = 0; k < c.Runs.size(); ++k)
  {
    RecordFirst(scene.Mapper(k), scene.Render(k), c.Runs[k]);
    images.push_back(scene.Capture());
  }
  // The other axes' encodings are built in the background after a first frame: done before the
  // timed rounds, which measure the steady frame.
  for (size_t k = 0; k < c.Runs.size(); ++k)
  {
    scene.Mapper(k)->FinishBackgroundEncoding();
  }
  auto index = [&](const std::string& id, int threads)
  { return static_cast<size_t>(c.Find(id, threads) - c.Runs.data()); };
  auto name = [](const std::string& id, int threads)
  { return id + "/" + std::to_string(threads) + "t"; };
  for (const Config& cfg : MakeConfigs(shade))
  {
    if (options.Threads > 1)
    {
      c.Checks.push_back(Compare(name(cfg.Id, 1), name(cfg.Id, options.Threads),
        images[index(cfg.Id, 1)], images[index(cfg.Id, options.Threads)], 0));
    }
  }
  const size_t balanced = index("balanced", 1);
  const size_t rle = index("rle", 1);
  c.Checks.push_back(
    Compare(name("rle", 1), name("balanced", 1), images[rle], images[balanced], 0));
  // Early ray termination leaves out at most (1 - threshold) of the brightest shaded colour.
  vtkVolumeProperty* property = scene.Property();
  const double brightest = shade
    ? std::max(1.0, property->GetAmbient() + property->GetDiffuse() + property->GetSpecular())
    : 1.0;
  const double threshold = scene.Mapper(balanced)->GetEarlyRayTerminationThreshold();
  const int ertBound = static_cast<int>(std::ceil(255.0 * (1.0 - threshold) * brightest)) + 1;
  c.Checks.push_back(
    Compare(name("dense", 1), name("rle", 1), images[index("dense", 1)], images[rle], ertBound));
  if (shade)
  {
    c.PhongVsTable = CompareVisible(images[balanced], images[index("phong", 1)], size, size);
  }
  ours = images[balanced];
  const std::string stem = options.Images + "/" + info.Name + "_" + tf +
    (shade ? "_shaded_" : "_unshaded_") + std::to_string(size);
  if (!options.Images.empty())
  {
    WritePng(stem + "_ours.png", ours, size, size);
  }

  vtkCamera* camera = scene.Camera();
  vtkVolume* volume = scene.Volume(balanced);
  if (!volpack)
  {
    c.VolPack.Note = options.VolPack ? "libvolpack not found at build time" : "--no-volpack";
  }
  else if (volpack->Prepare(
             property, shade, c.Runs[balanced].Axis, tf, options.VolPackGrey, c.VolPack.Note))
  {
    Image volpackImage;
    c.VolPack.Grey = options.VolPackGrey;
    c.VolPack.ClassifyMs = volpack->ClassifyMs();
    c.VolPack.OpacityExponent = volpack->OpacityExponent();
    c.VolPack.Ran = std::isfinite(
      volpack->Render(image, volume, camera, size, &volpackImage, c.VolPack.Axis, c.VolPack.Note));
    if (c.VolPack.Ran)
    {
      c.VolPack.VsOurs = CompareVisible(ours, volpackImage, size, size);
      c.VolPack.VsOursRgb = RgbError(ours, volpackImage, size);
      if (!options.Images.empty())
      {
        WritePng(stem + "_volpack.png", volpackImage, size, size);
      }
    }
  }

  // Rounds of --run-length frames: every configuration and VolPack render the same views one
  // after another, as a user's turning view does (its data stays in the caches between frames);
  // the configurations alternate between rounds, so load from other processes hits all alike.
  const double perFrame = 1.0 / options.Frames;
  for (int first = 0; first < options.Frames; first += options.RunLength)
  {
    const int frames = std::min(options.RunLength, options.Frames - first);
    for (size_t k = 0; k < c.Runs.size(); ++k)
    {
      for (int f = 0; f < frames; ++f)
      {
        scene.Turn(options.Turn);
        const double wall = scene.Render(k);
        Record(scene.Mapper(k), wall, scene.LastCores(), perFrame, c.Runs[k]);
      }
      scene.Turn(-options.Turn * frames);
    }
    for (int f = 0; f < frames; ++f)
    {
      scene.Turn(options.Turn);
      if (c.VolPack.Ran)
      {
        int axis = -1;
        c.VolPack.RenderMs.push_back(
          volpack->Render(image, volume, camera, size, nullptr, axis, c.VolPack.Note));
      }
    }
  }
  c.Seconds = SecondsSince(caseStart);
  return c;
}

// ---- MPI ----------------------------------------------------------------------------------------
std::string FileKey(const std::string& key)
{
  return std::regex_replace(key, std::regex("[^A-Za-z0-9_.-]"), "_");
}

#ifndef ACCELVOLUME_MPIEXEC
#define ACCELVOLUME_MPIEXEC ""
#define ACCELVOLUME_MPIEXEC_NUMPROC_FLAG "-n"
#define ACCELVOLUME_MPIEXEC_PREFLAGS ""
#define ACCELVOLUME_MPIEXEC_POSTFLAGS ""
#endif

// Runs (3) on `ranks` MPI ranks of one thread for every case of `dataset`: key -> the run, and
// key -> rank 0's image of the fixed view. False with note when the launch or its output failed.
bool LaunchMpi(const Options& options, const std::string& dataset, int ranks,
  const std::string& dir, std::map<std::string, RunResult>& runs,
  std::map<std::string, Image>& images, std::string& note)
{
  if (std::string(ACCELVOLUME_MPIEXEC).empty())
  {
    note = "mpiexec not found at build time";
    return false;
  }
  const std::string exe = fs::read_symlink("/proc/self/exe").string();
  const std::string log = dir + "/" + dataset + "_" + std::to_string(ranks) + ".log";
  std::string command = std::string("timeout 3600 ") + ACCELVOLUME_MPIEXEC + " " +
    ACCELVOLUME_MPIEXEC_NUMPROC_FLAG + " " + std::to_string(ranks) + " " +
    ACCELVOLUME_MPIEXEC_PREFLAGS + " " + ShellQuote(exe) + " " + ACCELVOLUME_MPIEXEC_POSTFLAGS;
  for (const std::string& argument : WorkerArguments(options, dataset, dir))
  {
    command += " " + ShellQuote(argument);
  }
  command += " > " + ShellQuote(log) + " 2>&1";
  const auto start = Clock::now();
  const int status = std::system(command.c_str());
  const std::string json = dir + "/" + dataset + "_" + std::to_string(ranks) + ".json";
  std::ifstream in(json);
  std::stringstream text;
  text << in.rdbuf();
  if (status != 0 || !in)
  {
    std::ifstream logIn(log);
    std::stringstream logText;
    logText << logIn.rdbuf();
    const std::string tail =
      logText.str().substr(logText.str().size() > 1500 ? logText.str().size() - 1500 : 0);
    note = "mpiexec run failed (status " + std::to_string(status) + "); log tail: " + tail;
    return false;
  }
  const Json root = Json::parse(text.str(), nullptr, false);
  if (root.is_discarded() || !root.contains("cases") || !root["cases"].is_array())
  {
    note = "cannot read the MPI worker's JSON " + json;
    return false;
  }
  for (const Json& item : root["cases"])
  {
    RunResult run;
    const std::string key = item.value("key", "");
    if (item.contains("run") && ReadRunJson(item["run"], run))
    {
      runs[key] = run;
      std::ifstream raw(
        dir + "/" + std::to_string(ranks) + "_" + FileKey(key) + ".rgb", std::ios::binary);
      images[key] = Image(std::istreambuf_iterator<char>(raw), {});
    }
  }
  std::cout << "  MPI: " << ranks << " rank(s) x 1 thread for " << dataset << " in "
            << Round(SecondsSince(start), 1) << " s\n"
            << std::flush;
  return true;
}

// One rank of the re-launched program: (3) on one thread with the controller, every case of the
// one dataset, in lockstep with the other ranks; rank 0 writes the JSON and its images.
int RunWorker(const Options& options, vtkMultiProcessController* controller)
{
  const int rank = controller->GetLocalProcessId();
  const int ranks = controller->GetNumberOfProcesses();
  int backend = 0;
  DatasetInfo info;
  vtkSmartPointer<vtkImageData> image;
  int ok = Harness::ResolveBackend(options.GL, backend) == 0 &&
      LoadDataset(options.DataDir, options.Datasets[0], info, image, true)
    ? 1
    : 0;
  int allOk = 0;
  controller->AllReduce(&ok, &allOk, 1, vtkCommunicator::MIN_OP);
  if (!allOk)
  {
    return 1;
  }
  Json out = { { "ranks", ranks }, { "dataset", info.Name }, { "cases", Json::array() } };
  const Config cfg = MakeConfigs(false)[2]; // (3)
  for (const std::string& tf : options.TransferFunctions)
  {
    for (bool shade : options.Shades)
    {
      for (int size : options.Sizes)
      {
        Scene scene(info, backend, tf, shade, size);
        scene.Add(image, cfg, 1, controller);
        RunResult run;
        run.Cfg = cfg;
        run.Ranks = ranks;
        scene.FixedView(options.Azimuth, options.Elevation);
        RecordFirst(scene.Mapper(0), scene.Render(0), run);
        scene.Mapper(0)->FinishBackgroundEncoding(); // as the in-process runs: steady frames
        const std::string key = CaseKey(info.Name, tf, shade, size);
        if (rank == 0)
        {
          const Image rgb = scene.Capture();
          std::ofstream raw(
            options.MpiDir + "/" + std::to_string(ranks) + "_" + FileKey(key) + ".rgb",
            std::ios::binary);
          raw.write(
            reinterpret_cast<const char*>(rgb.data()), static_cast<std::streamsize>(rgb.size()));
        }
        for (int f = 0; f < options.Frames; ++f)
        {
          scene.Turn(options.Turn);
          const double wall = scene.Render(0);
          Record(scene.Mapper(0), wall, scene.LastCores(), 1.0 / options.Frames, run);
        }
        out["cases"].push_back({ { "key", key }, { "run", RunJson(run) } });
      }
    }
  }
  if (rank == 0)
  {
    Harness::WriteJson(
      options.MpiDir + "/" + info.Name + "_" + std::to_string(ranks) + ".json", out);
  }
  return 0;
}

// A worker rank's wait for another rank ran out (the mapper's CommunicationTimeout): one line,
// then MPI_Abort ends every rank (called on the mapper's watchdog thread).
void AbortWorkers(const char* message)
{
  std::fprintf(stderr, "accelvolume_benchmark_shearwarp: error: %s\n", message);
  std::fflush(stderr);
  MPI_Abort(MPI_COMM_WORLD, 1);
}

class ShearWarpBenchmark : public Benchmark
{
public:
  const char* Name() const override { return "accelvolume_benchmark_shearwarp"; }
  const char* Description() const override
  {
    return "Kim 1998 Tables 2-3: parallel shear-warp with run-length encoding, skip links and "
           "load balancing, on threads, against VolPack, and on MPI ranks. Exit code: 0 ok, 1 a "
           "dataset, backend or MPI run failed, 2 bad options, 3 the image checks failed "
           "(thread counts / balancing not byte-identical, or no RLE vs RLE beyond the "
           "early-termination bound)";
  }
  const char* DefaultJson() const override { return "accelvolume_benchmark_shearwarp.json"; }
  // $ACCELVOLUME_GL when it names a headless backend, else egl.
  const char* DefaultGL() const override
  {
    const char* gl = std::getenv("ACCELVOLUME_GL");
    const std::string value = gl ? gl : "";
    return value == "egl" || value == "osmesa" || value == "auto" ? gl : "egl";
  }
  // Every scene opens its own window; the harness's (parent only) describes the GL.
  bool NeedsWindow() const override { return !this->O.MpiWorker; }
  int InitialSize() const override { return 64; }

  void AddOptions(CLI::App& app) override;
  void Resolve(const CLI::App& app, const MachineInfo& machine) override;
  int Run(Harness& harness, Json& result) override;

private:
  Options O;
  std::string Shade = "on";
  bool NoMpi = false;
  bool NoVolPack = false;
  void RunDataset(const std::string& name, int backend, CaseProgress& progress, int perDataset,
    const std::string& mpiDir, Json& result, bool& ok, bool& checksOk) const;
};

void ShearWarpBenchmark::AddOptions(CLI::App& app)
{
  AddList(app, "--datasets", this->O.Datasets,
    "dataset names: NAME_<X>x<Y>x<Z>_<type>.raw[.gz] in the data folder");
  app.add_flag(
    "--skip-large", this->O.SkipLarge, "drop volumes over 32 Mi voxels (the 512x512x275 CT)");
  AddList(app, "--sizes", this->O.Sizes, "square final image sizes (16..4096)");
  AddList(app, "--tfs", this->O.TransferFunctions,
    "transfer-function presets of `accelvolume render --tf` (tf2: opaque surfaces, tf1: "
    "semi-transparent)");
  app.add_option("--shade", this->Shade, "shaded, unshaded or both")
    ->check(CLI::IsMember({ "on", "off", "both" }))
    ->type_name("on|off|both");
  app.add_option("--frames", this->O.Frames, "timed frames per configuration")
    ->check(CLI::PositiveNumber);
  app.add_option("--threads", this->O.Threads, "the \"all threads\" count (0: hardware threads)")
    ->check(CLI::Range(0, 1024));
  app
    .add_option_function<std::vector<double>>(
      "--view",
      [this](const std::vector<double>& view)
      {
        this->O.Azimuth = view[0];
        this->O.Elevation = view[1];
      },
      "initial camera azimuth / elevation in degrees")
    ->expected(2)
    ->type_name("AZ EL")
    ->default_str("30 20");
  app.add_option("--turn", this->O.Turn, "azimuth turn per timed frame (1, as the paper)");
  app
    .add_option("--run-length", this->O.RunLength,
      "frames each configuration renders in a row per round (1: every frame interleaved, so "
      "each one starts with the caches the other configurations left)")
    ->check(CLI::PositiveNumber);
  AddList(app, "--mpi-ranks", this->O.MpiRanks, "rank counts of the MPI rows (1..256)");
  app.add_flag("--no-mpi", this->NoMpi, "skip the MPI rows (no mpiexec launch)");
  app.add_flag("--no-volpack", this->NoVolPack, "skip the VolPack rows");
  app.add_flag("--volpack-grey", this->O.VolPackGrey,
    "VolPack in luminance mode (grey = mean of the transfer function's R, G, B) instead of RGB");
  app
    .add_option("--images", this->O.Images,
      "save PNGs of the fixed view (ours (3) 1 thread, "
      "VolPack)")
    ->type_name("DIR");
  // Internal: this process is one rank of the MPI run the benchmark launched itself.
  app.add_flag("--mpi-worker", this->O.MpiWorker)->group("");
  app.add_option("--mpi-dir", this->O.MpiDir)->group("");
}

void ShearWarpBenchmark::Resolve(const CLI::App& app, const MachineInfo& machine)
{
  this->O.DataDir = app.get_option("--data")->as<std::string>();
  this->O.GL = app.get_option("--gl")->as<std::string>();
  this->O.Threads = this->O.Threads > 0 ? this->O.Threads : machine.HardwareThreads;
  this->O.Mpi = !this->NoMpi;
  this->O.VolPack = !this->NoVolPack;
  this->O.Shades = this->Shade == "both" ? std::vector<bool>{ true, false }
                                         : std::vector<bool>{ this->Shade == "on" };
  CheckTransferFunctions(this->O.TransferFunctions, "--tfs");
  bool valid = !this->O.Sizes.empty() && !this->O.Datasets.empty() && !this->O.MpiRanks.empty();
  for (int size : this->O.Sizes)
  {
    valid = valid && size >= 16 && size <= 4096;
  }
  for (int ranks : this->O.MpiRanks)
  {
    valid = valid && ranks >= 1 && ranks <= 256;
  }
  if (!valid || (this->O.MpiWorker && this->O.MpiDir.empty()))
  {
    throw CLI::ValidationError("options", "sizes 16..4096, MPI ranks 1..256, a dataset");
  }
}

// Every case of one dataset: the MPI rows first (one launch per rank count), then ours and VolPack.
void ShearWarpBenchmark::RunDataset(const std::string& name, int backend, CaseProgress& progress,
  int perDataset, const std::string& mpiDir, Json& result, bool& ok, bool& checksOk) const
{
  const Options& options = this->O;
  const std::string file = FindDatasetFile(options.DataDir, name);
  if (options.SkipLarge && VoxelsOfFile(file) > LargeVoxels)
  {
    std::cout << "=== " << name << ": skipped (--skip-large)\n";
    progress.Skip(perDataset);
    return;
  }
  DatasetInfo info;
  vtkSmartPointer<vtkImageData> image;
  if (!LoadDataset(options.DataDir, name, info, image, false))
  {
    ok = false;
    progress.Skip(perDataset);
    return;
  }
  std::map<int, std::map<std::string, RunResult>> mpiRuns;
  std::map<int, std::map<std::string, Image>> mpiImages;
  std::string mpiNote = options.Mpi ? "" : "--no-mpi";
  for (int ranks : options.Mpi ? options.MpiRanks : std::vector<int>())
  {
    if (!LaunchMpi(options, name, ranks, mpiDir, mpiRuns[ranks], mpiImages[ranks], mpiNote))
    {
      std::cout << "  MPI " << ranks << " rank(s): " << mpiNote << "\n";
      ok = false;
    }
  }
  std::unique_ptr<VolPackAnchor> volpack;
  if (options.VolPack && VolPackAnchor::Available())
  {
    volpack = std::make_unique<VolPackAnchor>(image, info);
  }
  for (const std::string& tf : options.TransferFunctions)
  {
    for (bool shade : options.Shades)
    {
      for (int size : options.Sizes)
      {
        Image ours;
        progress.Begin(name + " " + tf + (shade ? " shaded " : " ") + std::to_string(size));
        CaseResult c = RunCase(options, info, image, tf, shade, size, backend, volpack.get(), ours);
        for (auto& [ranks, runs] : mpiRuns)
        {
          const auto found = runs.find(c.Key());
          if (found != runs.end())
          {
            c.Mpi.push_back(found->second);
            c.Checks.push_back(Compare("balanced/1t", "MPI " + std::to_string(ranks) + "r", ours,
              mpiImages[ranks][c.Key()], 0));
          }
        }
        c.MpiNote =
          c.Mpi.empty() ? (mpiNote.empty() ? "no MPI result for this case" : mpiNote) : "";
        checksOk = checksOk && c.ChecksOk();
        result["cases"].push_back(CaseJson(c));
      }
    }
  }
  result["datasets"].push_back(DatasetJson(info));
}

int ShearWarpBenchmark::Run(Harness& harness, Json& result)
{
  const Options& options = this->O;
  if (options.MpiWorker)
  {
    vtkNew<vtkMPIController> controller;
    controller->Initialize(&harness.Argc, &harness.Argv);
    vtkMultiProcessController::SetGlobalController(controller);
    vtkAccelVolumeShearWarpMapper::SetCommunicationAbortFunction(AbortWorkers);
    const int code = RunWorker(options, controller);
    controller->Finalize();
    vtkMultiProcessController::SetGlobalController(nullptr);
    return code; // the worker writes its own JSON (rank 0)
  }
  const MachineInfo& machine = harness.Machine;
  result = { { "benchmark",
               "shearwarp (Kim 1998 Tables 2-3: parallel shear-warp, RLE, load "
               "balancing; VolPack; MPI)" },
    { "machine",
      { { "cpu", machine.Cpu }, { "hardware_threads", machine.HardwareThreads },
        { "gl_backend", machine.GLBackend }, { "gl_renderer", machine.GLRenderer },
        { "volpack", VolPackAnchor::Available() }, { "mpiexec", ACCELVOLUME_MPIEXEC } } },
    { "settings",
      { { "frames", options.Frames }, { "threads", options.Threads },
        { "view",
          { { "azimuth", Round(options.Azimuth, 2) },
            { "elevation", Round(options.Elevation, 2) } } },
        { "turn_degrees", Round(options.Turn, 2) }, { "run_length", options.RunLength },
        { "projection", "parallel" },
        { "blend", "composite" }, { "mpi", options.Mpi }, { "volpack", options.VolPack },
        { "volpack_mode", options.VolPackGrey ? "grey" : "rgb" },
        { "ms_per_frame", "median of the mapper's GetLastRenderTime" },
        { "engine_ms", "encode + tables + composite + gather + CPU warp (no display)" },
        { "wall_ms", "the window's Render() and a one-pixel read-back: the whole frame" },
        { "image_parts_ms",
          "drawing the image in parts while one thread composites (in ms_per_frame, not in "
          "engine_ms)" },
        { "volpack_ratio", "VolPack ms / our wall ms, (3) 1 thread" },
        { "volpack_ratio_engine", "VolPack ms / our engine ms, (3) 1 thread" },
        { "ratios", "median over frames of paired per-frame ratios" },
        { "targets",
          { { "volpack_speedup", VolPackTarget }, { "efficiency", EfficiencyTarget },
            { "imbalance", ImbalanceTarget } } } } },
    { "total_seconds", 0 }, { "datasets", Json::array() }, { "cases", Json::array() } };

  const std::string mpiDir =
    (fs::temp_directory_path() / ("accelvolume_swbench_" + std::to_string(getpid()))).string();
  std::error_code ec;
  fs::create_directories(mpiDir, ec);
  if (!options.Images.empty())
  {
    fs::create_directories(options.Images, ec);
  }
  bool ok = true, checksOk = true;
  const int perDataset = static_cast<int>(
    options.TransferFunctions.size() * options.Shades.size() * options.Sizes.size());
  CaseProgress progress(this->Name(), static_cast<int>(options.Datasets.size()) * perDataset);
  for (const std::string& name : options.Datasets)
  {
    this->RunDataset(name, harness.Backend(), progress, perDataset, mpiDir, result, ok, checksOk);
  }
  fs::remove_all(mpiDir, ec);
  result["total_seconds"] = Round(harness.Seconds(), 2);
  if (!checksOk)
  {
    std::cout << "FAILED: image checks (see the JSON's \"checks\")\n";
    return 3;
  }
  return ok && !result["cases"].empty() ? 0 : 1;
}

} // namespace
} // namespace accelvolume::benchmark::shearwarp

namespace accelvolume::benchmark
{
std::unique_ptr<Benchmark> MakeBenchmark()
{
  return std::make_unique<shearwarp::ShearWarpBenchmark>();
}
} // namespace accelvolume::benchmark
