// Settings, per-case results and their JSON of accelvolume_benchmark_shearwarp (the JSON the
// report reads, and the JSON an MPI worker hands back). A case is one volume x transfer function
// x shading x image size.
#ifndef accelvolume_benchmark_BenchmarkShearWarpResults_h
#define accelvolume_benchmark_BenchmarkShearWarpResults_h

#include "BenchmarkHarness.h"
#include "BenchmarkImageMetrics.h"

#include <cmath>
#include <string>
#include <vector>

namespace accelvolume::benchmark::shearwarp
{

// Volumes with more voxels than this are "large" (--skip-large drops them).
constexpr double LargeVoxels = 32.0 * 1024 * 1024;

// The settings of a run (its options).
struct Options
{
  std::string DataDir; // the harness's --data
  // The paper's MRI brain and CT head, and the 512x512x275 CT for scale.
  std::vector<std::string> Datasets = { "mri_t1_head", "cthead", "ct_chest_lidc0314" };
  std::vector<std::string> TransferFunctions = { "tf2", "tf1" };
  std::vector<int> Sizes = { 256, 512 };
  std::vector<bool> Shades = { true }; // --shade on|off|both
  int Frames = 10;
  int Threads = 0;       // the "all threads" count; 0: the hardware threads
  double Azimuth = 30.0; // the fixed view (image checks, first frame)
  double Elevation = 20.0;
  double Turn = 1.0; // azimuth degrees per timed frame (the paper: 1 degree per frame)
  int RunLength = 4; // frames one configuration renders in a row in each round
  bool SkipLarge = false;
  bool Mpi = true;
  std::vector<int> MpiRanks = { 1, 2 };
  bool VolPack = true;
  bool VolPackGrey = false; // VolPack in luminance mode (grey = mean of R, G, B), not RGB
  std::string GL;           // the harness's --gl
  std::string Images;       // PNGs of the fixed view, when set
  // Internal: this process is one rank of the MPI run the benchmark launched itself.
  bool MpiWorker = false;
  std::string MpiDir; // where the worker writes its JSON and images
};

// Targets of the issue: our single-threaded (3) this much faster than VolPack, this parallel
// efficiency of (3) on all threads (and on MPI ranks), at most this load imbalance.
constexpr double VolPackTarget = 1.5;
constexpr double EfficiencyTarget = 0.90;
constexpr double ImbalanceTarget = 1.10;

// One configuration of the mapper: the paper's experiments 1-3, and (3) with per-voxel Phong.
struct Config
{
  std::string Id; // "dense", "rle", "balanced", "phong"
  std::string Label;
  int Experiment = 1; // the paper's experiment number
  bool Rle = false;
  bool Ert = false;
  bool Balance = false;
  bool Phong = false;
};

// The configurations of a case: (1), (2), (3), and (3) with Phong per voxel when shading.
std::vector<Config> MakeConfigs(bool shade);

// One configuration on one thread count (or, for the MPI rows, one rank count), over the timed
// frames (one value per frame) and its first frame.
struct RunResult
{
  Config Cfg;
  int Threads = 1;
  int Ranks = 1;
  std::vector<double> RenderMs;    // the mapper's GetLastRenderTime: its whole Render()
  std::vector<double> EngineMs;    // encode + tables + composite + gather + warp (no display)
  std::vector<double> WallMs;      // window Render() + a 1x1 read-back
  std::vector<double> CompositeMs; // all bands
  std::vector<double> WarpMs;
  std::vector<double> TableMs;
  std::vector<double> ImagePartsMs; // drawing image parts while compositing (one thread)
  std::vector<double> GatherMs;       // MPI: bands sent to rank 0, costs shared
  std::vector<double> Imbalance;      // slowest band / mean band
  std::vector<double> Cores;          // process CPU time / wall time of the frame (this rank)
  std::vector<double> Workers;        // threads that composited the frame's bands (this rank)
  std::vector<double> BandMs;         // the last frame's band times (all ranks' bands)
  std::vector<std::vector<double>> ScanlineMs; // per timed frame: compositing ms per scanline
  double Voxels = 0;                  // per-frame means: voxels composited (this rank),
  double Samples = 0;                 //   pixels composited,
  double SkippedPixels = 0;           //   pixel visits skipped by skip links
  double FirstFrameMs = std::nan(""); // wall, at the fixed view (encoding included)
  double EncodeMs = std::nan("");     // GetLastEncodeTime of the first frame
  long long StoredVoxels = 0;         // in the principal axis's encoding
  long long EncodedBytes = 0;         // all encodings the mapper holds
  int Axis = -1;
  int Bands = 0;

  double MedianMs() const { return Median(this->RenderMs); }
  double MedianEngineMs() const { return Median(this->EngineMs); }
  double MeanImbalance() const;
};

// Median over the frames of a[f] / b[f] (paired frames of one round: robust to load from other
// processes); NaN without frames.
double PairedRatio(const std::vector<double>& a, const std::vector<double>& b);

struct VolPackResult
{
  bool Ran = false;
  std::string Note;                 // why not, when it did not run
  double ClassifyMs = std::nan(""); // vpClassifyVolume with its octree (and normals)
  std::vector<double> RenderMs;     // shading table + vpRenderClassifiedVolume
  int Axis = -1;
  double OpacityExponent = 1; // opacity per voxel = 1 - (1 - a)^exponent (spacing / unit)
  bool Grey = false;          // luminance mode (--volpack-grey) instead of RGB
  ErrorStats VsOurs;          // grey levels at the fixed view against ours (3), 1 thread
  ErrorStats VsOursRgb;       // the same over the R, G, B channels (each a sample)
  double MedianMs() const { return Median(this->RenderMs); }
};

// Two images of the fixed view: byte differences, and the bound they must stay within.
struct ImageCheck
{
  std::string A, B;
  int Bound = 0; // largest allowed byte difference (0: identical)
  long long DifferingPixels = 0;
  int MaxDifference = 0;
  bool Ok() const { return this->MaxDifference <= this->Bound; }
};

struct CaseResult
{
  std::string Dataset;
  std::string Tf;
  bool Shade = true;
  int Size = 0;
  int Frames = 0;
  int Threads = 1; // the "all threads" count
  long long TotalVoxels = 0;
  double Seconds = 0;
  std::vector<RunResult> Runs; // MakeConfigs() x { 1, all threads }
  std::vector<RunResult> Mpi;  // one per rank count
  std::string MpiNote;         // why there are no MPI rows
  VolPackResult VolPack;
  std::vector<ImageCheck> Checks;
  ErrorStats PhongVsTable; // information: the two shading evaluations, grey levels

  std::string Key() const; // "<dataset>/<tf>/<shaded|unshaded>/<size>"
  const RunResult* Find(const std::string& id, int threads) const;
  const RunResult* FindMpi(int ranks) const;
  // T(1 thread) / (threads x T(all threads)) of a configuration, paired per frame.
  double Efficiency(const std::string& id) const;
  double MpiEfficiency() const; // the largest rank count against 1 rank
  // Scaling model for `parts` cores from (3)'s 1-thread frames: each frame's bands chosen with
  // the previous frame's scanline costs (as the renderer does), its slowest band measured with
  // its own; imbalance = slowest / mean band, speed-up =
  // T1 / (T1 - C1 - B1 + (C1 x imbalance + B1) / parts) with T1 the mapper's Render(), C1 its
  // compositing and B1 its tables (medians; the rest, mostly showing the image, stays serial).
  // Ideal cores otherwise: no shared memory bandwidth or cache limits. NaN without two frames.
  // bandsPerWorker > 1: that many bands per core, each handed to the first free core in order
  // (the renderer's dynamic scheduling); imbalance = the last core's finish / the mean load.
  double ModelImbalance(int parts, int bandsPerWorker) const;
  double ModelSpeedup(int parts, int bandsPerWorker) const;
  // VolPack's frame (its image in memory) over ours, (3) on `threads` threads, paired per frame:
  // ours as a user sees it (wall: the window's Render with our image shown and read back), or
  // the engine alone (encode + tables + composite + gather + CPU warp; no display).
  double VolPackRatio(bool wholeFrame, int threads = 1) const;
  bool ChecksOk() const; // the image checks, and every run within its thread count
};

std::string CaseKey(const std::string& dataset, const std::string& tf, bool shade, int size);

struct DatasetInfo
{
  std::string Name;
  std::string File;
  std::string Description;
  double Spacing[3] = { 1, 1, 1 };
  double Range[2] = { 0, 1 };
  int Dims[3] = { 0, 0, 0 };
  double LoadSeconds = 0;
};

// One run as a JSON object (in the benchmark's JSON, and what an MPI worker writes), and back.
Json RunJson(const RunResult& run);
bool ReadRunJson(const Json& value, RunResult& run);
Json CaseJson(const CaseResult& c);
Json DatasetJson(const DatasetInfo& d);

} // namespace accelvolume::benchmark::shearwarp

#endif
