// Results of accelvolume_benchmark_memory as the parent process sees them, the printed table and
// the JSON file.
#ifndef accelvolume_benchmark_BenchmarkMemoryReport_h
#define accelvolume_benchmark_BenchmarkMemoryReport_h

#include "BenchmarkMemoryCase.h"
#include "BenchmarkMemoryOptions.h"

#include <string>
#include <vector>

namespace accelvolume::benchmark::memory
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
  double LifetimePeak() const;
  // Added() as a multiple of the volume's bytes.
  double AddedPerVolume() const;
};

struct MachineInfo
{
  std::string Cpu;
  int HardwareThreads = 0;
  double MemoryMiB = 0; // MemTotal
  std::string GlBackend;
  std::string GlRenderer;
};

MachineInfo ReadMachine();
// One row per case, printed as soon as it is known.
void PrintHeader();
void PrintRow(const CaseResult& c);
void WriteJson(const Options& options, const MachineInfo& machine,
  const std::vector<CaseResult>& cases, double totalSeconds);

} // namespace accelvolume::benchmark::memory

#endif
