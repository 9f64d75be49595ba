// vtkAccelVolumeCPUMask: the CPU ray caster's mask (private to the module): one byte per voxel
// from the user's mask input (binary, or a label map with its tables) or from the input's ghost
// arrays (hidden points, intersected with a binary user mask), chosen as the slice mapper
// chooses them, so both mappers hide and colour the same samples.
#ifndef vtkAccelVolumeCPUMask_h
#define vtkAccelVolumeCPUMask_h

#include "vtkSmartPointer.h" // For vtkSmartPointer

#include <cstdint>
#include <string>
#include <vector>

class vtkImageData;
class vtkVolumeProperty;

class vtkAccelVolumeCPUMask
{
public:
  /**
   * Brings the bytes up to date for a frame of `input` with the user's mask `user` (may be
   * null): `labelMap` when it is a label map that applies (composite, blend factor > 0, one
   * component), `binary` when it is a binary mask; a user mask that is neither is not used.
   * `changed` tells whether the bytes differ from the last frame's (the caster's caches then
   * need a new volume version). False with a user-facing message for a malformed mask.
   */
  bool Update(vtkImageData* input, vtkImageData* user, bool binary, bool labelMap, bool& changed,
    std::string& error);
  /** The label map's tables over [range[0], high] (`size` entries a row) when they changed. */
  void UpdateLabelTables(vtkVolumeProperty* property, const double range[2], double high, int size);

  /** Null when no mask applies. */
  const std::uint8_t* GetBytes() const { return this->Source ? this->Bytes.data() : nullptr; }
  /** The ghost arrays' rule: a sample is hidden when any voxel half a step away is. */
  bool GetNeighbours() const { return this->Neighbours; }
  /** The label tables, null unless a label map applies. */
  const float* GetLabelTables() const
  {
    return this->Source && this->LabelMap ? this->LabelTables.data() : nullptr;
  }

private:
  std::vector<std::uint8_t> Bytes;
  vtkImageData* Source = nullptr; // the image the bytes came from
  unsigned long SourceTime = 0;
  bool LabelMap = false;
  bool Neighbours = false;
  vtkSmartPointer<vtkImageData> GhostMask;
  unsigned long GhostMaskTime = 0;
  std::vector<float> LabelTables;
  vtkVolumeProperty* TableProperty = nullptr; // compared, never dereferenced
  unsigned long TableTime = 0;
  double TableRange[2] = { 0, 0 };
  int TableSize = 0;
};

#endif
