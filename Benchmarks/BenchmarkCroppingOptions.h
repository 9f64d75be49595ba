// Command-line settings of accelvolume_benchmark_cropping and the fixed views it measures.
#ifndef accelvolume_benchmark_BenchmarkCroppingOptions_h
#define accelvolume_benchmark_BenchmarkCroppingOptions_h

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
  std::vector<std::string> Datasets = { "cthead", "cta_avm" };
  int Width = 512;
  int Height = 512;
  int Frames = 10;
  int ReferenceFrames = 3;
  std::string GL = "egl";
  std::string Json = "benchmark_cropping.json";
  std::string Images;
  double CropLow = 0.2;
  double CropHigh = 0.8;
  double BandRadius = 2.5;     // pixels either side of the projected crop-box outline
  double AboveThreshold = 2.0; // grey levels: "visibly different" pixel
  double Zoom = 1.0;           // after fitting the camera to the crop box
  bool HaveWindow = false;     // --window overrides the per-dataset transfer-function window
  double Window[2] = { 0, 1 };
};

struct View
{
  const char* Name;
  double Azimuth;
  double Elevation;
};
// The error is measured at these two views; the timed sequence starts at the first.
inline constexpr View Views[] = { { "view1_az30_el25", 30.0, 25.0 },
  { "view2_az-55_el40", -55.0, 40.0 } };

// Fills `options` from the command line; prints the usage and exits on --help / -h. Returns
// false (after printing why) on an unknown option, a missing value or an invalid value.
bool ParseArguments(int argc, char* argv[], Options& options);

} // namespace accelvolume::benchmark

#endif
