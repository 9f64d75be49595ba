// The slice mapper's mask texture and label-map colour table.
#include "vtkAccelVolumeSliceMask.h"

#include "vtkColorTransferFunction.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkTextureObject.h"
#include "vtkUnsignedCharArray.h"
#include "vtkVolumeProperty.h"
#include "vtk_glew.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

vtkAccelVolumeSliceMask::vtkAccelVolumeSliceMask() = default;

vtkAccelVolumeSliceMask::~vtkAccelVolumeSliceMask() = default;

bool vtkAccelVolumeMaskBytes(vtkImageData* mask, const int dims[3], bool labelMap,
  std::vector<unsigned char>& bytes, std::string& error)
{
  int maskDims[3];
  mask->GetDimensions(maskDims);
  vtkDataArray* values = mask->GetPointData()->GetScalars();
  if (!std::equal(maskDims, maskDims + 3, dims))
  {
    std::ostringstream message;
    message << "The mask input's dimensions (" << maskDims[0] << "x" << maskDims[1] << "x"
            << maskDims[2] << ") differ from the volume's (" << dims[0] << "x" << dims[1] << "x"
            << dims[2] << ")";
    error = message.str();
    return false;
  }
  if (!values || values->GetNumberOfComponents() != 1 ||
    values->GetNumberOfTuples() != mask->GetNumberOfPoints())
  {
    error = "The mask input needs one-component point scalars, one per voxel";
    return false;
  }
  const vtkIdType count = values->GetNumberOfTuples();
  bytes.resize(static_cast<size_t>(count));
  for (vtkIdType i = 0; i < count; ++i)
  {
    const double v = values->GetComponent(i, 0);
    bytes[static_cast<size_t>(i)] = labelMap
      ? static_cast<unsigned char>(std::min(255.0, std::max(0.0, std::floor(v + 0.5))))
      : static_cast<unsigned char>(v != 0.0 && !std::isnan(v) ? 255 : 0);
  }
  return true;
}

unsigned long vtkAccelVolumeMaskTime(vtkImageData* mask)
{
  vtkDataArray* values = mask->GetPointData()->GetScalars();
  return std::max(mask->GetMTime(), values ? values->GetMTime() : 0);
}

bool vtkAccelVolumeSliceMask::Update(vtkOpenGLRenderWindow* window, vtkImageData* mask,
  const int dims[3], bool labelMap, std::string& error)
{
  const unsigned long time = vtkAccelVolumeMaskTime(mask);
  if (this->Texture->GetHandle() && this->Uploaded == mask && this->UploadTime == time &&
    this->UploadedLabelMap == labelMap)
  {
    return true;
  }
  std::vector<unsigned char> bytes;
  if (!vtkAccelVolumeMaskBytes(mask, dims, labelMap, bytes, error))
  {
    return false;
  }
  this->Texture->SetContext(window);
  this->Texture->ResetFormatAndType();
  window->GetState()->vtkglPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  if (!this->Texture->Create3DFromRaw(
        dims[0], dims[1], dims[2], 1, VTK_UNSIGNED_CHAR, bytes.data()))
  {
    error = "The mask texture could not be created";
    return false;
  }
  this->Texture->SetMinificationFilter(vtkTextureObject::Nearest);
  this->Texture->SetMagnificationFilter(vtkTextureObject::Nearest);
  this->Uploaded = mask;
  this->UploadTime = time;
  this->UploadedLabelMap = labelMap;
  return true;
}

std::vector<float> vtkAccelVolumeLabelTables(
  vtkVolumeProperty* property, const double range[2], int size)
{
  const double high = range[1] > range[0] ? range[1] : range[0] + 1.0;
  std::vector<float> table(static_cast<size_t>(size) * vtkAccelVolumeSliceMask::Labels * 4, 0.0f);
  std::vector<float> colour(3 * static_cast<size_t>(size));
  std::vector<float> opacity(static_cast<size_t>(size));
  for (int label = 1; label < vtkAccelVolumeSliceMask::Labels; ++label)
  {
    vtkColorTransferFunction* colours = property->GetLabelColor(label);
    colours = colours ? colours : property->GetRGBTransferFunction(0);
    vtkPiecewiseFunction* opacities = property->GetLabelScalarOpacity(label);
    opacities = opacities ? opacities : property->GetScalarOpacity(0);
    colours->GetTable(range[0], high, size, colour.data());
    opacities->GetTable(range[0], high, size, opacity.data());
    float* row = &table[static_cast<size_t>(label) * size * 4];
    for (int i = 0; i < size; ++i)
    {
      std::copy(&colour[3 * i], &colour[3 * i] + 3, row + 4 * i);
      row[4 * i + 3] = opacity[i];
    }
  }
  return table;
}

void vtkAccelVolumeSliceMask::UpdateLabelTable(
  vtkOpenGLRenderWindow* window, vtkVolumeProperty* property, const double range[2])
{
  const unsigned long time = std::max({ property->GetMTime(),
    property->GetLabelColorMTime().GetMTime(), property->GetLabelScalarOpacityMTime().GetMTime() });
  if (this->LabelTable->GetHandle() && this->TableProperty == property && this->TableTime == time &&
    range[0] == this->TableRange[0] && range[1] == this->TableRange[1])
  {
    return;
  }
  std::vector<float> table = vtkAccelVolumeLabelTables(property, range, TableSize);
  this->LabelTable->SetContext(window);
  this->LabelTable->Create2DFromRaw(TableSize, Labels, 4, VTK_FLOAT, table.data());
  this->LabelTable->SetWrapS(vtkTextureObject::ClampToEdge);
  this->LabelTable->SetWrapT(vtkTextureObject::ClampToEdge);
  // Linear like the 1D table; rows are read at their centres, so labels never mix.
  this->LabelTable->SetMinificationFilter(vtkTextureObject::Linear);
  this->LabelTable->SetMagnificationFilter(vtkTextureObject::Linear);
  this->TableProperty = property;
  this->TableTime = time;
  this->TableRange[0] = range[0];
  this->TableRange[1] = range[1];
}

void vtkAccelVolumeSliceMask::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Texture->ReleaseGraphicsResources(window);
  this->LabelTable->ReleaseGraphicsResources(window);
  this->Uploaded = nullptr;
  this->TableProperty = nullptr;
}

bool vtkAccelVolumeHiddenPointsMask(
  vtkImageData* input, vtkImageData* user, vtkSmartPointer<vtkImageData>& mask, unsigned long& time)
{
  vtkUnsignedCharArray* points = input->GetPointGhostArray();
  vtkUnsignedCharArray* cells = input->GetCellGhostArray();
  const vtkIdType count = input->GetNumberOfPoints();
  points = points && points->GetNumberOfTuples() == count ? points : nullptr;
  cells = cells && cells->GetNumberOfTuples() == input->GetNumberOfCells() ? cells : nullptr;
  if (!points && !cells)
  {
    return false;
  }
  vtkDataArray* userValues = user ? user->GetPointData()->GetScalars() : nullptr;
  const unsigned long newest =
    std::max({ points ? points->GetMTime() : 0, cells ? cells->GetMTime() : 0, input->GetMTime(),
      userValues ? userValues->GetMTime() : 0, user ? user->GetMTime() : 0 });
  if (!mask || newest > time)
  {
    // As vtkGPUVolumeRayCastMapper: any ghost flag hides (a duplicate belongs to another piece),
    // a cell's flag marks its lower corner point (the last row takes its neighbour's).
    bool anyHidden = false;
    for (vtkUnsignedCharArray* ghosts : { points, cells })
    {
      for (vtkIdType i = 0; ghosts && i < ghosts->GetNumberOfTuples() && !anyHidden; ++i)
      {
        anyHidden = ghosts->GetValue(i) != 0;
      }
    }
    mask = vtkSmartPointer<vtkImageData>::New();
    if (anyHidden)
    {
      int dims[3];
      input->GetDimensions(dims);
      mask->SetDimensions(dims);
      mask->AllocateScalars(VTK_UNSIGNED_CHAR, 1);
      auto* out = static_cast<unsigned char*>(mask->GetScalarPointer());
      const bool userFits = userValues && userValues->GetNumberOfTuples() == count;
      const int cx = std::max(1, dims[0] - 1);
      const int cy = std::max(1, dims[1] - 1);
      const int cz = std::max(1, dims[2] - 1);
      vtkIdType i = 0;
      for (int z = 0; z < dims[2]; ++z)
      {
        for (int y = 0; y < dims[1]; ++y)
        {
          for (int x = 0; x < dims[0]; ++x, ++i)
          {
            const vtkIdType cell =
              (static_cast<vtkIdType>(std::min(z, cz - 1)) * cy + std::min(y, cy - 1)) * cx +
              std::min(x, cx - 1);
            const bool visible = (!points || points->GetValue(i) == 0) &&
              (!cells || cells->GetValue(cell) == 0) &&
              (!userFits || userValues->GetComponent(i, 0) != 0.0);
            out[i] = visible ? 255 : 0;
          }
        }
      }
    }
    time = newest;
  }
  return mask->GetNumberOfPoints() > 0;
}
