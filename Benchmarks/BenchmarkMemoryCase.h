// One case of accelvolume_benchmark_memory (one mapper on one volume), measured inside the
// fresh child process that runs it, and the result it hands back to the parent.
#ifndef accelvolume_benchmark_BenchmarkMemoryCase_h
#define accelvolume_benchmark_BenchmarkMemoryCase_h

#include "BenchmarkMemoryOptions.h"

#include <string>

namespace accelvolume::benchmark::memory
{

// Resident memory of the child (/proc/self/status, MiB) at the steps of a case. The baseline is
// RssLoaded: the GL context exists and the volume is in memory. Peak is the high-water mark of
// the two frames alone: it is reset (/proc/self/clear_refs, "5") after loading, so the loader's
// own buffers do not count; PeakReset says whether the kernel allowed that (otherwise Peak
// includes the loading).
struct ChildResult
{
  bool Ok = false;
  std::string Error;  // why not Ok (first VTK error or the reason the case could not run)
  std::string Volume; // "512x512x275 uint16"
  double VolumeBytes = 0;
  double RssStart = 0;  // GL context up, no volume
  double RssLoaded = 0; // + the volume: the baseline
  double LoadPeak = 0;  // high-water mark while loading
  double LoadSeconds = 0;
  double Peak = 0;     // high-water mark of the two frames
  double RssAfter = 0; // after the second frame: what the mapper keeps
  bool PeakReset = false;
  double FirstMs = 0;  // first frame: structures built, textures uploaded
  double SecondMs = 0; // second frame, camera turned 5 degrees: structures reused
  double TfMs = 0;     // third frame, after a transfer-function change (window 2 % wider)
  double TfPeak = 0;   // high-water mark of the third frame alone (reset after the second)
  double AccelerationBytes = -1; // reported by the mapper; -1 when it reports none
  std::string GlBackend;
  std::string GlRenderer;
};

// Runs options.ChildMapper on options.ChildVolume and writes the result to options.ChildFd.
// Returns the process exit code (0 also when the case failed cleanly: the result says why).
int RunChildCase(const Options& options);

// "key value" lines, one per field, and back; false when a field is missing or malformed.
std::string FormatChildResult(const ChildResult& result);
bool ParseChildResult(const std::string& text, ChildResult& result);

} // namespace accelvolume::benchmark::memory

#endif
