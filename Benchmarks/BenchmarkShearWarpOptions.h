// Command-line settings of accelvolume_benchmark_shearwarp (Kim 1998, Tables 2-3: parallel
// shear-warp with run-length encoding and load balancing).
#ifndef accelvolume_benchmark_BenchmarkShearWarpOptions_h
#define accelvolume_benchmark_BenchmarkShearWarpOptions_h

#include <string>
#include <vector>

#ifndef ACCELVOLUME_BENCHMARK_DATA_DIR
#define ACCELVOLUME_BENCHMARK_DATA_DIR "../shared/data"
#endif

namespace accelvolume::benchmark::shearwarp
{

// Volumes with more voxels than this are "large" (--skip-large drops them).
constexpr double LargeVoxels = 32.0 * 1024 * 1024;

struct Options
{
  std::string DataDir = ACCELVOLUME_BENCHMARK_DATA_DIR;
  // The paper's MRI brain and CT head, and the 512x512x275 CT for scale.
  std::vector<std::string> Datasets = { "mri_t1_head", "cthead", "ct_chest_lidc0314" };
  std::vector<std::string> TransferFunctions = { "tf2", "tf1" };
  std::vector<int> Sizes = { 256, 512 };
  std::vector<bool> Shades = { true }; // --shade on|off|both
  int Frames = 10;
  int Threads = 0;       // the "all threads" count; 0: the hardware threads
  double Azimuth = 30.0; // the fixed view (image checks, first frame)
  double Elevation = 20.0;
  double Turn = 1.0; // azimuth degrees per timed round (the paper: 1 degree per frame)
  bool SkipLarge = false;
  bool Mpi = true;
  std::vector<int> MpiRanks = { 1, 2 };
  bool VolPack = true;
  bool VolPackGrey = false; // VolPack in luminance mode (grey = mean of R, G, B), not RGB
  std::string GL = "egl";
  std::string Json = "accelvolume_benchmark_shearwarp.json";
  std::string Images; // PNGs of the fixed view, when set
  // Internal: this process is one rank of the MPI run the benchmark launched itself.
  bool MpiWorker = false;
  std::string MpiDir; // where the worker writes its JSON and images
};

// Fills `options` from the command line; prints the usage and exits on --help / -h. Returns
// false (after printing why) on an unknown option, a missing value or an invalid value.
bool ParseArguments(int argc, char* argv[], Options& options);

// The command-line arguments that make a worker render the same cases of `dataset` (everything
// but the output options), for the MPI re-launch.
std::vector<std::string> WorkerArguments(
  const Options& options, const std::string& dataset, const std::string& mpiDir);

} // namespace accelvolume::benchmark::shearwarp

#endif
