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
// N rounds turn the camera by --turn degrees (1, as the paper) and render every configuration
// and VolPack (interleaved, so load from other processes hits all alike). ms/frame is the median
// of the mapper's GetLastRenderTime (its whole Render(), showing the image included); "engine" is
// encode + tables + composite + gather + warp, what VolPack's time covers, and is what the
// VolPack ratio uses. Speed-ups and efficiencies are medians of paired per-round ratios.
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
// Options: BenchmarkShearWarpOptions.{h,cxx}; tables and JSON: BenchmarkShearWarpReport.{h,cxx};
// the scene, frame records, run JSON and VolPack: BenchmarkShearWarpScene.{h,cxx}.
#include "BenchmarkCommon.h"
#include "BenchmarkImageMetrics.h"
#include "BenchmarkShearWarpOptions.h"
#include "BenchmarkShearWarpReport.h"
#include "BenchmarkShearWarpScene.h"
#include "JsonReader.h"

#include <vtkCommunicator.h>
#include <vtkImageData.h>
#include <vtkMPI.h> // MPI_Abort
#include <vtkMPIController.h>
#include <vtkAccelVolumeShearWarpMapper.h>

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
#include <string>
#include <thread>
#include <vector>

using namespace accelvolume::benchmark;
using namespace accelvolume::benchmark::shearwarp;
namespace fs = std::filesystem;

namespace
{
// Byte differences of two images against a bound (0: identical).
ImageCheck Compare(
  const std::string& a, const std::string& b, const Image& x, const Image& y, int bound)
{
  ImageCheck check;
  check.A = a;
  check.B = b;
  check.Bound = bound;
  check.MaxDifference = x.size() == y.size() ? 0 : 255;
  for (size_t p = 0; p + 2 < x.size() && p + 2 < y.size(); p += 3)
  {
    int differs = 0;
    for (size_t channel = p; channel < p + 3; ++channel)
    {
      differs = std::max(differs, std::abs(int(x[channel]) - int(y[channel])));
    }
    check.DifferingPixels += differs > 0;
    check.MaxDifference = std::max(check.MaxDifference, differs);
  }
  return check;
}

// Grey-level error over the pixels non-black in either image.
ErrorStats GreyError(const Image& reference, const Image& image, int size)
{
  return CompareImages(reference, image,
    MaskOr(NonBackgroundMask(reference, size, size), NonBackgroundMask(image, size, size)), 2.0);
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
  scene.FixedView(options);
  std::vector<Image> images;
  for (size_t k = 0; k < c.Runs.size(); ++k)
  {
    RecordFirst(scene.Mapper(k), scene.Render(k), c.Runs[k]);
    images.push_back(scene.Capture());
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
    c.PhongVsTable = GreyError(images[balanced], images[index("phong", 1)], size);
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
      c.VolPack.VsOurs = GreyError(ours, volpackImage, size);
      c.VolPack.VsOursRgb = RgbError(ours, volpackImage, size);
      if (!options.Images.empty())
      {
        WritePng(stem + "_volpack.png", volpackImage, size, size);
      }
    }
  }

  const double perFrame = 1.0 / options.Frames;
  for (int f = 0; f < options.Frames; ++f)
  {
    scene.Turn(options.Turn);
    for (size_t k = 0; k < c.Runs.size(); ++k)
    {
      const double wall = scene.Render(k);
      Record(scene.Mapper(k), wall, scene.LastCores(), perFrame, c.Runs[k]);
    }
    if (c.VolPack.Ran)
    {
      int axis = -1;
      c.VolPack.RenderMs.push_back(
        volpack->Render(image, volume, camera, size, nullptr, axis, c.VolPack.Note));
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

std::string Quote(const std::string& text)
{
  return "'" + std::regex_replace(text, std::regex("'"), "'\\''") + "'";
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
    ACCELVOLUME_MPIEXEC_PREFLAGS + " " + Quote(exe) + " " + ACCELVOLUME_MPIEXEC_POSTFLAGS;
  for (const std::string& argument : WorkerArguments(options, dataset, dir))
  {
    command += " " + Quote(argument);
  }
  command += " > " + Quote(log) + " 2>&1";
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
  try
  {
    const accelvolume::cli::JsonValue root = accelvolume::cli::ParseJson(text.str());
    for (const auto& item : root.members.at("cases").items)
    {
      RunResult run;
      const std::string key = item.members.at("key").text;
      if (ReadRunJson(item.members.at("run"), run))
      {
        runs[key] = run;
        std::ifstream raw(
          dir + "/" + std::to_string(ranks) + "_" + FileKey(key) + ".rgb", std::ios::binary);
        images[key] = Image(std::istreambuf_iterator<char>(raw), {});
      }
    }
  }
  catch (const std::exception& e)
  {
    note = std::string("cannot read the MPI worker's JSON: ") + e.what();
    return false;
  }
  std::cout << "  MPI: " << ranks << " rank(s) x 1 thread for " << dataset << " in "
            << Num(SecondsSince(start), 1) << " s\n"
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
  int ok = ResolveHeadlessBackend(options.GL, backend) == 0 &&
      LoadDataset(options, options.Datasets[0], info, image, true)
    ? 1
    : 0;
  int allOk = 0;
  controller->AllReduce(&ok, &allOk, 1, vtkCommunicator::MIN_OP);
  if (!allOk)
  {
    return 1;
  }
  std::ostringstream out;
  out << "{\"ranks\": " << ranks << ", \"dataset\": \"" << JsonEscape(info.Name)
      << "\", \"cases\": [\n";
  bool first = true;
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
        scene.FixedView(options);
        RecordFirst(scene.Mapper(0), scene.Render(0), run);
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
        out << (first ? "" : ",\n") << "{\"key\": \"" << JsonEscape(key) << "\", \"run\": ";
        WriteRunJson(out, run, " ");
        out << "}";
        first = false;
      }
    }
  }
  out << "\n]}\n";
  if (rank == 0)
  {
    std::ofstream file(options.MpiDir + "/" + info.Name + "_" + std::to_string(ranks) + ".json");
    file << out.str();
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

} // namespace

int main(int argc, char* argv[])
{
  const bool worker = std::any_of(
    argv + 1, argv + argc, [](const char* a) { return std::string(a) == "--mpi-worker"; });
  if (worker)
  {
    vtkNew<vtkMPIController> controller;
    controller->Initialize(&argc, &argv);
    vtkMultiProcessController::SetGlobalController(controller);
    vtkAccelVolumeShearWarpMapper::SetCommunicationAbortFunction(AbortWorkers);
    Options options;
    const int code = ParseArguments(argc, argv, options) ? RunWorker(options, controller) : 2;
    controller->Finalize();
    vtkMultiProcessController::SetGlobalController(nullptr);
    return code;
  }
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
  MachineInfo machine;
  {
    vtkNew<vtkAccelVolumeHeadlessRenderWindow> probe;
    StartHeadlessWindow(probe, backend, 64, 64);
    machine.GlRenderer = probe->GetOpenGLRendererString();
    machine.GlBackend =
      vtkAccelVolumeHeadlessRenderWindow::GetBackendName(probe->GetActiveBackend());
  }
  machine.Cpu = ReadCpuModel();
  machine.HardwareThreads = static_cast<int>(std::thread::hardware_concurrency());
  machine.HaveVolPack = VolPackAnchor::Available();
  machine.MpiExec = ACCELVOLUME_MPIEXEC;
  PrintHeader(options, machine);

  const std::string mpiDir =
    (fs::temp_directory_path() / ("accelvolume_swbench_" + std::to_string(getpid()))).string();
  std::error_code ec;
  fs::create_directories(mpiDir, ec);
  if (!options.Images.empty())
  {
    fs::create_directories(options.Images, ec);
  }
  const auto start = Clock::now();
  std::vector<DatasetInfo> datasets;
  std::vector<CaseResult> cases;
  bool ok = true;
  const int perDataset = static_cast<int>(
    options.TransferFunctions.size() * options.Shades.size() * options.Sizes.size());
  CaseProgress progress(
    "accelvolume_benchmark_shearwarp", static_cast<int>(options.Datasets.size()) * perDataset);
  for (const std::string& name : options.Datasets)
  {
    const std::string file = FindDatasetFile(options.DataDir, name);
    if (options.SkipLarge && VoxelsOfFile(file) > LargeVoxels)
    {
      std::cout << "=== " << name << ": skipped (--skip-large)\n";
      progress.Skip(perDataset);
      continue;
    }
    DatasetInfo info;
    vtkSmartPointer<vtkImageData> image;
    if (!LoadDataset(options, name, info, image, false))
    {
      ok = false;
      progress.Skip(perDataset);
      continue;
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
          CaseResult c =
            RunCase(options, info, image, tf, shade, size, backend, volpack.get(), ours);
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
          std::cout << "--- " << c.Key() << ": " << c.Frames << " frames (" << Num(c.Seconds, 1)
                    << " s)\n";
          PrintCase(c);
          cases.push_back(std::move(c));
        }
      }
    }
    datasets.push_back(info);
  }
  fs::remove_all(mpiDir, ec);
  if (!cases.empty())
  {
    PrintSummary(cases);
  }
  const double total = SecondsSince(start);
  WriteJson(options, machine, datasets, cases, total);
  std::cout << "results written to " << options.Json << "; total " << Num(total, 1) << " s\n";
  if (!std::all_of(cases.begin(), cases.end(), [](const CaseResult& c) { return c.ChecksOk(); }))
  {
    std::cout << "FAILED: image checks (see above)\n";
    return 3;
  }
  return ok && !cases.empty() ? 0 : 1;
}
