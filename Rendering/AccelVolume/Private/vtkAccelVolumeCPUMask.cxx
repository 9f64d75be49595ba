// The CPU ray caster's mask bytes and label tables.
#include "vtkAccelVolumeCPUMask.h"

#include "vtkAccelVolumeSliceMask.h" // the slice mapper's mask rules, shared

#include "vtkColorTransferFunction.h"
#include "vtkImageData.h"
#include "vtkPiecewiseFunction.h"
#include "vtkVolumeProperty.h"

#include <algorithm>

bool vtkAccelVolumeCPUMask::Update(vtkImageData* input, vtkImageData* user, bool binary,
  bool labelMap, bool& changed, std::string& error)
{
  vtkImageData* source = nullptr;
  bool neighbours = false;
  if (user && labelMap)
  {
    source =
      user; // a label map keeps its meaning; hidden points are then drawn (as the slice mapper)
  }
  else if (!user || binary)
  {
    if (vtkAccelVolumeHiddenPointsMask(input, user, this->GhostMask, this->GhostMaskTime))
    {
      source = this->GhostMask;
      neighbours = true;
    }
    else
    {
      source = user;
    }
  }
  labelMap = labelMap && source == user;
  const unsigned long time = source ? vtkAccelVolumeMaskTime(source) : 0;
  changed = source != this->Source || time != this->SourceTime || labelMap != this->LabelMap ||
    neighbours != this->Neighbours;
  if (!changed)
  {
    return true;
  }
  this->Source = nullptr; // until the bytes are valid
  this->LabelMap = labelMap;
  this->Neighbours = neighbours;
  if (!source)
  {
    std::vector<std::uint8_t>().swap(this->Bytes);
    return true;
  }
  if (!vtkAccelVolumeMaskBytes(source, input->GetDimensions(), labelMap, this->Bytes, error))
  {
    return false;
  }
  this->Source = source;
  this->SourceTime = time;
  return true;
}

void vtkAccelVolumeCPUMask::UpdateLabelTables(
  vtkVolumeProperty* property, const double range[2], double high, int size)
{
  if (!this->Source || !this->LabelMap)
  {
    return;
  }
  // The property's time covers its own functions (the labels' defaults); each label's functions
  // are asked for theirs.
  unsigned long time = std::max({ property->GetMTime(), property->GetLabelColorMTime().GetMTime(),
    property->GetLabelScalarOpacityMTime().GetMTime() });
  for (const int label : property->GetLabelMapLabels())
  {
    if (vtkColorTransferFunction* colours = property->GetLabelColor(label))
    {
      time = std::max(time, colours->GetMTime());
    }
    if (vtkPiecewiseFunction* opacities = property->GetLabelScalarOpacity(label))
    {
      time = std::max(time, opacities->GetMTime());
    }
  }
  if (!this->LabelTables.empty() && property == this->TableProperty && time == this->TableTime &&
    range[0] == this->TableRange[0] && high == this->TableRange[1] && size == this->TableSize)
  {
    return;
  }
  const double tableRange[2] = { range[0], high };
  this->LabelTables = vtkAccelVolumeLabelTables(property, tableRange, size);
  this->TableProperty = property;
  this->TableTime = time;
  this->TableRange[0] = range[0];
  this->TableRange[1] = high;
  this->TableSize = size;
}
