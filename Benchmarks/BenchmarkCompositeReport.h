// Per-case results of accelvolume_benchmark_composite, its printed table and its JSON file.
// A case is one volume x transfer function x image size.
#ifndef accelvolume_benchmark_BenchmarkCompositeReport_h
#define accelvolume_benchmark_BenchmarkCompositeReport_h

#include "BenchmarkCommon.h"
#include "BenchmarkCompositeOptions.h"
#include "BenchmarkImageMetrics.h"

#include <cmath>
#include <string>
#include <vector>

namespace accelvolume::benchmark::composite
{

// One rendering configuration: a column of Table V-3.
struct Config
{
  std::string Id;
  std::string Label;
  bool Vtk = false; // vtkGPUVolumeRayCastMapper instead of the slice mapper
  bool Ert = false;
  int Ess = 0; // vtkAccelVolumeSliceMapper::SKIP_*
};

struct ConfigResult
{
  Config Cfg;
  std::vector<double> FrameMs;  // Render() + 1x1 read-back
  std::vector<double> MapperMs; // slice mapper's GetLastRenderTime (it waits for the GPU)
  int TerminationPasses = 0;
  double TransparentLeafFraction = -1;
  int Slices = 0;
  double MedianMs() const { return Median(this->FrameMs); }
  double Fps() const { return this->FrameMs.empty() ? std::nan("") : 1000.0 / this->MedianMs(); }
  // Median over the interleaved rounds of (other's frame / this frame of the same round): the
  // speed-up over `other`, robust to load from other processes on a shared machine.
  double PairedSpeedUp(const ConfigResult& other) const
  {
    std::vector<double> ratios;
    for (size_t f = 0; f < this->FrameMs.size() && f < other.FrameMs.size(); ++f)
    {
      ratios.push_back(other.FrameMs[f] / this->FrameMs[f]);
    }
    return ratios.empty() ? std::nan("") : Median(ratios);
  }
};

struct CaseResult
{
  std::string Dataset;
  std::string Tf;
  int Size = 0;
  int Frames = 0;
  double Seconds = 0;
  std::vector<ConfigResult> Results; // in MakeConfigs() order
  // Grey-level (0..255) differences at the fixed view over pixels non-black in either image.
  ErrorStats ErtBothVsBase;
  ErrorStats OursVsVtk;
  const ConfigResult* Find(const std::string& id) const;
  const ConfigResult* Best() const; // fastest slice-mapper configuration
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

std::vector<Config> MakeConfigs();
void PrintTable(const std::vector<DatasetInfo>& datasets, const std::vector<CaseResult>& cases);
void WriteJson(const Options& options, const std::string& renderer, const std::string& backend,
  const std::vector<DatasetInfo>& datasets, const std::vector<CaseResult>& cases,
  double totalSeconds);

} // namespace accelvolume::benchmark::composite

#endif
