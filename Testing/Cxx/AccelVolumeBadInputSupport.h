// Shared helpers of the bad- and odd-input tests (label "badinput"): every mapper by kind, a small
// probe scene with a parallel camera (the shear-warp mapper renders parallel projections only)
// that records the mapper's errors and warnings instead of printing them, and pixel checks with
// explicit tolerances.
#ifndef AccelVolumeBadInputSupport_h
#define AccelVolumeBadInputSupport_h

#include "AccelVolumeTestUtilities.h"
#include "vtkAccelVolumeRayCastMapper.h"
#include "vtkAccelVolumeShearWarpMapper.h"
#include "vtkAccelVolumeSliceMapper.h"
#include "vtkAccelVolumeSmartMapper.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

namespace accelvolume_test
{
enum class MapperKind
{
  Slice,
  RayCast,
  ShearWarp,
  Smart
};
constexpr MapperKind AllMappers[] = { MapperKind::Slice, MapperKind::RayCast, MapperKind::ShearWarp,
  MapperKind::Smart };

inline const char* MapperName(MapperKind kind)
{
  switch (kind)
  {
    case MapperKind::Slice:
      return "slice";
    case MapperKind::RayCast:
      return "raycast";
    case MapperKind::ShearWarp:
      return "shearwarp";
    default:
      return "smart";
  }
}

inline vtkSmartPointer<vtkVolumeMapper> NewMapper(MapperKind kind)
{
  switch (kind)
  {
    case MapperKind::Slice:
      return vtkSmartPointer<vtkAccelVolumeSliceMapper>::New();
    case MapperKind::RayCast:
      return vtkSmartPointer<vtkAccelVolumeRayCastMapper>::New();
    case MapperKind::ShearWarp:
      return vtkSmartPointer<vtkAccelVolumeShearWarpMapper>::New();
    default:
      return vtkSmartPointer<vtkAccelVolumeSmartMapper>::New();
  }
}

// One background for every probe: no volume colour in these tests is this blue.
constexpr double Background[3] = { 0.2, 0.4, 0.6 };
// One 8-bit level (read-back pixels are multiples of 1/255), with float slack.
constexpr double OneLevel = 1.0 / 255.0 + 1.0e-6;

// A volume in a size x size window without multisampling, seen with a parallel camera along
// -z fitted to the image's bounds (LookAt picks another view, or one view shared by probes of
// different inputs); records the mapper's errors and warnings instead of printing them.
struct Probe
{
  MapperKind Kind;
  vtkSmartPointer<vtkVolumeMapper> Mapper;
  vtkNew<vtkVolume> Volume;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkRenderWindow> Window;
  vtkNew<ErrorRecorder> Errors;
  vtkNew<ErrorRecorder> Warnings;

  explicit Probe(MapperKind kind, vtkImageData* image = nullptr, int size = 40)
    : Kind(kind)
    , Mapper(NewMapper(kind))
  {
    this->Mapper->AddObserver(vtkCommand::ErrorEvent, this->Errors);
    this->Mapper->AddObserver(vtkCommand::WarningEvent, this->Warnings);
    if (image)
    {
      this->Mapper->SetInputData(image);
    }
    this->Volume->SetMapper(this->Mapper);
    this->Renderer->SetBackground(Background[0], Background[1], Background[2]);
    this->Renderer->AddVolume(this->Volume);
    this->Window->SetSize(size, size);
    this->Window->SetMultiSamples(0);
    this->Window->AddRenderer(this->Renderer);
    if (image)
    {
      double bounds[6];
      image->GetBounds(bounds);
      this->LookAt(bounds);
    }
  }

  // Parallel view of the box along -axis (0, 1, 2: x, y, z), then turned by azimuth and
  // elevation about the box centre; the box's largest extent fills 80% of the window.
  void LookAt(const double bounds[6], int axis = 2, double azimuth = 0, double elevation = 0)
  {
    vtkCamera* camera = this->Renderer->GetActiveCamera();
    const double centre[3] = { 0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3]),
      0.5 * (bounds[4] + bounds[5]) };
    const double extent =
      std::max({ bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4], 1.0 });
    double position[3] = { centre[0], centre[1], centre[2] };
    position[axis] += 4.0 * extent + 10.0;
    camera->SetParallelProjection(1);
    camera->SetFocalPoint(centre);
    camera->SetPosition(position);
    if (axis == 1)
    {
      camera->SetViewUp(0, 0, 1); // y up would be the view direction
    }
    else
    {
      camera->SetViewUp(0, 1, 0);
    }
    camera->Azimuth(azimuth);
    camera->Elevation(elevation);
    camera->OrthogonalizeViewUp();
    camera->SetParallelScale(0.5 * extent / 0.8);
    camera->SetClippingRange(1.0, 10.0 * extent + 20.0);
  }

  // Renders; RGB in [0,1], bottom row first (empty for an empty window).
  std::vector<float> Render()
  {
    this->Window->Render();
    const int* size = this->Window->GetSize();
    if (size[0] < 1 || size[1] < 1)
    {
      return {};
    }
    return ReadPixels(this->Window);
  }

  std::string Name(const std::string& what) const
  {
    return std::string(MapperName(this->Kind)) + ", " + what;
  }
};

// RGB of pixel (x, y) of a size-wide image.
inline std::vector<float> PixelAt(const std::vector<float>& rgb, int size, int x, int y)
{
  const size_t at = 3 * (static_cast<size_t>(y) * size + x);
  return { rgb[at], rgb[at + 1], rgb[at + 2] };
}

// Largest per-channel difference (1e9 for different sizes or empty images).
inline double MaximumDifference(const std::vector<float>& a, const std::vector<float>& b)
{
  if (a.size() != b.size() || a.empty())
  {
    return 1.0e9;
  }
  double largest = 0;
  for (size_t i = 0; i < a.size(); ++i)
  {
    largest = std::max(largest, static_cast<double>(std::fabs(a[i] - b[i])));
  }
  return largest;
}

// Largest difference of any pixel from one colour.
inline double MaximumDifferenceFrom(const std::vector<float>& rgb, const double colour[3])
{
  if (rgb.empty())
  {
    return 1.0e9;
  }
  double largest = 0;
  for (size_t i = 0; i < rgb.size(); ++i)
  {
    largest = std::max(largest, std::fabs(rgb[i] - colour[i % 3]));
  }
  return largest;
}

// Prints one line per check; false (and "FAILED") when it does not hold.
inline bool Check(bool condition, const std::string& what, const std::string& detail = "")
{
  std::cout << (condition ? "ok     " : "FAILED ") << what << (detail.empty() ? "" : ": ") << detail
            << "\n";
  return condition;
}

// The image equals `expected` within `tolerance` per channel.
inline bool CheckImage(const std::vector<float>& image, const std::vector<float>& expected,
  double tolerance, const std::string& what)
{
  const double difference = MaximumDifference(image, expected);
  return Check(difference <= tolerance, what,
    "max difference " + std::to_string(difference) + " (tolerance " + std::to_string(tolerance) +
      ")");
}

// The centre pixel (size / 2, size / 2) of a size-wide image is `expected` within tolerance.
inline bool CheckCentre(const std::vector<float>& image, int size, const double expected[3],
  double tolerance, const std::string& what)
{
  if (image.empty())
  {
    return Check(false, what, "no image");
  }
  const std::vector<float> centre = PixelAt(image, size, size / 2, size / 2);
  double difference = 0;
  for (int c = 0; c < 3; ++c)
  {
    difference = std::max(difference, std::fabs(centre[c] - expected[c]));
  }
  return Check(difference <= tolerance, what,
    "centre (" + std::to_string(centre[0]) + ", " + std::to_string(centre[1]) + ", " +
      std::to_string(centre[2]) + "), expected (" + std::to_string(expected[0]) + ", " +
      std::to_string(expected[1]) + ", " + std::to_string(expected[2]) + ")");
}

// Every pixel is the background within one level.
inline bool CheckBackground(const std::vector<float>& image, const std::string& what)
{
  const double difference = MaximumDifferenceFrom(image, Background);
  return Check(difference <= OneLevel, what,
    "max difference from the background " + std::to_string(difference));
}

// The recorded messages on one line, without VTK's "ERROR: In file, line" and "vtkClass (0x...):"
// prefixes (ctest fails a test that prints a line starting "ERROR: ").
inline std::string Messages(const ErrorRecorder* log)
{
  std::string text;
  size_t at = 0;
  const std::string& all = log->Messages;
  while (at < all.size())
  {
    const size_t start = all.find("): ", at);
    if (start == std::string::npos)
    {
      break;
    }
    size_t end = all.find("\n\n", start);
    end = end == std::string::npos ? all.size() : end;
    text += (text.empty() ? "" : " | ") + all.substr(start + 3, end - start - 3);
    at = end + 2;
  }
  for (char& c : text)
  {
    c = c == '\n' ? ' ' : c;
  }
  return text.empty() ? all : text;
}

// `log` holds `text`; prints what it holds.
inline bool CheckMessage(const ErrorRecorder* log, const std::string& text, const std::string& what)
{
  const bool found = log->Messages.find(text) != std::string::npos;
  return Check(found, what,
    "expected \"" + text + "\", got " +
      (log->Messages.empty() ? std::string("nothing") : "\"" + Messages(log) + "\""));
}

inline bool CheckNoMessage(const ErrorRecorder* log, const std::string& what)
{
  return Check(log->Count == 0, what,
    log->Messages.empty() ? std::string("no message") : "unexpected \"" + Messages(log) + "\"");
}

// A nx x ny x nz volume of `type` holding `value` everywhere except an inner block (a quarter of
// each axis away from the faces, at least one voxel) holding `block`.
inline vtkSmartPointer<vtkImageData> BlockVolume(
  int type, int nx, int ny, int nz, double value, double block)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(nx, ny, nz);
  image->AllocateScalars(type, 1);
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  const int n[3] = { nx, ny, nz };
  vtkIdType at = 0;
  for (int k = 0; k < nz; ++k)
  {
    for (int j = 0; j < ny; ++j)
    {
      for (int i = 0; i < nx; ++i, ++at)
      {
        const int ijk[3] = { i, j, k };
        bool inside = true;
        for (int a = 0; a < 3; ++a)
        {
          inside = inside && (n[a] < 3 || (ijk[a] >= n[a] / 4 && ijk[a] <= n[a] - 1 - n[a] / 4));
        }
        scalars->SetTuple1(at, inside ? block : value);
      }
    }
  }
  return image;
}

// Colour and opacity functions of a property from explicit points (value, r, g, b, opacity).
struct TransferPoint
{
  double Value, Red, Green, Blue, Opacity;
};
inline void SetTransfer(vtkVolumeProperty* property, const std::vector<TransferPoint>& points)
{
  vtkNew<vtkColorTransferFunction> colours;
  vtkNew<vtkPiecewiseFunction> opacity;
  for (const TransferPoint& p : points)
  {
    colours->AddRGBPoint(p.Value, p.Red, p.Green, p.Blue);
    opacity->AddPoint(p.Value, p.Opacity);
  }
  property->SetColor(colours);
  property->SetScalarOpacity(opacity);
  property->SetInterpolationTypeToLinear();
  property->ShadeOff();
}
}

#endif
