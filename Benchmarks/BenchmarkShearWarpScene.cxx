// The scene one process of accelvolume_benchmark_shearwarp renders, its frame records, and
// VolPack rendering the same scene (see BenchmarkShearWarpScene.h).
#include "BenchmarkShearWarpScene.h"

#include "BenchmarkImageMetrics.h"
#include "Options.h"
#include "TransferFunctions.h"
#include "VolumeIO.h"

#include <vtkCamera.h>
#include <vtkColorTransferFunction.h>
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkMatrix4x4.h>
#include <vtkMultiProcessController.h>
#include <vtkPiecewiseFunction.h>
#include <vtkPointData.h>

#ifdef ACCELVOLUME_HAVE_VOLPACK
#include "VolPackRenderer.h"
#endif

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <regex>

namespace accelvolume::benchmark::shearwarp
{
namespace
{
// voxel index -> image pixel coordinates of the renderer's parallel camera (as the mapper).
void VoxelToImage(vtkImageData* image, vtkVolume* volume, vtkCamera* camera, int width, int height,
  double out[3][4])
{
  vtkNew<vtkMatrix4x4> indexToWorld;
  vtkMatrix4x4::Multiply4x4(volume->GetMatrix(), image->GetIndexToPhysicalMatrix(), indexToWorld);
  vtkMatrix4x4* view = camera->GetViewTransformMatrix();
  const double ps = camera->GetParallelScale();
  const double aspect = static_cast<double>(width) / height;
  const double scale[3] = { width / (2.0 * ps * aspect), height / (2.0 * ps), -1.0 };
  double centre[2];
  camera->GetWindowCenter(centre);
  const double offset[3] = { width / 2.0 + centre[0] * width / 2.0,
    height / 2.0 + centre[1] * height / 2.0, 0.0 };
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      double value = c == 3 ? view->GetElement(r, 3) : 0.0;
      for (int q = 0; q < 3; ++q)
      {
        value += view->GetElement(r, q) * indexToWorld->GetElement(q, c);
      }
      out[r][c] = scale[r] * value + (c == 3 ? offset[r] : 0.0);
    }
  }
}
} // namespace

bool LoadDataset(const std::string& dataDir, const std::string& name, DatasetInfo& info,
  vtkSmartPointer<vtkImageData>& image, bool quiet)
{
  info.Name = name;
  info.File = FindDatasetFile(dataDir, name);
  std::string error = "no file " + name + "_<X>x<Y>x<Z>_<type>.raw[.gz] in " + dataDir;
  if (!info.File.empty())
  {
    accelvolume::cli::VolumeRequest request;
    request.inputPath = info.File;
    const auto start = Clock::now();
    image = accelvolume::cli::LoadVolume(request, error);
    info.LoadSeconds = SecondsSince(start);
  }
  if (!image)
  {
    std::cerr << "dataset " << name << ": " << error << "\n";
    return false;
  }
  info.Description = accelvolume::cli::DescribeVolume(image);
  image->GetSpacing(info.Spacing);
  image->GetDimensions(info.Dims);
  image->GetPointData()->GetScalars()->GetRange(info.Range);
  if (!quiet)
  {
    std::cout << "=== " << name << ": " << info.Description << "\n" << std::flush;
  }
  return true;
}

// The voxels NAME_<X>x<Y>x<Z>_... says the file holds (0 when the name does not say).
double VoxelsOfFile(const std::string& file)
{
  std::smatch m;
  const std::string name = std::filesystem::path(file).filename().string();
  if (!std::regex_search(name, m, std::regex(R"(_(\d+)x(\d+)x(\d+)_)")))
  {
    return 0;
  }
  return std::stod(m[1]) * std::stod(m[2]) * std::stod(m[3]);
}

Scene::Scene(const DatasetInfo& info, int backend, const std::string& tf, bool shade, int size)
  : Size(size)
{
  Harness::StartWindow(this->Window, backend, size, size);
  this->Renderer->SetBackground(0, 0, 0);
  this->Window->AddRenderer(this->Renderer);
  accelvolume::cli::Options cli; // `render --blend composite --tf <tf> --shade on|off`
  cli.blend = accelvolume::cli::BlendKind::Composite;
  cli.haveShade = true;
  cli.shade = shade;
  cli.transferFunction = tf;
  const double high = info.Range[1] > info.Range[0] ? info.Range[1] : info.Range[0] + 1;
  const double window[2] = { info.Range[0], high };
  accelvolume::cli::ApplyTransferFunction(
    accelvolume::cli::LoadTransferFunction(cli), cli, window, this->VolumeProperty);
}

Scene::~Scene()
{
  this->Window->RemoveRenderer(this->Renderer);
}

void Scene::Add(
  vtkImageData* image, const Config& cfg, int threads, vtkMultiProcessController* controller)
{
  auto mapper = vtkSmartPointer<vtkAccelVolumeShearWarpMapper>::New();
  mapper->SetInputData(image);
  mapper->SetBlendModeToComposite();
  mapper->SetRunLengthEncoding(cfg.Rle);
  mapper->SetEarlyRayTermination(cfg.Ert);
  mapper->SetLoadBalancing(cfg.Balance);
  mapper->SetShadingMode(cfg.Phong ? vtkAccelVolumeShearWarpMapper::SHADING_PHONG
                                   : vtkAccelVolumeShearWarpMapper::SHADING_LOOKUP_TABLE);
  mapper->SetNumberOfThreads(threads);
  mapper->SetController(controller);
  auto volume = vtkSmartPointer<vtkVolume>::New();
  volume->SetMapper(mapper);
  volume->SetProperty(this->VolumeProperty);
  this->Renderer->AddVolume(volume);
  this->Volumes.push_back(volume);
  this->Mappers.push_back(mapper);
}

void Scene::FixedView(double azimuth, double elevation)
{
  double bounds[6];
  this->Renderer->ComputeVisiblePropBounds(bounds);
  const double centre[3] = { (bounds[0] + bounds[1]) / 2, (bounds[2] + bounds[3]) / 2,
    (bounds[4] + bounds[5]) / 2 };
  vtkCamera* camera = this->Renderer->GetActiveCamera();
  camera->ParallelProjectionOn();
  camera->SetFocalPoint(centre);
  camera->SetPosition(centre[0], centre[1], centre[2] - 1);
  camera->SetViewUp(0, 1, 0);
  this->Renderer->ResetCamera(bounds);
  camera->Azimuth(azimuth);
  camera->Elevation(elevation);
  camera->OrthogonalizeViewUp();
  this->Renderer->ResetCameraClippingRange(bounds);
}

void Scene::Turn(double degrees)
{
  this->Renderer->GetActiveCamera()->Azimuth(degrees);
  this->Renderer->ResetCameraClippingRange();
}

double Scene::Render(std::size_t k)
{
  for (std::size_t j = 0; j < this->Volumes.size(); ++j)
  {
    this->Volumes[j]->SetVisibility(j == k);
  }
  const double cpuStart = ProcessCpuMs();
  const auto start = Clock::now();
  this->Window->Render();
  const int centre = this->Size / 2;
  static_cast<vtkRenderWindow*>(this->Window)
    ->GetPixelData(centre, centre, centre, centre, 0, this->OnePixel.Get());
  const double wall = MsSince(start);
  this->Cores = SafeRatio(ProcessCpuMs() - cpuStart, wall);
  return wall;
}

Image Scene::Capture()
{
  return accelvolume::benchmark::Capture(this->Window, this->Size, this->Size);
}

vtkCamera* Scene::Camera() const
{
  return this->Renderer->GetActiveCamera();
}

void Record(
  vtkAccelVolumeShearWarpMapper* m, double wallMs, double cores, double perFrame, RunResult& r)
{
  r.Cores.push_back(cores);
  r.Workers.push_back(m->GetLastNumberOfWorkers());
  r.BandMs.clear();
  for (int band = 0; band < m->GetLastNumberOfBands(); ++band)
  {
    r.BandMs.push_back(1000.0 * m->GetLastBandTime(band));
  }
  r.RenderMs.push_back(1000.0 * m->GetLastRenderTime());
  r.EngineMs.push_back(1000.0 *
    (m->GetLastEncodeTime() + m->GetLastTableTime() + m->GetLastCompositeTime() +
      m->GetLastGatherTime() + m->GetLastWarpTime()));
  r.WallMs.push_back(wallMs);
  r.CompositeMs.push_back(1000.0 * m->GetLastCompositeTime());
  r.WarpMs.push_back(1000.0 * m->GetLastWarpTime());
  r.TableMs.push_back(1000.0 * m->GetLastTableTime());
  r.ImagePartsMs.push_back(1000.0 * m->GetLastImagePartsTime());
  r.GatherMs.push_back(1000.0 * m->GetLastGatherTime());
  r.Imbalance.push_back(m->GetLastImbalance());
  r.Voxels += perFrame * static_cast<double>(m->GetLastNumberOfVoxels());
  r.Samples += perFrame * static_cast<double>(m->GetLastNumberOfSamples());
  r.SkippedPixels += perFrame * static_cast<double>(m->GetLastNumberOfSkippedPixels());
  r.StoredVoxels = m->GetLastNumberOfStoredVoxels();
  r.EncodedBytes = std::max<long long>(r.EncodedBytes, m->GetEncodedBytes());
  r.Axis = m->GetLastPrincipalAxis();
  r.Bands = m->GetLastNumberOfBands();
  std::vector<double> scanlines(static_cast<std::size_t>(m->GetLastNumberOfScanlines()));
  for (std::size_t v = 0; v < scanlines.size(); ++v)
  {
    scanlines[v] = 1000.0 * m->GetLastScanlineTime(static_cast<int>(v));
  }
  r.ScanlineMs.push_back(std::move(scanlines));
}

void RecordFirst(vtkAccelVolumeShearWarpMapper* m, double wallMs, RunResult& r)
{
  r.FirstFrameMs = wallMs;
  r.EncodeMs = 1000.0 * m->GetLastEncodeTime();
  r.StoredVoxels = m->GetLastNumberOfStoredVoxels();
  r.EncodedBytes = m->GetEncodedBytes();
  r.Axis = m->GetLastPrincipalAxis();
}

// ---- VolPack ------------------------------------------------------------------------------------
struct VolPackAnchor::Internals
{
  DatasetInfo Info;
  std::vector<std::uint8_t> Scalars; // the volume quantized over its range to 0..255
  std::string PreparedKey;           // tf / shading / axis the classified volume was built for
  double ClassifyMs = std::nan("");
  double Exponent = 1;
#ifdef ACCELVOLUME_HAVE_VOLPACK
  std::unique_ptr<accelvolume::bench::VolPackRenderer> Renderer;
  accelvolume::bench::VolPackScene Scene;
#endif
};

VolPackAnchor::VolPackAnchor(vtkImageData* image, const DatasetInfo& info)
  : Impl(new Internals)
{
  this->Impl->Info = info;
  if (!Available())
  {
    return;
  }
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  const vtkIdType count = scalars->GetNumberOfTuples();
  std::vector<std::uint8_t>& out = this->Impl->Scalars;
  out.resize(static_cast<std::size_t>(count));
  const double low = info.Range[0];
  const double scale = 255.0 / std::max(1e-30, info.Range[1] - info.Range[0]);
  for (vtkIdType i = 0; i < count; ++i)
  {
    const double q = (scalars->GetComponent(i, 0) - low) * scale;
    out[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(std::clamp(q + 0.5, 0.0, 255.0));
  }
}

VolPackAnchor::~VolPackAnchor() = default;

bool VolPackAnchor::Available()
{
#ifdef ACCELVOLUME_HAVE_VOLPACK
  return true;
#else
  return false;
#endif
}

double VolPackAnchor::ClassifyMs() const
{
  return this->Impl->ClassifyMs;
}

double VolPackAnchor::OpacityExponent() const
{
  return this->Impl->Exponent;
}

bool VolPackAnchor::Prepare(vtkVolumeProperty* property, bool shade, int axis,
  const std::string& tf, bool grey, std::string& note)
{
#ifdef ACCELVOLUME_HAVE_VOLPACK
  Internals& vp = *this->Impl;
  const DatasetInfo& info = vp.Info;
  const double unit = std::max(1e-6, property->GetScalarOpacityUnitDistance(0));
  vp.Exponent = info.Spacing[std::clamp(axis, 0, 2)] / unit;
  const std::string key =
    tf + (shade ? "/shaded/" : "/unshaded/") + std::to_string(axis) + (grey ? "/grey" : "/rgb");
  if (key == vp.PreparedKey && vp.Renderer)
  {
    return true;
  }
  vp.PreparedKey.clear();
  accelvolume::bench::VolPackScene& s = vp.Scene;
  std::copy(info.Dims, info.Dims + 3, s.dims);
  s.scalars = vp.Scalars.data();
  s.opacity.assign(256, 0.0f);
  s.grey.assign(256, 0.0f);
  s.colour.assign(grey ? 0 : 256 * 3, 0.0f);
  // The same scalar -> level mapping as the quantization: level i is the value Range[0] +
  // (Range[1] - Range[0]) * i / 255, where the mapper's tables are sampled.
  for (int i = 0; i < 256; ++i)
  {
    const double x = info.Range[0] + (info.Range[1] - info.Range[0]) * i / 255.0;
    const double a = std::clamp(property->GetScalarOpacity(0)->GetValue(x), 0.0, 1.0);
    double rgb[3];
    property->GetRGBTransferFunction(0)->GetColor(x, rgb);
    s.opacity[i] = static_cast<float>(1.0 - std::pow(1.0 - a, vp.Exponent));
    s.grey[i] = static_cast<float>(std::clamp((rgb[0] + rgb[1] + rgb[2]) / 3.0, 0.0, 1.0));
    if (!grey)
    {
      for (int c = 0; c < 3; ++c)
      {
        s.colour[3 * i + c] = static_cast<float>(std::clamp(rgb[c], 0.0, 1.0));
      }
    }
  }
  s.shade = shade;
  s.ambient = static_cast<float>(property->GetAmbient(0));
  s.diffuse = static_cast<float>(property->GetDiffuse(0));
  s.specular = static_cast<float>(property->GetSpecular(0));
  s.specularPower = static_cast<float>(property->GetSpecularPower(0));
  s.lightDirection[0] = s.lightDirection[1] = 0;
  s.lightDirection[2] = -1; // VTK's headlight: towards the viewer (image depth grows away)
  s.maxRayOpacity = 0.99;   // the mapper's EarlyRayTerminationThreshold
  vp.Renderer = std::make_unique<accelvolume::bench::VolPackRenderer>();
  if (!vp.Renderer->Prepare(s, note))
  {
    vp.Renderer.reset();
    return false;
  }
  vp.ClassifyMs = 1000.0 * vp.Renderer->ClassifySeconds();
  vp.PreparedKey = key;
  return true;
#else
  (void)property, (void)shade, (void)axis, (void)tf, (void)grey;
  note = "libvolpack not found at build time";
  return false;
#endif
}

double VolPackAnchor::Render(vtkImageData* image, vtkVolume* volume, vtkCamera* camera, int size,
  Image* rgb, int& axis, std::string& note)
{
#ifdef ACCELVOLUME_HAVE_VOLPACK
  Internals& vp = *this->Impl;
  accelvolume::bench::VolPackScene& s = vp.Scene;
  s.width = s.height = size;
  VoxelToImage(image, volume, camera, size, size, s.voxelToImage);
  std::vector<float> rgba;
  if (!vp.Renderer || !vp.Renderer->Render(s, rgba, note))
  {
    return std::nan("");
  }
  axis = vp.Renderer->LastPrincipalAxis();
  if (rgb)
  {
    rgb->resize(static_cast<std::size_t>(size) * size * 3);
    for (std::size_t p = 0; p < rgb->size() / 3; ++p)
    {
      for (int c = 0; c < 3; ++c) // premultiplied on black: the colour shown
      {
        (*rgb)[3 * p + c] =
          static_cast<std::uint8_t>(std::clamp(rgba[4 * p + c] * 255.0f + 0.5f, 0.0f, 255.0f));
      }
    }
  }
  return 1000.0 * vp.Renderer->LastRenderSeconds();
#else
  (void)image, (void)volume, (void)camera, (void)size, (void)rgb, (void)axis;
  note = "libvolpack not found at build time";
  return std::nan("");
#endif
}

} // namespace accelvolume::benchmark::shearwarp
