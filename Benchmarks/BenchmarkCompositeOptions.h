// Command-line settings of accelvolume_benchmark_composite (Lee 2005, Table V-3).
#ifndef accelvolume_benchmark_BenchmarkCompositeOptions_h
#define accelvolume_benchmark_BenchmarkCompositeOptions_h

#include <string>
#include <vector>

#ifndef ACCELVOLUME_BENCHMARK_DATA_DIR
#define ACCELVOLUME_BENCHMARK_DATA_DIR "../shared/data"
#endif

namespace accelvolume::benchmark::composite
{

struct Options
{
  std::string DataDir = ACCELVOLUME_BENCHMARK_DATA_DIR;
  std::vector<std::string> Datasets = { "engine", "cthead", "bonsai_hazeremoved" };
  std::vector<std::string> TransferFunctions = { "tf1", "tf2" };
  std::vector<int> Sizes = { 256, 512 };
  int Frames = 5;
  // Timed frames at sizes above 256: a shaded 512^2 frame takes 0.5-1 s on llvmpipe, so the
  // full default run would not fit in ~6 minutes with --frames there. -1 = same as Frames.
  int LargeFrames = 3;
  std::string GL = "egl";
  std::string Json = "benchmark_composite.json";
  std::string Images; // PNGs of the quality-check view, when set
  double Azimuth = 30.0;
  double Elevation = 20.0;

  int FramesFor(int size) const { return size > 256 && LargeFrames > 0 ? LargeFrames : Frames; }
};

// Fills `options` from the command line; prints the usage and exits on --help / -h. Returns
// false (after printing why) on an unknown option, a missing value or an invalid value.
bool ParseArguments(int argc, char* argv[], Options& options);

} // namespace accelvolume::benchmark::composite

#endif
