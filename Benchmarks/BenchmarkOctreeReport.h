// Options, results, table and JSON of accelvolume_benchmark_octree.
#ifndef accelvolume_benchmark_BenchmarkOctreeReport_h
#define accelvolume_benchmark_BenchmarkOctreeReport_h

#include "BenchmarkCommon.h"

#include <cstddef>
#include <string>
#include <vector>

#ifndef ACCELVOLUME_BENCHMARK_DATA_DIR
#define ACCELVOLUME_BENCHMARK_DATA_DIR "../shared/data"
#endif

namespace accelvolume::benchmark
{

struct Options
{
  std::string DataDir = ACCELVOLUME_BENCHMARK_DATA_DIR;
  // File name prefixes in DataDir; "vessels" is the time-varying phantom.
  std::vector<std::string> Datasets = { "cta_avm", "aneurism", "engine", "ct_chest_lidc0314",
    "vessels" };
  int Repeat = 5;
  int Leaf = 8;
  int Frames = 5;         // time-varying phantom frames
  int PhantomSize = 256;  // its edge in voxels
  std::string GL = "egl"; // headless backend of the gpu builder and the renders
  std::string Json = "benchmark_octree.json";
  int AllThreads = 1; // vtkSMPTools' thread count at start-up (set by main)
};

// Prints the usage and exits on --help; false (after saying why) on bad options.
bool ParseArguments(int argc, char* argv[], Options& options);

struct BuildResult
{
  std::string Builder;     // reference | cpu | gpu
  int Threads = 0;         // 0 for gpu
  bool AllThreads = false; // the cpu build on every thread
  std::vector<double> Ms;
  int Repeats = 0;
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

struct Machine
{
  int Threads = 0;
  std::string SMPBackend, GLBackend, GLRenderer, GLVersion;
  std::string GPUNote; // why the gpu builder was skipped ("" when it ran)
};

// The shared Num() (BenchmarkCommon.h), with this program's usual precision as the default.
std::string Num(double value, int precision = 3);
double Median(std::vector<double> values);

void PrintReport(const Machine& machine, const std::vector<DatasetResult>& results);
void WriteJson(
  const Options& options, const Machine& machine, const std::vector<DatasetResult>& results);

} // namespace accelvolume::benchmark

#endif
