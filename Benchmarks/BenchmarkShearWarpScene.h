// What one process of accelvolume_benchmark_shearwarp renders and records: the volume, the
// headless window with the shear-warp mappers of a case, the frame records, and VolPack rendering
// the same scene.
#ifndef accelvolume_benchmark_BenchmarkShearWarpScene_h
#define accelvolume_benchmark_BenchmarkShearWarpScene_h

#include "BenchmarkShearWarpResults.h"

#include "vtkAccelVolumeHeadlessRenderWindow.h"
#include "vtkAccelVolumeShearWarpMapper.h"

#include <vtkNew.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkVolume.h>
#include <vtkVolumeProperty.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

class vtkCamera;
class vtkImageData;
class vtkMultiProcessController;

namespace accelvolume::benchmark::shearwarp
{

using Image = std::vector<std::uint8_t>; // RGB bytes, bottom row first

// Loads `name` from the data folder (a line on stdout unless quiet); false after saying why.
bool LoadDataset(const std::string& dataDir, const std::string& name, DatasetInfo& info,
  vtkSmartPointer<vtkImageData>& image, bool quiet);
// The voxels NAME_<X>x<Y>x<Z>_... says the file holds (0 when the name does not say).
double VoxelsOfFile(const std::string& file);

// One headless window, renderer and volume property (the `accelvolume render --tf` preset over the
// data range, shading on or off); mappers added with Add are shown one at a time.
class Scene
{
public:
  Scene(const DatasetInfo& info, int backend, const std::string& tf, bool shade, int size);
  ~Scene();
  Scene(const Scene&) = delete;
  Scene& operator=(const Scene&) = delete;

  void Add(
    vtkImageData* image, const Config& cfg, int threads, vtkMultiProcessController* controller);
  // Parallel camera fitted to the volume (looking along +z), turned to the fixed view.
  void FixedView(double azimuth, double elevation);
  void Turn(double degrees); // azimuth
  // Shows mapper k alone and renders it: wall milliseconds of Render() + a 1x1 read-back.
  double Render(std::size_t k);
  Image Capture();

  vtkAccelVolumeShearWarpMapper* Mapper(std::size_t k) const { return this->Mappers[k]; }
  vtkVolume* Volume(std::size_t k) const { return this->Volumes[k]; }
  vtkCamera* Camera() const;
  vtkVolumeProperty* Property() const { return this->VolumeProperty; }
  double LastCores() const { return this->Cores; } // process CPU / wall time of the last Render

private:
  vtkNew<vtkAccelVolumeHeadlessRenderWindow> Window;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkVolumeProperty> VolumeProperty;
  vtkNew<vtkUnsignedCharArray> OnePixel;
  std::vector<vtkSmartPointer<vtkVolume>> Volumes;
  std::vector<vtkAccelVolumeShearWarpMapper*> Mappers;
  int Size = 0;
  double Cores = 0;
};

// The first frame's numbers (at the fixed view, encoding included), and a timed frame's.
void RecordFirst(vtkAccelVolumeShearWarpMapper* m, double wallMs, RunResult& r);
void Record(
  vtkAccelVolumeShearWarpMapper* m, double wallMs, double cores, double perFrame, RunResult& r);

// VolPack rendering a case's scene: the volume quantized over its range to 8 bits, the property's
// tables at 256 entries (colour: the RGB transfer function, VolPack's RGB mode, or with grey the
// mean of R, G, B in its luminance mode; opacity raised to spacing(axis) / unit distance,
// VolPack's opacity being per voxel along the principal axis), VTK's headlight, maximum ray
// opacity 0.99 (the mapper's termination threshold), the camera's view as voxel -> pixel map.
// The image handed back is RGB (r = g = b in grey mode).
class VolPackAnchor
{
public:
  VolPackAnchor(vtkImageData* image, const DatasetInfo& info);
  ~VolPackAnchor();
  static bool Available(); // built with libvolpack
  // Classifies when the tf / shading / axis / colour mode changed; false with note when it can't.
  bool Prepare(vtkVolumeProperty* property, bool shade, int axis, const std::string& tf, bool grey,
    std::string& note);
  // Renders the camera's view: VolPack's milliseconds (shading table + render), NaN with note.
  double Render(vtkImageData* image, vtkVolume* volume, vtkCamera* camera, int size, Image* rgb,
    int& axis, std::string& note);
  double ClassifyMs() const;
  double OpacityExponent() const;

private:
  struct Internals;
  std::unique_ptr<Internals> Impl;
};

} // namespace accelvolume::benchmark::shearwarp

#endif
