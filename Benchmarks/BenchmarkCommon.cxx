// Helpers shared by the benchmark programs (see BenchmarkCommon.h).
#include "BenchmarkCommon.h"

#include "ProgressBar.h" // the accelvolume CLI's bar
#include "vtkAccelVolumeHeadlessRenderWindow.h"

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkPointData.h>
#include <vtkRenderWindow.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <regex>
#include <sstream>

namespace fs = std::filesystem;

namespace accelvolume::benchmark
{

CaseProgress::CaseProgress(const std::string& program, int cases)
  : Program(program)
  , Cases(std::max(cases, 1))
{
  if (accelvolume::cli::StderrIsTerminal())
  {
    const std::string label = program.substr(program.rfind('_') + 1); // "raycast"
    this->Bar = std::make_unique<accelvolume::cli::ProgressBar>(
      label, accelvolume::cli::ProgressMode::On);
  }
}

CaseProgress::~CaseProgress() = default;

void CaseProgress::Begin(const std::string& name)
{
  std::cout << std::flush; // the tables so far come first
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

void TakeValue(const char* text, std::string& value)
{
  value = text;
}
void TakeValue(const char* text, int& value)
{
  value = std::atoi(text);
}
void TakeValue(const char* text, double& value)
{
  value = std::atof(text);
}

std::vector<std::string> SplitList(const std::string& list)
{
  std::vector<std::string> items;
  std::stringstream stream(list);
  std::string item;
  while (std::getline(stream, item, ','))
  {
    if (!item.empty())
    {
      items.push_back(item);
    }
  }
  return items;
}

std::string JsonEscape(const std::string& text)
{
  std::string out;
  for (char c : text)
  {
    if (c == '"' || c == '\\')
    {
      out += '\\';
      out += c;
    }
    else if (static_cast<unsigned char>(c) < 0x20)
    {
      char buffer[8];
      std::snprintf(buffer, sizeof(buffer), "\\u%04x", c);
      out += buffer;
    }
    else
    {
      out += c;
    }
  }
  return out;
}

std::string Num(double value, int precision)
{
  if (!std::isfinite(value))
  {
    return "null";
  }
  std::ostringstream stream;
  stream << std::setprecision(precision) << std::fixed << value;
  return stream.str();
}

double SafeRatio(double a, double b)
{
  return b > 0 ? a / b : std::nan("");
}

double SecondsSince(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

double MsSince(Clock::time_point start)
{
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
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

int ResolveHeadlessBackend(const std::string& gl, int& backend)
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

void StartHeadlessWindow(
  vtkAccelVolumeHeadlessRenderWindow* window, int backend, int width, int height)
{
  window->SetBackend(backend);
  window->SetMultiSamples(0);
  window->SetSize(width, height);
  window->Render(); // creates the context
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

} // namespace accelvolume::benchmark
