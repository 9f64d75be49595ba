// Render: the accelvolume scene (volume, transfer functions, camera), frame timing and PNG output.
#include "Render.h"

#include "MapperSetup.h"
#include "ProgressBar.h"

#include <vtkAccelVolumeHeadlessRenderWindow.h>
#include <vtkAccelVolumeMPIExchange.h>
#include <vtkAccelVolumeSliceMapper.h>

#include <vtkCallbackCommand.h>
#include <vtkCamera.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkLogger.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkOutputWindow.h>
#include <vtkPNGWriter.h>
#include <vtkPointData.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkVolume.h>
#include <vtkVolumeProperty.h>
#include <vtkWindowToImageFilter.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <mutex>
#include <sstream>
#include <thread>

namespace accelvolume::cli
{

struct VTKMessages::State
{
  std::mutex Mutex;
  std::string FirstError;
  std::string FirstWarning;
  int Warnings = 0;

  static std::string Clean(const char* text)
  {
    // VTK formats "ERROR: In file, line N\nClass (0x...): message"; keep the message.
    std::string message = text ? text : "";
    while (!message.empty() && (message.back() == '\n' || message.back() == ' '))
    {
      message.pop_back();
    }
    message = message.substr(message.find_last_of('\n') + 1);
    const auto prefix = message.find("): ");
    return prefix == std::string::npos ? message : message.substr(prefix + 3);
  }
  void Error(const char* text)
  {
    std::lock_guard<std::mutex> lock(this->Mutex);
    if (this->FirstError.empty())
    {
      this->FirstError = Clean(text);
      this->FirstError = this->FirstError.empty() ? "unknown VTK error" : this->FirstError;
    }
  }
  void Warning(const char* text)
  {
    std::lock_guard<std::mutex> lock(this->Mutex);
    if (this->Warnings++ == 0)
    {
      this->FirstWarning = Clean(text);
    }
  }
};

namespace
{

class CaptureOutputWindow : public vtkOutputWindow
{
public:
  static CaptureOutputWindow* New();
  vtkTypeMacro(CaptureOutputWindow, vtkOutputWindow);
  void DisplayText(const char*) override {}
  void DisplayDebugText(const char*) override {}
  void DisplayErrorText(const char* text) override { this->Sink->Error(text); }
  void DisplayWarningText(const char* text) override { this->Sink->Warning(text); }
  void DisplayGenericWarningText(const char* text) override { this->Sink->Warning(text); }
  VTKMessages::State* Sink = nullptr;
};
vtkStandardNewMacro(CaptureOutputWindow);

void LoggerCallback(void* data, const vtkLogger::Message& message)
{
  auto* state = static_cast<VTKMessages::State*>(data);
  if (message.verbosity <= vtkLogger::VERBOSITY_ERROR)
  {
    state->Error(message.message);
  }
  else if (message.verbosity == vtkLogger::VERBOSITY_WARNING)
  {
    state->Warning(message.message);
  }
}

vtkSmartPointer<CaptureOutputWindow> TheOutputWindow;

} // namespace

VTKMessages::VTKMessages()
  : Data(new State)
{
  TheOutputWindow = vtkSmartPointer<CaptureOutputWindow>::New();
  TheOutputWindow->Sink = this->Data;
  vtkLogger::AddCallback(
    "accelvolume-capture", &LoggerCallback, this->Data, vtkLogger::VERBOSITY_WARNING);
  this->Install();
}

VTKMessages::~VTKMessages()
{
  vtkLogger::RemoveCallback("accelvolume-capture");
  vtkOutputWindow::SetInstance(nullptr);
  TheOutputWindow = nullptr;
  delete this->Data;
}

void VTKMessages::Install()
{
  vtkOutputWindow::SetInstance(TheOutputWindow);
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
}

void VTKMessages::ThrowIfError(const std::string& context)
{
  std::string error;
  {
    std::lock_guard<std::mutex> lock(this->Data->Mutex);
    error.swap(this->Data->FirstError);
  }
  if (!error.empty())
  {
    throw CliError(ExitRuntime, context + ": " + error);
  }
}

std::string VTKMessages::TakeError()
{
  std::string error;
  std::lock_guard<std::mutex> lock(this->Data->Mutex);
  error.swap(this->Data->FirstError);
  return error;
}

void VTKMessages::Clear()
{
  std::lock_guard<std::mutex> lock(this->Data->Mutex);
  this->Data->FirstError.clear();
}

int VTKMessages::GetNumberOfWarnings() const
{
  return this->Data->Warnings;
}

std::string VTKMessages::GetFirstWarning() const
{
  return this->Data->FirstWarning;
}

namespace
{

void CropPlanes(const Options& options, vtkImageData* image, double planes[6])
{
  const double* origin = image->GetOrigin();
  const double* spacing = image->GetSpacing();
  const int* extent = image->GetExtent();
  for (int i = 0; i < 6; ++i)
  {
    const int axis = i / 2;
    planes[i] = origin[axis] + (extent[2 * axis] + options.crop[i]) * spacing[axis];
  }
}

std::string RendererFromCapabilities(vtkRenderWindow* window)
{
  auto* openGL = vtkOpenGLRenderWindow::SafeDownCast(window);
  const char* report = openGL ? openGL->ReportCapabilities() : nullptr;
  std::istringstream lines(report ? report : "");
  const std::string key = "OpenGL renderer string:";
  for (std::string line; std::getline(lines, line);)
  {
    if (line.compare(0, key.size(), key) == 0)
    {
      const auto first = line.find_first_not_of(' ', key.size());
      return first == std::string::npos ? "unknown" : line.substr(first);
    }
  }
  return "unknown";
}

double Milliseconds(std::chrono::steady_clock::duration duration)
{
  return std::chrono::duration<double, std::milli>(duration).count();
}

// Test hook (the MPI fault tests, Testing/CLI/CliMpiFaultTests.cmake): the environment variable
// ACCELVOLUME_FAULT=KIND:RANK[:frame=N][:at=start|gather] makes rank RANK, in its N-th render
// (default 1; the warm-up frame is 1), hang forever (KIND hang), die by SIGKILL (die) or call
// std::abort (abort), either when the mapper starts the frame (at=start: before the ranks agree on
// the frame's status) or after compositing its band, before sending it to rank 0 (at=gather, the
// default). Not for users: it exists to show that the other ranks do not wait forever.
struct FaultInjection
{
  enum class Kind
  {
    None,
    Hang,
    Die,
    Abort
  };
  Kind What = Kind::None;
  int Rank = 0;
  int Frame = 1;
  bool AtStart = false;

  static FaultInjection FromEnvironment()
  {
    FaultInjection fault;
    const char* value = std::getenv("ACCELVOLUME_FAULT");
    const std::string text = value ? value : "";
    if (text.empty())
    {
      return fault;
    }
    const auto invalid = [&]()
    {
      return CliError(ExitUsage,
        "invalid ACCELVOLUME_FAULT '" + text +
          "' (test hook; expected hang|die|abort:RANK[:frame=N][:at=start|gather])");
    };
    std::vector<std::string> fields;
    std::istringstream stream(text);
    for (std::string field; std::getline(stream, field, ':');)
    {
      fields.push_back(field);
    }
    const auto number = [&](const std::string& digits, int low)
    {
      if (digits.empty() || digits.size() > 6 ||
        digits.find_first_not_of("0123456789") != std::string::npos || std::stoi(digits) < low)
      {
        throw invalid();
      }
      return std::stoi(digits);
    };
    if (fields.size() < 2 || fields.size() > 4)
    {
      throw invalid();
    }
    const std::string& kind = fields[0];
    fault.What = kind == "hang" ? Kind::Hang
      : kind == "die"           ? Kind::Die
      : kind == "abort"         ? Kind::Abort
                                : throw invalid();
    fault.Rank = number(fields[1], 0);
    for (std::size_t i = 2; i < fields.size(); ++i)
    {
      if (fields[i].compare(0, 6, "frame=") == 0)
      {
        fault.Frame = number(fields[i].substr(6), 1);
      }
      else if (fields[i] == "at=start" || fields[i] == "at=gather")
      {
        fault.AtStart = fields[i] == "at=start";
      }
      else
      {
        throw invalid();
      }
    }
    return fault;
  }

  [[noreturn]] void Strike() const
  {
    switch (this->What)
    {
      case Kind::Die:
        std::raise(SIGKILL);
        break;
      case Kind::Abort:
        std::abort();
      default:
        break;
    }
    for (;;) // hang (and what SIGKILL leaves): until the MPI launcher ends the job
    {
      std::this_thread::sleep_for(std::chrono::hours(1));
    }
  }
};

} // namespace

void ThrowIfAnyRankFailed(
  vtkAccelVolumeMPIExchange* mpi, int code, const std::string& message, const char* what)
{
  if (!mpi)
  {
    if (code != 0)
    {
      throw CliError(code, message);
    }
    return;
  }
  const vtkAccelVolumeMPIExchange::Failure failure = mpi->AgreeOnFailure(code, message, what);
  if (failure.Rank < 0)
  {
    return;
  }
  if (failure.Rank == mpi->GetRank())
  {
    throw CliError(failure.Code, message, true);
  }
  throw CliError(
    failure.Code, "rank " + std::to_string(failure.Rank) + ": " + failure.Message, true);
}

void CheckCrop(const Options& options, vtkImageData* image)
{
  if (!options.haveCrop)
  {
    return;
  }
  int dims[3];
  image->GetDimensions(dims);
  for (int axis = 0; axis < 3; ++axis)
  {
    const double low = options.crop[2 * axis], high = options.crop[2 * axis + 1];
    if (!(low < high) || low < 0 || high > dims[axis] - 1)
    {
      std::ostringstream message;
      message << "--crop "
              << "XYZ"[axis] << " range " << low << " " << high
              << (low < high ? " lies outside the volume" : " is inverted or empty")
              << " (valid: 0 <= lo < hi <= " << dims[axis] - 1 << ")";
      throw CliError(ExitUsage, message.str());
    }
  }
}

// The window (--window or the data range), the raysum unit and the sample distance.
void ChooseRanges(const Options& options, vtkImageData* image, RenderResult& result)
{
  image->GetPointData()->GetScalars()->GetRange(result.scalarRange, 0);
  if (options.haveWindow)
  {
    std::copy(options.window, options.window + 2, result.window);
  }
  else
  {
    result.window[0] = result.scalarRange[0];
    result.window[1] = result.scalarRange[1] > result.scalarRange[0] ? result.scalarRange[1]
                                                                     : result.scalarRange[0] + 1;
  }

  const double* spacing = image->GetSpacing();
  double bounds[6];
  image->GetBounds(bounds);
  const double extents[3] = { bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4] };
  const double largest = std::max({ extents[0], extents[1], extents[2] });
  const double diagonal =
    std::sqrt(extents[0] * extents[0] + extents[1] * extents[1] + extents[2] * extents[2]);
  result.raysumUnit = options.haveRaysumUnit ? options.raysumUnit : (largest > 0 ? largest / 4 : 1);
  if (options.haveSampleDistance)
  {
    result.sampleDistance = options.sampleDistance;
    result.sampleDistanceSource = "flag";
  }
  else if (options.slices > 0)
  {
    result.sampleDistance = (diagonal > 0 ? diagonal : 1) / options.slices;
    result.sampleDistanceSource = "slices";
  }
  else
  {
    result.sampleDistance = std::min({ spacing[0], spacing[1], spacing[2] });
    result.sampleDistanceSource = "min-spacing";
  }
}

// Blend mode, input and cropping of the mapper.
void ConfigureMapper(
  const Options& options, vtkImageData* image, vtkVolumeMapper* mapper, RenderResult& result)
{
  switch (options.blend)
  {
    case BlendKind::MIP:
      mapper->SetBlendModeToMaximumIntensity();
      break;
    case BlendKind::MinIP:
      mapper->SetBlendModeToMinimumIntensity();
      break;
    case BlendKind::Additive:
      mapper->SetBlendModeToAdditive();
      break;
    case BlendKind::Average:
      mapper->SetBlendModeToAverageIntensity();
      break;
    case BlendKind::Composite:
      mapper->SetBlendModeToComposite();
      break;
  }
  mapper->SetInputData(image);
  if (options.haveCrop)
  {
    CropPlanes(options, image, result.cropPlanes);
    mapper->SetCropping(1);
    mapper->SetCroppingRegionPlanes(result.cropPlanes);
    mapper->SetCroppingRegionFlagsToSubVolume();
  }
}

// Front view: looking along +z at the centre, view-up +y; then the requested moves.
void PlaceCamera(const Options& options, const double bounds[6], vtkRenderer* renderer)
{
  vtkCamera* camera = renderer->GetActiveCamera();
  const double centre[3] = { (bounds[0] + bounds[1]) / 2, (bounds[2] + bounds[3]) / 2,
    (bounds[4] + bounds[5]) / 2 };
  camera->SetFocalPoint(centre);
  camera->SetPosition(centre[0], centre[1], centre[2] - 1);
  camera->SetViewUp(0, 1, 0);
  camera->SetParallelProjection(options.parallel);
  renderer->ResetCamera();
  camera->Azimuth(options.azimuth);
  camera->Elevation(options.elevation);
  camera->OrthogonalizeViewUp();
  camera->Roll(options.roll);
  camera->Zoom(options.zoom);
  renderer->ResetCameraClippingRange();
}

vtkSmartPointer<vtkRenderWindow> CreateWindow(const Options& options, vtkRenderer* renderer)
{
  auto window = vtkSmartPointer<vtkRenderWindow>::Take(vtkRenderWindow::New());
  if (!window)
  {
    throw CliError(ExitRuntime, "cannot create a render window");
  }
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(0);
  window->SetSize(options.size[0], options.size[1]);
  window->AddRenderer(renderer);
  return window;
}

// ACCELVOLUME_FAULT (test hook): strikes from the mapper's own events on the main thread.
void PrepareFault(const FaultInjection& fault, vtkCallbackCommand* onFault)
{
  onFault->SetClientData(const_cast<FaultInjection*>(&fault));
  onFault->SetCallback(
    [](vtkObject*, unsigned long event, void* client, void* data)
    {
      const auto* plan = static_cast<const FaultInjection*>(client);
      // The shear-warp mapper reports 0.75 once its band is composited, before the gather;
      // VTK's pipeline sends 1 of its own when it updates a modified mapper.
      const double value =
        event == vtkCommand::ProgressEvent && data ? *static_cast<double*>(data) : -1;
      const bool due =
        plan->AtStart ? event == vtkCommand::StartEvent : value >= 0.75 && value < 0.9;
      if (due)
      {
        plan->Strike();
      }
    });
}

// The GL backend and renderer names for --stats, and the mappers' own results.
void ReadResults(const MapperSet& mappers, vtkImageData* image, vtkRenderWindow* window,
  vtkCamera* camera, VTKMessages& messages, vtkAccelVolumeMPIExchange* mpi, RenderResult& result)
{
  auto* headless = vtkAccelVolumeHeadlessRenderWindow::SafeDownCast(window);
  if (headless)
  {
    result.glBackend =
      vtkAccelVolumeHeadlessRenderWindow::GetBackendName(headless->GetActiveBackend());
  }
  else
  {
    const std::string name = window->GetClassName();
    result.glBackend = name.find("XOpenGL") != std::string::npos ? "x" : name;
  }
  ReadMapperResults(mappers, image, camera, mpi, result);
  const char* rendererName = nullptr;
  if (result.sliceUsed)
  {
    rendererName = mappers.Slice->GetOpenGLRenderer();
  }
  else if (headless)
  {
    rendererName = headless->GetOpenGLRendererString();
  }
  result.glRenderer =
    rendererName && *rendererName ? rendererName : RendererFromCapabilities(window);
  messages.Clear(); // a failed capability query is not a render failure
}

void WritePng(const Options& options, vtkRenderWindow* window, VTKMessages& messages)
{
  if (!options.outPath.empty())
  {
    vtkNew<vtkWindowToImageFilter> grab;
    grab->SetInput(window);
    grab->ReadFrontBufferOff();
    grab->ShouldRerenderOff();
    grab->SetInputBufferTypeToRGB();
    grab->Update();
    vtkNew<vtkPNGWriter> writer;
    writer->SetFileName(options.outPath.c_str());
    writer->SetInputConnection(grab->GetOutputPort());
    writer->Write();
    messages.ThrowIfError("cannot write '" + options.outPath + "'");
    if (writer->GetErrorCode() != 0)
    {
      throw CliError(ExitRuntime, "cannot write '" + options.outPath + "'");
    }
  }
}

RenderResult RunRender(const Options& options, const TransferFunctionSpec& tf, vtkImageData* image,
  VTKMessages& messages, vtkAccelVolumeMPIExchange* mpi)
{
  const FaultInjection fault = FaultInjection::FromEnvironment();
  RenderResult result;
  ChooseRanges(options, image, result);
  // Transfer functions and lighting shared by every mapper.
  vtkNew<vtkVolumeProperty> property;
  result.transferFunction = ApplyTransferFunction(tf, options, result.window, property);

  const MapperSet mappers = CreateMapper(options, result, mpi);
  vtkVolumeMapper* mapper = mappers.Mapper;
  ConfigureMapper(options, image, mapper, result);
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  volume->SetProperty(property);
  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(options.background[0], options.background[1], options.background[2]);
  renderer->AddVolume(volume);
  double bounds[6];
  image->GetBounds(bounds);
  PlaceCamera(options, bounds, renderer);
  vtkCamera* camera = renderer->GetActiveCamera();
  const vtkSmartPointer<vtkRenderWindow> window = CreateWindow(options, renderer);
  // --mpi: the ranks render in lockstep, so a failure on any rank must stop every rank (a rank
  // left alone would wait for the failed one forever); rank 0 reports the failed rank's error.
  const auto agree = [&](const std::string& context)
  {
    const std::string error = messages.TakeError();
    ThrowIfAnyRankFailed(mpi, error.empty() ? 0 : ExitRuntime,
      error.empty() ? std::string() : context + ": " + error, "render status");
  };
  agree("cannot set up the render window");

  // The bar (stderr; see options.progress): one task per frame, the warm-up first, each filled by
  // the mapper's ProgressEvent (VTK's own mappers send none: their frames fill at once).
  ProgressBar bar("render", options.progress);
  vtkNew<vtkCallbackCommand> onProgress;
  if (bar.IsShown())
  {
    onProgress->SetClientData(&bar);
    onProgress->SetCallback([](vtkObject*, unsigned long, void* client, void* data)
      { static_cast<ProgressBar*>(client)->Update(*static_cast<double*>(data)); });
    mapper->AddObserver(vtkCommand::ProgressEvent, onProgress);
  }
  const int tasks = options.frames + 1;

  int renders = 0;
  vtkNew<vtkCallbackCommand> onFault;
  const bool faultHere =
    fault.What != FaultInjection::Kind::None && fault.Rank == (mpi ? mpi->GetRank() : 0);
  if (faultHere)
  {
    PrepareFault(fault, onFault);
  }

  vtkNew<vtkUnsignedCharArray> pixel;
  auto renderFrame = [&](int task)
  {
    if (faultHere && ++renders == fault.Frame)
    {
      mapper->AddObserver(vtkCommand::StartEvent, onFault);
      mapper->AddObserver(vtkCommand::ProgressEvent, onFault);
    }
    bar.BeginTask(task, tasks, task == 0 ? "first frame" : "frame");
    const auto start = std::chrono::steady_clock::now();
    window->Render();
    // Reading one pixel back waits for the GPU, so the frame time includes its work.
    window->GetPixelData(0, 0, 0, 0, 0, pixel, 0);
    const double ms = Milliseconds(std::chrono::steady_clock::now() - start);
    bar.Update(1.0);
    agree("render failed");
    return ms;
  };
  result.firstFrameMs = renderFrame(0);
  ReadFirstFrame(mappers, result);
  for (int frame = 0; frame < options.frames; ++frame)
  {
    if (frame > 0)
    {
      camera->Azimuth(2.0);
      renderer->ResetCameraClippingRange();
    }
    result.frameMs.push_back(renderFrame(frame + 1));
  }
  bar.Finish();
  mapper->RemoveObserver(onProgress);

  ReadResults(mappers, image, window, camera, messages, mpi, result);
  if (!options.outPath.empty())
  {
    WritePng(options, window, messages);
  }
  return result;
}

} // namespace accelvolume::cli
