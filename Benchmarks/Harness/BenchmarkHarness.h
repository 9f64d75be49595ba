// The one harness of the benchmark programs: options common to every benchmark (CLI11), the
// headless GL backend and window, the machine description, repetition statistics and JSON output
// (nlohmann::json). Each benchmark is a case file that defines MakeBenchmark(): it registers its
// own options and fills one JSON document; the Python report (scripts/benchmark_report.py)
// renders every table from that document. The programs print only progress and where the JSON
// went.
#ifndef accelvolume_benchmark_BenchmarkHarness_h
#define accelvolume_benchmark_BenchmarkHarness_h

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <vtkSmartPointer.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#ifndef ACCELVOLUME_BENCHMARK_DATA_DIR
#define ACCELVOLUME_BENCHMARK_DATA_DIR "../shared/data"
#endif

class vtkAccelVolumeHeadlessRenderWindow;
class vtkImageData;
class vtkRenderWindow;

namespace accelvolume::cli
{
class ProgressBar;
}

namespace accelvolume::benchmark
{

// Keys keep the order in which a case writes them.
using Json = nlohmann::ordered_json;
using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start);
double MsSince(Clock::time_point start);
// User + system CPU time of the whole process (every thread) in milliseconds.
double ProcessCpuMs();
// `text` as one word of a POSIX shell command line (for child processes run by std::system).
std::string ShellQuote(const std::string& text);

// --- repetition statistics ----------------------------------------------------------------------
double Median(std::vector<double> values); // NaN when empty
double Mean(const std::vector<double>& values);
// a / b, or NaN when b is not positive (a missing or zero-time measurement).
double SafeRatio(double a, double b);

// Smallest and largest finite value seen.
struct Range
{
  double Low = std::nan("");
  double High = std::nan("");
  void Add(double value);
};

// --- JSON ---------------------------------------------------------------------------------------
// `value` rounded to `digits` decimals (an integer for 0); null when not finite.
Json Round(double value, int digits);
// Every value rounded to `digits` decimals.
Json RoundAll(const std::vector<double>& values, int digits);
// A string, or null when empty.
Json StringOrNull(const std::string& text);

// --- data ---------------------------------------------------------------------------------------
// NAME_<X>x<Y>x<Z>_<type>.raw[.gz] in the data folder; the first in name order, "" if none.
std::string FindDatasetFile(const std::string& dataDir, const std::string& name);

// A volume of the data folder as most benchmarks describe it.
struct DatasetInfo
{
  std::string Name;
  std::string File;
  std::string Description; // "256x256x128 uint8"
  double Spacing[3] = { 1, 1, 1 };
  double MinSpacing = 1;
  double Range[2] = { 0, 1 };
  double LoadSeconds = 0;
};

// Finds and loads `name` (spacing from datasets.json beside it); prints why and returns null when
// it cannot.
vtkSmartPointer<vtkImageData> LoadDataset(
  const std::string& dataDir, const std::string& name, DatasetInfo& info);

// name, file, volume, spacing, [sample_distance], range, load_seconds.
Json DatasetJson(const DatasetInfo& info, bool withSampleDistance);

// --- images -------------------------------------------------------------------------------------
// RGB bytes of the front buffer, bottom row first.
std::vector<std::uint8_t> Capture(vtkRenderWindow* window, int width, int height);
// False when the PNG writer reports an error.
bool WritePng(const std::string& path, const std::vector<std::uint8_t>& rgb, int width, int height);

// --- options ------------------------------------------------------------------------------------
// Comma-separated list ("a,b"; empty items dropped) into `values`, its default shown in --help.
CLI::Option* AddList(CLI::App& app, const std::string& name, std::vector<std::string>& values,
  const std::string& help);
CLI::Option* AddList(
  CLI::App& app, const std::string& name, std::vector<int>& values, const std::string& help);
// An on|off option stored as a bool.
CLI::Option* AddOnOff(CLI::App& app, const std::string& name, bool& value, const std::string& help);
// Every item of `values` must be tf1 or tf2 (the presets of `accelvolume render --tf`).
void CheckTransferFunctions(const std::vector<std::string>& values, const std::string& option);

// --- the harness --------------------------------------------------------------------------------

// Options every benchmark has.
struct CommonOptions
{
  std::string DataDir = ACCELVOLUME_BENCHMARK_DATA_DIR;
  std::string GL = "egl";
  std::string Json;
};

// What the program runs on (every case writes the parts its schema has).
struct MachineInfo
{
  std::string Cpu;         // "model name" of /proc/cpuinfo, "" if unknown
  int HardwareThreads = 0; // std::thread::hardware_concurrency
  int SMPThreads = 0;      // vtkSMPTools::GetEstimatedNumberOfThreads at start-up
  std::string SMPBackend;
  double MemoryMiB = 0; // MemTotal
  std::string GLBackend, GLRenderer, GLVersion;
  int GLMajor = 0, GLMinor = 0;
};

// One line per case on stderr: on a terminal the CLI's progress bar, otherwise
// "accelvolume_benchmark_raycast: case 3/9: engine tf1".
class CaseProgress
{
public:
  CaseProgress(const std::string& program, int cases);
  ~CaseProgress();
  CaseProgress(const CaseProgress&) = delete;
  CaseProgress& operator=(const CaseProgress&) = delete;
  void Begin(const std::string& name);
  void Skip(int cases = 1); // cases that will not run

private:
  std::string Program;
  int Cases = 0;
  int Index = 0;
  std::unique_ptr<accelvolume::cli::ProgressBar> Bar;
};

class Harness;

// One benchmark: its options, and the run that fills the JSON document.
class Benchmark
{
public:
  virtual ~Benchmark() = default;
  virtual const char* Name() const = 0;        // "accelvolume_benchmark_octree"
  virtual const char* Description() const = 0; // one line for --help
  virtual const char* DefaultJson() const = 0;
  virtual const char* DefaultGL() const { return "egl"; }
  // Registers the benchmark's own options (the harness adds --data, --gl, --json).
  virtual void AddOptions(CLI::App& app) = 0;
  // After parsing: derived defaults and cross-checks (throw CLI::ValidationError on bad values).
  virtual void Resolve(const CLI::App& /*app*/, const MachineInfo& /*machine*/) {}
  // False: the harness opens no window (Run may open its own, e.g. in a child process).
  virtual bool NeedsWindow() const { return true; }
  // Size of the window opened before Run.
  virtual int InitialSize() const { return 512; }
  // Fills `result`; returns the exit code. The harness writes `result` unless it is null.
  virtual int Run(Harness& harness, Json& result) = 0;
};

// Each case file defines this.
std::unique_ptr<Benchmark> MakeBenchmark();

class Harness
{
public:
  CommonOptions Options;
  MachineInfo Machine;
  // The command line as main() got it (MPI initialisation needs it).
  int Argc = 0;
  char** Argv = nullptr;
  // The headless window (null when the benchmark needs none).
  vtkAccelVolumeHeadlessRenderWindow* Window() const { return this->WindowPointer; }
  int Backend() const { return this->BackendId; }
  double Seconds() const { return SecondsSince(this->Start); }
  const std::string& Program() const { return this->ProgramName; }

  // Parses, opens the window, runs the benchmark and writes its JSON; returns the exit code
  // (0 ok, 1 runtime failure, 2 usage).
  int Main(Benchmark& benchmark, int argc, char* argv[]);

  // Turns a --gl name into a backend; returns 0, or the exit code after printing why not.
  static int ResolveBackend(const std::string& gl, int& backend);
  // Backend, no multisampling, size and a first Render() so that the context exists.
  static void StartWindow(
    vtkAccelVolumeHeadlessRenderWindow* window, int backend, int width, int height);
  // Fills the GL fields of `machine` from a started window.
  static void DescribeGL(vtkAccelVolumeHeadlessRenderWindow* window, MachineInfo& machine);
  static MachineInfo DescribeMachine();
  // Writes `document` to `path`, two-space indented; false (after saying why) on failure.
  static bool WriteJson(const std::string& path, const Json& document);

private:
  std::string ProgramName;
  Clock::time_point Start = Clock::now();
  int BackendId = 0;
  vtkAccelVolumeHeadlessRenderWindow* WindowPointer = nullptr;
};

} // namespace accelvolume::benchmark

#endif
