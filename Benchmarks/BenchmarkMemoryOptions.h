// Command-line settings of accelvolume_benchmark_memory (peak memory per mapper).
#ifndef accelvolume_benchmark_BenchmarkMemoryOptions_h
#define accelvolume_benchmark_BenchmarkMemoryOptions_h

#include <string>
#include <vector>

#ifndef ACCELVOLUME_BENCHMARK_DATA_DIR
#define ACCELVOLUME_BENCHMARK_DATA_DIR "../shared/data"
#endif

namespace accelvolume::benchmark::memory
{

// The volume name that means the generated volume rather than a file of the data folder.
inline constexpr const char* ProceduralName = "procedural";

struct Options
{
  std::string DataDir = ACCELVOLUME_BENCHMARK_DATA_DIR;
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
  int Threads = 0;          // "all threads": 0 = the hardware threads (resolved by ParseArguments)
  double CaseTimeout = 900; // seconds a child may run before it is killed
  // Address-space cap of each child (setrlimit RLIMIT_AS), MiB; 0: 60 % of the machine's memory
  // (resolved by ParseArguments), so that a mapper that needs more fails alone (std::bad_alloc)
  // instead of waking the OOM killer on a shared machine. Negative: no cap.
  double MemoryLimit = 0;
  bool Quick = false;
  std::string GL = "egl";
  std::string Json = "accelvolume_benchmark_memory.json";

  // Set in the child process that measures one case (internal options).
  bool Child = false;
  int ChildFd = -1;
  std::string ChildMapper;
  std::string ChildVolume;
};

// MemTotal of /proc/meminfo in MiB (0 when unknown).
double MachineMemoryMiB();

// Every mapper the benchmark knows, in table order.
const std::vector<std::string>& MapperIds();

// Fills `options` from the command line; prints the usage and exits on --help / -h. Returns
// false (after printing why) on an unknown option, a missing value or an invalid value.
// --quick: the procedural volume alone at 128x128x96, size 64, unless given explicitly.
bool ParseArguments(int argc, char* argv[], Options& options);

// The arguments that make a child process measure `mapper` on `volume` with these settings.
std::vector<std::string> ChildArguments(
  const Options& options, const std::string& mapper, const std::string& volume, int resultFd);

} // namespace accelvolume::benchmark::memory

#endif
