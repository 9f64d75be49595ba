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
// Options: BenchmarkMemoryOptions.{h,cxx}; the child: BenchmarkMemoryCase.{h,cxx}; table and
// JSON: BenchmarkMemoryReport.{h,cxx}.
#include "BenchmarkCommon.h"
#include "BenchmarkMemoryCase.h"
#include "BenchmarkMemoryOptions.h"
#include "BenchmarkMemoryReport.h"

#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

using namespace accelvolume::benchmark;
using namespace accelvolume::benchmark::memory;

namespace
{
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
  c.Reported = ParseChildResult(text, c.Child);
  if (timedOut)
  {
    c.Note = "timed out after " + Num(options.CaseTimeout, 0) + " s (killed)";
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

} // namespace

int main(int argc, char* argv[])
{
  Options options;
  if (!ParseArguments(argc, argv, options))
  {
    return 2;
  }
  if (options.Child)
  {
    return RunChildCase(options);
  }
  int backend = 0;
  if (const int exitCode = ResolveHeadlessBackend(options.GL, backend))
  {
    return exitCode;
  }

  MachineInfo machine = ReadMachine();
  std::cout << "accelvolume_benchmark_memory: peak resident memory per mapper, one child process "
               "per case\n"
            << "machine: " << (machine.Cpu.empty() ? "CPU unknown" : machine.Cpu) << ", "
            << machine.HardwareThreads << " hardware threads, " << Num(machine.MemoryMiB / 1024, 1)
            << " GiB\n"
            << "settings: " << options.Size << "x" << options.Size
            << " parallel, composite, shading " << (options.Shade ? "on" : "off") << ", "
            << options.Tf << " over the data range, one sample per smallest spacing, "
            << options.Threads << " threads ('all'); 2 frames; each case capped at "
            << (options.MemoryLimit > 0 ? Num(options.MemoryLimit / 1024, 1) + " GiB" : "none")
            << " of address space\n"
            << "memory in MiB: base = RSS with GL context + volume; peak = high-water mark of the "
               "two frames; +peak = peak - base (x vol: in volume sizes); +kept = RSS after the "
               "frames - base; tf ms / +tf peak = a third frame after a transfer-function change "
               "and its peak over the RSS before it; accel = the mapper's own count (ray caster: "
               "acceleration bytes, "
               "shear-warp: encoded bytes); life = the child's peak over its whole life, loading "
               "included\n"
            << "data: " << options.DataDir << "\n\n"
            << std::flush;

  const auto start = Clock::now();
  std::vector<CaseResult> cases;
  CaseProgress progress("accelvolume_benchmark_memory",
    static_cast<int>(options.Volumes.size() * options.Mappers.size()));
  int missingVolumes = 0;
  PrintHeader();
  for (const std::string& volume : options.Volumes)
  {
    const bool procedural = volume == ProceduralName;
    const bool present = procedural || !FindDatasetFile(options.DataDir, volume).empty();
    missingVolumes += present ? 0 : 1;
    for (const std::string& mapper : options.Mappers)
    {
      const bool skipped = procedural &&
        std::find(options.ProceduralSkip.begin(), options.ProceduralSkip.end(), mapper) !=
          options.ProceduralSkip.end();
      if (!present || skipped)
      {
        CaseResult c;
        c.VolumeName = volume;
        c.Mapper = mapper;
        c.Note = present
          ? std::string("skipped (--procedural-skip)")
          : "skipped: no " + volume + "_<X>x<Y>x<Z>_<type>.raw[.gz] in " + options.DataDir;
        progress.Skip();
        PrintRow(c);
        cases.push_back(c);
        continue;
      }
      progress.Begin(volume + " " + mapper);
      CaseResult c = RunInChild(options, mapper, volume);
      if (c.Ok() && c.Note.empty())
      {
        c.Note = CheckCase(c);
      }
      if (c.Reported && machine.GlRenderer.empty())
      {
        machine.GlBackend = c.Child.GlBackend;
        machine.GlRenderer = c.Child.GlRenderer;
      }
      PrintRow(c);
      cases.push_back(c);
    }
  }
  const double total = SecondsSince(start);
  WriteJson(options, machine, cases, total);
  std::cout << "\nGL: " << machine.GlBackend << " (" << machine.GlRenderer
            << ")\nresults written to " << options.Json << "; total " << Num(total, 1) << " s\n";
  const int ran = static_cast<int>(
    std::count_if(cases.begin(), cases.end(), [](const CaseResult& c) { return c.Ran; }));
  const int failed = static_cast<int>(std::count_if(
    cases.begin(), cases.end(), [](const CaseResult& c) { return c.Ran && !c.Ok(); }));
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
