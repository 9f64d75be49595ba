// One case of accelvolume_benchmark_memory (one mapper on one volume), measured inside the
// fresh child process that runs it, and the result it hands back to the parent.
#ifndef accelvolume_benchmark_BenchmarkMemoryCase_h
#define accelvolume_benchmark_BenchmarkMemoryCase_h

#include "BenchmarkHarness.h"

#include <string>
#include <vector>

namespace accelvolume::benchmark::memory
{

// The volume name that means the generated volume rather than a file of the data folder.
inline constexpr const char* ProceduralName = "procedural";

// The settings of a run (its options).
struct Options
{
  std::string DataDir; // the harness's --data
  // Data-folder names (NAME_<X>x<Y>x<Z>_<type>.raw[.gz]) or "procedural".
  std::vector<std::string> Volumes = { "ct_chest_lidc0314", ProceduralName };
  // Mapper ids (MapperIds()), run on every volume except those in ProceduralSkip on the
  // procedural volume.
  std::vector<std::string> Mappers;
  std::vector<std::string> ProceduralSkip;     // e.g. vtk-gpu where the GL cannot hold 1 GiB
  int ProceduralDims[3] = { 1024, 1024, 512 }; // uint16: 1 GiB
  int Size = 256;
  std::string Tf = "tf1";
  bool Shade = true;
  int Threads = 0;          // "all threads": 0 = the hardware threads (resolved after parsing)
  double CaseTimeout = 900; // seconds a child may run before it is killed
  // Address-space cap of each child (setrlimit RLIMIT_AS), MiB; 0: 60 % of the machine's memory
  // (resolved after parsing), so that a mapper that needs more fails alone (std::bad_alloc)
  // instead of waking the OOM killer on a shared machine. Negative: no cap.
  double MemoryLimit = 0;
  bool Quick = false;
  std::string GL; // the harness's --gl

  // Set in the child process that measures one case (internal options).
  bool Child = false;
  int ChildFd = -1;
  std::string ChildMapper;
  std::string ChildVolume;
};

// Every mapper the benchmark knows, in table order.
const std::vector<std::string>& MapperIds();

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

// The result as the JSON the child sends the parent, and back; false when a field is missing.
Json ChildResultJson(const ChildResult& result);
bool ReadChildResult(const std::string& text, ChildResult& result);

} // namespace accelvolume::benchmark::memory

#endif
