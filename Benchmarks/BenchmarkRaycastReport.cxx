// Printed tables (per case, and Table 2 of Lim, Kim and Shin 2009 beside ours) and JSON output of
// accelvolume_benchmark_raycast.
#include "BenchmarkRaycastReport.h"

#include "vtkAccelVolumeRayCastMapper.h"

#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>

namespace accelvolume::benchmark::raycast
{
namespace
{
// Lim, Kim and Shin 2009, Table 2: cell-leaping speed-up in % over distance-map leaping (case 1) and octree
// leaping (case 2) alone, by the paper's volume closest to ours (no teeth volume here).
struct PaperRow
{
  const char* Volume;
  double DistanceMap;
  double Octree;
};
const PaperRow* PaperRowFor(const std::string& dataset)
{
  static const std::map<std::string, PaperRow> rows = {
    { "cthead", { "head", 18.8, 16.8 } },
    { "aneurism", { "cerebral arteries", 23.0, 19.6 } },
    { "cta_avm", { "cerebral arteries", 23.0, 19.6 } },
    { "engine", { "engine", 20.5, 18.9 } },
    { "boston_teapot", { "teapot", 22.0, 20.1 } },
    { "bonsai_hazeremoved", { "bonsai", 24.1, 21.7 } },
  };
  const auto found = rows.find(dataset);
  return found == rows.end() ? nullptr : &found->second;
}

// "1.23x" / "12.3%" / "45.67M", or "-" when unknown.
std::string Times(double value)
{
  return std::isfinite(value) ? Num(value, 2) + "x" : std::string("-");
}
std::string Percent(double value)
{
  return std::isfinite(value) ? Num(value, 1) + "%" : std::string("-");
}
std::string Millions(double value)
{
  return Num(value / 1.0e6, 2) + "M";
}
std::string LeapOf(const std::string& id)
{
  return id.substr(0, id.find('_'));
}

void JsonArray(std::ostream& out, const std::vector<double>& values)
{
  out << "[";
  for (size_t i = 0; i < values.size(); ++i)
  {
    out << (i ? ", " : "") << Num(values[i], 2);
  }
  out << "]";
}

void JsonErrors(std::ostream& out, const char* name, const ErrorStats& e)
{
  out << "\"" << name << "\": {\"rms\": " << Num(e.Rms(), 3) << ", \"max\": " << Num(e.Max, 1)
      << ", \"pixels\": " << e.Pixels << "}";
}
} // namespace

std::vector<Config> MakeConfigs()
{
  using Mapper = vtkAccelVolumeRayCastMapper;
  return {
    { "none_off", "none, cell off", false, Mapper::LEAP_NONE, false },
    { "none_cell", "none, cell on", false, Mapper::LEAP_NONE, true },
    { "dmap_off", "dist. map, cell off", false, Mapper::LEAP_DISTANCE_MAP, false },
    { "dmap_cell", "dist. map, cell on", false, Mapper::LEAP_DISTANCE_MAP, true },
    { "octree_off", "octree, cell off", false, Mapper::LEAP_OCTREE, false },
    { "octree_cell", "octree, cell on", false, Mapper::LEAP_OCTREE, true },
    { "vtk_fixed", "vtkFixedPoint", true, 0, false },
  };
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

const ConfigResult* CaseResult::Find(const std::string& id) const
{
  for (const ConfigResult& r : this->Results)
  {
    if (r.Cfg.Id == id)
    {
      return &r;
    }
  }
  return nullptr;
}

bool CaseResult::Identical() const
{
  for (const ConfigResult& r : this->Results)
  {
    if (!r.Cfg.Vtk && r.DifferingPixels > 0)
    {
      return false;
    }
  }
  return true;
}

double CaseResult::CellGain(const std::string& leap) const
{
  const double off = this->Find(leap + "_off")->MedianMs();
  const double on = this->Find(leap + "_cell")->MedianMs();
  return off > 0 ? (off - on) / off * 100.0 : std::nan("");
}

double CaseResult::SpeedUpOverVtk(const ConfigResult& ours) const
{
  return SafeRatio(this->Find("vtk_fixed")->MedianMs(), ours.MedianMs());
}

bool CaseResult::SpeedTargetMet() const
{
  return this->SpeedUpOverVtk(*this->Find("dmap_off")) >= SpeedUpTarget &&
    this->OursVsReference.Rms() <= this->VtkVsReference.Rms();
}

bool CaseResult::CellTargetMet(const std::string& leap) const
{
  return this->CellGain(leap) >= CellGainTarget;
}

void PrintCase(const CaseResult& c)
{
  const ConfigResult* base = c.Find("none_off");
  std::cout << std::left << std::setw(22) << "  config" << std::right << std::setw(10) << "ms/frame"
            << std::setw(9) << "x none" << std::setw(10) << "cell gain" << std::setw(8) << "x VTK"
            << std::setw(11) << "samples/f" << std::setw(11) << "space-leap" << std::setw(11)
            << "cell-leap" << std::setw(11) << "empty-cell" << std::setw(18) << "1st / TF prep ms"
            << std::setw(7) << "cores"
            << "\n";
  for (const ConfigResult& r : c.Results)
  {
    std::cout << "  " << std::left << std::setw(20) << r.Cfg.Label << std::right << std::setw(10)
              << Num(r.MedianMs(), 1) << std::setw(9)
              << Times(SafeRatio(base->MedianMs(), r.MedianMs())) << std::setw(10)
              << (r.Cfg.Cell ? Percent(c.CellGain(LeapOf(r.Cfg.Id))) : "-") << std::setw(8)
              << Times(c.SpeedUpOverVtk(r));
    if (r.Cfg.Vtk)
    {
      std::cout << std::setw(11) << "-" << std::setw(11) << "-" << std::setw(11) << "-"
                << std::setw(11) << "-" << std::setw(18)
                << ("(1st frame " + Num(r.FirstFrameMs, 0) + ")") << std::setw(7)
                << Num(Median(r.Cores), 2) << "\n";
      continue;
    }
    std::cout << std::setw(11) << Millions(r.Count.Samples) << std::setw(11)
              << Millions(r.Count.LeapedSpace) << std::setw(11) << Millions(r.Count.LeapedCell)
              << std::setw(11) << Millions(r.Count.EmptyCell) << std::setw(18)
              << (Num(r.FirstPrepareMs, 1) + " / " + Num(r.TfPrepareMs, 1)) << std::setw(7)
              << Num(Median(r.Cores), 2) << "\n";
  }
  if (c.Identical())
  {
    std::cout << "  images at the fixed view: our 6 configurations identical\n";
  }
  else
  {
    std::cout << "  images at the fixed view: NOT IDENTICAL to none, cell off:";
    for (const ConfigResult& r : c.Results)
    {
      if (!r.Cfg.Vtk && r.DifferingPixels > 0)
      {
        std::cout << " " << r.Cfg.Id << " " << r.DifferingPixels << " pixels (max "
                  << r.MaxDifference << ")";
      }
    }
    std::cout << "\n";
  }
  std::cout << "  quality vs fine reference (ours, leap none, cell off, sample distance "
            << c.ReferenceSampleDistance << " = 1/"
            << Num(c.SampleDistance / c.ReferenceSampleDistance, 0) << " of " << c.SampleDistance
            << "; " << Num(c.ReferenceMs, 0)
            << " ms): grey-level RMS ours (dist. map, cell off: the default) "
            << Num(c.OursVsReference.Rms(), 2) << ", vtkFixedPoint "
            << Num(c.VtkVsReference.Rms(), 2) << " over " << c.OursVsReference.Pixels << " / "
            << c.VtkVsReference.Pixels << " non-black pixels; ours vs vtkFixedPoint "
            << Num(c.OursVsVtk.Rms(), 2) << "\n";
  std::cout << "  targets: ours >= " << Num(SpeedUpTarget, 0)
            << "x vtkFixedPoint at <= its RMS: " << (c.SpeedTargetMet() ? "met" : "NOT met") << " ("
            << Times(c.SpeedUpOverVtk(*c.Find("dmap_off")))
            << "); cell leaping >= " << Num(CellGainTarget, 0) << "%: dist. map "
            << Percent(c.CellGain("dmap")) << (c.CellTargetMet("dmap") ? " met" : " NOT met")
            << ", octree " << Percent(c.CellGain("octree"))
            << (c.CellTargetMet("octree") ? " met" : " NOT met") << "\n"
            << std::flush;
}

void PrintSummary(const std::vector<CaseResult>& cases)
{
  std::cout << "\nTable 2 and beyond: speed-up from cell leaping, (t_off - t_on) / t_off, within "
               "each leap mode; paper values beside ours\n"
            << std::left << std::setw(20) << "volume" << std::setw(5) << "tf" << std::right
            << std::setw(8) << "none" << std::setw(8) << "dmap" << std::setw(8) << "octree"
            << std::setw(13) << "paper d/o" << std::setw(10) << "dm/VTK" << std::setw(13)
            << "RMS ours/VTK" << std::setw(11) << "identical"
            << "  targets (2x VTK, 20% dmap, 20% octree)\n";
  int met[3] = { 0, 0, 0 };
  for (const CaseResult& c : cases)
  {
    const PaperRow* paper = PaperRowFor(c.Dataset);
    std::cout << std::left << std::setw(20) << c.Dataset << std::setw(5) << c.Tf << std::right
              << std::setw(8) << Percent(c.CellGain("none")) << std::setw(8)
              << Percent(c.CellGain("dmap")) << std::setw(8) << Percent(c.CellGain("octree"))
              << std::setw(13)
              << (paper ? Num(paper->DistanceMap, 1) + "/" + Num(paper->Octree, 1) : "-")
              << std::setw(10) << Times(c.SpeedUpOverVtk(*c.Find("dmap_off"))) << std::setw(13)
              << (Num(c.OursVsReference.Rms(), 2) + "/" + Num(c.VtkVsReference.Rms(), 2))
              << std::setw(11) << (c.Identical() ? "yes" : "NO") << "  "
              << (c.SpeedTargetMet() ? "yes" : "no") << " "
              << (c.CellTargetMet("dmap") ? "yes" : "no") << " "
              << (c.CellTargetMet("octree") ? "yes" : "no") << "\n";
    met[0] += c.SpeedTargetMet();
    met[1] += c.CellTargetMet("dmap");
    met[2] += c.CellTargetMet("octree");
  }
  std::cout
    << "targets met in " << met[0] << " / " << cases.size()
    << " cases (>= " << Num(SpeedUpTarget, 0) << "x vtkFixedPoint at <= its RMS), " << met[1]
    << " / " << cases.size() << " (cell leaping >= " << Num(CellGainTarget, 0)
    << "% over dist. map), " << met[2] << " / " << cases.size() << " (over octree)\n"
    << "Lim, Kim and Shin 2009 Table 2 (Athlon 64 X2 4200+, 512x512x322..512 volumes, 512^2 perspective): "
       "case 1 (dist. map) 18.8-24.1%, case 2 (octree) 16.8-21.7%; teeth volume not "
       "available here\n";
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
  out << "{\n  \"benchmark\": \"raycast (Lim, Kim and Shin 2009 Table 2: semi-transparent cell leaping)\",\n";
  out << "  \"machine\": {\"cpu\": \"" << JsonEscape(machine.Cpu)
      << "\", \"hardware_threads\": " << machine.HardwareThreads << ", \"gl_backend\": \""
      << JsonEscape(machine.GlBackend) << "\", \"gl_renderer\": \""
      << JsonEscape(machine.GlRenderer) << "\"},\n";
  out << "  \"settings\": {\"size\": " << options.Size << ", \"frames\": " << options.Frames
      << ", \"threads\": " << options.Threads << ", \"sample_factor\": " << options.SampleFactor
      << ", \"reference_factor\": " << options.ReferenceFactor
      << ", \"view\": {\"azimuth\": " << Num(options.Azimuth, 2)
      << ", \"elevation\": " << Num(options.Elevation, 2)
      << "}, \"turn_degrees\": " << Num(options.Turn, 2)
      << ", \"shade\": " << (options.Shade ? "true" : "false")
      << ", \"projection\": \"perspective\", \"blend\": \"composite\", "
         "\"image_sample_distance\": 1, \"auto_adjust_sample_distances\": false, "
         "\"early_ray_termination\": true, \"quick\": "
      << (options.Quick ? "true" : "false") << ", \"speedup_target\": " << SpeedUpTarget
      << ", \"cell_gain_target_percent\": " << CellGainTarget << "},\n";
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
    out << "    {\n      \"dataset\": \"" << JsonEscape(c.Dataset) << "\", \"tf\": \"" << c.Tf
        << "\", \"size\": " << c.Size << ", \"frames\": " << c.Frames
        << ", \"sample_distance\": " << c.SampleDistance
        << ", \"reference_sample_distance\": " << c.ReferenceSampleDistance
        << ", \"reference_ms\": " << Num(c.ReferenceMs, 1) << ", \"seconds\": " << Num(c.Seconds, 2)
        << ",\n      \"identical\": " << (c.Identical() ? "true" : "false") << ", ";
    JsonErrors(out, "ours_vs_reference", c.OursVsReference);
    out << ", ";
    JsonErrors(out, "vtk_vs_reference", c.VtkVsReference);
    out << ", ";
    JsonErrors(out, "ours_vs_vtk", c.OursVsVtk);
    out << ",\n      \"cell_gain_percent\": {\"none\": " << Num(c.CellGain("none"), 2)
        << ", \"dmap\": " << Num(c.CellGain("dmap"), 2)
        << ", \"octree\": " << Num(c.CellGain("octree"), 2)
        << "}, \"targets_met\": {\"speed\": " << (c.SpeedTargetMet() ? "true" : "false")
        << ", \"cell_dmap\": " << (c.CellTargetMet("dmap") ? "true" : "false")
        << ", \"cell_octree\": " << (c.CellTargetMet("octree") ? "true" : "false")
        << "},\n      \"configs\": [\n";
    const double baseMs = c.Find("none_off")->MedianMs();
    for (size_t k = 0; k < c.Results.size(); ++k)
    {
      const ConfigResult& r = c.Results[k];
      out << "        {\"id\": \"" << r.Cfg.Id << "\", \"label\": \"" << JsonEscape(r.Cfg.Label)
          << "\", \"median_ms\": " << Num(r.MedianMs(), 2)
          << ", \"speedup_over_none_off\": " << Num(SafeRatio(baseMs, r.MedianMs()), 3)
          << ", \"speedup_over_vtk\": " << Num(c.SpeedUpOverVtk(r), 3)
          << ", \"first_frame_ms\": " << Num(r.FirstFrameMs, 1)
          << ", \"tf_change_frame_ms\": " << Num(r.TfFrameMs, 1)
          << ", \"median_cores\": " << Num(Median(r.Cores), 2);
      if (!r.Cfg.Vtk)
      {
        const Counters& n = r.Count;
        out << ", \"first_prepare_ms\": " << Num(r.FirstPrepareMs, 2)
            << ", \"tf_change_prepare_ms\": " << Num(r.TfPrepareMs, 2)
            << ", \"median_cast_ms\": " << Num(Median(r.CastMs), 2)
            << ", \"differing_pixels\": " << r.DifferingPixels
            << ", \"max_difference\": " << r.MaxDifference
            << ",\n         \"per_frame\": {\"rays\": " << Num(n.Rays, 0)
            << ", \"samples\": " << Num(n.Samples, 0)
            << ", \"leaped_space\": " << Num(n.LeapedSpace, 0)
            << ", \"leaped_cell_table\": " << Num(n.LeapedCell, 0)
            << ", \"in_transparent_cells\": " << Num(n.EmptyCell, 0)
            << ", \"terminated_rays\": " << Num(n.Terminated, 0) << "}";
      }
      out << ", \"frame_ms\": ";
      JsonArray(out, r.FrameMs);
      out << "}" << (k + 1 < c.Results.size() ? "," : "") << "\n";
    }
    out << "      ]\n    }" << (i + 1 < cases.size() ? "," : "") << "\n";
  }
  out << "  ]\n}\n";
}

} // namespace accelvolume::benchmark::raycast
