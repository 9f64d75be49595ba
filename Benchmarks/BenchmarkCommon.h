// Helpers shared by the benchmark programs: option parsing, report formatting, timing and the
// headless window / image plumbing around the timed renders.
#ifndef accelvolume_benchmark_BenchmarkCommon_h
#define accelvolume_benchmark_BenchmarkCommon_h

#include <chrono>
#include <cstdint>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

class vtkAccelVolumeHeadlessRenderWindow;
class vtkRenderWindow;

namespace accelvolume::cli
{
class ProgressBar;
}

namespace accelvolume::benchmark
{

// Which case of how many a benchmark is on, one stderr line per case (stdout keeps the tables):
// on a terminal the CLI's progress bar, drawn at the case's start and ended at once so the
// tables printed meanwhile never land inside it ("raycast [####......]  33%  3/9  engine tf1");
// otherwise "accelvolume_benchmark_raycast: case 3/9: engine tf1".
class CaseProgress
{
public:
  CaseProgress(const std::string& program, int cases);
  ~CaseProgress();
  CaseProgress(const CaseProgress&) = delete;
  CaseProgress& operator=(const CaseProgress&) = delete;

  // Announces the next case.
  void Begin(const std::string& name);
  // Counts cases that will not run (a dataset that failed to load, skipped sizes).
  void Skip(int cases = 1);

private:
  std::string Program;
  int Cases = 0;
  int Index = 0;
  std::unique_ptr<accelvolume::cli::ProgressBar> Bar; // on a terminal only
};

// One option value per field; the field's type picks the conversion. atoi / atof are kept from
// the original parsers, so a malformed number still reads as 0 rather than being an error.
void TakeValue(const char* text, std::string& value);
void TakeValue(const char* text, int& value);
void TakeValue(const char* text, double& value);

// True when argv[i] is `name` and is followed by one value per field, which it then consumes
// (advancing `i`); a missing value is reported and reads as "not this option".
template <typename... Values>
bool TakeOption(int argc, char* argv[], int& i, const char* name, Values&... values)
{
  if (std::string(argv[i]) != name)
  {
    return false;
  }
  if (i + static_cast<int>(sizeof...(values)) >= argc)
  {
    std::cerr << "missing value after " << argv[i] << "\n";
    return false;
  }
  (TakeValue(argv[++i], values), ...);
  return true;
}

// Comma-separated list; empty items (",," or a trailing comma) are dropped.
std::vector<std::string> SplitList(const std::string& list);

// `text` with quotes, backslashes and control characters escaped for a JSON string.
std::string JsonEscape(const std::string& text);

// Fixed-point text, or "null" (valid JSON) when the value is not finite.
std::string Num(double value, int precision);

// a / b, or NaN when b is not positive (a missing or zero-time measurement).
double SafeRatio(double a, double b);

using Clock = std::chrono::steady_clock;
double SecondsSince(Clock::time_point start);
double MsSince(Clock::time_point start);

// NAME_<X>x<Y>x<Z>_<type>.raw[.gz] in the data folder; the first in name order, "" if none.
std::string FindDatasetFile(const std::string& dataDir, const std::string& name);

// Turns --gl into a headless backend. Returns 0, or the exit code after printing why it can't be
// used: 2 for a bad name, 1 for a backend this machine lacks.
int ResolveHeadlessBackend(const std::string& gl, int& backend);

// Backend, no multisampling (it would change both the timings and the compared pixels), size, and
// a first Render() so that the GL context exists before its strings are queried.
void StartHeadlessWindow(
  vtkAccelVolumeHeadlessRenderWindow* window, int backend, int width, int height);

// RGB bytes of the front buffer, bottom row first.
std::vector<std::uint8_t> Capture(vtkRenderWindow* window, int width, int height);

// False when the PNG writer reports an error.
bool WritePng(const std::string& path, const std::vector<std::uint8_t>& rgb, int width, int height);

} // namespace accelvolume::benchmark

#endif
