// Command-line settings of accelvolume_benchmark_raycast (Lim, Kim and Shin 2009, Table 2).
#ifndef accelvolume_benchmark_BenchmarkRaycastOptions_h
#define accelvolume_benchmark_BenchmarkRaycastOptions_h

#include <string>
#include <vector>

#ifndef ACCELVOLUME_BENCHMARK_DATA_DIR
#define ACCELVOLUME_BENCHMARK_DATA_DIR "../shared/data"
#endif

namespace accelvolume::benchmark::raycast
{

struct Options
{
  std::string DataDir = ACCELVOLUME_BENCHMARK_DATA_DIR;
  // The paper's six volumes, as far as the data folder has them: head, cerebral arteries (two),
  // teapot, engine, bonsai.
  std::vector<std::string> Datasets = { "cthead", "aneurism", "cta_avm", "boston_teapot", "engine",
    "bonsai_hazeremoved" };
  std::vector<std::string> TransferFunctions = { "tf2", "tf1" };
  int Size = 512;
  int Frames = 10;
  int Threads = 0;         // 0: the hardware threads (resolved by ParseArguments)
  double SampleFactor = 1; // sample distance = factor x the smallest voxel spacing
  int ReferenceFactor = 4; // the fine reference samples this many times more densely
  double Azimuth = 30.0;   // fixed initial view (image checks, first timed round)
  double Elevation = 20.0;
  double Turn = 3.0; // azimuth degrees per timed round
  bool Shade = true;
  bool Quick = false;
  std::string GL = "egl";
  std::string Json = "accelvolume_benchmark_raycast.json";
  std::string Images; // PNGs of the fixed view, when set
};

// Fills `options` from the command line; prints the usage and exits on --help / -h. Returns
// false (after printing why) on an unknown option, a missing value or an invalid value.
// --quick sets size 128, 2 frames, one dataset (engine) and one transfer function (tf2), unless
// those are given explicitly.
bool ParseArguments(int argc, char* argv[], Options& options);

} // namespace accelvolume::benchmark::raycast

#endif
