// Per-configuration and per-dataset results of accelvolume_benchmark_cropping, and the printed
// comparison table and JSON file made from them.
#ifndef accelvolume_benchmark_BenchmarkCroppingReport_h
#define accelvolume_benchmark_BenchmarkCroppingReport_h

#include "BenchmarkCommon.h"
#include "BenchmarkCroppingOptions.h"
#include "BenchmarkImageMetrics.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace accelvolume::benchmark
{

// One rendering configuration: a row of the table.
struct Config
{
  std::string Id;
  std::string Label;
  bool Gpu = false;
  bool Rerender = false;
  bool AutoAdjust = false;
  double SliceFactor = 1.0; // slices per smallest voxel spacing
  bool Reference = false;
};

struct ConfigResult
{
  Config Cfg;
  std::vector<double> FrameMs;  // Render() + 1x1 read-back
  std::vector<double> MapperMs; // slice mapper's own GetLastRenderTime (it waits for the GPU)
  int Slices = 0;
  int Faces = 0;
  double SliceSpacing = 0;
  std::vector<std::vector<std::uint8_t>> Images; // per view, RGB, bottom row first
  std::vector<ErrorStats> Footprint;             // per view
  std::vector<ErrorStats> Band;                  // per view
  std::vector<ErrorStats> Face;                  // per view
  ErrorStats FootprintAll;
  ErrorStats BandAll;
  ErrorStats FaceAll;
  double MedianMs() const { return Median(this->FrameMs); }
  double MinMs() const
  {
    return this->FrameMs.empty() ? 0.0
                                 : *std::min_element(this->FrameMs.begin(), this->FrameMs.end());
  }
  // Median over the interleaved rounds of (this frame / the other's frame of the same round):
  // robust to load changes on a shared machine.
  double PairedRatio(const ConfigResult& other) const
  {
    std::vector<double> ratios;
    for (size_t f = 0; f < this->FrameMs.size() && f < other.FrameMs.size(); ++f)
    {
      ratios.push_back(this->FrameMs[f] / other.FrameMs[f]);
    }
    return ratios.empty() ? std::nan("") : Median(ratios);
  }
  double MedianMapperMs() const { return Median(this->MapperMs); }
};

struct DatasetResult
{
  std::string Name;
  std::string File;
  std::string Description;
  double Spacing[3] = { 1, 1, 1 };
  double MinSpacing = 1;
  double Window[2] = { 0, 1 };
  double CropPlanes[6] = { 0, 0, 0, 0, 0, 0 };
  double LoadSeconds = 0;
  double TotalSeconds = 0;
  std::vector<long long> FootprintPixels; // per view
  std::vector<long long> BandPixels;      // per view
  std::vector<long long> FacePixels;      // per view
  std::vector<ConfigResult> Results;
};

// The shared Num() (BenchmarkCommon.h), with this program's usual precision as the default.
std::string Num(double value, int precision = 4);

// Prints the comparison table of one dataset and the paper's claims checked against it.
void PrintTable(const DatasetResult& d);

// Writes every dataset's results to options.Json (reports on std::cerr if it cannot).
void WriteJson(const Options& options, const std::string& renderer, const std::string& backend,
  const std::vector<DatasetResult>& datasets);

} // namespace accelvolume::benchmark

#endif
