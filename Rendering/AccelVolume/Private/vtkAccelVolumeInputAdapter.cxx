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
  this->Resampled = false;
  for (int a = 0; a < 3; ++a)
  {
    this->Resampled = this->Resampled || !EvenCoordinates(axes[a], origin[a], spacing[a]);
  }
  if (this->Resampled)
  {
    if (!this->PlanResampling(axes, origin, spacing, dims, error))
    {
      return false;
    }
    adapted->SetOrigin(origin);
    adapted->SetSpacing(spacing);
    vtkNew<vtkMatrix3x3> identity;
    adapted->SetDirectionMatrix(identity);
    adapted->SetDimensions(dims);
    return true;
  }
  for (int a = 0; a < 3; ++a)
  {
    EvenCoordinates(axes[a], origin[a], spacing[a]);
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

bool vtkAccelVolumeInputAdapter::PlanResampling(
  vtkDataArray* const axes[3], double origin[3], double spacing[3], int dims[3], std::string& error)
{
  if (this->CellFlag)
  {
    error = "Cell scalars on an unevenly spaced vtkRectilinearGrid are not rendered; use point "
            "scalars (vtkCellDataToPointData) or resample it to a vtkImageData";
    return false;
  }
  double count[3];
  for (int a = 0; a < 3; ++a)
  {
    vtkDataArray* c = axes[a];
    const vtkIdType n = c ? c->GetNumberOfTuples() : 0;
    this->SourceDimensions[a] = static_cast<int>(n);
    double smallest = VTK_DOUBLE_MAX;
    for (vtkIdType i = 1; i < n; ++i)
    {
      const double step = c->GetComponent(i, 0) - c->GetComponent(i - 1, 0);
      if (!(step > 0) || !std::isfinite(step))
      {
        error =
          std::string("The vtkRectilinearGrid's ") + "xyz"[a] + " coordinates are not increasing";
        return false;
      }
      smallest = std::min(smallest, step);
    }
    if (n < 1)
    {
      error = "The vtkRectilinearGrid has no coordinates";
      return false;
    }
    origin[a] = c->GetComponent(0, 0);
    const double length = n > 1 ? c->GetComponent(n - 1, 0) - origin[a] : 0.0;
    count[a] = n > 1 ? std::min(std::ceil(length / smallest - 1.0e-6) + 1.0, 4.0 * n) : 1.0;
  }
  constexpr double MaximumSamples = 67108864.0; // 2^26
  const double total = count[0] * count[1] * count[2];
  const double shrink = total > MaximumSamples ? std::cbrt(MaximumSamples / total) : 1.0;
  for (int a = 0; a < 3; ++a)
  {
    vtkDataArray* c = axes[a];
    const vtkIdType n = this->SourceDimensions[a];
    dims[a] = n > 1 ? std::max(2, static_cast<int>(count[a] * shrink)) : 1;
    const double length = n > 1 ? c->GetComponent(n - 1, 0) - origin[a] : 0.0;
    spacing[a] = n > 1 ? length / (dims[a] - 1) : 1.0;
    AxisMap& map = this->Axes[a];
    map.Index.assign(dims[a], 0);
    map.Weight.assign(dims[a], 0.0);
    vtkIdType i = 0;
    for (int t = 0; t < dims[a] && n > 1; ++t)
    {
      const double x = origin[a] + t * spacing[a];
      while (i + 2 < n && c->GetComponent(i + 1, 0) <= x)
      {
        ++i;
      }
      const double lower = c->GetComponent(i, 0);
      const double upper = c->GetComponent(i + 1, 0);
      map.Index[t] = i;
      map.Weight[t] = std::min(1.0, std::max(0.0, (x - lower) / (upper - lower)));
    }
  }
  return true;
}

vtkSmartPointer<vtkDataArray> vtkAccelVolumeInputAdapter::Resample(vtkDataArray* scalars) const
{
  const int* n = this->SourceDimensions;
  const int dims[3] = { static_cast<int>(this->Axes[0].Index.size()),
    static_cast<int>(this->Axes[1].Index.size()), static_cast<int>(this->Axes[2].Index.size()) };
  const int components = scalars->GetNumberOfComponents();
  vtkNew<vtkFloatArray> out;
  out->SetName(scalars->GetName());
  out->SetNumberOfComponents(components);
  out->SetNumberOfTuples(static_cast<vtkIdType>(dims[0]) * dims[1] * dims[2]);
  const auto source = [&](vtkIdType x, vtkIdType y, vtkIdType z)
  { return (z * n[1] + y) * n[0] + x; };
  vtkIdType t = 0;
  for (int z = 0; z < dims[2]; ++z)
  {
    const vtkIdType z0 = this->Axes[2].Index[z];
    const vtkIdType z1 = std::min<vtkIdType>(z0 + 1, n[2] - 1);
    const double wz = this->Axes[2].Weight[z];
    for (int y = 0; y < dims[1]; ++y)
    {
      const vtkIdType y0 = this->Axes[1].Index[y];
      const vtkIdType y1 = std::min<vtkIdType>(y0 + 1, n[1] - 1);
      const double wy = this->Axes[1].Weight[y];
      for (int x = 0; x < dims[0]; ++x, ++t)
      {
        const vtkIdType x0 = this->Axes[0].Index[x];
        const vtkIdType x1 = std::min<vtkIdType>(x0 + 1, n[0] - 1);
        const double wx = this->Axes[0].Weight[x];
        for (int c = 0; c < components; ++c)
        {
          const auto at = [&](vtkIdType i, vtkIdType j, vtkIdType k)
          { return scalars->GetComponent(source(i, j, k), c); };
          const double front = (1 - wy) * ((1 - wx) * at(x0, y0, z0) + wx * at(x1, y0, z0)) +
            wy * ((1 - wx) * at(x0, y1, z0) + wx * at(x1, y1, z0));
          const double back = (1 - wy) * ((1 - wx) * at(x0, y0, z1) + wx * at(x1, y0, z1)) +
            wy * ((1 - wx) * at(x0, y1, z1) + wx * at(x1, y1, z1));
          out->SetComponent(t, c, static_cast<float>((1 - wz) * front + wz * back));
        }
      }
    }
  }
  return out;
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
    if (this->Resampled)
    {
      this->Converted = this->Resample(scalars);
    }
    else if (EngineType(scalars->GetDataType()))
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
    vtkUnsignedCharArray* ghosts =
      cellFlag ? input->GetCellGhostArray() : input->GetPointGhostArray();
    if (ghosts && !this->Resampled)
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
    if (!cellFlag && input->GetCellGhostArray() && !this->Resampled)
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
