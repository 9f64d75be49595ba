// VTK face of the min-max octree: input validation, rebuild/re-classify timestamps, builders.
#include "vtkAccelVolumeMinMaxOctree.h"

#include "vtkAccelVolumeMapperSupport.h"

#include "vtkAccelVolumeMinMaxOctreeInternals.h"
#include "vtkAccelVolumeRenderProgress.h"
#include "vtkAccelVolumeScalarEncoding.h"
#include "vtkAccelVolumeWorkers.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkSMPTools.h"
#include "vtkTextureObject.h"
#include "vtkTimerLog.h"

#include <algorithm>
#include <string>
#include <vector>

namespace
{
// The transfer-table resolution the slice mapper uses, so both see the same opacities.
constexpr int OpacityTableSize = 1024;

// The core's parallel loops on vtkSMPTools. The leaf pass hands out leaf slabs (one layer of
// leaves per z step: a few hundred at most, each a lot of work), so small counts get a grain of
// one slab; the upper levels hand out parents (up to millions of 8-child reductions), where a
// grain of count / (8 threads) keeps the tasks few but still balanced.
void SMPFor(std::size_t count, const std::function<void(std::size_t, std::size_t)>& body)
{
  constexpr vtkIdType MaximumSlabs = 1024; // a 2048^3 texture-sized volume with 2-voxel leaves
  const vtkIdType items = static_cast<vtkIdType>(count);
  const vtkIdType threads = std::max(1, vtkSMPTools::GetEstimatedNumberOfThreads());
  const vtkIdType grain = items <= MaximumSlabs ? 1 : std::max<vtkIdType>(1, items / (8 * threads));
  vtkSMPTools::For(0, items, grain,
    [&body](vtkIdType begin, vtkIdType end)
    { body(static_cast<std::size_t>(begin), static_cast<std::size_t>(end)); });
}

// Update's input checks: dimensions, one-component point scalars of a supported type that
// match them. False (reported) otherwise.
bool CheckInput(vtkObject* self, vtkImageData* image, int dims[3], vtkDataArray*& scalars,
  accelvolume::ScalarType& type)
{
  if (!image)
  {
    vtkErrorWithObjectMacro(self, "No input: call SetInputData() before Update().");
    return false;
  }
  image->GetDimensions(dims);
  if (dims[0] < 1 || dims[1] < 1 || dims[2] < 1)
  {
    vtkErrorWithObjectMacro(
      self, "Empty input: dimensions " << dims[0] << "x" << dims[1] << "x" << dims[2]);
    return false;
  }
  scalars = image->GetPointData()->GetScalars();
  if (!scalars)
  {
    vtkErrorWithObjectMacro(self, "The input has no point scalars.");
    return false;
  }
  if (scalars->GetNumberOfComponents() != 1)
  {
    vtkErrorWithObjectMacro(self,
      "The octree needs single-component scalars; the input has "
        << scalars->GetNumberOfComponents() << " components.");
    return false;
  }
  if (!vtkAccelVolumeScalarType(scalars->GetDataType(), type))
  {
    vtkErrorWithObjectMacro(self,
      "Unsupported scalar type " << scalars->GetDataTypeAsString()
                                 << " (use char, short, unsigned short, int, "
                                    "float or double).");
    return false;
  }
  if (scalars->GetNumberOfTuples() != static_cast<vtkIdType>(dims[0]) * dims[1] * dims[2])
  {
    vtkErrorWithObjectMacro(self, "The scalars do not match the dimensions.");
    return false;
  }
  return true;
}

// The builder this build uses: without compute shaders the GPU builder falls back to the
// CPU builder, which gives the identical octree (what a context without compute needs).
// False (reported) when BUILDER_GPU has no render window.
bool ChooseBuilder(
  vtkObject* self, int requested, vtkAccelVolumeMinMaxOctree::vtkInternals& internals, int& builder)
{
  builder = requested;
  if (builder == vtkAccelVolumeMinMaxOctree::BUILDER_GPU)
  {
    std::string why;
    if (!internals.Window)
    {
      vtkErrorWithObjectMacro(
        self, "BUILDER_GPU needs a render window: call SetRenderWindow() first.");
      return false;
    }
    if (!vtkAccelVolumeOctreeGPUBuilder::IsSupported(internals.Window, why))
    {
      builder = vtkAccelVolumeMinMaxOctree::BUILDER_CPU;
      if (why != internals.FallbackReason)
      {
        internals.FallbackReason = why; // once per reason: time-varying data rebuild often
        vtkWarningWithObjectMacro(
          self, << why << "; falling back to the CPU builder (same octree).");
      }
    }
  }
  return true;
}

// Builds the octree's levels from `view` (the GPU builder reads `image` itself).
bool BuildLevels(int builder, int numberOfThreads,
  vtkAccelVolumeMinMaxOctree::vtkInternals& internals, vtkImageData* image,
  const accelvolume::VolumeView& view, std::string& error)
{
  bool ok = false;
  switch (builder)
  {
    case vtkAccelVolumeMinMaxOctree::BUILDER_REFERENCE:
      ok = internals.Octree.BuildReference(view, error);
      break;
    case vtkAccelVolumeMinMaxOctree::BUILDER_CPU:
    {
      // Exactly the set thread count (vtkSMPTools::LocalScope does not hold it with VTK 9.1's
      // TBB backend, vtkAccelVolumeWorkers.h); otherwise vtkSMPTools' own.
      vtkAccelVolumeWorkers workers;
      const accelvolume::ParallelFor parallel =
        numberOfThreads > 0 ? workers.For(numberOfThreads) : accelvolume::ParallelFor(SMPFor);
      ok = internals.Octree.BuildParallel(view, parallel, error);
      break;
    }
    default:
      if (internals.InputTexture && internals.InputTexture->GetHandle())
      {
        // The caller's texture holds the scalars already: decode it as they were encoded.
        vtkDataArray* scalars = image->GetPointData()->GetScalars();
        double range[2];
        vtkAccelVolumeScalarRange(scalars, range);
        vtkAccelVolumeEncodedScalars encoding;
        ok = vtkAccelVolumeScalarEncodingOf(scalars, range, encoding, error) &&
          internals.GPUBuilder.BuildFromTexture(internals.Window,
            internals.InputTexture->GetHandle(), vtkAccelVolumeOctreeGPUBuilder::DecodeOf(encoding),
            internals.Octree, error);
        internals.LastUploadTime = 0.0;
      }
      else
      {
        ok = internals.GPUBuilder.Build(internals.Window, image, internals.Octree, error);
        internals.LastUploadTime = internals.GPUBuilder.GetLastUploadTime();
      }
      break;
  }
  return ok;
}
}

accelvolume::MinMaxOctree* vtkAccelVolumeMinMaxOctree::vtkInternals::GetCPUOctree()
{
  if (!this->Built)
  {
    return nullptr;
  }
  if (!this->LevelsOnCPU)
  {
    vtkNew<vtkTimerLog> timer;
    timer->StartTimer();
    std::string error;
    if (!this->GPUBuilder.ReadBack(this->Window, this->Octree, error))
    {
      return nullptr;
    }
    timer->StopTimer();
    this->LastReadBackTime = timer->GetElapsedTime();
    this->LevelsOnCPU = true;
  }
  return &this->Octree;
}

vtkStandardNewMacro(vtkAccelVolumeMinMaxOctree);

vtkAccelVolumeMinMaxOctree::vtkAccelVolumeMinMaxOctree()
  : Internals(new vtkInternals)
{
}

vtkAccelVolumeMinMaxOctree::~vtkAccelVolumeMinMaxOctree()
{
  // The window must outlive this object (SetRenderWindow's contract), so its buffers can go.
  this->ReleaseGraphicsResources();
}

void vtkAccelVolumeMinMaxOctree::SetInputData(vtkImageData* image)
{
  if (this->Internals->Input != image)
  {
    this->Internals->Input = image;
    this->Modified();
  }
}

vtkImageData* vtkAccelVolumeMinMaxOctree::GetInput()
{
  return this->Internals->Input;
}

void vtkAccelVolumeMinMaxOctree::SetRenderWindow(vtkOpenGLRenderWindow* window)
{
  if (this->Internals->Window != window)
  {
    // Buffers belong to the old context: free them there and rebuild in the new one.
    this->ReleaseGraphicsResources();
    this->Internals->Window = window;
    this->Modified();
  }
}

void vtkAccelVolumeMinMaxOctree::SetInputTexture(vtkTextureObject* texture)
{
  if (this->Internals->InputTexture != texture)
  {
    this->Internals->InputTexture = texture;
    this->Modified();
  }
}

bool vtkAccelVolumeMinMaxOctree::Update()
{
  vtkInternals& internals = *this->Internals;
  vtkImageData* image = internals.Input;
  int dims[3] = { 0, 0, 0 };
  vtkDataArray* scalars = nullptr;
  accelvolume::ScalarType type;
  int builder = this->Builder;
  if (!CheckInput(this, image, dims, scalars, type) ||
    !ChooseBuilder(this, this->Builder, internals, builder))
  {
    return false;
  }

  const bool current = internals.Built && internals.BuiltImage == image &&
    internals.BuiltScalars == scalars && image->GetMTime() <= this->BuildTime &&
    scalars->GetMTime() <= this->BuildTime && internals.BuiltLeafSize == this->LeafSize &&
    internals.BuiltBuilder == builder && std::equal(dims, dims + 3, internals.BuiltDimensions) &&
    // GPU levels also need their buffers (gone after ReleaseGraphicsResources or a new window).
    (builder != BUILDER_GPU || internals.GPUBuilder.GetNumberOfLevels() > 0);
  if (current)
  {
    return true;
  }

  // A real build: StartEvent, ProgressEvent 0 and 1, EndEvent. No finer steps: the CPU builder
  // is one pass over the volume (the reference builder is a test oracle).
  vtkAccelVolumeRenderProgress progress(this);
  internals.Built = false;
  internals.Classified = false;
  internals.LevelsOnCPU = false;
  internals.LastUploadTime = 0.0;
  std::string error;
  // NaN and infinite floats count as the slice mapper's texture (and the GPU builder's upload)
  // holds them: NaN and -Inf as the finite minimum, +Inf as the finite maximum. Otherwise a
  // leaf of NaNs would be empty here but show the minimum's opacity in the slice mapper.
  double range[2];
  vtkAccelVolumeScalarRange(scalars, range);
  vtkSmartPointer<vtkDataArray> finite;
  if (builder != BUILDER_GPU)
  {
    finite = vtkAccelVolumeFiniteScalars(scalars, range);
  }
  accelvolume::VolumeView view;
  view.data = (finite ? finite.GetPointer() : scalars)->GetVoidPointer(0);
  view.type = type;
  std::copy(dims, dims + 3, view.dims);
  vtkNew<vtkTimerLog> timer;
  timer->StartTimer();
  const bool ok = internals.Octree.Configure(dims, this->LeafSize, error) &&
    BuildLevels(builder, this->NumberOfThreads, internals, image, view, error);
  timer->StopTimer();
  if (!ok)
  {
    vtkErrorMacro("Octree build failed: " << error);
    return false;
  }
  this->LastBuildTime = timer->GetElapsedTime();
  internals.Built = true;
  internals.LevelsOnCPU = builder != BUILDER_GPU;
  internals.BuiltImage = image;
  internals.BuiltScalars = scalars;
  internals.BuiltLeafSize = this->LeafSize;
  internals.BuiltBuilder = builder;
  this->LastBuilder = builder;
  std::copy(dims, dims + 3, internals.BuiltDimensions);
  this->BuildTime.Modified();
  return true;
}

bool vtkAccelVolumeMinMaxOctree::Classify(vtkPiecewiseFunction* opacity, const double range[2])
{
  vtkInternals& internals = *this->Internals;
  if (!opacity || !range)
  {
    vtkErrorMacro("Classify() needs an opacity function and a scalar range.");
    return false;
  }
  if (!internals.Built)
  {
    vtkErrorMacro("Classify() needs a built octree: call Update() first.");
    return false;
  }
  // Two timestamps: the octree (BuildTime) and the classification (ClassifyTime).
  if (internals.Classified && internals.ClassifiedFunction == opacity &&
    opacity->GetMTime() <= this->ClassifyTime && this->BuildTime <= this->ClassifyTime &&
    internals.ClassifiedRange[0] == range[0] && internals.ClassifiedRange[1] == range[1])
  {
    return true;
  }
  accelvolume::MinMaxOctree* octree = internals.GetCPUOctree();
  if (!octree)
  {
    vtkErrorMacro("Could not read the GPU octree back for classification.");
    return false;
  }
  vtkNew<vtkTimerLog> timer;
  timer->StartTimer();
  // Same table as the slice mapper (an empty range is widened the same way).
  const double high = range[1] > range[0] ? range[1] : range[0] + 1.0;
  std::vector<float> table(OpacityTableSize);
  opacity->GetTable(range[0], high, OpacityTableSize, table.data());
  octree->Classify(table, range[0], high);
  timer->StopTimer();
  this->LastClassifyTime = timer->GetElapsedTime();
  internals.Classified = true;
  internals.ClassifiedFunction = opacity;
  internals.ClassifiedRange[0] = range[0];
  internals.ClassifiedRange[1] = range[1];
  this->ClassifyTime.Modified();
  return true;
}

int vtkAccelVolumeMinMaxOctree::GetDepth()
{
  return this->Internals->Built ? this->Internals->Octree.GetDepth() : -1;
}

vtkIdType vtkAccelVolumeMinMaxOctree::GetNumberOfNodes()
{
  return this->Internals->Built ? static_cast<vtkIdType>(this->Internals->Octree.GetNumberOfNodes())
                                : 0;
}

void vtkAccelVolumeMinMaxOctree::GetLeafGridSize(int size[3])
{
  for (int i = 0; i < 3; ++i)
  {
    size[i] = this->Internals->Built ? this->Internals->Octree.GetLevel(0).gridSize[i] : 0;
  }
}

bool vtkAccelVolumeMinMaxOctree::GetNodeRange(int level, vtkIdType mortonIndex, double range[2])
{
  accelvolume::MinMaxOctree* octree = this->Internals->GetCPUOctree();
  if (!octree || level < 0 || level > octree->GetDepth() || mortonIndex < 0 ||
    static_cast<std::size_t>(mortonIndex) >= octree->GetLevel(level).minimum.size())
  {
    return false;
  }
  range[0] = octree->GetLevel(level).minimum[mortonIndex];
  range[1] = octree->GetLevel(level).maximum[mortonIndex];
  return true;
}

bool vtkAccelVolumeMinMaxOctree::IsNodeTransparent(int level, vtkIdType mortonIndex)
{
  accelvolume::MinMaxOctree* octree = this->Internals->GetCPUOctree();
  if (!octree || !this->Internals->Classified || !octree->IsClassified() || level < 0 ||
    level > octree->GetDepth() || mortonIndex < 0 ||
    static_cast<std::size_t>(mortonIndex) >= octree->GetTransparentFlags(level).size())
  {
    return false;
  }
  return octree->IsTransparent(level, static_cast<std::uint64_t>(mortonIndex));
}

double vtkAccelVolumeMinMaxOctree::GetTransparentLeafFraction()
{
  accelvolume::MinMaxOctree* octree = this->Internals->GetCPUOctree();
  if (!octree || !this->Internals->Classified || !octree->IsClassified())
  {
    return 0.0;
  }
  // Count only leaves inside the volume: padding is transparent by convention, not by data.
  const std::vector<std::uint8_t>& flags = octree->GetTransparentFlags(0);
  std::size_t inside = 0;
  std::size_t transparent = 0;
  for (std::size_t i = 0; i < flags.size(); ++i)
  {
    if (!octree->IsPadding(0, i))
    {
      ++inside;
      transparent += flags[i] ? 1 : 0;
    }
  }
  return inside ? static_cast<double>(transparent) / static_cast<double>(inside) : 0.0;
}

double vtkAccelVolumeMinMaxOctree::NextNonEmpty(
  const double origin[3], const double direction[3], double t0, double t1)
{
  accelvolume::MinMaxOctree* octree = this->Internals->GetCPUOctree();
  if (!octree || !this->Internals->Classified || !octree->IsClassified())
  {
    return t0; // nothing known to be empty: skip nothing
  }
  const accelvolume::Vec3 o{ origin[0], origin[1], origin[2] };
  const accelvolume::Vec3 d{ direction[0], direction[1], direction[2] };
  return octree->NextNonEmpty(o, d, t0, t1);
}

unsigned int vtkAccelVolumeMinMaxOctree::GetGPULevelBuffer(int level)
{
  const vtkInternals& internals = *this->Internals;
  return internals.Built && internals.BuiltBuilder == BUILDER_GPU
    ? internals.GPUBuilder.GetLevelBuffer(level)
    : 0;
}

void vtkAccelVolumeMinMaxOctree::ReleaseGraphicsResources()
{
  vtkInternals& internals = *this->Internals;
  internals.GPUBuilder.ReleaseGraphicsResources(internals.Window);
  if (internals.BuiltBuilder == BUILDER_GPU)
  {
    // Levels that were never read back are gone with the buffers.
    if (!internals.LevelsOnCPU)
    {
      internals.Built = false;
      internals.Classified = false;
    }
  }
}

void vtkAccelVolumeMinMaxOctree::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  const vtkInternals& internals = *this->Internals;
  const char* builders[] = { "BUILDER_REFERENCE", "BUILDER_CPU", "BUILDER_GPU" };
  os << indent << "Input: " << internals.Input.GetPointer() << "\n";
  os << indent << "LeafSize: " << this->LeafSize << "\n";
  os << indent << "Builder: " << builders[this->Builder] << "\n";
  os << indent << "LastBuilder: " << (this->LastBuilder >= 0 ? builders[this->LastBuilder] : "none")
     << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
  os << indent << "RenderWindow: " << internals.Window << "\n";
  os << indent << "InputTexture: " << internals.InputTexture << "\n";
  os << indent << "Built: " << (internals.Built ? "yes" : "no") << "\n";
  if (internals.Built)
  {
    const int* grid = internals.Octree.GetLevel(0).gridSize;
    os << indent << "Depth: " << internals.Octree.GetDepth() << "\n";
    os << indent << "NumberOfNodes: " << internals.Octree.GetNumberOfNodes() << "\n";
    os << indent << "LeafGridSize: " << grid[0] << " x " << grid[1] << " x " << grid[2] << "\n";
    os << indent << "LevelsOnCPU: " << (internals.LevelsOnCPU ? "yes" : "no") << "\n";
  }
  os << indent << "Classified: " << (internals.Classified ? "yes" : "no") << "\n";
  os << indent << "LastBuildTime: " << this->LastBuildTime << " s\n";
  os << indent << "LastUploadTime (GPU, part of LastBuildTime): " << internals.LastUploadTime
     << " s\n";
  os << indent << "LastReadBackTime (GPU, not in LastBuildTime): " << internals.LastReadBackTime
     << " s\n";
  os << indent << "LastClassifyTime: " << this->LastClassifyTime << " s\n";
  os << indent << "BuildTime: " << this->BuildTime.GetMTime() << "\n";
  os << indent << "ClassifyTime: " << this->ClassifyTime.GetMTime() << "\n";
}
