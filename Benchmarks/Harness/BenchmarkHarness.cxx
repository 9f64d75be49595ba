// The benchmark harness (see BenchmarkHarness.h) and the main() of every benchmark program.
#include "BenchmarkHarness.h"

#include "ProgressBar.h" // the accelvolume CLI's bar
#include "VolumeIO.h"
#include "vtkAccelVolumeHeadlessRenderWindow.h"

#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkPointData.h>
#include <vtkRenderWindow.h>
#include <vtkSMPTools.h>
#include <vtkUnsignedCharArray.h>

#include <sys/resource.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <regex>
#include <sstream>
#include <thread>

namespace fs = std::filesystem;

namespace accelvolume::benchmark
{

double SecondsSince(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

double MsSince(Clock::time_point start)
{
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

std::string ShellQuote(const std::string& text)
{
  return "'" + std::regex_replace(text, std::regex("'"), "'\\''") + "'";
}

double ProcessCpuMs()
{
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return 1000.0 * (usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
    (usage.ru_utime.tv_usec + usage.ru_stime.tv_usec) / 1000.0;
}

double Median(std::vector<double> values)
{
  if (values.empty())
  {
    return std::nan("");
  }
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : (values[n / 2 - 1] + values[n / 2]) / 2;
}

double Mean(const std::vector<double>& values)
{
  double sum = 0;
  for (double value : values)
  {
    sum += value;
  }
  return values.empty() ? std::nan("") : sum / static_cast<double>(values.size());
}

double SafeRatio(double a, double b)
{
  return b > 0 ? a / b : std::nan("");
}

void Range::Add(double value)
{
  if (std::isfinite(value))
  {
    this->Low = std::isfinite(this->Low) ? std::min(this->Low, value) : value;
    this->High = std::isfinite(this->High) ? std::max(this->High, value) : value;
  }
}

Json Round(double value, int digits)
{
  if (!std::isfinite(value))
  {
    return nullptr;
  }
  if (digits <= 0)
  {
    return static_cast<long long>(std::llround(value)); // counts and bytes as integers
  }
  const double scale = std::pow(10.0, digits);
  return std::round(value * scale) / scale;
}

Json RoundAll(const std::vector<double>& values, int digits)
{
  Json list = Json::array();
  for (double value : values)
  {
    list.push_back(Round(value, digits));
  }
  return list;
}

Json StringOrNull(const std::string& text)
{
  return text.empty() ? Json(nullptr) : Json(text);
}

std::string FindDatasetFile(const std::string& dataDir, const std::string& name)
{
  // The name is matched literally: regex metacharacters in it are escaped.
  const std::regex pattern("^" +
    std::regex_replace(name, std::regex(R"([.^$|()\[\]{}*+?\\])"), R"(\$&)") +
    R"(_\d+x\d+x\d+_[A-Za-z0-9]+\.raw(\.gz)?$)");
  std::error_code ec;
  std::vector<std::string> matches;
  for (const auto& entry : fs::directory_iterator(dataDir, ec))
  {
    if (std::regex_match(entry.path().filename().string(), pattern))
    {
      matches.push_back(entry.path().string());
    }
  }
  std::sort(matches.begin(), matches.end());
  return matches.empty() ? std::string() : matches.front();
}

vtkSmartPointer<vtkImageData> LoadDataset(
  const std::string& dataDir, const std::string& name, DatasetInfo& info)
{
  info.Name = name;
  info.File = FindDatasetFile(dataDir, name);
  if (info.File.empty())
  {
    std::cerr << "dataset " << name << ": no file " << name << "_<X>x<Y>x<Z>_<type>.raw[.gz] in "
              << dataDir << "\n";
    return nullptr;
  }
  accelvolume::cli::VolumeRequest request;
  request.inputPath = info.File; // spacing comes from datasets.json next to the file
  std::string error;
  const auto start = Clock::now();
  vtkSmartPointer<vtkImageData> image = accelvolume::cli::LoadVolume(request, error);
  info.LoadSeconds = SecondsSince(start);
  if (!image)
  {
    std::cerr << "dataset " << name << ": " << error << "\n";
    return nullptr;
  }
  info.Description = accelvolume::cli::DescribeVolume(image);
  image->GetSpacing(info.Spacing);
  info.MinSpacing = std::min({ info.Spacing[0], info.Spacing[1], info.Spacing[2] });
  image->GetPointData()->GetScalars()->GetRange(info.Range);
  return image;
}

Json DatasetJson(const DatasetInfo& info, bool withSampleDistance)
{
  Json d = { { "name", info.Name }, { "file", info.File }, { "volume", info.Description },
    { "spacing", { info.Spacing[0], info.Spacing[1], info.Spacing[2] } } };
  if (withSampleDistance)
  {
    d["sample_distance"] = info.MinSpacing;
  }
  d["range"] = { info.Range[0], info.Range[1] };
  d["load_seconds"] = Round(info.LoadSeconds, 3);
  return d;
}

std::vector<std::uint8_t> Capture(vtkRenderWindow* window, int width, int height)
{
  vtkNew<vtkUnsignedCharArray> pixels;
  window->GetPixelData(0, 0, width - 1, height - 1, 0, pixels.Get());
  const auto* data = pixels->GetPointer(0);
  return std::vector<std::uint8_t>(data, data + static_cast<size_t>(width) * height * 3);
}

bool WritePng(const std::string& path, const std::vector<std::uint8_t>& rgb, int width, int height)
{
  vtkNew<vtkImageData> image;
  image->SetDimensions(width, height, 1);
  vtkNew<vtkUnsignedCharArray> array;
  array->SetNumberOfComponents(3);
  array->SetNumberOfTuples(static_cast<vtkIdType>(width) * height);
  std::copy(rgb.begin(), rgb.end(), array->GetPointer(0));
  image->GetPointData()->SetScalars(array);
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(path.c_str());
  writer->SetInputData(image);
  writer->Write();
  return writer->GetErrorCode() == 0;
}

namespace
{
std::vector<std::string> SplitList(const std::string& list)
{
  std::vector<std::string> items;
  std::stringstream stream(list);
  for (std::string item; std::getline(stream, item, ',');)
  {
    if (!item.empty())
    {
      items.push_back(item);
    }
  }
  return items;
}

template <typename T>
std::string Join(const std::vector<T>& values)
{
  std::ostringstream text;
  for (std::size_t i = 0; i < values.size(); ++i)
  {
    text << (i ? "," : "") << values[i];
  }
  return text.str();
}

std::string ReadCpuModel()
{
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);)
  {
    if (line.rfind("model name", 0) == 0 && line.find(':') != std::string::npos)
    {
      return line.substr(line.find(':') + 2);
    }
  }
  return "";
}

double ReadMemoryMiB()
{
  std::ifstream in("/proc/meminfo");
  for (std::string line; std::getline(in, line);)
  {
    if (line.rfind("MemTotal:", 0) == 0)
    {
      return std::atof(line.c_str() + 9) / 1024.0; // kB
    }
  }
  return 0;
}
} // namespace

CLI::Option* AddList(
  CLI::App& app, const std::string& name, std::vector<std::string>& values, const std::string& help)
{
  return app
    .add_option_function<std::string>(
      name, [&values](const std::string& text) { values = SplitList(text); }, help)
    ->type_name("A,B")
    ->default_str(Join(values));
}

CLI::Option* AddList(
  CLI::App& app, const std::string& name, std::vector<int>& values, const std::string& help)
{
  return app
    .add_option_function<std::string>(
      name,
      [&values, name](const std::string& text)
      {
        values.clear();
        for (const std::string& item : SplitList(text))
        {
          values.push_back(std::atoi(item.c_str()));
        }
      },
      help)
    ->type_name("A,B")
    ->default_str(Join(values));
}

CLI::Option* AddOnOff(CLI::App& app, const std::string& name, bool& value, const std::string& help)
{
  return app
    .add_option_function<std::string>(
      name, [&value](const std::string& text) { value = text == "on"; }, help)
    ->check(CLI::IsMember({ "on", "off" }))
    ->type_name("on|off")
    ->default_str(value ? "on" : "off");
}

void CheckTransferFunctions(const std::vector<std::string>& values, const std::string& option)
{
  bool valid = !values.empty();
  for (const std::string& tf : values)
  {
    valid = valid && (tf == "tf1" || tf == "tf2");
  }
  if (!valid)
  {
    throw CLI::ValidationError(option, "needs presets among tf1,tf2");
  }
}

CaseProgress::CaseProgress(const std::string& program, int cases)
  : Program(program)
  , Cases(std::max(cases, 1))
{
  if (accelvolume::cli::StderrIsTerminal())
  {
    const std::string label = program.substr(program.rfind('_') + 1); // "raycast"
    this->Bar =
      std::make_unique<accelvolume::cli::ProgressBar>(label, accelvolume::cli::ProgressMode::On);
  }
}

CaseProgress::~CaseProgress() = default;

void CaseProgress::Begin(const std::string& name)
{
  std::cout << std::flush;
  const int index = std::min(this->Index, this->Cases - 1);
  if (this->Bar)
  {
    this->Bar->BeginTask(index, this->Cases, name);
    this->Bar->Finish();
  }
  else
  {
    std::cerr << this->Program << ": case " << index + 1 << "/" << this->Cases << ": " << name
              << std::endl;
  }
  ++this->Index;
}

void CaseProgress::Skip(int cases)
{
  this->Index += std::max(cases, 0);
}

int Harness::ResolveBackend(const std::string& gl, int& backend)
{
  backend = vtkAccelVolumeHeadlessRenderWindow::ParseBackendName(gl.c_str());
  if (backend < 0 || backend == vtkAccelVolumeHeadlessRenderWindow::BACKEND_X)
  {
    std::cerr << "--gl must be egl, osmesa or auto\n";
    return 2;
  }
  if (backend != vtkAccelVolumeHeadlessRenderWindow::BACKEND_AUTOMATIC &&
    !vtkAccelVolumeHeadlessRenderWindow::IsBackendAvailable(backend))
  {
    std::cerr << "headless backend " << gl << " is not available here\n";
    return 1;
  }
  return 0;
}

void Harness::StartWindow(
  vtkAccelVolumeHeadlessRenderWindow* window, int backend, int width, int height)
{
  window->SetBackend(backend);
  window->SetMultiSamples(0);
  window->SetSize(width, height);
  window->Render(); // creates the context
}

void Harness::DescribeGL(vtkAccelVolumeHeadlessRenderWindow* window, MachineInfo& machine)
{
  machine.GLBackend =
    vtkAccelVolumeHeadlessRenderWindow::GetBackendName(window->GetActiveBackend());
  const char* renderer = window->GetOpenGLRendererString();
  machine.GLRenderer = renderer ? renderer : "";
  window->GetOpenGLVersion(machine.GLMajor, machine.GLMinor);
  machine.GLVersion = std::to_string(machine.GLMajor) + "." + std::to_string(machine.GLMinor);
}

MachineInfo Harness::DescribeMachine()
{
  MachineInfo machine;
  machine.Cpu = ReadCpuModel();
  machine.HardwareThreads = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  machine.SMPThreads = vtkSMPTools::GetEstimatedNumberOfThreads();
  machine.SMPBackend = vtkSMPTools::GetBackend() ? vtkSMPTools::GetBackend() : "unknown";
  machine.MemoryMiB = ReadMemoryMiB();
  return machine;
}

bool Harness::WriteJson(const std::string& path, const Json& document)
{
  std::ofstream out(path);
  out << document.dump(2, ' ', false, Json::error_handler_t::replace) << "\n";
  if (!out)
  {
    std::cerr << "could not write " << path << "\n";
    return false;
  }
  return true;
}

int Harness::Main(Benchmark& benchmark, int argc, char* argv[])
{
  this->ProgramName = benchmark.Name();
  this->Argc = argc;
  this->Argv = argv;
  this->Options.GL = benchmark.DefaultGL();
  this->Options.Json = benchmark.DefaultJson();
  CLI::App app(std::string(benchmark.Description()), this->ProgramName);
  app.option_defaults()->always_capture_default();
  app.add_option("--data", this->Options.DataDir, "folder of the volumes and datasets.json")
    ->type_name("DIR");
  app.add_option("--gl", this->Options.GL, "headless OpenGL backend: egl, osmesa or auto")
    ->type_name("NAME");
  app.add_option("--json", this->Options.Json, "machine-readable results")->type_name("FILE");
  benchmark.AddOptions(app);
  this->Machine = DescribeMachine();
  try
  {
    app.parse(argc, argv);
    benchmark.Resolve(app, this->Machine);
  }
  catch (const CLI::CallForHelp&)
  {
    std::cout << app.help();
    return 0;
  }
  catch (const CLI::ParseError& error)
  {
    std::cerr << this->ProgramName << ": " << error.what() << " (see --help)\n";
    return 2;
  }

  vtkNew<vtkAccelVolumeHeadlessRenderWindow> window;
  if (benchmark.NeedsWindow())
  {
    if (const int exitCode = ResolveBackend(this->Options.GL, this->BackendId))
    {
      return exitCode;
    }
    StartWindow(window, this->BackendId, benchmark.InitialSize(), benchmark.InitialSize());
    DescribeGL(window, this->Machine);
    this->WindowPointer = window;
    std::cout << this->ProgramName << ": GL " << this->Machine.GLBackend << " "
              << this->Machine.GLVersion << " (" << this->Machine.GLRenderer << "), "
              << this->Machine.SMPThreads << " threads (" << this->Machine.SMPBackend
              << "); data: " << this->Options.DataDir << "\n"
              << std::flush;
  }
  Json result;
  const int exitCode = benchmark.Run(*this, result);
  this->WindowPointer = nullptr;
  if (!result.is_null())
  {
    if (!WriteJson(this->Options.Json, result))
    {
      return 1;
    }
    std::cout << "results written to " << this->Options.Json << "; total "
              << Round(this->Seconds(), 1) << " s\n";
  }
  return exitCode;
}

} // namespace accelvolume::benchmark

int main(int argc, char* argv[])
{
  std::unique_ptr<accelvolume::benchmark::Benchmark> benchmark =
    accelvolume::benchmark::MakeBenchmark();
  accelvolume::benchmark::Harness harness;
  return harness.Main(*benchmark, argc, argv);
}
