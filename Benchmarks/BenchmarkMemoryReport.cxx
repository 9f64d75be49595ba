// Table and JSON of accelvolume_benchmark_memory (see BenchmarkMemoryReport.h).
#include "BenchmarkMemoryReport.h"

#include "BenchmarkCommon.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <thread>

namespace accelvolume::benchmark::memory
{
namespace
{
constexpr double MiB = 1024.0 * 1024.0;

std::string Field(const std::string& prefix, const std::string& file)
{
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line))
  {
    if (line.rfind(prefix, 0) == 0 && line.find(':') != std::string::npos)
    {
      const std::size_t value = line.find_first_not_of(" \t", line.find(':') + 1);
      return value == std::string::npos ? "" : line.substr(value);
    }
  }
  return "";
}
} // namespace

double CaseResult::LifetimePeak() const
{
  return std::max({ this->Child.LoadPeak, this->Child.Peak, this->Child.TfPeak, this->MaxRss });
}

double CaseResult::AddedPerVolume() const
{
  return SafeRatio(this->Added() * MiB, this->Child.VolumeBytes);
}

MachineInfo ReadMachine()
{
  MachineInfo machine;
  machine.Cpu = Field("model name", "/proc/cpuinfo");
  machine.HardwareThreads = static_cast<int>(std::thread::hardware_concurrency());
  machine.MemoryMiB = std::atof(Field("MemTotal", "/proc/meminfo").c_str()) / 1024.0;
  return machine;
}

void PrintHeader()
{
  std::printf("%-18s %-14s %8s %8s %8s %8s %6s %8s %8s %9s %9s %9s %8s %8s  %s\n", "volume",
    "mapper", "vol MiB", "base MiB", "peak MiB", "+peak", "x vol", "+kept", "accel", "1st ms",
    "2nd ms", "tf ms", "+tf peak", "life", "note");
  std::fflush(stdout);
}

void PrintRow(const CaseResult& c)
{
  if (!c.Ran || !c.Reported)
  {
    std::printf("%-18s %-14s %s\n", c.VolumeName.c_str(), c.Mapper.c_str(), c.Note.c_str());
    std::fflush(stdout);
    return;
  }
  const ChildResult& r = c.Child;
  const std::string accel = r.AccelerationBytes >= 0 ? Num(r.AccelerationBytes / MiB, 1) : "-";
  std::string note = c.Note;
  if (!r.Ok)
  {
    note += (note.empty() ? "" : "; ") + std::string("error: ") + r.Error.substr(0, 160);
  }
  if (!r.PeakReset)
  {
    note += (note.empty() ? "" : "; ") + std::string("peak includes loading");
  }
  std::printf(
    "%-18s %-14s %8.1f %8.1f %8.1f %8.1f %6.2f %8.1f %8s %9.1f %9.1f %9.1f %8.1f %8.1f  %s\n",
    c.VolumeName.c_str(), c.Mapper.c_str(), r.VolumeBytes / MiB, r.RssLoaded, r.Peak, c.Added(),
    c.AddedPerVolume(), c.Retained(), accel.c_str(), r.FirstMs, r.SecondMs, r.TfMs, c.TfAdded(),
    c.LifetimePeak(), note.c_str());
  std::fflush(stdout);
}

void WriteJson(const Options& options, const MachineInfo& machine,
  const std::vector<CaseResult>& cases, double totalSeconds)
{
  std::ofstream out(options.Json);
  if (!out)
  {
    std::cerr << "cannot write " << options.Json << "\n";
    return;
  }
  out << "{\n  \"benchmark\": \"memory (peak resident memory per mapper, one process per "
         "case)\",\n";
  out << "  \"machine\": {\"cpu\": \"" << JsonEscape(machine.Cpu)
      << "\", \"hardware_threads\": " << machine.HardwareThreads
      << ", \"memory_mib\": " << Num(machine.MemoryMiB, 0) << ", \"gl_backend\": \""
      << JsonEscape(machine.GlBackend) << "\", \"gl_renderer\": \""
      << JsonEscape(machine.GlRenderer) << "\"},\n";
  const int* d = options.ProceduralDims;
  out << "  \"settings\": {\"size\": " << options.Size << ", \"tf\": \"" << options.Tf
      << "\", \"shade\": " << (options.Shade ? "true" : "false")
      << ", \"threads\": " << options.Threads
      << ", \"memory_limit_mib\": " << Num(options.MemoryLimit, 0) << ", \"procedural_dims\": ["
      << d[0] << ", " << d[1] << ", " << d[2]
      << "], \"projection\": \"parallel\", \"blend\": \"composite\", "
      << "\"frames\": 2, \"quick\": " << (options.Quick ? "true" : "false")
      << ", \"units\": \"MiB\", \"baseline\": \"RSS with the GL context and the volume loaded\", "
         "\"peak\": \"VmHWM over the two frames (reset after loading)\"},\n";
  out << "  \"total_seconds\": " << Num(totalSeconds, 2) << ",\n  \"cases\": [\n";
  for (std::size_t i = 0; i < cases.size(); ++i)
  {
    const CaseResult& c = cases[i];
    const ChildResult& r = c.Child;
    out << "    {\"volume\": \"" << JsonEscape(c.VolumeName) << "\", \"mapper\": \""
        << JsonEscape(c.Mapper) << "\", \"ran\": " << (c.Ran ? "true" : "false")
        << ", \"ok\": " << (c.Ok() ? "true" : "false") << ", \"note\": \"" << JsonEscape(c.Note)
        << "\"";
    if (c.Ran && c.Reported)
    {
      out << ",\n     \"description\": \"" << JsonEscape(r.Volume)
          << "\", \"volume_bytes\": " << Num(r.VolumeBytes, 0)
          << ", \"rss_start_mib\": " << Num(r.RssStart, 1)
          << ", \"baseline_mib\": " << Num(r.RssLoaded, 1)
          << ", \"load_peak_mib\": " << Num(r.LoadPeak, 1)
          << ", \"load_seconds\": " << Num(r.LoadSeconds, 2) << ", \"peak_mib\": " << Num(r.Peak, 1)
          << ", \"peak_minus_baseline_mib\": " << Num(c.Added(), 1)
          << ", \"peak_minus_baseline_per_volume\": " << Num(c.AddedPerVolume(), 3)
          << ", \"retained_mib\": " << Num(c.Retained(), 1)
          << ", \"peak_reset\": " << (r.PeakReset ? "true" : "false")
          << ",\n     \"first_frame_ms\": " << Num(r.FirstMs, 1)
          << ", \"second_frame_ms\": " << Num(r.SecondMs, 1)
          << ", \"tf_change_frame_ms\": " << Num(r.TfMs, 1)
          << ", \"tf_change_peak_minus_before_mib\": " << Num(c.TfAdded(), 1)
          << ", \"acceleration_bytes\": "
          << (r.AccelerationBytes >= 0 ? Num(r.AccelerationBytes, 0) : "null")
          << ", \"lifetime_peak_mib\": " << Num(c.LifetimePeak(), 1)
          << ", \"wait4_maxrss_mib\": " << Num(c.MaxRss, 1)
          << ", \"seconds\": " << Num(c.Seconds, 2) << ", \"error\": \"" << JsonEscape(r.Error)
          << "\"";
    }
    out << "}" << (i + 1 < cases.size() ? "," : "") << "\n";
  }
  out << "  ]\n}\n";
}

} // namespace accelvolume::benchmark::memory
