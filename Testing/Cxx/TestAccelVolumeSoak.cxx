// Soak test (label "soak"): each of the four mappers renders 1,000 small frames (64x64 / 80x48)
// while every frame moves the camera (azimuth, elevation, zoom) and, periodically, the transfer
// functions change (new objects and in-place edits of colour / opacity points, shading, gradient
// opacity, interpolation), the blend mode, the input (a new vtkImageData of another size and
// scalar type, Modified() after in-place edits of the scalars, a switch between two images),
// cropping, the projection, the window size and mapper settings (leap mode, run-length
// encoding, the smart mapper's requested mode).
//
// The schedule repeats every Cycle frames, so memory measured after frame Cycle (every cache and
// shader variant warm; resident memory after frame 2 Cycle, see Result::RssWarm) and after the
// last frame is taken in the same state: whatever grew between them was leaked. Heap in use (mallinfo2: uordblks + hblkhd, which includes llvmpipe's
// textures) may grow by at most HeapBoundKiB and resident memory (/proc/self/statm, after
// malloc_trim) by at most RssBoundMiB; on llvmpipe both stay within +-25 KiB / 0.15 MiB. The
// measured window (frames 200-1,000) holds 192 transfer-function changes, 16 new input images,
// 64 in-place edits and 32 switches between the two kept images, so leaking one copy of the
// smallest volume (40x36x32 uint8, 45 KiB) per new image (720 KiB) or a 4 KiB transfer-function
// texture per change (768 KiB) exceeds the heap bound.
// Also fails on any mapper error, or when a mapper stops drawing. VTK's leak check at exit
// covers VTK objects. Prints one row per mapper: frames, memory at warm-up and end, growth,
// ms per frame.
//
// Arguments (after the test name; the defaults are the ctest run): --frames N (rounded up to
// whole cycles, at least 2), --mappers slice,raycast,shearwarp,smart, --inject-leak BYTES (keep
// BYTES of touched heap per transfer-function change: shows the check firing), --expect-leak
// (pass only if the memory check fails: the ctest that proves the check can fail).
#include "AccelVolumeTestUtilities.h"
#include "vtkAccelVolumeRayCastMapper.h"
#include "vtkAccelVolumeShearWarpMapper.h"
#include "vtkAccelVolumeSliceMapper.h"
#include "vtkAccelVolumeSmartMapper.h"
#include "vtkDataArray.h"
#include "vtkTimerLog.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <memory>
#include <sstream>

#if defined(__GLIBC__)
#include <malloc.h>
#endif
#include <unistd.h>

namespace
{
using namespace accelvolume_test;

constexpr int DefaultFrames = 1000;
constexpr int Cycle = 200;                 // the schedule repeats every Cycle frames
constexpr double HeapBoundKiB = 256.0;     // growth of heap in use allowed after warm-up
constexpr double RssBoundMiB = 1.0;        // growth of resident memory allowed after warm-up
constexpr double MinimumDrawnShare = 0.25; // of the sampled frames of every cycle

// The frame up to which resident memory is taken as warm (its high-water mark until then): the
// second cycle's end when there are three or more cycles (see Result::RssWarm), else the first's.
int RssWarmFrame(int frames)
{
  return (frames / Cycle >= 3 ? 2 : 1) * Cycle;
}
constexpr double MiB = 1024.0 * 1024.0;

enum class Kind
{
  Slice,
  RayCast,
  ShearWarp,
  Smart
};

const char* KindName(Kind kind)
{
  switch (kind)
  {
    case Kind::Slice:
      return "slice";
    case Kind::RayCast:
      return "raycast";
    case Kind::ShearWarp:
      return "shearwarp";
    default:
      return "smart";
  }
}

struct Memory
{
  double Rss = -1;  // MiB, -1 when unknown
  double Heap = -1; // MiB, -1 when unknown
};

Memory MeasureMemory()
{
  Memory memory;
#if defined(__GLIBC__)
  malloc_trim(0); // hand freed pages back so that RSS follows what is in use, not malloc's cache
#endif
  std::ifstream statm("/proc/self/statm");
  long long pages = 0;
  long long resident = 0;
  if (statm >> pages >> resident)
  {
    memory.Rss = static_cast<double>(resident) * sysconf(_SC_PAGESIZE) / MiB;
  }
#if defined(__GLIBC__) && (__GLIBC__ > 2 || (__GLIBC__ == 2 && __GLIBC_MINOR__ >= 33))
  const struct mallinfo2 info = mallinfo2();
  memory.Heap = static_cast<double>(info.uordblks + info.hblkhd) / MiB;
#endif
  return memory;
}

// A phantom converted to a VTK scalar type: value * scale + offset, rounded for integer types.
vtkSmartPointer<vtkImageData> MakeTyped(
  const char* phantom, int nx, int ny, int nz, int type, double scale, double offset)
{
  vtkSmartPointer<vtkImageData> source = MakePhantom(phantom, nx, ny, nz, 1.0, 1.0, 1.25);
  if (!source)
  {
    return nullptr;
  }
  vtkDataArray* from = source->GetPointData()->GetScalars();
  vtkSmartPointer<vtkDataArray> to =
    vtkSmartPointer<vtkDataArray>::Take(vtkDataArray::CreateDataArray(type));
  to->SetName("scalars");
  to->SetNumberOfTuples(from->GetNumberOfTuples());
  const bool integral = type != VTK_FLOAT && type != VTK_DOUBLE;
  for (vtkIdType i = 0; i < from->GetNumberOfTuples(); ++i)
  {
    const double v = from->GetTuple1(i) * scale + offset;
    to->SetTuple1(i, integral ? std::round(v) : v);
  }
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(nx, ny, nz);
  image->SetSpacing(1.0, 1.0, 1.25);
  image->GetPointData()->SetScalars(to);
  return image;
}

// The four fresh inputs, by index: other sizes and scalar types every time.
vtkSmartPointer<vtkImageData> MakeFresh(int index)
{
  switch (index)
  {
    case 0:
      return MakeTyped("blobs", 40, 36, 32, VTK_UNSIGNED_CHAR, 0.25, 0.0);
    case 1:
      return MakeTyped("shells", 48, 40, 30, VTK_SHORT, 1.0, -300.0);
    case 2:
      return MakeTyped("vessels", 56, 48, 40, VTK_UNSIGNED_SHORT, 4.0, 0.0);
    default:
      return MakeTyped("blobs", 32, 44, 36, VTK_FLOAT, 0.001, 0.0);
  }
}

// Counts a mapper's error or warning events and keeps the first message (keeping them all would
// itself grow the heap).
class EventCounter : public vtkCommand
{
public:
  static EventCounter* New() { return new EventCounter; }
  void Execute(vtkObject*, unsigned long, void* data) override
  {
    if (this->Count++ == 0)
    {
      this->First = data ? static_cast<const char*>(data) : "(null)";
    }
  }
  std::string First;
  int Count = 0;
};

struct Result
{
  Kind Which = Kind::Slice;
  int Frames = 0;
  Memory Warm;
  Memory End;
  // Resident memory is judged from its high-water mark over the first two cycles when there are
  // three or more: a loaded machine can reach it (a worker thread's first malloc arena, a
  // llvmpipe shader JIT) only in the second cycle, a one-time step that is no leak (seen once in
  // CI: +1.0 MiB between frames 200 and 400, flat after), or drop below the first cycle's in the
  // second and climb back (seen once: 132.6, 131.7, ..., 132.7 MiB). Heap in use is judged from
  // the first.
  Memory RssWarm;
  std::vector<Memory> Checkpoints; // after every cycle
  double MsPerFrame = 0;
  int Errors = 0;
  int Warnings = 0;
  std::string FirstError;
  std::string FirstWarning;
  std::vector<double> DrawnShare; // per cycle, of the frames sampled
};

// One mapper's scene and the schedule that drives it.
class Soak
{
public:
  Soak(Kind kind, std::size_t injectLeak)
    : Which(kind)
    , InjectLeak(injectLeak)
  {
    switch (kind)
    {
      case Kind::Slice:
        this->Mapper = vtkSmartPointer<vtkAccelVolumeSliceMapper>::New();
        break;
      case Kind::RayCast:
        this->RayCast = vtkSmartPointer<vtkAccelVolumeRayCastMapper>::New();
        this->Mapper = this->RayCast;
        break;
      case Kind::ShearWarp:
        this->ShearWarp = vtkSmartPointer<vtkAccelVolumeShearWarpMapper>::New();
        this->Mapper = this->ShearWarp;
        break;
      case Kind::Smart:
        this->Smart = vtkSmartPointer<vtkAccelVolumeSmartMapper>::New();
        this->Mapper = this->Smart;
        break;
    }
    this->Mapper->AddObserver(vtkCommand::ErrorEvent, this->Errors);
    this->Mapper->AddObserver(vtkCommand::WarningEvent, this->Warnings);
    this->Volume->SetMapper(this->Mapper);
    this->Renderer->SetBackground(0.1, 0.1, 0.2);
    this->Renderer->AddVolume(this->Volume);
    this->Window->SetMultiSamples(0);
    this->Window->AddRenderer(this->Renderer);
    this->A = MakeTyped("vessels", 64, 56, 48, VTK_FLOAT, 1.0, 0.0);
    this->B = MakeTyped("shells", 48, 48, 48, VTK_UNSIGNED_SHORT, 8.0, 0.0);
  }

  Result Run(int frames)
  {
    Result result;
    result.Which = this->Which;
    result.Frames = frames;
    vtkNew<vtkTimerLog> timer;
    timer->StartTimer();
    int sampled = 0;
    int drawn = 0;
    for (int f = 0; f < frames; ++f)
    {
      this->Schedule(f);
      this->Window->Render();
      if (f % 10 == 3)
      {
        ++sampled;
        drawn += this->DrawnPixels() > 0 ? 1 : 0;
      }
      if (f % Cycle == Cycle - 1)
      {
        result.Checkpoints.push_back(MeasureMemory());
        result.DrawnShare.push_back(sampled > 0 ? static_cast<double>(drawn) / sampled : 0.0);
        sampled = drawn = 0;
      }
    }
    timer->StopTimer();
    result.MsPerFrame = 1000.0 * timer->GetElapsedTime() / frames;
    result.Warm = result.Checkpoints.front();
    result.End = result.Checkpoints.back();
    // Resident memory's high-water mark over the warm cycles: a process whose RSS dropped in the
    // second cycle (pages the kernel or llvmpipe's scenes handed back under load) and climbed
    // back to the first cycle's level has not grown; a leak raises every checkpoint, so its
    // mark is the last warm one, as before.
    const std::size_t warmCheckpoints = static_cast<std::size_t>(RssWarmFrame(frames) / Cycle);
    result.RssWarm = *std::max_element(result.Checkpoints.begin(),
      result.Checkpoints.begin() + static_cast<std::ptrdiff_t>(warmCheckpoints),
      [](const Memory& a, const Memory& b) { return a.Rss < b.Rss; });
    result.Errors = this->Errors->Count;
    result.Warnings = this->Warnings->Count;
    result.FirstError = this->Errors->First;
    result.FirstWarning = this->Warnings->First;
    return result;
  }

private:
  // Everything that frame f changes. Periods divide Cycle, so the state after frame
  // Cycle - 1 is the same in every cycle.
  void Schedule(int f)
  {
    const int phase = f % 50;
    bool inputChanged = false;
    if (phase == 0)
    {
      this->Fresh = MakeFresh((f / 50) % 4); // a new image object every time
      this->SetInput(this->Fresh);
      inputChanged = true;
    }
    else if (phase == 25)
    {
      this->SetInput(this->A);
      this->Fresh = nullptr; // the mapper held the last reference: freed here
      inputChanged = true;
    }
    else if (phase == 40)
    {
      this->SetInput(this->B);
      inputChanged = true;
    }
    else if (phase == 30 || phase == 35)
    {
      // In place: x2, then /2 (exact in float, so every cycle sees the same values).
      auto* values = static_cast<float*>(this->A->GetScalarPointer());
      const vtkIdType count = this->A->GetNumberOfPoints();
      for (vtkIdType i = 0; i < count; ++i)
      {
        values[i] = phase == 30 ? values[i] * 2.0f : values[i] * 0.5f;
      }
      this->A->GetPointData()->GetScalars()->Modified();
      inputChanged = true;
    }
    else if (phase == 42 || phase == 47)
    {
      // In place on a slab of B: an XOR applied twice restores it.
      auto* values = static_cast<unsigned short*>(this->B->GetScalarPointer());
      for (vtkIdType i = 0; i < 48 * 48 * 16; ++i)
      {
        values[i] = static_cast<unsigned short>(values[i] ^ 0x00F0);
      }
      this->B->GetPointData()->GetScalars()->Modified();
      inputChanged = true;
    }
    if (f % 5 == 0 || inputChanged)
    {
      this->ApplyTransfer((f / 5) % 4);
    }
    if (f % 20 == 0)
    {
      static const int all[5] = { vtkVolumeMapper::COMPOSITE_BLEND,
        vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND, vtkVolumeMapper::MINIMUM_INTENSITY_BLEND,
        vtkVolumeMapper::ADDITIVE_BLEND, vtkVolumeMapper::AVERAGE_INTENSITY_BLEND };
      // Shear-warp renders composite, MIP and MinIP only.
      static const int shearWarp[5] = { vtkVolumeMapper::COMPOSITE_BLEND,
        vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND, vtkVolumeMapper::MINIMUM_INTENSITY_BLEND,
        vtkVolumeMapper::COMPOSITE_BLEND, vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND };
      const int index = (f / 20) % 5;
      this->Mapper->SetBlendMode(this->ShearWarp ? shearWarp[index] : all[index]);
    }
    this->ApplyCropping(f);
    this->ApplyMapperSettings(f);
    const bool small = f % 100 < 50;
    this->Window->SetSize(small ? 64 : 80, small ? 64 : 48);
    this->ApplyCamera(f);
  }

  void SetInput(vtkImageData* image)
  {
    this->Current = image;
    this->Mapper->SetInputData(image);
  }

  // Four transfer functions over the current data range; 0 and 2 are new objects, 1 and 3
  // edit the current ones in place.
  void ApplyTransfer(int variant)
  {
    double range[2];
    this->Current->GetPointData()->GetScalars()->GetRange(range);
    const double lo = range[0];
    const double span = range[1] > range[0] ? range[1] - range[0] : 1.0;
    auto at = [&](double t) { return lo + t * span; };
    vtkVolumeProperty* property = this->Volume->GetProperty();
    if (variant == 0 || variant == 2 || !this->Colour)
    {
      this->Colour = vtkSmartPointer<vtkColorTransferFunction>::New();
      this->Opacity = vtkSmartPointer<vtkPiecewiseFunction>::New();
      property->SetColor(this->Colour);
      property->SetScalarOpacity(this->Opacity);
    }
    this->Colour->RemoveAllPoints();
    this->Opacity->RemoveAllPoints();
    switch (variant)
    {
      case 0:
        this->Colour->AddRGBPoint(at(0.1), 0, 0, 0);
        this->Colour->AddRGBPoint(at(0.9), 1, 1, 1);
        this->Opacity->AddPoint(at(0.1), 0.0);
        this->Opacity->AddPoint(at(0.9), 1.0);
        property->ShadeOff();
        property->DisableGradientOpacityOn();
        property->SetInterpolationTypeToLinear();
        break;
      case 1:
        this->Colour->AddRGBPoint(at(0.05), 0.1, 0.0, 0.3);
        this->Colour->AddRGBPoint(at(0.5), 0.9, 0.3, 0.1);
        this->Colour->AddRGBPoint(at(1.0), 1.0, 1.0, 0.8);
        this->Opacity->AddPoint(at(0.05), 0.0);
        this->Opacity->AddPoint(at(0.4), 0.6);
        this->Opacity->AddPoint(at(0.6), 0.2);
        this->Opacity->AddPoint(at(1.0), 0.9);
        property->ShadeOn();
        property->SetSpecular(0.2);
        break;
      case 2:
      {
        for (int i = 0; i < 5; ++i)
        {
          this->Colour->AddRGBPoint(at(0.2 * i + 0.1), 0.2 * i, 1.0 - 0.2 * i, 0.5);
          this->Opacity->AddPoint(at(0.2 * i + 0.1), i % 2 ? 0.8 : 0.1);
        }
        vtkNew<vtkPiecewiseFunction> gradient;
        gradient->AddPoint(0.0, 0.2);
        gradient->AddPoint(0.25 * span, 1.0);
        property->SetGradientOpacity(gradient);
        property->DisableGradientOpacityOff();
        property->ShadeOn();
        property->SetSpecular(0.5);
        break;
      }
      default:
        this->Colour->AddRGBPoint(at(0.0), 0.0, 0.2, 0.0);
        this->Colour->AddRGBPoint(at(0.7), 1.0, 0.9, 0.2);
        this->Opacity->AddPoint(at(0.2), 0.0);
        this->Opacity->AddPoint(at(0.7), 0.7);
        property->ShadeOff();
        property->DisableGradientOpacityOn();
        property->SetInterpolationTypeToNearest();
        break;
    }
    if (this->InjectLeak > 0)
    {
      this->Leaked.emplace_back(this->InjectLeak, '\1'); // touched, so resident too
    }
  }

  // Off, sub-volume, off, cross, off: 20 frames each; planes from the current bounds.
  void ApplyCropping(int f)
  {
    const int part = (f % 100) / 20;
    if (part % 2 == 0)
    {
      this->Mapper->CroppingOff();
      return;
    }
    double b[6];
    this->Current->GetBounds(b);
    this->Mapper->SetCroppingRegionPlanes(b[0] + 0.2 * (b[1] - b[0]), b[0] + 0.8 * (b[1] - b[0]),
      b[2] + 0.25 * (b[3] - b[2]), b[2] + 0.75 * (b[3] - b[2]), b[4] + 0.3 * (b[5] - b[4]),
      b[4] + 0.7 * (b[5] - b[4]));
    if (part == 1)
    {
      this->Mapper->SetCroppingRegionFlagsToSubVolume();
    }
    else
    {
      this->Mapper->SetCroppingRegionFlagsToCross();
    }
    this->Mapper->CroppingOn();
  }

  void ApplyMapperSettings(int f)
  {
    if (this->RayCast)
    {
      static const int leaps[4] = { vtkAccelVolumeRayCastMapper::LEAP_OCTREE,
        vtkAccelVolumeRayCastMapper::LEAP_DISTANCE_MAP, vtkAccelVolumeRayCastMapper::LEAP_NONE,
        vtkAccelVolumeRayCastMapper::LEAP_DISTANCE_MAP };
      const int index = (f / 25) % 4;
      this->RayCast->SetLeapMode(leaps[index]);
      this->RayCast->SetCellLeaping(index == 3);
    }
    if (this->ShearWarp)
    {
      this->ShearWarp->SetRunLengthEncoding(f % 100 < 80); // dense encodings too
    }
    if (this->Smart)
    {
      static const int modes[4] = { vtkAccelVolumeSmartMapper::DEFAULT_RENDER,
        vtkAccelVolumeSmartMapper::SLICE_RENDER, vtkAccelVolumeSmartMapper::RAYCAST_RENDER,
        vtkAccelVolumeSmartMapper::SHEARWARP_RENDER };
      this->Smart->SetRequestedRenderMode(modes[(f / 10) % 4]);
    }
  }

  // Azimuth turns 360 degrees every 50 frames; elevation and zoom oscillate.
  void ApplyCamera(int f)
  {
    vtkCamera* camera = this->Renderer->GetActiveCamera();
    camera->SetFocalPoint(0, 0, 0);
    camera->SetPosition(0, 0, 1);
    camera->SetViewUp(0, 1, 0);
    // Shear-warp needs a parallel camera; the others alternate every 100 frames.
    camera->SetParallelProjection(this->ShearWarp || f % 200 >= 100 ? 1 : 0);
    this->Renderer->ResetCamera();
    constexpr double TwoPi = 6.283185307179586;
    camera->Azimuth(7.2 * (f % 50));
    camera->Elevation(25.0 * std::sin(TwoPi * (f % 50) / 50.0));
    camera->OrthogonalizeViewUp();
    camera->Zoom(1.0 + 0.3 * std::sin(TwoPi * (f % 25) / 25.0));
    this->Renderer->ResetCameraClippingRange();
  }

  int DrawnPixels()
  {
    const int* size = this->Window->GetSize();
    vtkNew<vtkUnsignedCharArray> pixels;
    this->Window->GetPixelData(0, 0, size[0] - 1, size[1] - 1, 0, pixels);
    const unsigned char* rgb = pixels->GetPointer(0);
    const unsigned char background[3] = { 26, 26, 51 }; // 0.1, 0.1, 0.2
    int count = 0;
    for (vtkIdType p = 0; p + 2 < pixels->GetNumberOfValues(); p += 3)
    {
      count += (std::abs(rgb[p] - background[0]) > 1 || std::abs(rgb[p + 1] - background[1]) > 1 ||
                 std::abs(rgb[p + 2] - background[2]) > 1)
        ? 1
        : 0;
    }
    return count;
  }

  Kind Which;
  std::size_t InjectLeak = 0;
  std::vector<std::string> Leaked; // --inject-leak: kept until the scene goes
  vtkSmartPointer<vtkVolumeMapper> Mapper;
  vtkSmartPointer<vtkAccelVolumeRayCastMapper> RayCast;
  vtkSmartPointer<vtkAccelVolumeShearWarpMapper> ShearWarp;
  vtkSmartPointer<vtkAccelVolumeSmartMapper> Smart;
  vtkNew<EventCounter> Errors;
  vtkNew<EventCounter> Warnings;
  vtkNew<vtkVolume> Volume;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkRenderWindow> Window;
  vtkSmartPointer<vtkImageData> A;
  vtkSmartPointer<vtkImageData> B;
  vtkSmartPointer<vtkImageData> Fresh;
  vtkImageData* Current = nullptr;
  vtkSmartPointer<vtkColorTransferFunction> Colour;
  vtkSmartPointer<vtkPiecewiseFunction> Opacity;
};

struct Arguments
{
  int Frames = DefaultFrames;
  std::vector<Kind> Mappers = { Kind::Slice, Kind::RayCast, Kind::ShearWarp, Kind::Smart };
  std::size_t InjectLeak = 0;
  bool ExpectLeak = false;
};

// Reads this test's own options; the test driver's (-T dir, -V file, ...) are ignored.
bool ParseArguments(int argc, char* argv[], Arguments& args)
{
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    const bool hasValue = i + 1 < argc;
    if (arg == "--frames" && hasValue)
    {
      args.Frames = std::atoi(argv[++i]);
    }
    else if (arg == "--inject-leak" && hasValue)
    {
      args.InjectLeak = static_cast<std::size_t>(std::atoll(argv[++i]));
    }
    else if (arg == "--expect-leak")
    {
      args.ExpectLeak = true;
    }
    else if (arg == "--mappers" && hasValue)
    {
      args.Mappers.clear();
      std::stringstream list(argv[++i]);
      std::string name;
      while (std::getline(list, name, ','))
      {
        bool known = false;
        for (Kind kind : { Kind::Slice, Kind::RayCast, Kind::ShearWarp, Kind::Smart })
        {
          if (name == KindName(kind))
          {
            args.Mappers.push_back(kind);
            known = true;
          }
        }
        if (!known)
        {
          std::cerr << "unknown mapper '" << name << "' (slice, raycast, shearwarp, smart)\n";
          return false;
        }
      }
    }
  }
  // Whole cycles, at least two: the first warms up, the rest are measured.
  args.Frames = std::max(2, (std::max(args.Frames, 1) + Cycle - 1) / Cycle) * Cycle;
  return !args.Mappers.empty();
}

std::string Fixed(double value, int precision)
{
  char text[64];
  std::snprintf(text, sizeof(text), "%.*f", precision, value);
  return text;
}
}

int TestAccelVolumeSoak(int argc, char* argv[])
{
  Arguments args;
  if (!ParseArguments(argc, argv, args))
  {
    return EXIT_FAILURE;
  }
  if (MeasureMemory().Rss < 0)
  {
    std::cout << "no /proc/self/statm: cannot measure resident memory; skipped\n";
    return 125;
  }
  std::cout << "soak: " << args.Frames << " frames per mapper, schedule period " << Cycle
            << " frames; heap in use after frame " << Cycle << " (warm), resident memory's high-water mark up to frame "
            << RssWarmFrame(args.Frames) << ", both after frame " << args.Frames
            << "; bounds: heap in use +" << HeapBoundKiB << " KiB, RSS +" << RssBoundMiB << " MiB"
            << (args.InjectLeak ? ", injected leak " + std::to_string(args.InjectLeak) +
                     " bytes per transfer-function change"
                                : std::string())
            << "\n";
  std::vector<Result> results;
  for (Kind kind : args.Mappers)
  {
    Soak soak(kind, args.InjectLeak);
    results.push_back(soak.Run(args.Frames));
    const Result& r = results.back();
    std::cout << KindName(kind) << " checkpoints (RSS / heap MiB):";
    for (const Memory& m : r.Checkpoints)
    {
      std::cout << " " << Fixed(m.Rss, 2) << "/" << Fixed(m.Heap, 3);
    }
    std::cout << "; drawn share per cycle:";
    for (double share : r.DrawnShare)
    {
      std::cout << " " << Fixed(share, 2);
    }
    std::cout << "\n";
    if (r.Warnings > 0)
    {
      // Expected ones: shear-warp ignores cropping; the smart mapper falls back from a requested
      // mapper that cannot render the scene.
      // VTK's text is "Warning: In <file>, line <n>\n<class> (<address>): <message>".
      const std::size_t at = r.FirstWarning.find('\n');
      const std::string message =
        at == std::string::npos ? r.FirstWarning : r.FirstWarning.substr(at + 1);
      std::cout << "  " << r.Warnings
                << " warnings, the first: " << message.substr(0, message.find('\n')) << "\n";
    }
    std::cout << std::flush;
  }

  bool memoryOk = true;
  bool otherOk = true;
  std::cout << "\nmapper     frames  RSS@" << RssWarmFrame(args.Frames)
            << "  RSS@end  RSS growth  heap@" << Cycle
            << "  heap@end  heap growth  ms/frame  errors  warnings\n";
  for (const Result& r : results)
  {
    const double rssGrowth = r.End.Rss - r.RssWarm.Rss;
    const double heapGrowthKiB = (r.End.Heap - r.Warm.Heap) * 1024.0;
    const bool haveHeap = r.Warm.Heap >= 0;
    const bool rssOk = rssGrowth <= RssBoundMiB;
    const bool heapOk = !haveHeap || heapGrowthKiB <= HeapBoundKiB;
    memoryOk = memoryOk && rssOk && heapOk;
    bool drawing = true;
    for (double share : r.DrawnShare)
    {
      drawing = drawing && share >= MinimumDrawnShare;
    }
    otherOk = otherOk && r.Errors == 0 && drawing;
    std::printf(
      "%-10s %6d  %7.2f  %7.2f  %+7.2f MiB  %8.3f  %8.3f  %+8.1f KiB  %8.2f  %6d  %8d%s%s%s\n",
      KindName(r.Which), r.Frames, r.RssWarm.Rss, r.End.Rss, rssGrowth, r.Warm.Heap, r.End.Heap,
      haveHeap ? heapGrowthKiB : 0.0, r.MsPerFrame, r.Errors, r.Warnings,
      rssOk && heapOk ? "" : "  MEMORY GROWTH OVER BOUND", drawing ? "" : "  STOPPED DRAWING",
      r.Errors ? ("  first error: " + r.FirstError).c_str() : "");
  }
  std::cout << std::flush;
  if (!otherOk)
  {
    return EXIT_FAILURE;
  }
  if (args.ExpectLeak)
  {
    if (results.front().Warm.Heap < 0)
    {
      std::cout << "no mallinfo2: the injected leak is below the RSS bound alone; skipped\n";
      return 125;
    }
    std::cout << (memoryOk ? "expected the injected leak to be detected, but it was not\n"
                           : "the injected leak was detected, as expected\n");
    return memoryOk ? EXIT_FAILURE : EXIT_SUCCESS;
  }
  return memoryOk ? EXIT_SUCCESS : EXIT_FAILURE;
}
