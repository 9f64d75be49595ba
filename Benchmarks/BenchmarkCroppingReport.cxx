// Printed comparison table and JSON output of accelvolume_benchmark_cropping.
#include "BenchmarkCroppingReport.h"

#include <fstream>
#include <iomanip>
#include <iostream>
#include <iterator>
#include <sstream>

namespace accelvolume::benchmark
{
void PrintTable(const DatasetResult& d)
{
  const ConfigResult* oneAndHalf = nullptr;
  const ConfigResult* base = nullptr;
  const ConfigResult* rerender = nullptr;
  const ConfigResult* doubled = nullptr;
  for (const ConfigResult& r : d.Results)
  {
    base = r.Cfg.Id == "a" ? &r : base;
    rerender = r.Cfg.Id == "b" ? &r : rerender;
    doubled = r.Cfg.Id == "d" ? &r : doubled;
    oneAndHalf = r.Cfg.Id == "c" ? &r : oneAndHalf;
  }
  std::cout << "\n"
            << d.Name << " (" << d.Description << "), MIP, errors in grey levels (0..255) vs ref,"
            << " pooled over 2 views; pixels: footprint " << d.FootprintPixels[0] << "+"
            << d.FootprintPixels[1] << ", band " << d.BandPixels[0] << "+" << d.BandPixels[1]
            << ", cut-face " << d.FacePixels[0] << "+" << d.FacePixels[1] << "\n";
  std::cout << std::left << std::setw(5) << "cfg" << std::setw(35) << "configuration" << std::right
            << std::setw(7) << "slices" << std::setw(10) << "ms/frame" << std::setw(7) << "fps"
            << std::setw(8) << "min ms" << std::setw(7) << "time x" << std::setw(7) << "RMS"
            << std::setw(5) << "max" << std::setw(7) << "err x" << std::setw(8) << ">2lv%"
            << std::setw(8) << "bandRMS" << std::setw(6) << "bmax" << std::setw(7) << "band x"
            << std::setw(8) << "faceRMS" << std::setw(7) << "face x"
            << "\n";
  for (const ConfigResult& r : d.Results)
  {
    const double ms = r.MedianMs();
    std::cout << std::left << std::setw(5) << r.Cfg.Id << std::setw(35) << r.Cfg.Label << std::right
              << std::setw(7) << (r.Cfg.Gpu ? std::string("-") : std::to_string(r.Slices))
              << std::setw(10) << Num(ms, 1) << std::setw(7) << Num(1000.0 / ms, 2) << std::setw(8)
              << Num(r.MinMs(), 1) << std::setw(7) << Num(r.PairedRatio(*base), 2) << std::setw(7)
              << Num(r.FootprintAll.Rms(), 2) << std::setw(5) << Num(r.FootprintAll.Max, 0)
              << std::setw(7) << Num(SafeRatio(r.FootprintAll.Rms(), base->FootprintAll.Rms()), 2)
              << std::setw(8) << Num(100.0 * r.FootprintAll.AboveFraction(), 2) << std::setw(8)
              << Num(r.BandAll.Rms(), 2) << std::setw(6) << Num(r.BandAll.Max, 0) << std::setw(7)
              << Num(SafeRatio(r.BandAll.Rms(), base->BandAll.Rms()), 2) << std::setw(8)
              << Num(r.FaceAll.Rms(), 2) << std::setw(7)
              << Num(SafeRatio(r.FaceAll.Rms(), base->FaceAll.Rms()), 2) << "\n";
  }
  const double overhead = 100.0 * (rerender->PairedRatio(*base) - 1.0);
  std::cout << "  re-rendering overhead: " << Num(overhead, 1)
            << "% of frame time (median of per-round b/a; from medians "
            << Num(100.0 * (rerender->MedianMs() / base->MedianMs() - 1.0), 1) << "%, from minima "
            << Num(100.0 * (rerender->MinMs() / base->MinMs() - 1.0), 1)
            << "%); paper: " << Num(100.0 * (150.81 / 149.83 - 1.0), 1) << "%\n";
  std::cout << "  1.5x slices: " << Num(100.0 * (oneAndHalf->PairedRatio(*base) - 1.0), 1)
            << "% more time, 2x slices: " << Num(100.0 * (doubled->PairedRatio(*base) - 1.0), 1)
            << "% more (paper: 400 vs 256 slices +" << Num(100.0 * (150.81 / 97.24 - 1.0), 1)
            << "%, 512 vs 256 +" << Num(100.0 * (150.81 / 73.85 - 1.0), 1) << "%)\n";
  auto verdict = [&](const char* what, const ErrorStats& b, const ErrorStats& dd)
  {
    std::cout << (b.Rms() < dd.Rms() ? "holds" : "DOES NOT hold") << " " << what << " (b "
              << Num(b.Rms(), 2) << " vs d " << Num(dd.Rms(), 2) << ")";
  };
  std::cout << "  \"re-rendering leaves less boundary error than doubling the slices\": ";
  verdict("in the outline band", rerender->BandAll, doubled->BandAll);
  std::cout << "; ";
  verdict("on the cut-face pixels", rerender->FaceAll, doubled->FaceAll);
  std::cout << "; ";
  verdict("over the whole footprint", rerender->FootprintAll, doubled->FootprintAll);
  std::cout << "\n";
}

void WriteJson(const Options& options, const std::string& renderer, const std::string& backend,
  const std::vector<DatasetResult>& datasets)
{
  std::ofstream out(options.Json);
  if (!out)
  {
    std::cerr << "cannot write " << options.Json << "\n";
    return;
  }
  out << "{\n  \"benchmark\": \"cropping (Hong, Kye and Shin 2007 Table 2)\",\n";
  out << "  \"gl_backend\": \"" << JsonEscape(backend) << "\",\n";
  out << "  \"gl_renderer\": \"" << JsonEscape(renderer) << "\",\n";
  out << "  \"size\": [" << options.Width << ", " << options.Height << "],\n";
  out << "  \"frames\": " << options.Frames
      << ",\n  \"reference_frames\": " << options.ReferenceFrames << ",\n";
  out << "  \"crop_fraction\": [" << options.CropLow << ", " << options.CropHigh << "],\n";
  out << "  \"band_radius_px\": " << options.BandRadius << ",\n";
  out << "  \"above_threshold_grey_levels\": " << options.AboveThreshold << ",\n";
  out << "  \"views\": [";
  for (size_t v = 0; v < std::size(Views); ++v)
  {
    out << (v ? ", " : "") << "{\"name\": \"" << Views[v].Name
        << "\", \"azimuth\": " << Views[v].Azimuth << ", \"elevation\": " << Views[v].Elevation
        << "}";
  }
  out << "],\n";
  out << "  \"error_units\": \"grey levels 0..255 (mean of R,G,B) vs the 8x re-rendered slice "
         "reference\",\n";
  out << "  \"paper_table2_fps\": {\"rerender_256\": 149.83, \"plain_256\": 150.81, "
         "\"plain_400\": 97.24, \"plain_512\": 73.85},\n";
  out << "  \"datasets\": [\n";
  for (size_t i = 0; i < datasets.size(); ++i)
  {
    const DatasetResult& d = datasets[i];
    const ConfigResult* base = nullptr;
    const ConfigResult* rerender = nullptr;
    const ConfigResult* doubled = nullptr;
    for (const ConfigResult& r : d.Results)
    {
      base = r.Cfg.Id == "a" ? &r : base;
      rerender = r.Cfg.Id == "b" ? &r : rerender;
      doubled = r.Cfg.Id == "d" ? &r : doubled;
    }
    out << "    {\n      \"name\": \"" << JsonEscape(d.Name) << "\",\n      \"file\": \""
        << JsonEscape(d.File) << "\",\n      \"volume\": \"" << JsonEscape(d.Description)
        << "\",\n      \"spacing\": [" << d.Spacing[0] << ", " << d.Spacing[1] << ", "
        << d.Spacing[2] << "],\n      \"tf_window\": [" << d.Window[0] << ", " << d.Window[1]
        << "],\n      \"crop_planes\": [";
    for (int k = 0; k < 6; ++k)
    {
      out << (k ? ", " : "") << Num(d.CropPlanes[k], 4);
    }
    out << "],\n      \"cut_face_pixels\": [" << d.FacePixels[0] << ", " << d.FacePixels[1]
        << "],\n      \"footprint_pixels\": [" << d.FootprintPixels[0] << ", "
        << d.FootprintPixels[1] << "],\n      \"band_pixels\": [" << d.BandPixels[0] << ", "
        << d.BandPixels[1] << "],\n      \"seconds\": " << Num(d.TotalSeconds, 2)
        << ",\n      \"rerender_overhead_percent\": "
        << Num(100.0 * (rerender->PairedRatio(*base) - 1.0), 2)
        << ",\n      \"rerender_beats_2x_in_band\": "
        << (rerender->BandAll.Rms() < doubled->BandAll.Rms() ? "true" : "false")
        << ",\n      \"rerender_beats_2x_on_cut_faces\": "
        << (rerender->FaceAll.Rms() < doubled->FaceAll.Rms() ? "true" : "false")
        << ",\n      \"rerender_beats_2x_in_footprint\": "
        << (rerender->FootprintAll.Rms() < doubled->FootprintAll.Rms() ? "true" : "false")
        << ",\n      \"configs\": [\n";
    for (size_t k = 0; k < d.Results.size(); ++k)
    {
      const ConfigResult& r = d.Results[k];
      out << "        {\"id\": \"" << r.Cfg.Id << "\", \"label\": \"" << JsonEscape(r.Cfg.Label)
          << "\", \"mapper\": \""
          << (r.Cfg.Gpu ? "vtkGPUVolumeRayCastMapper" : "vtkAccelVolumeSliceMapper")
          << "\", \"boundary_rerendering\": " << (r.Cfg.Rerender ? "true" : "false")
          << ", \"slice_factor\": " << r.Cfg.SliceFactor
          << ", \"auto_adjust\": " << (r.Cfg.AutoAdjust ? "true" : "false");
      if (!r.Cfg.Gpu)
      {
        out << ", \"slices\": " << r.Slices << ", \"boundary_faces\": " << r.Faces
            << ", \"slice_spacing\": " << Num(r.SliceSpacing, 5);
      }
      out << ",\n         \"median_ms\": " << Num(r.MedianMs(), 3)
          << ", \"fps\": " << Num(1000.0 / r.MedianMs(), 3) << ", \"min_ms\": " << Num(r.MinMs(), 3)
          << ", \"time_ratio_vs_a\": " << Num(r.PairedRatio(*base), 4)
          << ", \"median_ratio_vs_a\": " << Num(r.MedianMs() / base->MedianMs(), 4);
      if (!r.Cfg.Gpu)
      {
        out << ", \"median_mapper_ms\": " << Num(r.MedianMapperMs(), 3);
      }
      out << ", \"frame_ms\": [";
      for (size_t f = 0; f < r.FrameMs.size(); ++f)
      {
        out << (f ? ", " : "") << Num(r.FrameMs[f], 2);
      }
      out << "],\n         \"rms_error\": " << Num(r.FootprintAll.Rms(), 4)
          << ", \"max_error\": " << Num(r.FootprintAll.Max, 2) << ", \"error_ratio_vs_a\": "
          << Num(SafeRatio(r.FootprintAll.Rms(), base->FootprintAll.Rms()), 4)
          << ", \"above_threshold_fraction\": " << Num(r.FootprintAll.AboveFraction(), 5)
          << ", \"band_rms_error\": " << Num(r.BandAll.Rms(), 4)
          << ", \"band_max_error\": " << Num(r.BandAll.Max, 2) << ", \"band_error_ratio_vs_a\": "
          << Num(SafeRatio(r.BandAll.Rms(), base->BandAll.Rms()), 4)
          << ", \"cut_face_rms_error\": " << Num(r.FaceAll.Rms(), 4)
          << ", \"cut_face_max_error\": " << Num(r.FaceAll.Max, 2)
          << ", \"cut_face_error_ratio_vs_a\": "
          << Num(SafeRatio(r.FaceAll.Rms(), base->FaceAll.Rms()), 4)
          << ",\n         \"per_view\": [";
      for (size_t v = 0; v < r.Footprint.size(); ++v)
      {
        out << (v ? ", " : "") << "{\"view\": \"" << Views[v].Name
            << "\", \"rms_error\": " << Num(r.Footprint[v].Rms(), 4)
            << ", \"max_error\": " << Num(r.Footprint[v].Max, 2)
            << ", \"above_threshold_fraction\": " << Num(r.Footprint[v].AboveFraction(), 5)
            << ", \"band_rms_error\": " << Num(r.Band[v].Rms(), 4)
            << ", \"band_max_error\": " << Num(r.Band[v].Max, 2)
            << ", \"cut_face_rms_error\": " << Num(r.Face[v].Rms(), 4) << "}";
      }
      out << "]}" << (k + 1 < d.Results.size() ? "," : "") << "\n";
    }
    out << "      ]\n    }" << (i + 1 < datasets.size() ? "," : "") << "\n";
  }
  out << "  ]\n}\n";
}

} // namespace accelvolume::benchmark
