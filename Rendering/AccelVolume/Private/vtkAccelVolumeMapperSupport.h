// vtkAccelVolumeMapperSupport: scene and input handling shared by the AccelVolume mappers
// (input checks, scalar range, transfer-function tables, cropping regions and clipping planes
// in index space, VTK lights in eye space). Not installed.
#ifndef vtkAccelVolumeMapperSupport_h
#define vtkAccelVolumeMapperSupport_h

#include "common/Geometry.h"
#include "common/Lighting.h"
#include "common/ParallelFor.h"
#include "raycast/RayCastEngine.h" // RayCastTransfer, RayCastLighting
#include "skipping/MinMaxOctree.h" // ScalarType, VolumeView

#include "vtkDataArray.h"    // For vtkSmartPointer<vtkDataArray>
#include "vtkSmartPointer.h" // For vtkSmartPointer

#include <cstdint>

#include <string>
#include <vector>

class vtkAccelVolumeInputAdapter;
class vtkImageData;
class vtkMatrix4x4;
class vtkPlane;
class vtkPlaneCollection;
class vtkCamera;
class vtkOpenGLRenderWindow;
class vtkRenderer;
class vtkVolume;
class vtkTimeStamp;
class vtkVolumeMapper;
class vtkVolumeProperty;

// Point scalars the mappers can render: 1..maximumComponents components, a supported type,
// matching the image. False with a user-facing message otherwise (input may be null).
bool vtkAccelVolumeCheckInput(
  vtkImageData* input, vtkDataArray* scalars, std::string& error, int maximumComponents = 1);

// Core's ParallelFor on vtkSMPTools, one work item per range (the CPU mappers' tiles and bands
// are heavy items).
accelvolume::ParallelFor vtkAccelVolumeSMPParallelFor();

// The checks a CPU mapper's Render starts with: an OpenGL window to show the image in, a
// renderable input (vtkAccelVolumeInputAdapter::Fetch) and a volume property. Null, after a
// vtkErrorMacro on the mapper, when one is missing.
vtkOpenGLRenderWindow* vtkAccelVolumeBeginCPURender(vtkVolumeMapper* mapper,
  vtkAccelVolumeInputAdapter& adapter, vtkRenderer* renderer, vtkVolume* volume,
  vtkImageData*& input, vtkDataArray*& scalars, vtkVolumeProperty*& property);

// The core's view of VTK scalars (no copy); false for a type the mappers do not render.
bool vtkAccelVolumeScalarType(int vtkType, accelvolume::ScalarType& type);
bool vtkAccelVolumeView(vtkImageData* input, vtkDataArray* scalars, accelvolume::VolumeView& view);

// Cropping planes that are numbers (+-Inf clamp to the volume) when cropping is on, and
// clipping planes with a finite origin and a finite, non-zero normal. False with a user-facing
// message naming the plane otherwise.
bool vtkAccelVolumeCheckGeometry(vtkVolumeMapper* mapper, std::string& error);

// Finite scalar range; NaN / infinite data fall back to a unit range so tables stay defined.
void vtkAccelVolumeScalarRange(vtkDataArray* scalars, double range[2]);

// The values the slice mapper's texture holds for float / double scalars with NaN or infinite
// values: a copy with NaN and -Inf replaced by range[0] and +Inf by range[1] (range: the finite
// range above). Null when every value is finite (or the type is an integer type): use the
// scalars as they are.
vtkSmartPointer<vtkDataArray> vtkAccelVolumeFiniteScalars(
  vtkDataArray* scalars, const double range[2]);

// RGBA table of `size` entries over [range[0], range[1]] (range[1] <= range[0] widens to
// range[0] + 1): colour (or grey) and scalar opacity of the property's first component.
std::vector<float> vtkAccelVolumeTransferTable(
  vtkVolumeProperty* property, const double range[2], int size);

// The volume's index-space box; a one-voxel axis becomes a slab one voxel thick.
accelvolume::Box vtkAccelVolumeIndexBox(const int dims[3]);

// Index (0-based voxel numbers, as the mappers' textures and encodings count them) to world: the
// prop's matrix times the image's index-to-physical matrix, which VTK indexes by extent (voxel
// (0,0,0) of the array is structured point (extent[0], extent[2], extent[4])).
void vtkAccelVolumeIndexToWorld(vtkVolume* volume, vtkImageData* input, vtkMatrix4x4* indexToWorld);

// The visible cropping regions (or the whole box) in index coordinates.
std::vector<accelvolume::Box> vtkAccelVolumeRegions(
  vtkVolumeMapper* mapper, vtkImageData* input, const accelvolume::Box& volumeBox);

// A world plane as an index-space half-space (kept side: n.p + offset >= 0, the side its
// normal points to).
accelvolume::HalfSpace vtkAccelVolumeIndexHalfSpace(vtkPlane* plane, vtkMatrix4x4* indexToWorld);

// The mapper's clipping planes as index-space half-spaces (kept side: n.p + offset >= 0).
std::vector<accelvolume::HalfSpace> vtkAccelVolumeClipHalfSpaces(
  vtkPlaneCollection* planes, vtkMatrix4x4* indexToWorld);

// The smallest world length of one index step along the axes with more than one voxel (1 if
// none).
double vtkAccelVolumeSmallestSpacing(vtkMatrix4x4* indexToWorld, const int dims[3]);

// VTK's light model in eye space (every switched-on light of the renderer, as VTK's GPU mapper
// sees them after the renderer placed its headlights and camera lights; the property's
// coefficients; the renderer's two-sided lighting), and the matrix that takes an index-space
// gradient to eye space (inverse transpose of index -> eye), row-major.
struct vtkAccelVolumeLights
{
  accelvolume::LightModel Model;
  double NormalMatrix[3][3] = {};
};
void vtkAccelVolumeGetLights(vtkRenderer* renderer, vtkVolumeProperty* property,
  vtkMatrix4x4* indexToEye, vtkMatrix4x4* view, vtkAccelVolumeLights& lights);

// The CPU mappers' inputs to their engines: the transfer tables (TableSize entries over the data
// range, gradient opacity, unit distance) and versions that change when the scalars or the
// tables do, so engines rebuild their caches only then.
// (Its Components member is of a hidden Core type: harmless, the class never leaves the module.)
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wattributes"
#endif
class vtkAccelVolumeCPUInputs
{
public:
  static constexpr int TableSize = 1024; // as the slice mapper, so all classify alike

  // Bumps VolumeVersion when the scalars array, its MTime or the input's MTime changed; then
  // also renews the finite copy of float data with NaN / infinite values (so that the CPU
  // mappers see them as the slice mapper does).
  void UpdateVolume(vtkImageData* input, vtkDataArray* scalars);
  // The scalars the engines render: that finite copy, or the input's scalars.
  vtkDataArray* GetScalars() const;
  // Fills transfer for [range[0], high] (high: range[1], or range[0] + 1 for a constant volume),
  // with gradient opacity when the composite property uses it, in VTK's GPU mapper's units
  // (vtkAccelVolumeGradientAxisScale of the input; table over [0, (high - range[0]) / 4]);
  // bumps TransferVersion on change.
  void UpdateTransfer(vtkVolumeProperty* property, const double range[2], bool composite,
    vtkImageData* input, accelvolume::RayCastTransfer& transfer, double& high);
  // Multi-component scalars: fills transfer.components as vtkGPUVolumeRayCastMapper classifies
  // them (vtkAccelVolumeCPUComponents.cxx; count 1 for one component) and bumps
  // TransferVersion on change. Call after UpdateTransfer.
  void UpdateComponents(vtkVolumeProperty* property, vtkDataArray* scalars, bool composite,
    accelvolume::RayCastTransfer& transfer);

  std::uint64_t VolumeVersion = 0;
  std::uint64_t TransferVersion = 0;

private:
  vtkDataArray* Scalars = nullptr;
  vtkSmartPointer<vtkDataArray> Finite;
  unsigned long ScalarsTime = 0;
  unsigned long InputTime = 0;
  std::vector<float> Table;
  std::vector<float> GradientTable;
  double TableRange[2] = { 0, 0 };
  accelvolume::RayCastComponents Components;
};
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

// Dependent RGBA colours as VTK's GPU mapper reads them (no scale or bias for dependent 3-4
// components): normalised integer textures for 8- and 16-bit types, floats as they are; 0 for
// wider integers (VTK normalises them to their range).
double vtkAccelVolumeColourComponentScale(int dataType);

// Gradient magnitude in VTK's GPU mapper's units: per index axis, the factor taking the data
// value's central difference per index step to VTK's (mean spacing / spacing of that axis).
void vtkAccelVolumeGradientAxisScale(vtkImageData* input, double scale[3]);

// Component `index`'s gradient opacity table over [0, maximum], `size` entries, into `table`;
// empty when the function is 1 everywhere (VTK's mappers create that default when they ask a
// property for it, and vtkFixedPointVolumeRayCastMapper skips it too): the CPU mappers then keep
// their fast paths.
void vtkAccelVolumeGradientOpacityTable(
  vtkVolumeProperty* property, int index, double maximum, int size, std::vector<float>& table);

// What a vtkHardwareSelector pass asks of a volume (as VTK's GPU mapper): 0 = no selection,
// render; 1 = the actor / process pass: `colour` (the selector's prop colour) where the volume is
// seen; 2 = an attribute-id pass: nothing (voxel ids are not reported).
int vtkAccelVolumeSelectionMode(vtkRenderer* renderer, float colour[3]);

// VTK's lights and lighting coefficients in eye space for the CPU engines (shade: Phong on).
void vtkAccelVolumeCPULighting(vtkRenderer* renderer, vtkVolumeProperty* property,
  vtkMatrix4x4* indexToWorld, const int dims[3], vtkCamera* camera, bool shade,
  accelvolume::RayCastLighting& lighting);

#endif
