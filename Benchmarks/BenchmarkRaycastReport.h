// Per-case results of accelvolume_benchmark_raycast, its printed tables and its JSON file.
// A case is one volume x transfer function.
#ifndef accelvolume_benchmark_BenchmarkRaycastReport_h
#define accelvolume_benchmark_BenchmarkRaycastReport_h

#include "BenchmarkCommon.h"
#include "BenchmarkImageMetrics.h"
#include "BenchmarkRaycastOptions.h"

#include <cmath>
#include <string>
#include <vector>

namespace accelvolume::benchmark::raycast
{

// Targets of the issue: ours (the default: distance map, cell leaping off) at least this much
// faster than vtkFixedPointVolumeRayCastMapper at an RMS no larger than its, and cell leaping worth
// this many percent within a leap mode (the paper: 16.8-24.1 %).
constexpr double SpeedUpTarget = 2.0;
constexpr double CellGainTarget = 20.0;

// One row of the table: our mapper in one leap mode with cell leaping off / on, or VTK's.
struct Config
{
  std::string Id;
  std::string Label;
  bool Vtk = false; // vtkFixedPointVolumeRayCastMapper
  int Leap = 0;     // vtkAccelVolumeRayCastMapper::LEAP_*
  bool Cell = false;
};

// Our mapper's counters, as per-frame means over the timed rounds.
struct Counters
{
  double Rays = 0;
  double Samples = 0;     // interpolated
  double LeapedSpace = 0; // skipped by the octree or the distance map
  double LeapedCell = 0;  // semi-transparent cells: skipped by the modified MC table
  double EmptyCell = 0;   // all-transparent cells met by the cell table
  double Terminated = 0;  // rays closed by early ray termination
};

struct ConfigResult
{
  Config Cfg;
  std::vector<double> FrameMs; // Render() + 1x1 read-back, one per timed round
  std::vector<double> CastMs;  // ours: GetLastCastTime (ray casting alone)
  std::vector<double> Cores;   // process CPU time / wall time of each timed frame
  Counters Count;              // ours
  // First frame of the mapper (structures built from the scalars, then classified) and first
  // frame after a transfer-function change (classification only): wall time and, for ours,
  // GetLastPrepareTime. Excluded from FrameMs.
  double FirstFrameMs = std::nan("");
  double FirstPrepareMs = std::nan("");
  double TfFrameMs = std::nan("");
  double TfPrepareMs = std::nan("");
  // Ours at the fixed view against ours with leap none and cell leaping off (same samples).
  long long DifferingPixels = 0;
  int MaxDifference = 0; // bytes
  double MedianMs() const { return Median(this->FrameMs); }
};

struct CaseResult
{
  std::string Dataset;
  std::string Tf;
  int Size = 0;
  int Frames = 0;
  double SampleDistance = 1;
  double ReferenceSampleDistance = 0.25;
  double ReferenceMs = 0; // the one frame of the fine reference
  double Seconds = 0;
  std::vector<ConfigResult> Results; // in MakeConfigs() order
  // Grey-level (0..255) differences at the fixed view against the fine reference, over pixels
  // non-black in either image.
  ErrorStats OursVsReference; // octree + cell leaping
  ErrorStats VtkVsReference;
  ErrorStats OursVsVtk; // for information: includes VTK's own shading and table quantisation

  const ConfigResult* Find(const std::string& id) const;
  bool Identical() const;
  // (t_off - t_on) / t_off * 100 of the leap mode's two rows ("none", "dmap", "octree").
  double CellGain(const std::string& leap) const;
  double SpeedUpOverVtk(const ConfigResult& ours) const;
  bool SpeedTargetMet() const;
  bool CellTargetMet(const std::string& leap) const;
};

struct DatasetInfo
{
  std::string Name;
  std::string File;
  std::string Description;
  double Spacing[3] = { 1, 1, 1 };
  double MinSpacing = 1;
  double Range[2] = { 0, 1 };
  double LoadSeconds = 0;
};

struct MachineInfo
{
  std::string Cpu; // "model name" of /proc/cpuinfo, "" if unknown
  int HardwareThreads = 0;
  std::string GlBackend;
  std::string GlRenderer;
};

std::vector<Config> MakeConfigs();
std::string ReadCpuModel();
// The table of one case, printed as soon as it is measured.
void PrintCase(const CaseResult& c);
// Table 2 of the paper beside ours: cell-leaping speed-up per volume and leap mode.
void PrintSummary(const std::vector<CaseResult>& cases);
void WriteJson(const Options& options, const MachineInfo& machine,
  const std::vector<DatasetInfo>& datasets, const std::vector<CaseResult>& cases,
  double totalSeconds);

} // namespace accelvolume::benchmark::raycast

#endif
