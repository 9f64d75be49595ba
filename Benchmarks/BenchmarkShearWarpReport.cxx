// Printed tables (per case, and Tables 2-3 of Kim 1998 beside ours) and JSON output of
// accelvolume_benchmark_shearwarp, and the JSON of one run that an MPI worker hands back.
#include "BenchmarkShearWarpReport.h"

#include "BenchmarkShearWarpScene.h"

#include <algorithm>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <numeric>
#include <sstream>

namespace accelvolume::benchmark::shearwarp
{
namespace
{
std::string Times(double value)
{
  return std::isfinite(value) ? Num(value, 2) + "x" : std::string("-");
}
std::string Percent(double fraction)
{
  return std::isfinite(fraction) ? Num(100.0 * fraction, 1) + "%" : std::string("-");
}
std::string Ms(double value, int precision = 1)
{
  return std::isfinite(value) ? Num(value, precision) : std::string("-");
}
std::string Verdict(bool met, double value)
{
  return std::isfinite(value) ? (met ? "PASS" : "MISS") : "n/a";
}

void JsonErrors(std::ostream& out, const ErrorStats& e)
{
  out << "{\"rms\": " << Num(e.Rms(), 3) << ", \"max\": " << Num(e.Max, 1)
      << ", \"pixels\": " << e.Pixels << "}";
}

// Kim 1998: MasPar MP-2 (4,096 PEs), seconds per frame averaged over 90 frames turned 1 degree.
constexpr double PaperRleSpeedUp = 1.6102 / 0.7331;      // Table 2: (2) over (1), 2.2x
constexpr double PaperBalancedSpeedUp = 1.6102 / 0.3109; // Table 2: (3) over (1), 5.18x
} // namespace

std::vector<Config> MakeConfigs(bool shade)
{
  std::vector<Config> configs = {
    { "dense", "(1) no RLE", 1, false, false, false, false },
    { "rle", "(2) RLE+ERT, equal", 2, true, true, false, false },
    { "balanced", "(3) RLE+ERT+balance", 3, true, true, true, false },
  };
  if (shade)
  {
    configs.push_back({ "phong", "(3) Phong per voxel", 3, true, true, true, true });
  }
  return configs;
}

double RunResult::MeanImbalance() const
{
  if (this->Imbalance.empty())
  {
    return std::nan("");
  }
  return std::accumulate(this->Imbalance.begin(), this->Imbalance.end(), 0.0) /
    static_cast<double>(this->Imbalance.size());
}

double PairedRatio(const std::vector<double>& a, const std::vector<double>& b)
{
  std::vector<double> ratios;
  for (size_t f = 0; f < a.size() && f < b.size(); ++f)
  {
    if (b[f] > 0 && std::isfinite(a[f]))
    {
      ratios.push_back(a[f] / b[f]);
    }
  }
  return ratios.empty() ? std::nan("") : Median(ratios);
}

std::string CaseKey(const std::string& dataset, const std::string& tf, bool shade, int size)
{
  return dataset + "/" + tf + "/" + (shade ? "shaded" : "unshaded") + "/" + std::to_string(size);
}

std::string CaseResult::Key() const
{
  return CaseKey(this->Dataset, this->Tf, this->Shade, this->Size);
}

const RunResult* CaseResult::Find(const std::string& id, int threads) const
{
  for (const RunResult& r : this->Runs)
  {
    if (r.Cfg.Id == id && r.Threads == threads)
    {
      return &r;
    }
  }
  return nullptr;
}

const RunResult* CaseResult::FindMpi(int ranks) const
{
  for (const RunResult& r : this->Mpi)
  {
    if (r.Ranks == ranks)
    {
      return &r;
    }
  }
  return nullptr;
}

double CaseResult::Efficiency(const std::string& id) const
{
  const RunResult* one = this->Find(id, 1);
  const RunResult* all = this->Find(id, this->Threads);
  if (!one || !all || this->Threads < 2)
  {
    return std::nan("");
  }
  return PairedRatio(one->RenderMs, all->RenderMs) / this->Threads;
}

double CaseResult::MpiEfficiency() const
{
  const RunResult* one = this->FindMpi(1);
  const RunResult* most = nullptr;
  for (const RunResult& r : this->Mpi)
  {
    most = r.Ranks > 1 && (!most || r.Ranks > most->Ranks) ? &r : most;
  }
  if (!one || !most)
  {
    return std::nan("");
  }
  return SafeRatio(one->MedianMs(), most->Ranks * most->MedianMs());
}

double CaseResult::VolPackRatio() const
{
  const RunResult* ours = this->Find("balanced", 1);
  return this->VolPack.Ran && ours ? PairedRatio(this->VolPack.RenderMs, ours->EngineMs)
                                   : std::nan("");
}

bool CaseResult::ChecksOk() const
{
  return std::all_of(
    this->Checks.begin(), this->Checks.end(), [](const ImageCheck& c) { return c.Ok(); });
}

std::string ReadCpuModel()
{
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line))
  {
    if (line.rfind("model name", 0) == 0 && line.find(':') != std::string::npos)
    {
      return line.substr(line.find(':') + 2);
    }
  }
  return "";
}

void PrintHeader(const Options& options, const MachineInfo& machine)
{
  std::cout
    << "accelvolume_benchmark_shearwarp: Kim 1998 Tables 2-3 (parallel shear-warp: no RLE / "
       "RLE + skip links / RLE + balanced partition), VolPack and MPI\n"
    << "machine: " << (machine.Cpu.empty() ? "CPU unknown" : machine.Cpu) << ", "
    << machine.HardwareThreads << " hardware threads; GL " << machine.GlBackend << " ("
    << machine.GlRenderer << "); VolPack " << (machine.HaveVolPack ? "yes" : "no") << "; mpiexec "
    << (machine.MpiExec.empty() ? "none" : machine.MpiExec) << "\n"
    << "settings: parallel camera, composite, tf presets of `accelvolume render --tf` over the "
       "data range, view azimuth "
    << options.Azimuth << " elevation " << options.Elevation << ", turned " << options.Turn
    << " deg per frame, " << options.Frames << " timed frames (interleaved) after the first; "
    << "threads 1 and " << options.Threads << "; MPI ranks x 1 thread\n"
    << "  ms/frame = median of the mapper's Render() time; engine = encode + tables + composite + "
       "gather + warp (no display), what VolPack's time covers; x (1), eff. = median of paired "
       "per-frame ratios; imbal. = mean of slowest / mean band time; cores = process CPU / wall "
       "time; stored = voxels in the encoding / all voxels\n"
    << "data: " << options.DataDir << "\n"
    << std::flush;
}

void PrintCase(const CaseResult& c)
{
  std::cout << std::left << std::setw(26) << "  config" << std::right << std::setw(5) << "thr"
            << std::setw(10) << "ms/frame" << std::setw(9) << "engine" << std::setw(8) << "x (1)"
            << std::setw(8) << "eff." << std::setw(8) << "imbal." << std::setw(9) << "compos."
            << std::setw(7) << "warp" << std::setw(8) << "gather" << std::setw(9) << "Mvox/f"
            << std::setw(7) << "cores" << std::setw(10) << "encode ms" << std::setw(8) << "stored"
            << std::setw(8) << "enc MB"
            << "\n";
  const double total = static_cast<double>(std::max<long long>(1, c.TotalVoxels));
  auto row = [&](const RunResult& r, const std::string& label, const std::string& threads,
               double speedUp, double efficiency)
  {
    std::cout << "  " << std::left << std::setw(24) << label << std::right << std::setw(5)
              << threads << std::setw(10) << Ms(r.MedianMs()) << std::setw(9)
              << Ms(r.MedianEngineMs()) << std::setw(8) << Times(speedUp) << std::setw(8)
              << Percent(efficiency) << std::setw(8) << Ms(r.MeanImbalance(), 3) << std::setw(9)
              << Ms(Median(r.CompositeMs)) << std::setw(7) << Ms(Median(r.WarpMs)) << std::setw(8)
              << (r.Ranks > 1 ? Ms(Median(r.GatherMs), 2) : std::string("-")) << std::setw(9)
              << Num(r.Voxels / 1e6, 2) << std::setw(7) << Ms(Median(r.Cores), 2) << std::setw(10)
              << Ms(r.EncodeMs) << std::setw(8) << Percent(r.StoredVoxels / total) << std::setw(8)
              << Num(r.EncodedBytes / 1e6, 1) << "\n";
  };
  for (const RunResult& r : c.Runs)
  {
    const RunResult* dense = c.Find("dense", r.Threads);
    row(r, r.Cfg.Label, std::to_string(r.Threads),
      dense ? PairedRatio(dense->RenderMs, r.RenderMs) : std::nan(""),
      r.Threads > 1 ? c.Efficiency(r.Cfg.Id) : std::nan(""));
  }
  if (c.VolPack.Ran)
  {
    const RunResult* dense = c.Find("dense", 1);
    std::cout << "  " << std::left << std::setw(24)
              << (c.VolPack.Grey ? "VolPack grey (classif.)" : "VolPack RGB (classified)")
              << std::right
              << std::setw(5) << "1" << std::setw(10) << Ms(c.VolPack.MedianMs()) << std::setw(9)
              << Ms(c.VolPack.MedianMs()) << std::setw(8)
              << Times(dense ? PairedRatio(dense->RenderMs, c.VolPack.RenderMs) : std::nan(""))
              << std::setw(8) << "-" << std::setw(8) << "-" << std::setw(9) << "-" << std::setw(7)
              << "-" << std::setw(8) << "-" << std::setw(9) << "-" << std::setw(7) << "-"
              << std::setw(10) << Ms(c.VolPack.ClassifyMs) << "  (classify; axis " << c.VolPack.Axis
              << ")\n";
  }
  else
  {
    std::cout << "  VolPack: n/a (" << c.VolPack.Note << ")\n";
  }
  const RunResult* mpiOne = c.FindMpi(1);
  for (const RunResult& r : c.Mpi)
  {
    row(r, "(3) MPI, 1 thread/rank", std::to_string(r.Ranks) + "r", std::nan(""),
      r.Ranks > 1 && mpiOne ? SafeRatio(mpiOne->MedianMs(), r.Ranks * r.MedianMs()) : std::nan(""));
  }
  if (c.Mpi.empty())
  {
    std::cout << "  MPI: n/a (" << c.MpiNote << ")\n";
  }

  std::cout << "  image checks (fixed view):";
  for (const ImageCheck& k : c.Checks)
  {
    std::cout << " " << k.A << " vs " << k.B << ": ";
    if (k.DifferingPixels == 0)
    {
      std::cout << "identical;";
    }
    else
    {
      std::cout << k.DifferingPixels << " px, max " << k.MaxDifference
                << (k.Bound ? " <= " + std::to_string(k.Bound) : std::string(" (must be 0)"))
                << (k.Ok() ? " ok;" : " FAILED;");
    }
  }
  std::cout << (c.ChecksOk() ? " -> OK" : " -> FAILED") << "\n";
  if (c.Shade)
  {
    std::cout << "  shading table vs Phong per voxel, (3) 1 thread: grey RMS "
              << Num(c.PhongVsTable.Rms(), 2) << ", max " << Num(c.PhongVsTable.Max, 0)
              << "; time Phong / table "
              << Times(
                   [&]()
                   {
                     const RunResult* table = c.Find("balanced", 1);
                     const RunResult* phong = c.Find("phong", 1);
                     return table && phong ? PairedRatio(phong->RenderMs, table->RenderMs)
                                           : std::nan("");
                   }())
              << " (1 thread)\n";
  }
  if (c.VolPack.Ran)
  {
    std::cout << "  VolPack (" << (c.VolPack.Grey ? "grey" : "RGB")
              << ") vs ours (3) 1 thread at the fixed view: RGB RMS "
              << Num(c.VolPack.VsOursRgb.Rms(), 2) << ", max " << Num(c.VolPack.VsOursRgb.Max, 0)
              << "; grey RMS " << Num(c.VolPack.VsOurs.Rms(), 2) << ", max "
              << Num(c.VolPack.VsOurs.Max, 0) << " over " << c.VolPack.VsOurs.Pixels
              << " non-black px"
              << (c.Shade ? " (shaded: vpVolumeNormals gives the volume's border voxels normal "
                            "code 0, so where the volume's faces cut the object VolPack shades "
                            "them otherwise; unshaded cases compare the pictures alone)"
                          : "")
              << "\n";
  }
  const double ratio = c.VolPackRatio();
  const double efficiency = c.Efficiency("balanced");
  const RunResult* all = c.Find("balanced", c.Threads);
  const double imbalance = all && c.Threads > 1 ? all->MeanImbalance() : std::nan("");
  const double mpiEfficiency = c.MpiEfficiency();
  std::cout << "  targets: (3) 1 thread >= " << Num(VolPackTarget, 1)
            << "x VolPack: " << Times(ratio) << " " << Verdict(ratio >= VolPackTarget, ratio)
            << "; efficiency (3) " << c.Threads << " threads >= " << Percent(EfficiencyTarget)
            << ": " << Percent(efficiency) << " "
            << Verdict(efficiency >= EfficiencyTarget, efficiency)
            << "; imbalance (3) <= " << Num(ImbalanceTarget, 2) << ": " << Ms(imbalance, 3) << " "
            << Verdict(imbalance <= ImbalanceTarget, imbalance)
            << "; MPI efficiency >= " << Percent(EfficiencyTarget) << ": " << Percent(mpiEfficiency)
            << " " << Verdict(mpiEfficiency >= EfficiencyTarget, mpiEfficiency) << "\n"
            << std::flush;
}

void PrintSummary(const std::vector<CaseResult>& cases)
{
  std::cout << "\nTables 2-3 and beyond: ms/frame on all threads of (1) no RLE, (2) RLE + skip "
               "links (equal bands), (3) RLE + balanced partition; speed-ups over (1) (paper, "
               "MasPar MP-2: 2.20x and 5.18x)\n"
            << std::left << std::setw(34) << "case" << std::right << std::setw(11) << "stored vox"
            << std::setw(9) << "(1)" << std::setw(9) << "(2)" << std::setw(9) << "(3)"
            << std::setw(8) << "(2)/(1)" << std::setw(8) << "(3)/(1)" << std::setw(8) << "eff."
            << std::setw(8) << "imbal." << std::setw(9) << "x VolPk" << std::setw(9) << "MPI eff"
            << std::setw(8) << "images"
            << "\n";
  int met[4] = { 0, 0, 0, 0 };
  int measured[4] = { 0, 0, 0, 0 };
  for (const CaseResult& c : cases)
  {
    const int t = c.Threads;
    const RunResult* d = c.Find("dense", t);
    const RunResult* r = c.Find("rle", t);
    const RunResult* b = c.Find("balanced", t);
    if (!d || !r || !b)
    {
      continue;
    }
    const double efficiency = c.Efficiency("balanced");
    const double imbalance = t > 1 ? b->MeanImbalance() : std::nan("");
    const double ratio = c.VolPackRatio();
    const double mpi = c.MpiEfficiency();
    const double values[4] = { ratio, efficiency, imbalance, mpi };
    const bool ok[4] = { ratio >= VolPackTarget, efficiency >= EfficiencyTarget,
      imbalance <= ImbalanceTarget, mpi >= EfficiencyTarget };
    for (int k = 0; k < 4; ++k)
    {
      measured[k] += std::isfinite(values[k]) ? 1 : 0;
      met[k] += std::isfinite(values[k]) && ok[k] ? 1 : 0;
    }
    std::cout << std::left << std::setw(34) << c.Key() << std::right << std::setw(11)
              << b->StoredVoxels << std::setw(9) << Ms(d->MedianMs()) << std::setw(9)
              << Ms(r->MedianMs()) << std::setw(9) << Ms(b->MedianMs()) << std::setw(8)
              << Times(PairedRatio(d->RenderMs, r->RenderMs)) << std::setw(8)
              << Times(PairedRatio(d->RenderMs, b->RenderMs)) << std::setw(8) << Percent(efficiency)
              << std::setw(8) << Ms(imbalance, 3) << std::setw(9) << Times(ratio) << std::setw(9)
              << Percent(mpi) << std::setw(8) << (c.ChecksOk() ? "ok" : "FAILED") << "\n";
  }
  const char* names[4] = { "(3) 1 thread >= 1.5x VolPack", "efficiency (3) >= 90%",
    "imbalance (3) <= 1.10", "MPI efficiency >= 90%" };
  std::cout << "targets:";
  for (int k = 0; k < 4; ++k)
  {
    std::cout << (k ? ";" : "") << " " << names[k] << ": " << met[k] << "/" << measured[k]
              << (measured[k] == 0           ? " n/a"
                     : met[k] == measured[k] ? " PASS"
                                             : " MISS");
  }
  std::cout << "\nKim 1998 (MasPar MP-2, 4,096 PEs, 90 frames turned 1 degree): Table 2, 128^3 "
               "MRI brain: (1) 2,097,152 voxels 1.6102 s, (2) 274,487 voxels 0.7331 s, (3) "
               "0.3109 s; Table 3, 256x256x226 CT head: (3) 1,339,400 voxels 1.2101 s ((1), (2) "
               "did not fit); speed-ups "
            << Times(PaperRleSpeedUp) << " / " << Times(PaperBalancedSpeedUp) << "\n";
}

void WriteJson(const Options& options, const MachineInfo& machine,
  const std::vector<DatasetInfo>& datasets, const std::vector<CaseResult>& cases,
  double totalSeconds)
{
  std::ofstream out(options.Json);
  if (!out)
  {
    std::cerr << "cannot write " << options.Json << "\n";
    return;
  }
  out << "{\n  \"benchmark\": \"shearwarp (Kim 1998 Tables 2-3: parallel shear-warp, RLE, "
         "load balancing; VolPack; MPI)\",\n";
  out << "  \"machine\": {\"cpu\": \"" << JsonEscape(machine.Cpu)
      << "\", \"hardware_threads\": " << machine.HardwareThreads << ", \"gl_backend\": \""
      << JsonEscape(machine.GlBackend) << "\", \"gl_renderer\": \""
      << JsonEscape(machine.GlRenderer)
      << "\", \"volpack\": " << (machine.HaveVolPack ? "true" : "false") << ", \"mpiexec\": \""
      << JsonEscape(machine.MpiExec) << "\"},\n";
  out << "  \"settings\": {\"frames\": " << options.Frames << ", \"threads\": " << options.Threads
      << ", \"view\": {\"azimuth\": " << Num(options.Azimuth, 2)
      << ", \"elevation\": " << Num(options.Elevation, 2)
      << "}, \"turn_degrees\": " << Num(options.Turn, 2)
      << ", \"projection\": \"parallel\", \"blend\": \"composite\", \"mpi\": "
      << (options.Mpi ? "true" : "false")
      << ", \"volpack\": " << (options.VolPack ? "true" : "false")
      << ", \"volpack_mode\": \"" << (options.VolPackGrey ? "grey" : "rgb") << "\""
      << ", \"ms_per_frame\": \"median of the mapper's "
      << "GetLastRenderTime\", \"engine_ms\": \"encode + tables + composite + gather + warp\", "
         "\"ratios\": \"median over frames of paired per-frame ratios\", \"targets\": "
         "{\"volpack_speedup\": "
      << VolPackTarget << ", \"efficiency\": " << EfficiencyTarget
      << ", \"imbalance\": " << ImbalanceTarget << "}},\n";
  out << "  \"total_seconds\": " << Num(totalSeconds, 2) << ",\n  \"datasets\": [\n";
  for (size_t i = 0; i < datasets.size(); ++i)
  {
    const DatasetInfo& d = datasets[i];
    out << "    {\"name\": \"" << JsonEscape(d.Name) << "\", \"file\": \"" << JsonEscape(d.File)
        << "\", \"volume\": \"" << JsonEscape(d.Description) << "\", \"spacing\": [" << d.Spacing[0]
        << ", " << d.Spacing[1] << ", " << d.Spacing[2] << "], \"range\": [" << d.Range[0] << ", "
        << d.Range[1] << "], \"load_seconds\": " << Num(d.LoadSeconds, 3) << "}"
        << (i + 1 < datasets.size() ? "," : "") << "\n";
  }
  out << "  ],\n  \"cases\": [\n";
  for (size_t i = 0; i < cases.size(); ++i)
  {
    const CaseResult& c = cases[i];
    const RunResult* all = c.Find("balanced", c.Threads);
    const double ratio = c.VolPackRatio();
    const double efficiency = c.Efficiency("balanced");
    const double imbalance = all && c.Threads > 1 ? all->MeanImbalance() : std::nan("");
    const double mpi = c.MpiEfficiency();
    out << "    {\n      \"key\": \"" << JsonEscape(c.Key()) << "\", \"dataset\": \""
        << JsonEscape(c.Dataset) << "\", \"tf\": \"" << c.Tf
        << "\", \"shade\": " << (c.Shade ? "true" : "false") << ", \"size\": " << c.Size
        << ", \"frames\": " << c.Frames << ", \"threads\": " << c.Threads
        << ", \"total_voxels\": " << c.TotalVoxels << ", \"seconds\": " << Num(c.Seconds, 2)
        << ",\n      \"volpack_ratio\": " << Num(ratio, 3)
        << ", \"efficiency\": " << Num(efficiency, 4)
        << ", \"efficiency_rle\": " << Num(c.Efficiency("rle"), 4)
        << ", \"efficiency_dense\": " << Num(c.Efficiency("dense"), 4)
        << ", \"imbalance\": " << Num(imbalance, 4) << ", \"mpi_efficiency\": " << Num(mpi, 4)
        << ",\n      \"targets_met\": {\"volpack\": "
        << (std::isfinite(ratio) ? (ratio >= VolPackTarget ? "true" : "false") : "null")
        << ", \"efficiency\": "
        << (std::isfinite(efficiency) ? (efficiency >= EfficiencyTarget ? "true" : "false")
                                      : "null")
        << ", \"imbalance\": "
        << (std::isfinite(imbalance) ? (imbalance <= ImbalanceTarget ? "true" : "false") : "null")
        << ", \"mpi_efficiency\": "
        << (std::isfinite(mpi) ? (mpi >= EfficiencyTarget ? "true" : "false") : "null")
        << "},\n      \"checks_ok\": " << (c.ChecksOk() ? "true" : "false") << ", \"checks\": [";
    for (size_t k = 0; k < c.Checks.size(); ++k)
    {
      const ImageCheck& x = c.Checks[k];
      out << (k ? ", " : "") << "{\"a\": \"" << x.A << "\", \"b\": \"" << x.B
          << "\", \"bound\": " << x.Bound << ", \"differing_pixels\": " << x.DifferingPixels
          << ", \"max_difference\": " << x.MaxDifference << "}";
    }
    out << "],\n      \"phong_vs_table\": ";
    JsonErrors(out, c.PhongVsTable);
    out << ",\n      \"volpack\": {\"ran\": " << (c.VolPack.Ran ? "true" : "false")
        << ", \"note\": \"" << JsonEscape(c.VolPack.Note)
        << "\", \"mode\": \"" << (c.VolPack.Grey ? "grey" : "rgb")
        << "\", \"classify_ms\": " << Num(c.VolPack.ClassifyMs, 2)
        << ", \"median_ms\": " << Num(c.VolPack.MedianMs(), 3) << ", \"axis\": " << c.VolPack.Axis
        << ", \"opacity_exponent\": " << Num(c.VolPack.OpacityExponent, 4) << ", \"vs_ours\": ";
    JsonErrors(out, c.VolPack.VsOurs);
    out << ", \"vs_ours_rgb\": ";
    JsonErrors(out, c.VolPack.VsOursRgb);
    out << ", \"render_ms\": ";
    JsonArray(out, c.VolPack.RenderMs);
    out << "},\n      \"runs\": [\n";
    for (size_t k = 0; k < c.Runs.size(); ++k)
    {
      out << "        ";
      WriteRunJson(out, c.Runs[k], "         ");
      out << (k + 1 < c.Runs.size() ? "," : "") << "\n";
    }
    out << "      ],\n      \"mpi_note\": \"" << JsonEscape(c.MpiNote) << "\", \"mpi\": [\n";
    for (size_t k = 0; k < c.Mpi.size(); ++k)
    {
      out << "        ";
      WriteRunJson(out, c.Mpi[k], "         ");
      out << (k + 1 < c.Mpi.size() ? "," : "") << "\n";
    }
    out << "      ]\n    }" << (i + 1 < cases.size() ? "," : "") << "\n";
  }
  out << "  ]\n}\n";
}

} // namespace accelvolume::benchmark::shearwarp
