// accelvolume_benchmark_bricking: the slice mapper under GPU memory budgets. For one real volume
// (default the 512x512x275 16-bit chest CT) and each blend mode, renders with no budget (one
// brick) and with each budget, and reports bricks, uploads per frame, frame times (first frame,
// median of the next ones) as ratios to the unbricked frame, and the image difference to it.
// Bricked volumes take gradients by central differences; the unbricked mapper precomputes them
// by default, so a second unbricked row ("none/cd", PrecomputeGradients off) separates that
// cost from the bricks' own. Exit code 125 (skipped) when the volume is not in the data folder.
// JSON (only with --json): bricking.json of the report (scripts/bench_report/bricking.py).
#include "BenchmarkHarness.h"
#include "Options.h"
#include "TransferFunctions.h"
#include "VolumeIO.h"

#include "vtkAccelVolumeHeadlessRenderWindow.h"
#include "vtkAccelVolumeSliceMapper.h"

#include <vtkCamera.h>
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkRenderer.h>
#include <vtkVolume.h>
#include <vtkVolumeProperty.h>

#include <algorithm>
#include <iostream>

namespace accelvolume::benchmark
{
namespace
{

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
  double MaxDiff = 0; // grey levels against the unbricked image
  double MeanDiff = 0;
};

// The upper median (this benchmark's rule since it was written): values[n / 2] after sorting.
double UpperMedian(std::vector<double> values)
{
  std::sort(values.begin(), values.end());
  return values.empty() ? 0.0 : values[values.size() / 2];
}

Json RowJson(const Row& r)
{
  return { { "blend", r.Blend }, { "case", r.Label }, { "budget_mib", Round(r.BudgetMiB, 1) },
    { "bricks", r.Bricks }, { "drawn", r.Drawn }, { "uploads_per_frame", r.Uploads },
    { "uploaded_mib_per_frame", Round(r.UploadedMiB, 2) },
    { "resident_mib", Round(r.ResidentMiB, 2) }, { "first_ms", Round(r.FirstMs, 2) },
    { "frame_ms", Round(r.FrameMs, 2) }, { "max_diff", Round(r.MaxDiff, 0) },
    { "mean_diff", Round(r.MeanDiff, 5) } };
}

class BrickingBenchmark : public Benchmark
{
public:
  const char* Name() const override { return "accelvolume_benchmark_bricking"; }
  const char* Description() const override
  {
    return "The slice mapper under GPU memory budgets: bricks, uploads per frame, frame times "
           "and image difference against the unbricked frame";
  }
  const char* DefaultJson() const override { return ""; } // no JSON unless asked for
  const char* DefaultGL() const override { return "auto"; }
  int InitialSize() const override { return this->Size; }

  void AddOptions(CLI::App& app) override
  {
    app.add_option("--dataset", this->Dataset,
      "volume: NAME_<X>x<Y>x<Z>_<type>.raw[.gz] in the "
      "data folder");
    app.add_option("--size", this->Size, "square image size")->check(CLI::PositiveNumber);
    app.add_option("--frames", this->Frames, "timed frames after the first")
      ->check(CLI::PositiveNumber);
    AddList(app, "--budgets", this->Budgets, "GPU memory budgets in MiB (0 = none)");
    AddList(app, "--blends", this->Blends, "blend modes: composite, mip");
    app.add_option("--tf", this->Tf, "transfer-function preset of `accelvolume render --tf`");
  }

  // The volume is loaded before the window opens, so that a missing one is a skip (125).
  bool NeedsWindow() const override { return false; }

  int Run(Harness& harness, Json& result) override;

private:
  std::string Dataset = "ct_chest_lidc0314";
  int Size = 512;
  int Frames = 5;
  std::vector<std::string> Budgets = { "0", "64", "32", "16", "8" };
  std::vector<std::string> Blends = { "composite", "mip" };
  std::string Tf = "tf1";

  Row Measure(vtkRenderWindow* window, vtkAccelVolumeSliceMapper* mapper, double budgetMiB,
    const std::string& blend, const std::vector<std::uint8_t>* reference,
    std::vector<std::uint8_t>& image) const;
  void RunBlend(vtkRenderWindow* window, vtkAccelVolumeSliceMapper* mapper,
    const std::string& blend, Json& rows) const;
};

Row BrickingBenchmark::Measure(vtkRenderWindow* window, vtkAccelVolumeSliceMapper* mapper,
  double budgetMiB, const std::string& blend, const std::vector<std::uint8_t>* reference,
  std::vector<std::uint8_t>& image) const
{
  Row row;
  row.Blend = blend;
  row.BudgetMiB = budgetMiB;
  mapper->SetGPUMemoryBudget(static_cast<vtkIdType>(budgetMiB * 1024 * 1024));
  mapper->ReleaseGraphicsResources(window); // every case starts with nothing on the GPU
  std::vector<double> times;
  int uploads = 0;
  double uploaded = 0;
  for (int frame = 0; frame <= this->Frames; ++frame)
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
  row.FrameMs = UpperMedian(times);
  row.Uploads = static_cast<int>(std::lround(static_cast<double>(uploads) / this->Frames));
  row.UploadedMiB = uploaded / this->Frames;
  row.Bricks = mapper->GetLastNumberOfBricks();
  row.Drawn = mapper->GetLastNumberOfBricksDrawn();
  row.ResidentMiB = mapper->GetLastResidentBytes() / 1048576.0;
  image = Capture(window, this->Size, this->Size);
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

// The unbricked row first (the reference image), then "none/cd" for composite, then the budgets.
void BrickingBenchmark::RunBlend(vtkRenderWindow* window, vtkAccelVolumeSliceMapper* mapper,
  const std::string& blend, Json& rows) const
{
  mapper->SetBlendMode(
    blend == "mip" ? vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND : vtkVolumeMapper::COMPOSITE_BLEND);
  std::vector<std::uint8_t> reference, pixels;
  std::vector<std::string> cases = this->Budgets;
  if (blend == "composite")
  {
    cases.insert(cases.begin() + std::min<std::size_t>(1, cases.size()), "none/cd");
  }
  for (const std::string& budget : cases)
  {
    const bool central = budget == "none/cd";
    const double mib = central ? 0.0 : std::atof(budget.c_str());
    mapper->SetPrecomputeGradients(!central);
    Row row =
      this->Measure(window, mapper, mib, blend, mib > 0 || central ? &reference : nullptr, pixels);
    row.Label = central ? budget : (mib > 0 ? std::to_string(std::lround(mib)) : "none");
    if (mib <= 0 && !central)
    {
      reference = pixels;
    }
    rows.push_back(RowJson(row));
  }
}

int BrickingBenchmark::Run(Harness& harness, Json& result)
{
  const std::string file = FindDatasetFile(harness.Options.DataDir, this->Dataset);
  if (file.empty())
  {
    std::cerr << this->Name() << ": no " << this->Dataset << " volume in "
              << harness.Options.DataDir << ": skipped\n";
    return 125;
  }
  accelvolume::cli::VolumeRequest request;
  request.inputPath = file;
  std::string error;
  vtkSmartPointer<vtkImageData> image = accelvolume::cli::LoadVolume(request, error);
  if (!image)
  {
    std::cerr << this->Name() << ": " << error << "\n";
    return 1;
  }
  int backend = 0;
  if (const int code = Harness::ResolveBackend(harness.Options.GL, backend))
  {
    return code;
  }
  vtkNew<vtkAccelVolumeHeadlessRenderWindow> window;
  Harness::StartWindow(window, backend, this->Size, this->Size);
  Harness::DescribeGL(window, harness.Machine);
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  double range[2];
  scalars->GetRange(range);
  const double volumeMiB = scalars->GetDataSize() * scalars->GetDataTypeSize() / 1048576.0;

  vtkNew<vtkAccelVolumeSliceMapper> mapper;
  mapper->SetInputData(image);
  vtkNew<vtkVolumeProperty> property;
  accelvolume::cli::Options cli;
  cli.blend = accelvolume::cli::BlendKind::Composite;
  cli.haveShade = true;
  cli.shade = true;
  cli.transferFunction = this->Tf;
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

  Json rows = Json::array();
  CaseProgress progress(this->Name(), static_cast<int>(this->Blends.size()));
  for (const std::string& blend : this->Blends)
  {
    progress.Begin(blend);
    this->RunBlend(window, mapper, blend, rows);
  }
  window->RemoveRenderer(renderer);
  if (!harness.Options.Json.empty())
  {
    result = { { "benchmark", "bricking" }, { "dataset", this->Dataset },
      { "volume_mib", Round(volumeMiB, 1) }, { "size", this->Size },
      { "renderer", harness.Machine.GLRenderer }, { "rows", rows } };
  }
  return 0;
}

} // namespace

std::unique_ptr<Benchmark> MakeBenchmark()
{
  return std::make_unique<BrickingBenchmark>();
}

} // namespace accelvolume::benchmark
