// Adapts VTK volume-mapper inputs (cell scalars, other integer types, rectilinear grids,
// selected arrays) to the one-component point-scalar images the engines render.
#include "vtkAccelVolumeInputAdapter.h"

#include "vtkAccelVolumeMapperSupport.h"
#include "vtkAlgorithm.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMatrix3x3.h"
#include "vtkPointData.h"
#include "vtkRectilinearGrid.h"
#include "vtkUnsignedCharArray.h"
#include "vtkVolumeMapper.h"

#include <cmath>
#include <sstream>

namespace
{
// Types the engines read directly (vtkAccelVolumeCheckInput's list).
bool EngineType(int type)
{
  accelvolume::ScalarType ignored;
  return vtkAccelVolumeScalarType(type, ignored);
}

// Integer types VTK's GPU mapper renders that the engines do not read: sampled as floats.
bool ConvertibleType(int type)
{
  switch (type)
  {
    case VTK_UNSIGNED_INT:
    case VTK_LONG:
    case VTK_UNSIGNED_LONG:
    case VTK_LONG_LONG:
    case VTK_UNSIGNED_LONG_LONG:
    case VTK_ID_TYPE:
      return true;
    default:
      return false;
  }
}

// Evenly spaced, increasing coordinates: their first value and step (1 for one value).
bool EvenCoordinates(vtkDataArray* coordinates, double& first, double& step)
{
  const vtkIdType n = coordinates ? coordinates->GetNumberOfTuples() : 0;
  if (n < 1)
  {
    return false;
  }
  first = coordinates->GetComponent(0, 0);
  step = n > 1 ? (coordinates->GetComponent(n - 1, 0) - first) / static_cast<double>(n - 1) : 1.0;
  if (!(step > 0) || !std::isfinite(first) || !std::isfinite(step))
  {
    return false;
  }
  for (vtkIdType i = 1; i < n - 1; ++i)
  {
    if (std::abs(coordinates->GetComponent(i, 0) - (first + step * i)) > 1.0e-4 * step)
    {
      return false;
    }
  }
  return true;
}
}

vtkAccelVolumeInputAdapter::vtkAccelVolumeInputAdapter() = default;

vtkAccelVolumeInputAdapter::~vtkAccelVolumeInputAdapter() = default;

bool vtkAccelVolumeInputAdapter::Fetch(
  vtkVolumeMapper* mapper, vtkImageData*& image, vtkDataArray*& scalars, std::string& error)
{
  vtkDataSet* input = nullptr;
  if (mapper->GetNumberOfInputConnections(0) > 0)
  {
    mapper->GetInputAlgorithm()->Update();
    input = mapper->GetInput();
  }
  return this->Adapt(mapper, input, image, scalars, error);
}

bool vtkAccelVolumeInputAdapter::Structure(vtkDataSet* input, std::string& error)
{
  vtkImageData* adapted = this->Adapted;
  if (auto* source = vtkImageData::SafeDownCast(input))
  {
    int extent[6];
    source->GetExtent(extent);
    double origin[3];
    // Index 0 of the adapted image is the source's first point (or first cell centre).
    const double half = this->CellFlag ? 0.5 : 0.0;
    int dims[3];
    source->GetDimensions(dims);
    double index[3];
    for (int a = 0; a < 3; ++a)
    {
      index[a] = extent[2 * a] + (dims[a] > 1 ? half : 0.0);
    }
    source->TransformContinuousIndexToPhysicalPoint(index, origin);
    adapted->SetOrigin(origin);
    adapted->SetSpacing(source->GetSpacing());
    adapted->SetDirectionMatrix(source->GetDirectionMatrix());
    for (int a = 0; a < 3; ++a)
    {
      dims[a] = this->CellFlag && dims[a] > 1 ? dims[a] - 1 : dims[a];
    }
    adapted->SetDimensions(dims);
    return true;
  }
  auto* grid = vtkRectilinearGrid::SafeDownCast(input);
  vtkDataArray* axes[3] = { grid->GetXCoordinates(), grid->GetYCoordinates(),
    grid->GetZCoordinates() };
  double origin[3];
  double spacing[3];
  int dims[3];
  for (int a = 0; a < 3; ++a)
  {
    if (!EvenCoordinates(axes[a], origin[a], spacing[a]))
    {
      error = std::string("The vtkRectilinearGrid's ") + "xyz"[a] +
        " coordinates are not evenly spaced and increasing; resample it to a vtkImageData "
        "(vtkResampleToImage)";
      return false;
    }
    dims[a] = static_cast<int>(axes[a]->GetNumberOfTuples());
    if (this->CellFlag && dims[a] > 1)
    {
      origin[a] += 0.5 * spacing[a];
      dims[a] -= 1;
    }
  }
  adapted->SetOrigin(origin);
  adapted->SetSpacing(spacing);
  vtkNew<vtkMatrix3x3> identity;
  adapted->SetDirectionMatrix(identity);
  adapted->SetDimensions(dims);
  return true;
}

bool vtkAccelVolumeInputAdapter::Adapt(vtkVolumeMapper* mapper, vtkDataSet* input,
  vtkImageData*& image, vtkDataArray*& scalars, std::string& error)
{
  image = vtkImageData::SafeDownCast(input);
  scalars = nullptr;
  if (input && !image && !vtkRectilinearGrid::SafeDownCast(input))
  {
    error = std::string("Unsupported input ") + input->GetClassName() +
      ": the mapper renders vtkImageData and vtkRectilinearGrid";
    return false;
  }
  int cellFlag = 0;
  if (input)
  {
    scalars = vtkAbstractMapper::GetScalars(input, mapper->GetScalarMode(),
      mapper->GetArrayAccessMode(), mapper->GetArrayId(), mapper->GetArrayName(), cellFlag);
  }
  const bool passThrough = image && scalars && !cellFlag &&
    scalars == image->GetPointData()->GetScalars() && EngineType(scalars->GetDataType());
  if (!input || !scalars || passThrough ||
    scalars->GetNumberOfComponents() > this->MaximumComponents ||
    (!EngineType(scalars->GetDataType()) && !ConvertibleType(scalars->GetDataType())))
  {
    // As it is, or a clear refusal from the common checks.
    return vtkAccelVolumeCheckInput(image, scalars, error, this->MaximumComponents);
  }
  const vtkIdType expected = cellFlag ? input->GetNumberOfCells() : input->GetNumberOfPoints();
  if (scalars->GetNumberOfTuples() != expected)
  {
    std::ostringstream message;
    message << "Scalar array size (" << scalars->GetNumberOfTuples()
            << " tuples) does not match the " << (cellFlag ? "input's " : "image's ") << expected
            << (cellFlag ? " cells" : " points");
    error = message.str();
    return false;
  }
  if (input != this->Source || scalars != this->SourceArray ||
    input->GetMTime() != this->SourceTime || scalars->GetMTime() != this->ArrayTime ||
    cellFlag != this->CellFlag)
  {
    this->CellFlag = cellFlag;
    if (!this->Structure(input, error))
    {
      this->Source = nullptr;
      return false;
    }
    if (EngineType(scalars->GetDataType()))
    {
      this->Converted = scalars;
    }
    else
    {
      // 32-bit floats, as VTK's GPU mapper samples these types.
      vtkNew<vtkFloatArray> converted;
      converted->DeepCopy(scalars);
      converted->SetName(scalars->GetName());
      this->Converted = converted;
    }
    this->Adapted->GetPointData()->Initialize();
    this->Adapted->GetPointData()->SetScalars(this->Converted);
    // Blanking travels with the scalars: ghost cells of cell scalars become hidden points
    // (any flag, as VTK's GPU mapper); point scalars keep both ghost arrays.
    this->Adapted->GetCellData()->Initialize();
    if (vtkUnsignedCharArray* ghosts =
          cellFlag ? input->GetCellGhostArray() : input->GetPointGhostArray())
    {
      vtkNew<vtkUnsignedCharArray> hidden;
      hidden->SetName(vtkDataSetAttributes::GhostArrayName());
      hidden->SetNumberOfTuples(ghosts->GetNumberOfTuples());
      for (vtkIdType i = 0; i < ghosts->GetNumberOfTuples(); ++i)
      {
        hidden->SetValue(i, ghosts->GetValue(i) != 0 ? vtkDataSetAttributes::HIDDENPOINT : 0);
      }
      this->Adapted->GetPointData()->AddArray(hidden);
    }
    if (!cellFlag && input->GetCellGhostArray())
    {
      this->Adapted->GetCellData()->AddArray(input->GetCellGhostArray());
    }
    this->Adapted->Modified();
    this->Source = input;
    this->SourceArray = scalars;
    this->SourceTime = input->GetMTime();
    this->ArrayTime = scalars->GetMTime();
  }
  image = this->Adapted;
  scalars = this->Converted;
  return vtkAccelVolumeCheckInput(image, scalars, error, this->MaximumComponents);
}
