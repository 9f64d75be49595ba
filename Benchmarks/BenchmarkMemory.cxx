// accelvolume_benchmark_memory: peak resident memory of every mapper (issue 8: "the CPU mappers
// handle the 512x512x275 16-bit CT and a procedural ~1 GiB volume without copying the volume
// more than necessary; report peak memory per mapper").
//
// Each (volume, mapper) case runs in a fresh child process (this program re-executed with
// --child), so that one case's allocations, caches and malloc arenas never inflate another's
// peak. The child starts the headless GL context, loads the volume (the CT through the CLI's
// loader, streamed from gzip into the image; the procedural volume generated in place as
// uint16), sets up the scene and reads its RSS: the baseline. It then resets the kernel's
// high-water mark (/proc/self/clear_refs "5"), renders two frames (the second with the camera
// turned 5 degrees, so structures are reused) and reads the high-water mark (peak) and the RSS
// after them (what the mapper keeps). Peak - baseline is what the mapper added on top of the
// volume at its worst moment: acceleration structures, textures (llvmpipe keeps them in process
// memory), copies, the image and the fixed cost of its first frame (shader compilation, thread
// stacks: about 25-50 MiB, see the --quick run). A third frame after a transfer-function change
// (window 2 % wider) gets its own peak, over the RSS before it: what an interactive edit
// rebuilds. The child's lifetime peak is the largest of its three high-water marks (loading,
// frames 1-2, frame 3); wait4's ru_maxrss, which the parent reads too (JSON only), follows the
// kernel's mark and so covers only what came after the last reset. Each child runs under an
// address-space cap, so a mapper that needs more memory than the machine can spare fails alone.
//
// Settings: composite, parallel projection (shear-warp needs it), a square image (--size,
// default 256: the image buffers stay small next to any volume), one sample per smallest voxel
// spacing, shading on, transfer function tf1 of `accelvolume render --tf` over the data range.
// The child: BenchmarkMemoryCase.{h,cxx}; the harness (Harness/) parses the options and writes
// the JSON (memory.json of the report, scripts/bench_report/memory.py renders it).
#include "BenchmarkHarness.h"
#include "BenchmarkMemoryCase.h"

#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

namespace accelvolume::benchmark::memory
{
namespace
{
struct CaseResult
{
  std::string VolumeName; // as given to --volumes
  std::string Mapper;     // MapperIds()
  bool Ran = false;       // a child process ran it (false: skipped)
  std::string Note;       // why skipped or failed ("" when it ran cleanly)
  ChildResult Child;      // valid when the child reported
  bool Reported = false;  // the child sent a complete result
  // MiB, wait4's ru_maxrss of the child: the kernel's high-water mark, which the child resets
  // before its frames and before the third, so it covers the last frame and the teardown only.
  double MaxRss = 0;
  double Seconds = 0; // the child's wall time

  bool Ok() const { return this->Ran && this->Reported && this->Child.Ok && this->Note.empty(); }
  // Peak of the frames minus the baseline (GL context + volume), MiB.
  double Added() const { return this->Child.Peak - this->Child.RssLoaded; }
  // What the mapper still holds after the second frame, MiB.
  double Retained() const { return this->Child.RssAfter - this->Child.RssLoaded; }
  // Peak of the transfer-function-change frame minus the RSS before it, MiB.
  double TfAdded() const { return this->Child.TfPeak - this->Child.RssAfter; }
  // The child's whole life, loading included: the largest of its three high-water marks, MiB.
  double LifetimePeak() const
  {
    return std::max({ this->Child.LoadPeak, this->Child.Peak, this->Child.TfPeak, this->MaxRss });
  }
  // Added() as a multiple of the volume's bytes.
  double AddedPerVolume() const
  {
    return SafeRatio(this->Added() * 1024.0 * 1024.0, this->Child.VolumeBytes);
  }
};

std::vector<std::string> ChildArguments(
  const Options& options, const std::string& mapper, const std::string& volume, int resultFd);

// Runs one case in a child process: this program with --child, reporting through a pipe.
CaseResult RunInChild(const Options& options, const std::string& mapper, const std::string& volume)
{
  CaseResult c;
  c.VolumeName = volume;
  c.Mapper = mapper;
  c.Ran = true;
  int fds[2];
  if (pipe(fds) != 0)
  {
    c.Note = std::string("pipe failed: ") + std::strerror(errno);
    return c;
  }
  std::vector<std::string> args = ChildArguments(options, mapper, volume, fds[1]);
  args.insert(args.begin(), "accelvolume_benchmark_memory");
  std::vector<char*> argv;
  for (std::string& arg : args)
  {
    argv.push_back(arg.data());
  }
  argv.push_back(nullptr);
  const auto start = Clock::now();
  const pid_t pid = fork();
  if (pid == 0)
  {
    close(fds[0]);
    execv("/proc/self/exe", argv.data());
    _exit(127);
  }
  close(fds[1]);
  if (pid < 0)
  {
    close(fds[0]);
    c.Note = std::string("fork failed: ") + std::strerror(errno);
    return c;
  }
  // The result until the child closes the pipe; the child is killed after CaseTimeout.
  std::string text;
  bool timedOut = false;
  char buffer[4096];
  for (;;)
  {
    const double left = options.CaseTimeout - SecondsSince(start);
    if (left <= 0)
    {
      timedOut = true;
      kill(pid, SIGKILL);
      break;
    }
    pollfd p{ fds[0], POLLIN, 0 };
    const int ready = poll(&p, 1, static_cast<int>(std::min(left, 1.0) * 1000) + 1);
    if (ready < 0 && errno != EINTR)
    {
      break;
    }
    if (ready > 0)
    {
      const ssize_t n = read(fds[0], buffer, sizeof(buffer));
      if (n <= 0)
      {
        break; // EOF: the result is complete
      }
      text.append(buffer, static_cast<std::size_t>(n));
    }
  }
  close(fds[0]);
  int status = 0;
  rusage usage{};
  for (;;)
  {
    const pid_t done = wait4(pid, &status, timedOut ? 0 : WNOHANG, &usage);
    if (done == pid || (done < 0 && errno != EINTR))
    {
      break;
    }
    if (SecondsSince(start) > options.CaseTimeout)
    {
      timedOut = true; // hangs while tearing down: killed, then reaped by the blocking wait
      kill(pid, SIGKILL);
    }
    else
    {
      usleep(20000);
    }
  }
  c.Seconds = SecondsSince(start);
  c.MaxRss = static_cast<double>(usage.ru_maxrss) / 1024.0; // kB on Linux
  c.Reported = ReadChildResult(text, c.Child);
  if (timedOut)
  {
    c.Note = "timed out after " + std::to_string(std::lround(options.CaseTimeout)) + " s (killed)";
  }
  else if (WIFSIGNALED(status))
  {
    c.Note = std::string(c.Reported ? "crashed after reporting" : "crashed") + " (signal " +
      std::to_string(WTERMSIG(status)) + ", " + strsignal(WTERMSIG(status)) + ")";
  }
  else if (WIFEXITED(status) && WEXITSTATUS(status) != 0)
  {
    c.Note = "child exit code " + std::to_string(WEXITSTATUS(status));
  }
  else if (!c.Reported)
  {
    c.Note = "no result from the child process";
  }
  return c;
}

// Consistency of a clean case: the steps are ordered, and a large volume shows up in the RSS
// (small ones may land in memory malloc already holds).
std::string CheckCase(const CaseResult& c)
{
  const ChildResult& r = c.Child;
  if (!(r.RssStart > 0 && r.RssLoaded >= r.RssStart && r.Peak >= r.RssAfter && r.Peak > 0))
  {
    return "inconsistent memory readings";
  }
  constexpr double LargeBytes = 64.0 * 1024 * 1024;
  if (r.VolumeBytes >= LargeBytes &&
    (r.RssLoaded - r.RssStart) * 1024.0 * 1024.0 < 0.9 * r.VolumeBytes)
  {
    return "the loaded volume does not show in the RSS";
  }
  return "";
}

class MemoryBenchmark : public Benchmark
{
public:
  const char* Name() const override { return "accelvolume_benchmark_memory"; }
  const char* Description() const override
  {
    return "Peak resident memory of every mapper, one child process per case. Exit code: 0 "
           "every case ran, 1 a case failed (error, crash, timeout) or a backend is missing, 2 "
           "bad options, 125 no case could run because the data is absent";
  }
  const char* DefaultJson() const override { return "accelvolume_benchmark_memory.json"; }
  // The parent opens no GL context; each child opens its own under its memory cap.
  bool NeedsWindow() const override { return false; }

  void AddOptions(CLI::App& app) override;
  void Resolve(const CLI::App& app, const MachineInfo& machine) override;
  int Run(Harness& harness, Json& result) override;

private:
  Options O;
  std::vector<int> Dims = { 1024, 1024, 512 };
  std::vector<std::string> Child; // --child MAPPER VOLUME
  CLI::Option* VolumesOption = nullptr;
  CLI::Option* DimsOption = nullptr;
  CLI::Option* SizeOption = nullptr;
  Json CaseJson(const CaseResult& c) const;
  Json SettingsJson() const;
};

void MemoryBenchmark::AddOptions(CLI::App& app)
{
  this->O.Mappers = MapperIds();
  this->VolumesOption = AddList(app, "--volumes", this->O.Volumes,
    "data-folder names (NAME_<X>x<Y>x<Z>_<type>.raw[.gz]) or 'procedural'");
  this->DimsOption =
    app.add_option("--procedural-dims", this->Dims, "the generated uint16 volume (1 GiB)")
      ->expected(3)
      ->type_name("X Y Z");
  AddList(app, "--mappers", this->O.Mappers, "mappers to run");
  AddList(app, "--procedural-skip", this->O.ProceduralSkip,
    "mappers not run on the procedural volume (A,B or none)")
    ->default_str("none");
  this->SizeOption = app.add_option("--size", this->O.Size, "square image size in pixels")
                       ->check(CLI::Range(16, 4096));
  app.add_option("--tf", this->O.Tf, "transfer-function preset of `accelvolume render --tf`")
    ->check(CLI::IsMember({ "tf1", "tf2" }));
  AddOnOff(app, "--shade", this->O.Shade, "Phong shading");
  app.add_option("--threads", this->O.Threads, "'all threads' (0: hardware threads)")
    ->check(CLI::Range(0, 1024));
  app
    .add_option("--case-timeout", this->O.CaseTimeout, "seconds before a case's process is killed")
    ->check(CLI::PositiveNumber);
  app.add_option("--memory-limit", this->O.MemoryLimit,
    "address-space cap of each case's process in MiB (0: 60 % of the machine's memory; "
    "negative: none)");
  app.add_flag(
    "--quick", this->O.Quick, "smoke run: procedural 128x128x96, size 64 (unless given)");
  // Internal: this process is the child that measures one case.
  app.add_option("--child", this->Child)->expected(2)->group("");
  app.add_option("--child-fd", this->O.ChildFd)->group("");
}

void MemoryBenchmark::Resolve(const CLI::App& app, const MachineInfo& machine)
{
  Options& o = this->O;
  o.DataDir = app.get_option("--data")->as<std::string>();
  o.GL = app.get_option("--gl")->as<std::string>();
  if (o.Quick)
  {
    o.Size = this->SizeOption->count() ? o.Size : 64;
    if (!this->VolumesOption->count())
    {
      o.Volumes = { ProceduralName };
    }
    if (!this->DimsOption->count())
    {
      this->Dims = { 128, 128, 96 };
    }
  }
  std::copy(this->Dims.begin(), this->Dims.end(), o.ProceduralDims);
  o.Child = this->Child.size() == 2;
  if (o.Child)
  {
    o.ChildMapper = this->Child[0];
    o.ChildVolume = this->Child[1];
  }
  if (o.ProceduralSkip == std::vector<std::string>{ "none" })
  {
    o.ProceduralSkip.clear();
  }
  o.Threads = o.Threads > 0 ? o.Threads : machine.HardwareThreads;
  o.MemoryLimit = o.MemoryLimit == 0 ? 0.6 * machine.MemoryMiB : o.MemoryLimit;
  auto known = [](const std::string& id)
  {
    const auto& ids = MapperIds();
    return std::find(ids.begin(), ids.end(), id) != ids.end();
  };
  bool valid = !o.Mappers.empty() && !o.Volumes.empty() && (!o.Child || o.ChildFd >= 0) &&
    std::all_of(o.Mappers.begin(), o.Mappers.end(), known) &&
    std::all_of(o.ProceduralSkip.begin(), o.ProceduralSkip.end(), known);
  const int* d = o.ProceduralDims;
  valid = valid && d[0] >= 2 && d[1] >= 2 && d[2] >= 2 && d[0] <= 4096 && d[1] <= 4096 &&
    d[2] <= 4096 && static_cast<double>(d[0]) * d[1] * d[2] <= 4.0 * 1024 * 1024 * 1024;
  if (!valid)
  {
    throw CLI::ValidationError("options",
      "volumes non-empty, known mappers, procedural dims "
      "2..4096 and at most 2^32 voxels");
  }
}

// The arguments that make a child process measure `mapper` on `volume` with these settings.
std::vector<std::string> ChildArguments(
  const Options& options, const std::string& mapper, const std::string& volume, int resultFd)
{
  const int* d = options.ProceduralDims;
  return { "--child", mapper, volume, "--child-fd", std::to_string(resultFd), "--data",
    options.DataDir, "--procedural-dims", std::to_string(d[0]), std::to_string(d[1]),
    std::to_string(d[2]), "--size", std::to_string(options.Size), "--tf", options.Tf, "--shade",
    options.Shade ? "on" : "off", "--threads", std::to_string(options.Threads), "--gl", options.GL,
    "--memory-limit", std::to_string(options.MemoryLimit) };
}

Json MemoryBenchmark::CaseJson(const CaseResult& c) const
{
  Json out = { { "volume", c.VolumeName }, { "mapper", c.Mapper }, { "ran", c.Ran },
    { "ok", c.Ok() }, { "note", c.Note } };
  if (c.Ran && c.Reported)
  {
    const ChildResult& r = c.Child;
    out.update(Json{ { "description", r.Volume }, { "volume_bytes", Round(r.VolumeBytes, 0) },
      { "rss_start_mib", Round(r.RssStart, 1) }, { "baseline_mib", Round(r.RssLoaded, 1) },
      { "load_peak_mib", Round(r.LoadPeak, 1) }, { "load_seconds", Round(r.LoadSeconds, 2) },
      { "peak_mib", Round(r.Peak, 1) }, { "peak_minus_baseline_mib", Round(c.Added(), 1) },
      { "peak_minus_baseline_per_volume", Round(c.AddedPerVolume(), 3) },
      { "retained_mib", Round(c.Retained(), 1) }, { "peak_reset", r.PeakReset },
      { "first_frame_ms", Round(r.FirstMs, 1) }, { "second_frame_ms", Round(r.SecondMs, 1) },
      { "tf_change_frame_ms", Round(r.TfMs, 1) },
      { "tf_change_peak_minus_before_mib", Round(c.TfAdded(), 1) },
      { "acceleration_bytes",
        r.AccelerationBytes >= 0 ? Round(r.AccelerationBytes, 0) : Json(nullptr) },
      { "lifetime_peak_mib", Round(c.LifetimePeak(), 1) },
      { "wait4_maxrss_mib", Round(c.MaxRss, 1) }, { "seconds", Round(c.Seconds, 2) },
      { "error", r.Error } });
  }
  return out;
}

Json MemoryBenchmark::SettingsJson() const
{
  const Options& o = this->O;
  return { { "size", o.Size }, { "tf", o.Tf }, { "shade", o.Shade }, { "threads", o.Threads },
    { "memory_limit_mib", Round(o.MemoryLimit, 0) }, { "procedural_dims", this->Dims },
    { "projection", "parallel" }, { "blend", "composite" }, { "frames", 2 }, { "quick", o.Quick },
    { "units", "MiB" }, { "baseline", "RSS with the GL context and the volume loaded" },
    { "peak", "VmHWM over the two frames (reset after loading)" } };
}

int MemoryBenchmark::Run(Harness& harness, Json& result)
{
  const Options& options = this->O;
  if (options.Child)
  {
    return RunChildCase(options); // the result goes to the parent's pipe
  }
  int backend = 0;
  if (const int exitCode = Harness::ResolveBackend(options.GL, backend))
  {
    return exitCode;
  }
  const MachineInfo& m = harness.Machine;
  std::string glBackend, glRenderer;
  std::vector<CaseResult> cases;
  CaseProgress progress(
    this->Name(), static_cast<int>(options.Volumes.size() * options.Mappers.size()));
  int missingVolumes = 0;
  for (const std::string& volume : options.Volumes)
  {
    const bool procedural = volume == ProceduralName;
    const bool present = procedural || !FindDatasetFile(options.DataDir, volume).empty();
    missingVolumes += present ? 0 : 1;
    for (const std::string& mapper : options.Mappers)
    {
      const auto& skip = options.ProceduralSkip;
      const bool skipped = procedural && std::find(skip.begin(), skip.end(), mapper) != skip.end();
      if (!present || skipped)
      {
        CaseResult c;
        c.VolumeName = volume;
        c.Mapper = mapper;
        c.Note = present
          ? std::string("skipped (--procedural-skip)")
          : "skipped: no " + volume + "_<X>x<Y>x<Z>_<type>.raw[.gz] in " + options.DataDir;
        progress.Skip();
        cases.push_back(c);
        continue;
      }
      progress.Begin(volume + " " + mapper);
      CaseResult c = RunInChild(options, mapper, volume);
      if (c.Ok() && c.Note.empty())
      {
        c.Note = CheckCase(c);
      }
      if (c.Reported && glRenderer.empty())
      {
        glBackend = c.Child.GlBackend;
        glRenderer = c.Child.GlRenderer;
      }
      cases.push_back(c);
    }
  }
  result = { { "benchmark", "memory (peak resident memory per mapper, one process per case)" },
    { "machine",
      { { "cpu", m.Cpu }, { "hardware_threads", m.HardwareThreads },
        { "memory_mib", Round(m.MemoryMiB, 0) }, { "gl_backend", glBackend },
        { "gl_renderer", glRenderer } } },
    { "settings", this->SettingsJson() }, { "total_seconds", Round(harness.Seconds(), 2) },
    { "cases", Json::array() } };
  int ran = 0, failed = 0;
  for (const CaseResult& c : cases)
  {
    result["cases"].push_back(this->CaseJson(c));
    ran += c.Ran ? 1 : 0;
    failed += c.Ran && !c.Ok() ? 1 : 0;
  }
  if (ran == 0 && missingVolumes > 0)
  {
    std::cout << "skipped: the data is absent\n";
    return 125;
  }
  if (failed > 0)
  {
    std::cout << "FAILED: " << failed << " case(s) did not run cleanly (see the notes)\n";
    return 1;
  }
  return 0;
}

} // namespace
} // namespace accelvolume::benchmark::memory

namespace accelvolume::benchmark
{
std::unique_ptr<Benchmark> MakeBenchmark()
{
  return std::make_unique<memory::MemoryBenchmark>();
}
} // namespace accelvolume::benchmark
