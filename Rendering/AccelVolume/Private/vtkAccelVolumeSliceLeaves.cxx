// The slice mapper's empty-leaf classification (members of its vtkInternals): which inputs the
// min-max octree classifies, one per contributing component, and the leaf texture and
// non-empty boxes of their combined transparency.
#include "vtkAccelVolumeSliceMapperInternals.h"

#include "vtkAccelVolumeMinMaxOctreeInternals.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkTextureObject.h"
#include "vtkVolumeProperty.h"
#include "vtk_glew.h"

#include "skipping/MinMaxOctree.h"

#include <algorithm>

vtkImageData* vtkAccelVolumeSliceMapper::vtkInternals::ComponentImage(
  vtkImageData* input, vtkDataArray* scalars, int component)
{
  const vtkMTimeType time = std::max(input->GetMTime(), scalars->GetMTime());
  const auto components = static_cast<std::size_t>(scalars->GetNumberOfComponents());
  if (this->ComponentImagesSource != scalars || this->ComponentImagesTime != time ||
    this->ComponentImages.size() != components)
  {
    this->ComponentImages.assign(components, nullptr);
    this->ComponentImagesSource = scalars;
    this->ComponentImagesTime = time;
  }
  vtkSmartPointer<vtkImageData>& image = this->ComponentImages[component];
  if (!image)
  {
    // Float as the shader reads it (every type is exact or sampled as float there).
    vtkNew<vtkFloatArray> values;
    values->SetNumberOfTuples(scalars->GetNumberOfTuples());
    for (vtkIdType i = 0; i < scalars->GetNumberOfTuples(); ++i)
    {
      values->SetValue(i, static_cast<float>(scalars->GetComponent(i, component)));
    }
    image = vtkSmartPointer<vtkImageData>::New();
    image->CopyStructure(input);
    image->GetPointData()->SetScalars(values);
  }
  return image;
}

std::vector<vtkAccelVolumeLeafSource> vtkAccelVolumeSliceMapper::vtkInternals::LeafSources(
  vtkImageData* input, vtkDataArray* scalars, vtkVolumeProperty* property, const double range[2])
{
  std::vector<vtkAccelVolumeLeafSource> sources;
  const int components = scalars->GetNumberOfComponents();
  auto add = [&](vtkImageData* image, vtkPiecewiseFunction* opacity, const double* limits) {
    vtkAccelVolumeLeafSource source;
    source.Image = image;
    source.Opacity = opacity;
    source.Range[0] = limits[0];
    source.Range[1] = limits[1];
    sources.push_back(source);
  };
  if (components == 1)
  {
    add(input, property->GetScalarOpacity(0), range);
  }
  else if (!property->GetIndependentComponents())
  {
    // Dependent: function 0 over the last component (the shader's opacity).
    add(ComponentImage(input, scalars, components - 1), property->GetScalarOpacity(0),
      this->Resources.ComponentRanges[components - 1]);
  }
  else
  {
    for (int c = 0; c < components; ++c)
    {
      if (property->GetComponentWeight(c) > 0.0)
      {
        add(ComponentImage(input, scalars, c), property->GetScalarOpacity(c),
          this->Resources.ComponentRanges[c]);
      }
    }
  }
  return sources;
}

namespace
{
// The level-0 flag of a leaf inside the grid (what vtkAccelVolumeMinMaxOctree reports).
bool LeafTransparent(const accelvolume::MinMaxOctree& octree, std::uint64_t index)
{
  return index < octree.GetTransparentFlags(0).size() && octree.IsTransparent(0, index);
}
}

void vtkAccelVolumeSliceMapper::vtkInternals::ConfigureOctree(vtkAccelVolumeSliceMapper* self,
  vtkOpenGLRenderWindow* window, vtkAccelVolumeMinMaxOctree* octree, vtkImageData* image)
{
  octree->SetInputData(image);
  octree->SetLeafSize(self->OctreeLeafSize);
  octree->SetBuilder(self->OctreeBuilder);
  octree->SetInputTexture(nullptr);
  if (self->OctreeBuilder != vtkAccelVolumeMinMaxOctree::BUILDER_GPU)
  {
    return;
  }
  octree->SetRenderWindow(window);
  // The scalars themselves, in one brick: build from the texture the frame samples (brought up to
  // date first: a new time step is uploaded here rather than when the slices draw).
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  if (scalars && scalars == this->Resources.GetUploadedScalars() &&
    this->Resources.GetBrickLayout().Single())
  {
    std::string error;
    octree->SetInputTexture(this->Resources.Bricks.Acquire(window, 0, this->Frame.Linear, error));
  }
}

bool vtkAccelVolumeSliceMapper::vtkInternals::UploadEmptyBlocks(
  vtkOpenGLRenderWindow* window, const std::vector<unsigned char>& leafFlags)
{
  constexpr int Block = vtkAccelVolumeSliceResources::LeafBlock;
  const int* grid = this->LeafGrid;
  int blocks[3];
  vtkAccelVolumeSliceResources::BlockGridOf(grid, blocks);
  std::vector<unsigned char> flags(static_cast<size_t>(blocks[0]) * blocks[1] * blocks[2], 255);
  std::size_t at = 0;
  for (int k = 0; k < grid[2]; ++k)
  {
    for (int j = 0; j < grid[1]; ++j)
    {
      for (int i = 0; i < grid[0]; ++i)
      {
        if (leafFlags[at++] == 0)
        {
          flags[(static_cast<size_t>(k / Block) * blocks[1] + j / Block) * blocks[0] + i / Block] =
            0;
        }
      }
    }
  }
  vtkTextureObject* texture = this->Resources.EmptyBlocks;
  texture->SetContext(window);
  window->GetState()->vtkglPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  if (!texture->Create3DFromRaw(
        blocks[0], blocks[1], blocks[2], 1, VTK_UNSIGNED_CHAR, flags.data()))
  {
    return false;
  }
  texture->SetMinificationFilter(vtkTextureObject::Nearest);
  texture->SetMagnificationFilter(vtkTextureObject::Nearest);
  return true;
}

bool vtkAccelVolumeSliceMapper::vtkInternals::ClassifyOnGPU(vtkAccelVolumeSliceMapper* self,
  vtkOpenGLRenderWindow* window, const vtkAccelVolumeLeafSource& source)
{
  vtkAccelVolumeMinMaxOctree* octree = this->Octree;
  this->ConfigureOctree(self, window, octree, source.Image);
  if (!octree->Update() || octree->GetLastBuilder() != vtkAccelVolumeMinMaxOctree::BUILDER_GPU ||
    !octree->GetGPULevelBuffer(0))
  {
    return false;
  }
  vtkDataArray* scalars = source.Image->GetPointData()->GetScalars();
  // The GPU classification's textures are not the CPU path's (no non-empty boxes): its own key.
  const std::vector<double> key = { -1.0,
    static_cast<double>(std::max(source.Image->GetMTime(), scalars ? scalars->GetMTime() : 0)),
    static_cast<double>(source.Opacity->GetMTime()),
    static_cast<double>(reinterpret_cast<std::uintptr_t>(source.Image)), source.Range[0],
    source.Range[1], static_cast<double>(self->OctreeLeafSize) };
  if (this->Resources.EmptyLeaves->GetHandle() && key == this->LeavesKey)
  {
    self->LastTransparentLeafFraction = this->LeavesTransparentFraction;
    self->LastOctreeBuilder = vtkAccelVolumeMinMaxOctree::BUILDER_GPU;
    return true;
  }
  // The opacities of the shaders' transfer table (vtkAccelVolumeTransferTable's sampling).
  constexpr int TableSize = vtkAccelVolumeSliceResources::TableSize;
  const double high = source.Range[1] > source.Range[0] ? source.Range[1] : source.Range[0] + 1.0;
  std::vector<float> opacities(TableSize);
  source.Opacity->GetTable(source.Range[0], high, TableSize, opacities.data());
  octree->GetLeafGridSize(this->LeafGrid);
  int blocks[3];
  vtkAccelVolumeSliceResources::BlockGridOf(this->LeafGrid, blocks);
  const double tableRange[2] = { source.Range[0], high };
  long long transparent = 0;
  std::string error;
  if (!this->Resources.Classifier.Classify(window, octree->GetGPULevelBuffer(0), this->LeafGrid,
        opacities, tableRange, this->Resources.EmptyLeaves, this->Resources.EmptyBlocks, blocks,
        vtkAccelVolumeSliceResources::LeafBlock, transparent, error))
  {
    vtkErrorWithObjectMacro(self, "Classifying the octree on the GPU failed: " << error);
    return false;
  }
  const double leaves =
    static_cast<double>(this->LeafGrid[0]) * this->LeafGrid[1] * this->LeafGrid[2];
  this->LeavesTransparentFraction = leaves > 0 ? static_cast<double>(transparent) / leaves : 0.0;
  this->LeavesKey = key;
  this->HaveNonEmptyBoxes = false;
  this->NonEmptyBoxes.clear();
  self->LastTransparentLeafFraction = this->LeavesTransparentFraction;
  self->LastOctreeBuilder = vtkAccelVolumeMinMaxOctree::BUILDER_GPU;
  return true;
}

bool vtkAccelVolumeSliceMapper::vtkInternals::UpdateEmptyLeaves(vtkAccelVolumeSliceMapper* self,
  vtkOpenGLRenderWindow* window, const std::vector<vtkAccelVolumeLeafSource>& sources,
  bool computeSlices)
{
  // No weighted component: nothing is visible, but no skipping is simpler and still exact.
  if (sources.empty())
  {
    return false;
  }
  if (computeSlices && sources.size() == 1 &&
    self->OctreeBuilder == vtkAccelVolumeMinMaxOctree::BUILDER_GPU &&
    this->ClassifyOnGPU(self, window, sources.front()))
  {
    return true;
  }
  while (this->ComponentOctrees.size() + 1 < sources.size())
  {
    this->ComponentOctrees.push_back(vtkSmartPointer<vtkAccelVolumeMinMaxOctree>::New());
  }
  std::vector<double> key;
  std::vector<vtkAccelVolumeMinMaxOctree*> octrees;
  for (std::size_t s = 0; s < sources.size(); ++s)
  {
    const vtkAccelVolumeLeafSource& source = sources[s];
    vtkAccelVolumeMinMaxOctree* octree =
      s == 0 ? this->Octree.GetPointer() : this->ComponentOctrees[s - 1].GetPointer();
    this->ConfigureOctree(self, window, octree, source.Image);
    if (!octree->Update() || !octree->Classify(source.Opacity, source.Range))
    {
      return false;
    }
    octrees.push_back(octree);
    vtkDataArray* scalars = source.Image->GetPointData()->GetScalars();
    key.push_back(static_cast<double>(
      std::max(source.Image->GetMTime(), scalars ? scalars->GetMTime() : 0)));
    key.push_back(static_cast<double>(source.Opacity->GetMTime()));
    key.push_back(static_cast<double>(reinterpret_cast<std::uintptr_t>(source.Image)));
    key.push_back(source.Range[0]);
    key.push_back(source.Range[1]);
  }
  key.push_back(self->OctreeLeafSize);
  vtkTextureObject* leaves = this->Resources.EmptyLeaves;
  if (!leaves->GetHandle() || key != this->LeavesKey)
  {
    accelvolume::MinMaxOctree* first = octrees[0]->GetInternals()->GetCPUOctree();
    if (!first)
    {
      return false;
    }
    // A leaf is transparent where every source's is (their opacities add up).
    accelvolume::MinMaxOctree combined;
    const accelvolume::MinMaxOctree* classified = first;
    if (octrees.size() > 1)
    {
      combined = *first;
      for (std::size_t s = 1; s < octrees.size(); ++s)
      {
        const accelvolume::MinMaxOctree* other = octrees[s]->GetInternals()->GetCPUOctree();
        if (!other)
        {
          return false;
        }
        combined.IntersectTransparency(*other);
      }
      classified = &combined;
    }
    octrees[0]->GetLeafGridSize(this->LeafGrid);
    const int* grid = this->LeafGrid;
    std::vector<unsigned char> flags(static_cast<size_t>(grid[0]) * grid[1] * grid[2]);
    std::size_t at = 0;
    std::size_t transparent = 0;
    for (int k = 0; k < grid[2]; ++k)
    {
      for (int j = 0; j < grid[1]; ++j)
      {
        for (int i = 0; i < grid[0]; ++i)
        {
          const bool empty = LeafTransparent(*classified, accelvolume::MortonEncode(i, j, k));
          transparent += empty ? 1 : 0;
          flags[at++] = empty ? 255 : 0;
        }
      }
    }
    leaves->SetContext(window);
    window->GetState()->vtkglPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    if (!leaves->Create3DFromRaw(grid[0], grid[1], grid[2], 1, VTK_UNSIGNED_CHAR, flags.data()))
    {
      return false;
    }
    leaves->SetMinificationFilter(vtkTextureObject::Nearest);
    leaves->SetMagnificationFilter(vtkTextureObject::Nearest);
    if (!this->UploadEmptyBlocks(window, flags))
    {
      return false;
    }
    this->LeavesKey = key;
    this->LeavesTransparentFraction =
      flags.empty() ? 0.0 : static_cast<double>(transparent) / static_cast<double>(flags.size());
    // Only a new classification changes them: not a per-frame traversal.
    this->HaveNonEmptyBoxes = true;
    this->NonEmptyBoxes = classified->NonEmptyBoxes();
  }
  self->LastTransparentLeafFraction = this->LeavesTransparentFraction;
  self->LastOctreeBuilder = this->Octree->GetLastBuilder();
  return true;
}
