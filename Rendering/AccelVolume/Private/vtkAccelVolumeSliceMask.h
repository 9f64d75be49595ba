// vtkAccelVolumeSliceMask: the slice mapper's mask input on the GPU (private to the module): a
// nearest-sampled R8 3D texture over the volume's voxels and, for label maps, a 2D colour table
// over (scalar, label) built as vtkGPUVolumeRayCastMapper builds it (a label without its own
// colour or opacity function uses the property's).
#ifndef vtkAccelVolumeSliceMask_h
#define vtkAccelVolumeSliceMask_h

#include "vtkNew.h"          // For vtkNew
#include "vtkSmartPointer.h" // For vtkSmartPointer

#include <string>
#include <vector>

class vtkImageData;
class vtkOpenGLRenderWindow;
class vtkTextureObject;
class vtkVolumeProperty;
class vtkWindow;

class vtkAccelVolumeSliceMask
{
public:
  vtkAccelVolumeSliceMask();
  ~vtkAccelVolumeSliceMask();

  static constexpr int TableSize = 1024; // scalar entries per label row, as the 1D tables
  static constexpr int Labels = 256;     // rows: label values 0..255

  /**
   * Uploads `mask` (dimensions `dims`, one component; binary: nonzero = inside, label map:
   * values clamped to 0..255) when it or the type changed. False with a user-facing message.
   */
  bool Update(vtkOpenGLRenderWindow* window, vtkImageData* mask, const int dims[3], bool labelMap,
    std::string& error);
  /** The label map's table over `range` when the property's functions changed. */
  void UpdateLabelTable(
    vtkOpenGLRenderWindow* window, vtkVolumeProperty* property, const double range[2]);

  vtkTextureObject* GetTexture() { return this->Texture; }
  vtkTextureObject* GetLabelTable() { return this->LabelTable; }
  void ReleaseGraphicsResources(vtkWindow* window);

private:
  vtkAccelVolumeSliceMask(const vtkAccelVolumeSliceMask&) = delete;
  void operator=(const vtkAccelVolumeSliceMask&) = delete;

  vtkNew<vtkTextureObject> Texture;
  vtkNew<vtkTextureObject> LabelTable;
  vtkImageData* Uploaded = nullptr;
  unsigned long UploadTime = 0;
  bool UploadedLabelMap = false;
  vtkVolumeProperty* TableProperty = nullptr;
  unsigned long TableTime = 0;
  double TableRange[2] = { 0, 0 };
};

/**
 * One byte per voxel of `mask` (binary: 255 inside, 0 outside; label map: the value rounded and
 * clamped to 0..255). False with a user-facing message when its dimensions differ from `dims`
 * or its scalars are not one component per point.
 */
bool vtkAccelVolumeMaskBytes(vtkImageData* mask, const int dims[3], bool labelMap,
  std::vector<unsigned char>& bytes, std::string& error);
/** The newest of the mask image's and its scalars' modification times. */
unsigned long vtkAccelVolumeMaskTime(vtkImageData* mask);
/**
 * Label-map tables as vtkGPUVolumeRayCastMapper builds them: 256 rows (labels 0..255, row 0
 * unused) of `size` RGBA entries over [range[0], range[1]], from each label's colour and opacity
 * functions or the property's first ones.
 */
std::vector<float> vtkAccelVolumeLabelTables(
  vtkVolumeProperty* property, const double range[2], int size);

/**
 * The input's hidden points (ghost array HIDDENPOINT, as vtkUniformGrid blanking sets) as a binary
 * mask (255 visible, 0 hidden), intersected with the binary mask `user` (may be null). Rebuilt
 * into `mask` when the arrays changed since `time`. False when no point is hidden.
 */
bool vtkAccelVolumeHiddenPointsMask(vtkImageData* input, vtkImageData* user,
  vtkSmartPointer<vtkImageData>& mask, unsigned long& time);

#endif
