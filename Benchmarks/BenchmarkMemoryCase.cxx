// The child side of accelvolume_benchmark_memory: load or generate the volume, render two frames
// with one mapper, and report resident memory at each step (see BenchmarkMemoryCase.h).
#include "BenchmarkMemoryCase.h"

#include "Options.h"
#include "TransferFunctions.h"
#include "VolumeIO.h"

#include "vtkAccelVolumeHeadlessRenderWindow.h"
#include "vtkAccelVolumeRayCastMapper.h"
#include "vtkAccelVolumeShearWarpMapper.h"
#include "vtkAccelVolumeSliceMapper.h"

#include <vtkCamera.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkFixedPointVolumeRayCastMapper.h>
#include <vtkGPUVolumeRayCastMapper.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkOutputWindow.h>
#include <vtkPointData.h>
#include <vtkRenderer.h>
#include <vtkSMPTools.h>
#include <vtkSmartPointer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnsignedShortArray.h>
#include <vtkVolume.h>
#include <vtkVolumeProperty.h>

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <new>

namespace accelvolume::benchmark::memory
{
namespace
{
// "VmRSS" / "VmHWM" of /proc/self/status in MiB; -1 when unreadable.
double StatusMiB(const char* key)
{
  std::ifstream status("/proc/self/status");
  std::string line;
  const std::string prefix = std::string(key) + ":";
  while (std::getline(status, line))
  {
    if (line.rfind(prefix, 0) == 0)
    {
      return std::atof(line.c_str() + prefix.size()) / 1024.0; // the kernel writes kB
    }
  }
  return -1;
}

// Resets the high-water mark to the current RSS (Linux 4.0+); false when not allowed.
bool ResetPeak()
{
  std::ofstream clear("/proc/self/clear_refs");
  clear << "5" << std::flush;
  return static_cast<bool>(clear);
}

// Keeps the first VTK error (the output window reports every vtkErrorMacro).
class FirstError : public vtkCommand
{
public:
  static FirstError* New() { return new FirstError; }
  void Execute(vtkObject*, unsigned long, void* data) override
  {
    if (this->Text.empty())
    {
      this->Text = data ? static_cast<const char*>(data) : "(unknown VTK error)";
    }
  }
  std::string Text;
};

// A CT-like uint16 phantom written straight into the scalars, one z slab per task (no float
// volume in between): air with faint noise, an elliptic body of soft tissue (1000) with two
// lungs (150), a ribbed shell (2600) and a spine (2900). About the chest CT's value range.
vtkSmartPointer<vtkImageData> MakeProcedural(const int dims[3])
{
  const std::size_t count = static_cast<std::size_t>(dims[0]) * dims[1] * dims[2];
  vtkNew<vtkUnsignedShortArray> scalars;
  scalars->SetName("scalars");
  scalars->SetNumberOfValues(static_cast<vtkIdType>(count)); // every value is written below
  unsigned short* out = scalars->GetPointer(0);
  vtkSMPTools::For(0, dims[2],
    [&](vtkIdType k0, vtkIdType k1)
    {
      for (vtkIdType k = k0; k < k1; ++k)
      {
        const double z = 2.0 * (k + 0.5) / dims[2] - 1.0;
        const bool rib = std::sin(40.0 * z) > 0.2;
        for (int j = 0; j < dims[1]; ++j)
        {
          const double y = 2.0 * (j + 0.5) / dims[1] - 1.0;
          unsigned short* row = out + (static_cast<std::size_t>(k) * dims[1] + j) * dims[0];
          for (int i = 0; i < dims[0]; ++i)
          {
            const double x = 2.0 * (i + 0.5) / dims[0] - 1.0;
            const double body = (x / 0.85) * (x / 0.85) + (y / 0.65) * (y / 0.65);
            double value = 0;
            if (body < 1.0 && std::abs(z) < 0.9)
            {
              const double lx = std::abs(x) - 0.4;
              const bool lung =
                (lx / 0.28) * (lx / 0.28) + (y / 0.4) * (y / 0.4) + (z / 0.75) * (z / 0.75) < 1.0;
              const bool spine = x * x + (y + 0.45) * (y + 0.45) < 0.01;
              value = spine ? 2900.0 : (body > 0.8 && rib ? 2600.0 : (lung ? 150.0 : 1000.0));
            }
            std::uint32_t h = static_cast<std::uint32_t>(i) * 73856093u ^
              static_cast<std::uint32_t>(j) * 19349663u ^ static_cast<std::uint32_t>(k) * 83492791u;
            h ^= h >> 13;
            h *= 0x5bd1e995u;
            h ^= h >> 15;
            row[i] = static_cast<unsigned short>(value + static_cast<double>(h % 61u));
          }
        }
      }
    });
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(dims[0], dims[1], dims[2]);
  image->GetPointData()->SetScalars(scalars);
  return image;
}

vtkSmartPointer<vtkImageData> LoadCaseVolume(
  const Options& options, double& seconds, std::string& error)
{
  const auto start = Clock::now();
  vtkSmartPointer<vtkImageData> image;
  if (options.ChildVolume == ProceduralName)
  {
    image = MakeProcedural(options.ProceduralDims);
  }
  else
  {
    accelvolume::cli::VolumeRequest request;
    request.inputPath = FindDatasetFile(options.DataDir, options.ChildVolume);
    error = "no file " + options.ChildVolume + "_<X>x<Y>x<Z>_<type>.raw[.gz] in " + options.DataDir;
    if (!request.inputPath.empty())
    {
      image = accelvolume::cli::LoadVolume(request, error); // spacing from datasets.json
    }
  }
  seconds = SecondsSince(start);
  return image;
}

// The mapper with the other benchmarks' settings: one sample per smallest voxel spacing, full
// image resolution, no automatic adjustment; `threads` for the multi-threaded CPU mappers.
vtkSmartPointer<vtkVolumeMapper> MakeMapper(const std::string& id, double sampleDistance,
  int threads, vtkAccelVolumeRayCastMapper*& rayCast, vtkAccelVolumeShearWarpMapper*& shearWarp)
{
  rayCast = nullptr;
  shearWarp = nullptr;
  if (id == "slice")
  {
    return vtkSmartPointer<vtkAccelVolumeSliceMapper>::New(); // one slice per smallest spacing
  }
  if (id.rfind("raycast-", 0) == 0)
  {
    auto mapper = vtkSmartPointer<vtkAccelVolumeRayCastMapper>::New();
    mapper->SetAutoAdjustSampleDistances(0);
    mapper->SetSampleDistance(sampleDistance);
    mapper->SetInteractiveSampleDistance(sampleDistance);
    mapper->SetImageSampleDistance(1.0);
    mapper->SetNumberOfThreads(threads);
    mapper->SetLeapMode(id == "raycast-none"
        ? vtkAccelVolumeRayCastMapper::LEAP_NONE
        : (id == "raycast-octree" ? vtkAccelVolumeRayCastMapper::LEAP_OCTREE
                                  : vtkAccelVolumeRayCastMapper::LEAP_DISTANCE_MAP));
    rayCast = mapper;
    return mapper;
  }
  if (id.rfind("shearwarp-", 0) == 0)
  {
    auto mapper = vtkSmartPointer<vtkAccelVolumeShearWarpMapper>::New();
    mapper->SetNumberOfThreads(id == "shearwarp-1" ? 1 : threads);
    shearWarp = mapper;
    return mapper;
  }
  if (id == "vtk-fixed")
  {
    auto mapper = vtkSmartPointer<vtkFixedPointVolumeRayCastMapper>::New();
    mapper->SetAutoAdjustSampleDistances(0);
    mapper->SetLockSampleDistanceToInputSpacing(0);
    mapper->SetSampleDistance(static_cast<float>(sampleDistance));
    mapper->SetInteractiveSampleDistance(static_cast<float>(sampleDistance));
    mapper->SetImageSampleDistance(1.0f);
    mapper->SetNumberOfThreads(threads);
    return mapper;
  }
  auto mapper = vtkSmartPointer<vtkGPUVolumeRayCastMapper>::New();
  mapper->SetAutoAdjustSampleDistances(0);
  mapper->SetSampleDistance(static_cast<float>(sampleDistance));
  return mapper;
}

// Writes the result to the parent's pipe (all of it: a pipe may take it in parts).
void Send(int fd, const ChildResult& result)
{
  const std::string text = ChildResultJson(result).dump();
  std::size_t done = 0;
  while (done < text.size())
  {
    const ssize_t n = write(fd, text.data() + done, text.size() - done);
    if (n <= 0)
    {
      break;
    }
    done += static_cast<std::size_t>(n);
  }
  close(fd);
}

} // namespace

int RunChildCase(const Options& options)
{
  ChildResult result;
  if (options.MemoryLimit > 0)
  {
    const rlim_t bytes = static_cast<rlim_t>(options.MemoryLimit * 1024.0 * 1024.0);
    const rlimit limit{ bytes, bytes };
    setrlimit(RLIMIT_AS, &limit); // best effort: without it the case runs uncapped
  }
  int backend = 0;
  if (Harness::ResolveBackend(options.GL, backend) != 0)
  {
    result.Error = "headless backend " + options.GL + " is not available";
    Send(options.ChildFd, result);
    return 0;
  }
  vtkNew<FirstError> errors;
  vtkOutputWindow::GetInstance()->AddObserver(vtkCommand::ErrorEvent, errors);

  // The GL context first, so that the baseline holds it and the volume.
  vtkNew<vtkAccelVolumeHeadlessRenderWindow> window;
  Harness::StartWindow(window, backend, options.Size, options.Size);
  result.GlRenderer = window->GetOpenGLRendererString();
  result.GlBackend = vtkAccelVolumeHeadlessRenderWindow::GetBackendName(window->GetActiveBackend());
  result.RssStart = StatusMiB("VmRSS");
  std::string error;
  vtkSmartPointer<vtkImageData> image = LoadCaseVolume(options, result.LoadSeconds, error);
  if (!image)
  {
    result.Error = error;
    Send(options.ChildFd, result);
    return 0;
  }
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  result.Volume = accelvolume::cli::DescribeVolume(image);
  result.VolumeBytes =
    static_cast<double>(scalars->GetNumberOfValues()) * scalars->GetDataTypeSize();
  double range[2];
  scalars->GetRange(range); // cached in the array; every mapper asks for it
  double spacing[3];
  image->GetSpacing(spacing);
  const double sampleDistance = *std::min_element(spacing, spacing + 3);

  // The scene: small objects only, before the baseline.
  vtkAccelVolumeRayCastMapper* rayCast = nullptr;
  vtkAccelVolumeShearWarpMapper* shearWarp = nullptr;
  vtkSmartPointer<vtkVolumeMapper> mapper =
    MakeMapper(options.ChildMapper, sampleDistance, options.Threads, rayCast, shearWarp);
  mapper->SetInputData(image);
  mapper->SetBlendModeToComposite();
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  accelvolume::cli::Options cli;
  cli.blend = accelvolume::cli::BlendKind::Composite;
  cli.haveShade = true;
  cli.shade = options.Shade;
  cli.transferFunction = options.Tf;
  const double tfWindow[2] = { range[0], range[1] > range[0] ? range[1] : range[0] + 1 };
  accelvolume::cli::ApplyTransferFunction(
    accelvolume::cli::LoadTransferFunction(cli), cli, tfWindow, volume->GetProperty());
  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(0, 0, 0);
  renderer->AddVolume(volume);
  window->AddRenderer(renderer);
  // Parallel projection for every mapper (shear-warp needs it), oblique view.
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->ParallelProjectionOn();
  renderer->ResetCamera();
  camera->Azimuth(30);
  camera->Elevation(20);
  camera->OrthogonalizeViewUp();
  renderer->ResetCamera();

  result.LoadPeak = StatusMiB("VmHWM");
  result.RssLoaded = StatusMiB("VmRSS");
  result.PeakReset = ResetPeak();
  vtkNew<vtkUnsignedCharArray> onePixel;
  auto frame = [&]()
  {
    const auto start = Clock::now();
    window->Render();
    static_cast<vtkRenderWindow*>(window)->GetPixelData(0, 0, 0, 0, 0, onePixel.Get()); // finish
    return MsSince(start);
  };
  // Frames 1-2, then frame 3 after a transfer-function change (the window 2 % wider): what an
  // interactive edit costs, its peak measured from the RSS after frame 2.
  const double wider[2] = { tfWindow[0], tfWindow[1] + 0.02 * (tfWindow[1] - tfWindow[0]) };
  try
  {
    result.FirstMs = frame();
    camera->Azimuth(5);
    renderer->ResetCameraClippingRange();
    result.SecondMs = frame();
    result.RssAfter = StatusMiB("VmRSS");
    result.Peak = StatusMiB("VmHWM");
    ResetPeak();
    accelvolume::cli::ApplyTransferFunction(
      accelvolume::cli::LoadTransferFunction(cli), cli, wider, volume->GetProperty());
    result.TfMs = frame();
    result.TfPeak = StatusMiB("VmHWM");
  }
  catch (const std::bad_alloc&)
  {
    // Reported with the readings so far; the process may be in no state to go on.
    result.Error = "out of memory (std::bad_alloc) within the " +
      Json(Round(options.MemoryLimit / 1024, 1)).dump() + " GiB address-space cap";
    result.RssAfter = result.RssAfter > 0 ? result.RssAfter : StatusMiB("VmRSS");
    result.Peak = result.Peak > 0 ? result.Peak : StatusMiB("VmHWM");
    Send(options.ChildFd, result);
    std::_Exit(0);
  }
  if (rayCast)
  {
    result.AccelerationBytes = static_cast<double>(rayCast->GetAccelerationBytes());
  }
  else if (shearWarp)
  {
    result.AccelerationBytes = static_cast<double>(shearWarp->GetEncodedBytes());
  }
  result.Ok = errors->Text.empty();
  result.Error = errors->Text;
  Send(options.ChildFd, result);
  window->RemoveRenderer(renderer);
  return 0;
}

const std::vector<std::string>& MapperIds()
{
  static const std::vector<std::string> ids = { "slice", "raycast-none", "raycast-octree",
    "raycast-dmap", "shearwarp-1", "shearwarp-all", "vtk-fixed", "vtk-gpu" };
  return ids;
}

Json ChildResultJson(const ChildResult& r)
{
  return { { "ok", r.Ok }, { "volume_bytes", r.VolumeBytes }, { "rss_start", r.RssStart },
    { "rss_loaded", r.RssLoaded }, { "load_peak", r.LoadPeak }, { "load_seconds", r.LoadSeconds },
    { "peak", r.Peak }, { "rss_after", r.RssAfter }, { "peak_reset", r.PeakReset },
    { "first_ms", r.FirstMs }, { "second_ms", r.SecondMs }, { "tf_ms", r.TfMs },
    { "tf_peak", r.TfPeak }, { "acceleration_bytes", r.AccelerationBytes }, { "volume", r.Volume },
    { "gl_backend", r.GlBackend }, { "gl_renderer", r.GlRenderer }, { "error", r.Error } };
}

bool ReadChildResult(const std::string& text, ChildResult& r)
{
  const Json v = Json::parse(text, nullptr, false);
  if (v.is_discarded() || !v.is_object() || !v.contains("error"))
  {
    return false;
  }
  try
  {
    r.Ok = v.at("ok").get<bool>();
    r.PeakReset = v.at("peak_reset").get<bool>();
    for (const auto& [key, field] :
      { std::pair<const char*, double*>{ "volume_bytes", &r.VolumeBytes },
        { "rss_start", &r.RssStart }, { "rss_loaded", &r.RssLoaded }, { "load_peak", &r.LoadPeak },
        { "load_seconds", &r.LoadSeconds }, { "peak", &r.Peak }, { "rss_after", &r.RssAfter },
        { "first_ms", &r.FirstMs }, { "second_ms", &r.SecondMs }, { "tf_ms", &r.TfMs },
        { "tf_peak", &r.TfPeak }, { "acceleration_bytes", &r.AccelerationBytes } })
    {
      *field = v.at(key).get<double>();
    }
    r.Volume = v.at("volume").get<std::string>();
    r.GlBackend = v.at("gl_backend").get<std::string>();
    r.GlRenderer = v.at("gl_renderer").get<std::string>();
    r.Error = v.at("error").get<std::string>();
  }
  catch (const Json::exception&)
  {
    return false;
  }
  return true;
}

} // namespace accelvolume::benchmark::memory
