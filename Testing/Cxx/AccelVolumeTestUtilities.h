// Shared helpers of the image tests: phantom inputs, standard scenes, the CPU reference image
// (accelvolume::RenderReference) coloured exactly like the mapper's resolve pass, comparisons.
#ifndef AccelVolumeTestUtilities_h
#define AccelVolumeTestUtilities_h

#include "common/Geometry.h"
#include "reference/Phantoms.h"
#include "reference/ReferenceRenderer.h"

#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkCommand.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkPNGWriter.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPlane.h"
#include "vtkPlaneCollection.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"
#include "vtkVolume.h"
#include "vtkVolumeMapper.h"
#include "vtkVolumeProperty.h"

#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

namespace accelvolume_test
{
constexpr int TableSize = 1024; // the mapper's transfer table resolution

inline vtkSmartPointer<vtkImageData> MakePhantom(const std::string& name, int nx, int ny, int nz,
  double sx = 1.0, double sy = 1.0, double sz = 1.0)
{
  accelvolume::PhantomVolume phantom;
  std::string error;
  const int dims[3] = { nx, ny, nz };
  if (!accelvolume::GeneratePhantom(name, dims, 0.0, phantom, error))
  {
    std::cerr << error << "\n";
    return nullptr;
  }
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(nx, ny, nz);
  image->SetSpacing(sx, sy, sz);
  vtkNew<vtkFloatArray> scalars;
  scalars->SetName("scalars");
  scalars->SetNumberOfValues(static_cast<vtkIdType>(phantom.values.size()));
  std::copy(phantom.values.begin(), phantom.values.end(), scalars->GetPointer(0));
  image->GetPointData()->SetScalars(scalars);
  return image;
}

// Records VTK error messages instead of printing them (ctest fails on printed errors).
class ErrorRecorder : public vtkCommand
{
public:
  static ErrorRecorder* New() { return new ErrorRecorder; }
  void Execute(vtkObject*, unsigned long, void* data) override
  {
    this->Messages += data ? static_cast<const char*>(data) : "(null)";
    this->Messages += "\n";
    ++this->Count;
  }
  std::string Messages;
  int Count = 0;
};

// A gzipped headerless 8-bit raw volume (../shared/data style); nullptr when unreadable.
inline vtkSmartPointer<vtkImageData> LoadRawGz(const std::string& path, int nx, int ny, int nz)
{
  gzFile file = gzopen(path.c_str(), "rb");
  if (!file)
  {
    return nullptr;
  }
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(nx, ny, nz);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 1);
  const size_t bytes = static_cast<size_t>(nx) * ny * nz;
  const int read = gzread(file, image->GetScalarPointer(), static_cast<unsigned int>(bytes));
  gzclose(file);
  return read == static_cast<int>(bytes) ? image : nullptr;
}

// An 8-bit volume from $ACCELVOLUME_DATA_DIR (../shared/data); nullptr when absent.
inline vtkSmartPointer<vtkImageData> LoadSharedVolume(const char* file, int nx, int ny, int nz)
{
  const char* folder = std::getenv("ACCELVOLUME_DATA_DIR");
  return folder ? LoadRawGz(std::string(folder) + "/" + file, nx, ny, nz) : nullptr;
}

// Grey ramp colour and a linear opacity ramp over [low, high].
inline void SetRampProperty(
  vtkVolumeProperty* property, double low, double high, bool colour = false)
{
  vtkNew<vtkColorTransferFunction> colours;
  if (colour)
  {
    colours->AddRGBPoint(low, 0.1, 0.0, 0.3);
    colours->AddRGBPoint(0.5 * (low + high), 0.9, 0.3, 0.1);
    colours->AddRGBPoint(high, 1.0, 1.0, 0.8);
  }
  else
  {
    colours->AddRGBPoint(low, 0, 0, 0);
    colours->AddRGBPoint(high, 1, 1, 1);
  }
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(low, 0.0);
  opacity->AddPoint(high, 1.0);
  property->SetColor(colours);
  property->SetScalarOpacity(opacity);
  property->SetInterpolationTypeToLinear();
}

// Opaque-ish colours for the low values the minimum runs through (MinIP scenes).
inline void SetMinimumProperty(vtkVolumeProperty* property)
{
  vtkNew<vtkColorTransferFunction> colours;
  colours->AddRGBPoint(0.0, 0.0, 0.0, 0.0);
  colours->AddRGBPoint(60.0, 1.0, 0.9, 0.6);
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0.0, 0.5);
  opacity->AddPoint(60.0, 1.0);
  property->SetColor(colours);
  property->SetScalarOpacity(opacity);
}

// Square window without multisampling, camera fitted then turned to an oblique view.
inline void SetupObliqueView(vtkRenderWindow* window, vtkRenderer* renderer, int size,
  double azimuth, double elevation, bool perspective)
{
  window->SetSize(size, size);
  window->SetMultiSamples(0);
  window->AddRenderer(renderer);
  renderer->ResetCamera();
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetParallelProjection(perspective ? 0 : 1);
  camera->Azimuth(azimuth);
  camera->Elevation(elevation);
  camera->OrthogonalizeViewUp();
  renderer->ResetCamera();
}

// RGB in [0,1] of the window, bottom row first.
inline std::vector<float> ReadPixels(vtkRenderWindow* window)
{
  const int* size = window->GetSize();
  vtkNew<vtkUnsignedCharArray> pixels;
  window->GetPixelData(0, 0, size[0] - 1, size[1] - 1, 0, pixels);
  std::vector<float> rgb(static_cast<size_t>(size[0]) * size[1] * 3);
  for (size_t i = 0; i < rgb.size(); ++i)
  {
    rgb[i] = pixels->GetValue(static_cast<vtkIdType>(i)) / 255.0f;
  }
  return rgb;
}

inline accelvolume::Camera ToCoreCamera(vtkCamera* camera)
{
  accelvolume::Camera result;
  double p[3];
  camera->GetPosition(p);
  result.position = { p[0], p[1], p[2] };
  camera->GetFocalPoint(p);
  result.focalPoint = { p[0], p[1], p[2] };
  camera->GetViewUp(p);
  result.viewUp = { p[0], p[1], p[2] };
  result.viewAngleDegrees = camera->GetViewAngle();
  result.parallelScale = camera->GetParallelScale();
  result.parallel = camera->GetParallelProjection() != 0;
  return result;
}

struct ReferenceSettings
{
  int blendMode = vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND;
  double stepWorld = 0.1;
  double additiveUnit = 1.0;
  double averageRange[2] = { 0.0, 1.0 };    // normalized
  std::vector<accelvolume::Box> regions;    // empty = whole volume
  std::vector<accelvolume::HalfSpace> clip; // index space
};

// CPU reference of what the slice mapper should show over a black background (RGB, [0,1]).
// raysEnd: optional per-pixel distance to opaque geometry; alpha: optional per-pixel coverage.
inline std::vector<float> RenderReferenceImage(vtkImageData* image, vtkVolume* volume,
  vtkRenderer* renderer, int width, int height, const ReferenceSettings& settings,
  const std::vector<double>* raysEnd = nullptr, std::vector<float>* alpha = nullptr)
{
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  double range[2];
  scalars->GetRange(range);
  const double span = range[1] > range[0] ? range[1] - range[0] : 1.0;
  accelvolume::ScalarVolume core;
  image->GetDimensions(core.dims);
  core.values.resize(static_cast<size_t>(scalars->GetNumberOfTuples()));
  for (size_t i = 0; i < core.values.size(); ++i)
  {
    core.values[i] =
      static_cast<float>((scalars->GetTuple1(static_cast<vtkIdType>(i)) - range[0]) / span);
  }
  vtkNew<vtkMatrix4x4> indexToWorld;
  vtkMatrix4x4::Multiply4x4(volume->GetMatrix(), image->GetIndexToPhysicalMatrix(), indexToWorld);
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      core.indexToWorld.m[r][c] = indexToWorld->GetElement(r, c);
    }
  }
  vtkVolumeProperty* property = volume->GetProperty();
  std::vector<float> opacity(TableSize);
  std::vector<float> colour(3 * TableSize);
  property->GetScalarOpacity()->GetTable(range[0], range[0] + span, TableSize, opacity.data());
  property->GetRGBTransferFunction()->GetTable(range[0], range[0] + span, TableSize, colour.data());
  accelvolume::OpacityTable opacityTable;
  opacityTable.values = opacity;
  accelvolume::ReferenceOptions options;
  options.stepWorld = settings.stepWorld;
  options.additiveUnitDistance = settings.additiveUnit;
  options.averageRangeMin = settings.averageRange[0];
  options.averageRangeMax = settings.averageRange[1];
  options.nearest = property->GetInterpolationType() == VTK_NEAREST_INTERPOLATION;
  switch (settings.blendMode)
  {
    case vtkVolumeMapper::MINIMUM_INTENSITY_BLEND:
      options.blend = accelvolume::Blend::Minimum;
      break;
    case vtkVolumeMapper::ADDITIVE_BLEND:
      options.blend = accelvolume::Blend::Additive;
      break;
    case vtkVolumeMapper::AVERAGE_INTENSITY_BLEND:
      options.blend = accelvolume::Blend::Average;
      break;
    default:
      options.blend = accelvolume::Blend::Maximum;
  }
  std::vector<accelvolume::Box> regions = settings.regions;
  if (regions.empty())
  {
    accelvolume::Box box;
    box.upper = { core.dims[0] - 1.0, core.dims[1] - 1.0, core.dims[2] - 1.0 };
    regions.push_back(box);
  }
  const auto pixels = accelvolume::RenderReference(core, regions, settings.clip, opacityTable,
    ToCoreCamera(renderer->GetActiveCamera()), width, height, options, raysEnd);
  auto lookup = [&](const std::vector<float>& table, int components, int component, float value)
  {
    const float position = std::min(1.0f, std::max(0.0f, value)) * (TableSize - 1);
    const int below = std::min(TableSize - 2, static_cast<int>(position));
    const float fraction = position - below;
    return table[below * components + component] * (1 - fraction) +
      table[(below + 1) * components + component] * fraction;
  };
  std::vector<float> rgb(static_cast<size_t>(width) * height * 3, 0.0f);
  if (alpha)
  {
    alpha->assign(pixels.size(), 0.0f);
  }
  for (size_t i = 0; i < pixels.size(); ++i)
  {
    if (!pixels[i].hit)
    {
      continue;
    }
    const float v = pixels[i].value;
    if (alpha)
    {
      const bool projection = settings.blendMode == vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND ||
        settings.blendMode == vtkVolumeMapper::MINIMUM_INTENSITY_BLEND;
      (*alpha)[i] = projection ? lookup(opacity, 1, 0, v) : 1.0f;
    }
    for (int c = 0; c < 3; ++c)
    {
      if (settings.blendMode == vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND ||
        settings.blendMode == vtkVolumeMapper::MINIMUM_INTENSITY_BLEND)
      {
        rgb[3 * i + c] = lookup(colour, 3, c, v) * lookup(opacity, 1, 0, v);
      }
      else
      {
        rgb[3 * i + c] = std::min(1.0f, std::max(0.0f, v));
      }
    }
  }
  return rgb;
}

// Writes an RGB [0,1] image as PNG into $ACCELVOLUME_TEST_DUMP (when set) for inspection.
inline void DumpImage(const std::string& name, const std::vector<float>& rgb, int width, int height)
{
  const char* folder = std::getenv("ACCELVOLUME_TEST_DUMP");
  if (!folder || !*folder)
  {
    return;
  }
  vtkNew<vtkImageData> image;
  image->SetDimensions(width, height, 1);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  auto* out = static_cast<unsigned char*>(image->GetScalarPointer());
  for (size_t i = 0; i < rgb.size(); ++i)
  {
    out[i] = static_cast<unsigned char>(std::min(1.0f, std::max(0.0f, rgb[i])) * 255.0f + 0.5f);
  }
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName((std::string(folder) + "/" + name + ".png").c_str());
  writer->SetInputData(image);
  writer->Write();
}

struct ImageDifference
{
  double mean = 0;
  double maximum = 0;
  double fractionAbove = 0; // of pixels differing by more than the threshold
};

inline ImageDifference CompareImages(
  const std::vector<float>& a, const std::vector<float>& b, double threshold)
{
  ImageDifference result;
  if (a.size() != b.size() || a.empty())
  {
    result.mean = result.maximum = result.fractionAbove = 1e9;
    return result;
  }
  size_t above = 0;
  const size_t pixelCount = a.size() / 3;
  for (size_t p = 0; p < pixelCount; ++p)
  {
    double pixelMax = 0;
    for (int c = 0; c < 3; ++c)
    {
      const double d = std::fabs(a[3 * p + c] - b[3 * p + c]);
      result.mean += d;
      pixelMax = std::max(pixelMax, d);
    }
    result.maximum = std::max(result.maximum, pixelMax);
    above += pixelMax > threshold ? 1 : 0;
  }
  result.mean /= static_cast<double>(a.size());
  result.fractionAbove = static_cast<double>(above) / pixelCount;
  return result;
}

inline bool Report(
  const char* what, const ImageDifference& d, double meanLimit, double fractionLimit)
{
  const bool ok = d.mean <= meanLimit && d.fractionAbove <= fractionLimit;
  std::cout << what << ": mean |diff| " << d.mean << " (limit " << meanLimit << "), max "
            << d.maximum << ", fraction over threshold " << d.fractionAbove << " (limit "
            << fractionLimit << ")" << (ok ? "" : "  FAILED") << "\n";
  return ok;
}
}

#endif
