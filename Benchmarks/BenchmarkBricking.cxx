// accelvolume_benchmark_bricking: the slice mapper under GPU memory budgets. For one real volume
// (default the 512x512x275 16-bit chest CT) and each blend mode, renders with no budget (one
// brick) and with each budget, and reports bricks, uploads per frame, frame times (first frame,
// median of the next ones) as ratios to the unbricked frame, and the image difference to it.
// Bricked volumes take gradients by central differences; the unbricked mapper precomputes them
// by default, so a second unbricked row ("none/cd", PrecomputeGradients off) separates that
// cost from the bricks' own.
//   accelvolume_benchmark_bricking [--data DIR] [--dataset NAME] [--size N] [--frames N]
//     [--budgets MIB,...] [--blends composite,mip] [--tf tf1|tf2] [--gl egl|osmesa|auto]
//     [--json FILE]
#include "BenchmarkCommon.h"

#include "Options.h"
#include "TransferFunctions.h"
#include "VolumeIO.h"

#include "vtkAccelVolumeHeadlessRenderWindow.h"
#include "vtkAccelVolumeSliceMapper.h"
#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkRenderer.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

using namespace accelvolume::benchmark;

namespace
{
struct Settings
{
  std::string DataDir = ACCELVOLUME_BENCHMARK_DATA_DIR;
  std::string Dataset = "ct_chest_lidc0314";
  int Size = 512;
  int Frames = 5;
  std::string Budgets = "0,64,32,16,8";
  std::string Blends = "composite,mip";
  std::string Tf = "tf1";
  std::string GL = "auto";
  std::string Json;
};

struct Row
{
  std::string Blend;
  std::string Label; // the budget, "none" or "none/cd"
  double BudgetMiB = 0;
  int Bricks = 0;
  int Drawn = 0;
  int Uploads = 0;
  double UploadedMiB = 0;
  double ResidentMiB = 0;
  double FirstMs = 0;
  double FrameMs = 0;
  double MaxDiff = 0;  // grey levels against the unbricked image
  double MeanDiff = 0;
  std::string Error;
};

bool Parse(int argc, char* argv[], Settings& s)
{
  for (int i = 1; i < argc; ++i)
  {
    if (!(TakeOption(argc, argv, i, "--data", s.DataDir) ||
          TakeOption(argc, argv, i, "--dataset", s.Dataset) ||
          TakeOption(argc, argv, i, "--size", s.Size) ||
          TakeOption(argc, argv, i, "--frames", s.Frames) ||
          TakeOption(argc, argv, i, "--budgets", s.Budgets) ||
          TakeOption(argc, argv, i, "--blends", s.Blends) ||
          TakeOption(argc, argv, i, "--tf", s.Tf) || TakeOption(argc, argv, i, "--gl", s.GL) ||
          TakeOption(argc, argv, i, "--json", s.Json)))
    {
      std::cerr << "accelvolume_benchmark_bricking: unknown or incomplete option " << argv[i]
                << " (see the header of Benchmarks/BenchmarkBricking.cxx)\n";
      return false;
    }
  }
  return s.Size > 0 && s.Frames > 0;
}

double Median(std::vector<double> values)
{
  std::sort(values.begin(), values.end());
  return values.empty() ? 0.0 : values[values.size() / 2];
}

Row Measure(vtkRenderWindow* window, vtkAccelVolumeSliceMapper* mapper, const Settings& s,
  double budgetMiB, const std::string& blend, const std::vector<std::uint8_t>* reference,
  std::vector<std::uint8_t>& image)
{
  Row row;
  row.Blend = blend;
  row.BudgetMiB = budgetMiB;
  mapper->SetGPUMemoryBudget(static_cast<vtkIdType>(budgetMiB * 1024 * 1024));
  mapper->ReleaseGraphicsResources(window); // every case starts with nothing on the GPU
  std::vector<double> times;
  int uploads = 0;
  double uploaded = 0;
  for (int frame = 0; frame <= s.Frames; ++frame)
  {
    const auto start = Clock::now();
    window->Render();
    const double ms = MsSince(start);
    if (frame == 0)
    {
      row.FirstMs = ms;
    }
    else
    {
      times.push_back(ms);
      uploads += mapper->GetLastNumberOfBrickUploads();
      uploaded += mapper->GetLastUploadedBytes() / 1048576.0;
    }
  }
  row.FrameMs = Median(times);
  row.Uploads = static_cast<int>(std::lround(static_cast<double>(uploads) / s.Frames));
  row.UploadedMiB = uploaded / s.Frames;
  row.Bricks = mapper->GetLastNumberOfBricks();
  row.Drawn = mapper->GetLastNumberOfBricksDrawn();
  row.ResidentMiB = mapper->GetLastResidentBytes() / 1048576.0;
  image = Capture(window, s.Size, s.Size);
  if (reference && reference->size() == image.size())
  {
    double sum = 0;
    for (size_t i = 0; i < image.size(); ++i)
    {
      const double d = std::fabs(double(image[i]) - double((*reference)[i]));
      row.MaxDiff = std::max(row.MaxDiff, d);
      sum += d;
    }
    row.MeanDiff = sum / image.size();
  }
  return row;
}
}

int main(int argc, char* argv[])
{
  Settings s;
  if (!Parse(argc, argv, s))
  {
    return 2;
  }
  const std::string file = FindDatasetFile(s.DataDir, s.Dataset);
  if (file.empty())
  {
    std::cerr << "accelvolume_benchmark_bricking: no " << s.Dataset << " volume in " << s.DataDir
              << ": skipped\n";
    return 125;
  }
  accelvolume::cli::VolumeRequest request;
  request.inputPath = file;
  std::string error;
  vtkSmartPointer<vtkImageData> image = accelvolume::cli::LoadVolume(request, error);
  if (!image)
  {
    std::cerr << "accelvolume_benchmark_bricking: " << error << "\n";
    return 1;
  }
  int backend = 0;
  if (const int code = ResolveHeadlessBackend(s.GL, backend))
  {
    return code;
  }
  vtkNew<vtkAccelVolumeHeadlessRenderWindow> window;
  StartHeadlessWindow(window, backend, s.Size, s.Size);
  double range[2];
  image->GetPointData()->GetScalars()->GetRange(range);
  const double volumeMiB = image->GetPointData()->GetScalars()->GetDataSize() *
    image->GetPointData()->GetScalars()->GetDataTypeSize() / 1048576.0;

  vtkNew<vtkAccelVolumeSliceMapper> mapper;
  mapper->SetInputData(image);
  vtkNew<vtkVolumeProperty> property;
  accelvolume::cli::Options cli;
  cli.blend = accelvolume::cli::BlendKind::Composite;
  cli.haveShade = true;
  cli.shade = true;
  cli.transferFunction = s.Tf;
  accelvolume::cli::ApplyTransferFunction(
    accelvolume::cli::LoadTransferFunction(cli), cli, range, property);
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  volume->SetProperty(property);
  vtkNew<vtkRenderer> renderer;
  renderer->AddVolume(volume);
  window->AddRenderer(renderer);
  renderer->ResetCamera();
  renderer->GetActiveCamera()->Azimuth(30);
  renderer->GetActiveCamera()->Elevation(20);
  renderer->GetActiveCamera()->OrthogonalizeViewUp();
  renderer->ResetCameraClippingRange();

  std::cout << "accelvolume_benchmark_bricking: slice mapper under GPU memory budgets\n"
            << "volume " << s.Dataset << " " << accelvolume::cli::DescribeVolume(image) << " ("
            << std::fixed << std::setprecision(1) << volumeMiB << " MiB), " << s.Size << "^2, "
            << s.Tf << " shaded, GL " << window->GetOpenGLRendererString() << ", median of "
            << s.Frames << " frames after the first\n";
  std::vector<Row> rows;
  const std::vector<std::string> budgets = SplitList(s.Budgets);
  for (const std::string& blend : SplitList(s.Blends))
  {
    mapper->SetBlendMode(blend == "mip" ? vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND
                                        : vtkVolumeMapper::COMPOSITE_BLEND);
    std::vector<std::uint8_t> reference;
    std::vector<std::uint8_t> pixels;
    std::cout << "\n" << blend << "\n"
              << "  budget MiB  bricks  drawn  uploads/frame  MiB up/frame  resident MiB  "
                 "first ms  frame ms  unbricked/this  max diff  mean diff\n";
    double wholeMs = 0;
    std::vector<std::string> cases = budgets;
    if (blend == "composite")
    {
      cases.insert(cases.begin() + 1, "none/cd");
    }
    for (const std::string& budget : cases)
    {
      const bool central = budget == "none/cd";
      const double mib = central ? 0.0 : std::atof(budget.c_str());
      mapper->SetPrecomputeGradients(!central);
      Row row = Measure(
        window, mapper, s, mib, blend, mib > 0 || central ? &reference : nullptr, pixels);
      row.Label = central ? budget : (mib > 0 ? Num(mib, 0) : "none");
      if (mib <= 0 && !central)
      {
        reference = pixels;
        wholeMs = row.FrameMs;
      }
      std::cout << "  " << std::setw(10) << row.Label << std::setw(8)
                << row.Bricks << std::setw(7) << row.Drawn << std::setw(15) << row.Uploads
                << std::setw(14) << Num(row.UploadedMiB, 1) << std::setw(14)
                << Num(row.ResidentMiB, 1) << std::setw(10) << Num(row.FirstMs, 1)
                << std::setw(10) << Num(row.FrameMs, 1) << std::setw(16)
                << Num(SafeRatio(wholeMs, row.FrameMs), 2) << "x" << std::setw(9)
                << Num(row.MaxDiff, 0) << std::setw(11) << Num(row.MeanDiff, 4) << "\n";
      rows.push_back(row);
    }
  }
  if (!s.Json.empty())
  {
    std::ofstream out(s.Json);
    out << "{\n  \"benchmark\": \"bricking\",\n  \"dataset\": \"" << JsonEscape(s.Dataset)
        << "\",\n  \"volume_mib\": " << Num(volumeMiB, 1) << ",\n  \"size\": " << s.Size
        << ",\n  \"renderer\": \"" << JsonEscape(window->GetOpenGLRendererString())
        << "\",\n  \"rows\": [\n";
    for (size_t i = 0; i < rows.size(); ++i)
    {
      const Row& r = rows[i];
      out << "    {\"blend\": \"" << r.Blend << "\", \"case\": \"" << r.Label
          << "\", \"budget_mib\": " << Num(r.BudgetMiB, 1)
          << ", \"bricks\": " << r.Bricks << ", \"drawn\": " << r.Drawn
          << ", \"uploads_per_frame\": " << r.Uploads
          << ", \"uploaded_mib_per_frame\": " << Num(r.UploadedMiB, 2)
          << ", \"resident_mib\": " << Num(r.ResidentMiB, 2) << ", \"first_ms\": "
          << Num(r.FirstMs, 2) << ", \"frame_ms\": " << Num(r.FrameMs, 2)
          << ", \"max_diff\": " << Num(r.MaxDiff, 0) << ", \"mean_diff\": "
          << Num(r.MeanDiff, 5) << "}" << (i + 1 < rows.size() ? "," : "") << "\n";
    }
    out << "  ]\n}\n";
  }
  return 0;
}
