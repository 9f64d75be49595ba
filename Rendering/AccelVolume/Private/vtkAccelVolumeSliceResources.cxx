// GPU resources of the slice mapper: texture upload with exact integer encodings.
#include "vtkAccelVolumeSliceResources.h"

#include "vtkAccelVolumeSliceResolve.h"

#include "vtkAccelVolumeDepthCopy.h"
#include "vtkAccelVolumeMapperSupport.h"

#include "vtkAccelVolumeScalarEncoding.h"

#include "vtkColorTransferFunction.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkOpenGLBufferObject.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLRenderTimer.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkOpenGLVertexArrayObject.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkSMPTools.h"
#include "vtkTextureObject.h"
#include "vtkVolumeProperty.h"
#include "vtk_glew.h"

#include <algorithm>
#include <cmath>
#include <limits>

vtkAccelVolumeSliceResources::vtkAccelVolumeSliceResources() = default;
vtkAccelVolumeSliceResources::~vtkAccelVolumeSliceResources() = default;

bool vtkAccelVolumeSliceResources::UseContext(vtkOpenGLRenderWindow* window)
{
  const bool changed = this->Context != window;
  if (changed && this->Context)
  {
    this->ReleaseGraphicsResources(this->Context);
  }
  this->Context = window;
  return changed;
}

bool vtkAccelVolumeSliceResources::PrepareVolume(vtkOpenGLRenderWindow* window, vtkImageData* image,
  vtkDataArray* scalars, const double range[2], std::uint64_t budgetBytes, int maximumBrickSize,
  std::string& error)
{
  const bool contextChanged = this->UseContext(window);
  int dims[3];
  image->GetDimensions(dims);
  const bool stale = contextChanged || this->UploadedScalars != scalars ||
    scalars->GetMTime() > this->VolumeUploadTime || image->GetMTime() > this->VolumeUploadTime ||
    dims[0] != this->Dimensions[0] || dims[1] != this->Dimensions[1] ||
    dims[2] != this->Dimensions[2] || range[0] != this->UploadedRange[0] ||
    range[1] != this->UploadedRange[1] || budgetBytes != this->LayoutBudget ||
    maximumBrickSize != this->LayoutMaximumBrickSize ||
    (this->EncodedReleased && !this->Bricks.AllResident());
  if (!stale)
  {
    return true;
  }
  this->UploadedScalars = nullptr; // until this succeeds
  const double width = range[1] > range[0] ? range[1] - range[0] : 1.0;
  this->Encoded = vtkAccelVolumeEncodedScalars();
  this->EncodedReleased = false;
  if (!vtkAccelVolumeEncodeScalars(scalars, range, this->Encoded, error))
  {
    return false;
  }
  if (this->Encoded.Normalized)
  {
    this->ScalarScale = 1.0f;
    this->ScalarBias = 0.0f;
  }
  else
  {
    this->ScalarScale = static_cast<float>(this->Encoded.DecodeScale / width);
    this->ScalarBias = static_cast<float>((this->Encoded.DecodeOffset - range[0]) / width);
  }
  accelvolume::BrickRequest request;
  request.dimensions = { { dims[0], dims[1], dims[2] } };
  const int limit = vtkTextureObject::GetMaximumTextureSize3D(window);
  request.maximumTextureSize = limit > 0 ? limit : 2048;
  if (maximumBrickSize > 0)
  {
    request.maximumTextureSize = std::min(request.maximumTextureSize, maximumBrickSize);
  }
  request.bytesPerVoxel = this->Encoded.TextureType == VTK_UNSIGNED_CHAR
    ? 1
    : (this->Encoded.TextureType == VTK_UNSIGNED_SHORT ? 2 : 4);
  request.budgetBytes = budgetBytes;
  if (!accelvolume::ComputeBrickLayout(request, this->Layout, error))
  {
    return false;
  }
  const std::uint64_t capacity = budgetBytes == 0
    ? this->Layout.bricks.size()
    : std::max<std::uint64_t>(1, budgetBytes / this->Layout.largestBrickBytes);
  this->Bricks.Reset(this->Layout, dims, &this->Encoded,
    static_cast<int>(std::min<std::uint64_t>(capacity, this->Layout.bricks.size())));
  std::copy(dims, dims + 3, this->Dimensions);
  this->UploadedScalars = scalars;
  this->UploadedRange[0] = range[0];
  this->UploadedRange[1] = range[1];
  this->LayoutBudget = budgetBytes;
  this->LayoutMaximumBrickSize = maximumBrickSize;
  this->VolumeUploadTime.Modified();
  return true;
}

void vtkAccelVolumeSliceResources::ReleaseEncodedScalarsIfResident()
{
  if (!this->EncodedReleased && this->Bricks.AllResident())
  {
    // The textures hold everything now; a copy made for the encoding is dead weight.
    std::vector<unsigned char>().swap(this->Encoded.Bytes);
    std::vector<unsigned short>().swap(this->Encoded.Shorts);
    std::vector<float>().swap(this->Encoded.Floats);
    this->Encoded.Data = nullptr;
    this->EncodedReleased = true;
  }
}

void vtkAccelVolumeSliceResources::UpdateTransferTable(
  vtkOpenGLRenderWindow* window, vtkVolumeProperty* property, const double range[2])
{
  vtkPiecewiseFunction* opacity = property->GetScalarOpacity(0);
  const bool gray = property->GetColorChannels(0) == 1;
  vtkMTimeType newest = property->GetMTime();
  newest = std::max(newest, opacity->GetMTime());
  newest = std::max(newest,
    gray ? property->GetGrayTransferFunction(0)->GetMTime()
         : property->GetRGBTransferFunction(0)->GetMTime());
  if (this->TransferTable->GetHandle() && this->TableProperty == property &&
    newest <= this->TableBuildTime && range[0] == this->TableRange[0] &&
    range[1] == this->TableRange[1])
  {
    return;
  }
  std::vector<float> table = vtkAccelVolumeTransferTable(property, range, TableSize);
  this->TransferTable->SetContext(window);
  this->TransferTable->Create2DFromRaw(TableSize, 1, 4, VTK_FLOAT, table.data());
  this->TransferTable->SetWrapS(vtkTextureObject::ClampToEdge);
  this->TransferTable->SetWrapT(vtkTextureObject::ClampToEdge);
  this->TransferTable->SetMinificationFilter(vtkTextureObject::Linear);
  this->TransferTable->SetMagnificationFilter(vtkTextureObject::Linear);
  this->TableProperty = property;
  this->TableRange[0] = range[0];
  this->TableRange[1] = range[1];
  this->TableBuildTime.Modified();
}

void vtkAccelVolumeSliceResources::UpdateGradientOpacityTable(
  vtkOpenGLRenderWindow* window, vtkVolumeProperty* property, const double* maxima, int rows)
{
  bool current = this->GradientOpacityTable->GetHandle() && rows == this->GradientTableRows &&
    property == this->GradientTableProperty;
  for (int r = 0; r < rows && current; ++r)
  {
    current = maxima[r] == this->GradientTableMaxima[r] &&
      property->GetGradientOpacity(r)->GetMTime() <= this->GradientTableBuildTime;
  }
  if (current)
  {
    return;
  }
  constexpr int Size = 1024;
  std::vector<float> table(static_cast<size_t>(Size) * rows);
  for (int r = 0; r < rows; ++r)
  {
    property->GetGradientOpacity(r)->GetTable(0.0, maxima[r], Size, table.data() + r * Size);
    this->GradientTableMaxima[r] = maxima[r];
  }
  this->GradientOpacityTable->SetContext(window);
  this->GradientOpacityTable->Create2DFromRaw(Size, rows, 1, VTK_FLOAT, table.data());
  this->GradientOpacityTable->SetWrapS(vtkTextureObject::ClampToEdge);
  this->GradientOpacityTable->SetWrapT(vtkTextureObject::ClampToEdge);
  this->GradientOpacityTable->SetMinificationFilter(vtkTextureObject::Linear);
  this->GradientOpacityTable->SetMagnificationFilter(vtkTextureObject::Linear);
  this->GradientTableRows = rows;
  this->GradientTableProperty = property;
  this->GradientTableBuildTime.Modified();
}

namespace
{
// Slices per step of the gradient texture build: its buffers are a slab, never the volume.
constexpr int GradientSlab = 16;

// The normalised, NaN-free values of slices [first, last) of the volume.
void NormalizedSlices(vtkDataArray* scalars, const int dims[3], const double range[2], int first,
  int last, std::vector<float>& values)
{
  const double width = range[1] > range[0] ? range[1] - range[0] : 1.0;
  const vtkIdType sliceSize = static_cast<vtkIdType>(dims[0]) * dims[1];
  const vtkIdType offset = first * sliceSize;
  values.resize(static_cast<size_t>((last - first) * sliceSize));
  vtkSMPTools::For(0, static_cast<vtkIdType>(values.size()),
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType i = begin; i < end; ++i)
      {
        const double v = scalars->GetComponent(offset + i, 0);
        values[i] = std::isfinite(v)
          ? static_cast<float>(std::min(1.0, std::max(0.0, (v - range[0]) / width)))
          : 0.0f;
      }
    });
}

// Calls visit(at, gradient[3], value) for every voxel of slices [z0, z1), rows in parallel:
// clamped central differences (edges one-sided, like clamp-to-edge sampling of the volume
// texture) from `values`, which hold slices [valuesFirst, ...) and one slice around [z0, z1).
template <typename Visit>
void ForEachGradient(
  const std::vector<float>& values, int valuesFirst, const int dims[3], int z0, int z1, Visit visit)
{
  const vtkIdType sliceSize = static_cast<vtkIdType>(dims[0]) * dims[1];
  vtkSMPTools::For(static_cast<vtkIdType>(z0) * dims[1], static_cast<vtkIdType>(z1) * dims[1],
    [&](vtkIdType rowBegin, vtkIdType rowEnd)
    {
      for (vtkIdType row = rowBegin; row < rowEnd; ++row)
      {
        const int z = static_cast<int>(row / dims[1]);
        const int y = static_cast<int>(row % dims[1]);
        for (int x = 0; x < dims[0]; ++x)
        {
          const vtkIdType at =
            (z - valuesFirst) * sliceSize + static_cast<vtkIdType>(y) * dims[0] + x;
          const vtkIdType step[3] = { 1, dims[0], sliceSize };
          const int position[3] = { x, y, z };
          float gradient[3];
          for (int c = 0; c < 3; ++c)
          {
            const vtkIdType low = position[c] > 0 ? at - step[c] : at;
            const vtkIdType high = position[c] < dims[c] - 1 ? at + step[c] : at;
            gradient[c] = 0.5f * (values[high] - values[low]);
          }
          visit(
            (z - z0) * sliceSize + static_cast<vtkIdType>(y) * dims[0] + x, gradient, values[at]);
        }
      }
    });
}
}

bool vtkAccelVolumeSliceResources::UpdateGradients(
  vtkOpenGLRenderWindow* window, vtkImageData* image, vtkDataArray* scalars, const double range[2])
{
  if (this->Gradients->GetHandle() && this->GradientScalars == scalars &&
    scalars->GetMTime() <= this->GradientBuildTime && image->GetMTime() <= this->GradientBuildTime)
  {
    return true;
  }
  int dims[3];
  image->GetDimensions(dims);
  const vtkIdType sliceSize = static_cast<vtkIdType>(dims[0]) * dims[1];
  // Two passes over slabs of slices (with one slice around them): the largest component fixes
  // the 16-bit scale, then the packed texels go up slab by slab. Buffers stay a slab's size, so
  // the build needs no volume-sized copy (the old one-pass build peaked at 24 bytes a voxel).
  std::vector<float> values;
  std::vector<float> slabLargest(static_cast<size_t>(dims[2]) * dims[1], 0.0f);
  for (int z0 = 0; z0 < dims[2]; z0 += GradientSlab)
  {
    const int z1 = std::min(dims[2], z0 + GradientSlab);
    const int first = std::max(0, z0 - 1);
    NormalizedSlices(scalars, dims, range, first, std::min(dims[2], z1 + 1), values);
    ForEachGradient(values, first, dims, z0, z1,
      [&](vtkIdType at, const float gradient[3], float)
      {
        // One slot per row: rows are visited by one thread each, and max is order-free.
        float& largest = slabLargest[static_cast<size_t>(z0) * dims[1] + at / dims[0]];
        for (int c = 0; c < 3; ++c)
        {
          largest = std::max(largest, std::fabs(gradient[c]));
        }
      });
  }
  float largest = 1.0e-12f;
  for (float value : slabLargest)
  {
    largest = std::max(largest, value);
  }
  this->Gradients->SetContext(window);
  window->GetState()->vtkglPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  if (!this->Gradients->Create3DFromRaw(dims[0], dims[1], dims[2], 4, VTK_UNSIGNED_SHORT, nullptr))
  {
    return false;
  }
  std::vector<unsigned short> packed;
  for (int z0 = 0; z0 < dims[2]; z0 += GradientSlab)
  {
    const int z1 = std::min(dims[2], z0 + GradientSlab);
    const int first = std::max(0, z0 - 1);
    NormalizedSlices(scalars, dims, range, first, std::min(dims[2], z1 + 1), values);
    packed.resize(static_cast<size_t>((z1 - z0) * sliceSize) * 4);
    ForEachGradient(values, first, dims, z0, z1,
      [&](vtkIdType at, const float gradient[3], float value)
      {
        for (int c = 0; c < 3; ++c)
        {
          packed[4 * at + c] = static_cast<unsigned short>(
            std::lround((gradient[c] / largest * 0.5f + 0.5f) * 65535.0f));
        }
        packed[4 * at + 3] = static_cast<unsigned short>(std::lround(value * 65535.0f));
      });
    this->Gradients->Activate(); // its own texture unit: no other binding is disturbed
    glTexSubImage3D(GL_TEXTURE_3D, 0, 0, 0, z0, dims[0], dims[1], z1 - z0, GL_RGBA,
      GL_UNSIGNED_SHORT, packed.data());
    this->Gradients->Deactivate();
  }
  this->Gradients->SetWrapS(vtkTextureObject::ClampToEdge);
  this->Gradients->SetWrapT(vtkTextureObject::ClampToEdge);
  this->Gradients->SetWrapR(vtkTextureObject::ClampToEdge);
  this->Gradients->SetMinificationFilter(vtkTextureObject::Linear);
  this->Gradients->SetMagnificationFilter(vtkTextureObject::Linear);
  this->GradientScale = largest;
  this->GradientScalars = scalars;
  this->GradientBuildTime.Modified();
  return true;
}

bool vtkAccelVolumeSliceResources::UpdateTransferFunction2D(
  vtkOpenGLRenderWindow* window, vtkImageData* function, std::string& error)
{
  if (!function || !function->GetPointData()->GetScalars())
  {
    error =
      "TF_2D mode needs a 2D transfer function image (vtkVolumeProperty::SetTransferFunction2D)";
    return false;
  }
  vtkDataArray* values = function->GetPointData()->GetScalars();
  int dims[3];
  function->GetDimensions(dims);
  if (values->GetNumberOfComponents() != 4 || dims[0] < 1 || dims[1] < 1 || dims[2] != 1)
  {
    error = "the 2D transfer function must be an X x Y x 1 image with 4 components (RGBA)";
    return false;
  }
  if (this->TransferTable2D->GetHandle() && this->Table2DSource == function &&
    function->GetMTime() <= this->Table2DBuildTime && values->GetMTime() <= this->Table2DBuildTime)
  {
    return true;
  }
  std::vector<float> rgba(static_cast<size_t>(dims[0]) * dims[1] * 4);
  for (size_t i = 0; i < rgba.size(); ++i)
  {
    rgba[i] = static_cast<float>(
      values->GetComponent(static_cast<vtkIdType>(i / 4), static_cast<int>(i % 4)));
  }
  this->TransferTable2D->SetContext(window);
  this->TransferTable2D->Create2DFromRaw(dims[0], dims[1], 4, VTK_FLOAT, rgba.data());
  this->TransferTable2D->SetWrapS(vtkTextureObject::ClampToEdge);
  this->TransferTable2D->SetWrapT(vtkTextureObject::ClampToEdge);
  this->TransferTable2D->SetMinificationFilter(vtkTextureObject::Linear);
  this->TransferTable2D->SetMagnificationFilter(vtkTextureObject::Linear);
  this->Table2DSource = function;
  this->Table2DBuildTime.Modified();
  return true;
}

bool vtkAccelVolumeSliceResources::PrepareTargets(vtkOpenGLRenderWindow* window, int width,
  int height, int channels, int depthFormat, bool halfFloat)
{
  if (!this->Accumulation->GetHandle() || this->SceneDepthFormat != depthFormat ||
    this->AccumulationHalfFloat != halfFloat ||
    static_cast<int>(this->Accumulation->GetWidth()) != width ||
    static_cast<int>(this->Accumulation->GetHeight()) != height ||
    this->Accumulation->GetComponents() != channels)
  {
    this->Accumulation->SetContext(window);
    // vtkTextureObject keeps the first internal format it chose: a new channel count (another
    // blend mode) needs it forgotten, or a 4-channel target stays R32F (an all-black frame).
    this->Accumulation->ResetFormatAndType();
    if (halfFloat)
    {
      static const unsigned int halfFormats[4] = { GL_R16F, GL_RG16F, GL_RGB16F, GL_RGBA16F };
      this->Accumulation->SetInternalFormat(halfFormats[std::clamp(channels, 1, 4) - 1]);
    }
    if (!this->Accumulation->Create2D(width, height, channels, VTK_FLOAT, false))
    {
      return false;
    }
    this->AccumulationHalfFloat = halfFloat;
    this->Accumulation->SetMinificationFilter(vtkTextureObject::Nearest);
    this->Accumulation->SetMagnificationFilter(vtkTextureObject::Nearest);
    this->SceneDepth->SetContext(window);
    if (!vtkAccelVolumeAllocateDepth(this->SceneDepth, width, height, depthFormat))
    {
      return false;
    }
    this->SceneDepthFormat = depthFormat;
    this->SceneDepth->SetMinificationFilter(vtkTextureObject::Nearest);
    this->SceneDepth->SetMagnificationFilter(vtkTextureObject::Nearest);
    this->Framebuffer->SetContext(window);
    this->Framebuffer->SaveCurrentBindingsAndBuffers();
    this->Framebuffer->Bind();
    this->Framebuffer->AddColorAttachment(0, this->Accumulation);
    // The copy of the scene depth doubles as depth buffer: fragments behind opaque geometry
    // fail the early depth test before any shading.
    this->Framebuffer->AddDepthAttachment(this->SceneDepth);
    this->Framebuffer->RestorePreviousBindingsAndBuffers();
  }
  return true;
}

bool vtkAccelVolumeSliceResources::PrepareMultiComponentVolume(vtkOpenGLRenderWindow* window,
  vtkImageData* image, vtkDataArray* scalars, bool colourComponents, std::string& error)
{
  const bool contextChanged = this->UseContext(window);
  int dims[3];
  image->GetDimensions(dims);
  const int components = scalars->GetNumberOfComponents();
  if (!contextChanged && this->ComponentVolume->GetHandle() && this->UploadedScalars == scalars &&
    scalars->GetMTime() <= this->VolumeUploadTime && image->GetMTime() <= this->VolumeUploadTime &&
    colourComponents == this->UploadedColourComponents)
  {
    return true;
  }
  accelvolume::BrickRequest request;
  request.dimensions = { { dims[0], dims[1], dims[2] } };
  const int limit = vtkTextureObject::GetMaximumTextureSize3D(window);
  request.maximumTextureSize = limit > 0 ? limit : 2048;
  request.bytesPerVoxel = 4 * static_cast<std::uint64_t>(components);
  if (!accelvolume::ComputeBrickLayout(request, this->Layout, error))
  {
    return false;
  }
  if (!this->Layout.Single())
  {
    error = "multi-component scalars larger than GL_MAX_3D_TEXTURE_SIZE are not bricked";
    return false;
  }
  const vtkIdType count = scalars->GetNumberOfTuples();
  std::vector<float> values(static_cast<size_t>(count) * components);
  for (int c = 0; c < components; ++c)
  {
    double range[2];
    scalars->GetFiniteRange(range, c);
    if (!(range[1] > range[0]))
    {
      range[1] = range[0] + 1.0;
    }
    this->ComponentRanges[c][0] = range[0];
    this->ComponentRanges[c][1] = range[1];
    const double colourScale =
      colourComponents && c < 3 ? vtkAccelVolumeColourComponentScale(scalars->GetDataType()) : 0.0;
    const double scale = colourScale > 0.0 ? colourScale : 1.0 / (range[1] - range[0]);
    const double offset = colourScale > 0.0 ? 0.0 : range[0];
    for (vtkIdType i = 0; i < count; ++i)
    {
      const double v = scalars->GetComponent(i, c);
      values[static_cast<size_t>(i) * components + c] =
        std::isfinite(v) ? static_cast<float>((v - offset) * scale) : 0.0f;
    }
  }
  this->ComponentVolume->SetContext(window);
  this->ComponentVolume->ResetFormatAndType();
  window->GetState()->vtkglPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  if (!this->ComponentVolume->Create3DFromRaw(
        dims[0], dims[1], dims[2], components, VTK_FLOAT, values.data()))
  {
    error = "the multi-component volume texture could not be created";
    return false;
  }
  this->ComponentVolume->SetWrapS(vtkTextureObject::ClampToEdge);
  this->ComponentVolume->SetWrapT(vtkTextureObject::ClampToEdge);
  this->ComponentVolume->SetWrapR(vtkTextureObject::ClampToEdge);
  std::copy(dims, dims + 3, this->Dimensions);
  this->ScalarScale = 1.0f;
  this->ScalarBias = 0.0f;
  this->UploadedScalars = scalars;
  this->UploadedColourComponents = colourComponents;
  this->VolumeUploadTime.Modified();
  return true;
}

void vtkAccelVolumeSliceResources::UpdateComponentTables(
  vtkOpenGLRenderWindow* window, vtkVolumeProperty* property, int components, bool independent)
{
  // Rebuilt only when the property, its functions, the layout or the ranges changed.
  vtkMTimeType newest = property->GetMTime();
  for (int c = 0; c < components; ++c)
  {
    newest = std::max({ newest, property->GetScalarOpacity(c)->GetMTime(),
      property->GetColorChannels(c) == 1 ? property->GetGrayTransferFunction(c)->GetMTime()
                                         : property->GetRGBTransferFunction(c)->GetMTime() });
  }
  const int layout = independent ? components : -components;
  if (this->ComponentTables->GetHandle() && this->ComponentTableProperty == property &&
    newest <= this->ComponentTableTime && layout == this->ComponentTableLayout &&
    this->ComponentTableVolumeTime == this->VolumeUploadTime.GetMTime())
  {
    return;
  }
  std::vector<float> table(4 * 4 * static_cast<size_t>(TableSize), 0.0f);
  std::vector<float> rgb(3 * static_cast<size_t>(TableSize));
  std::vector<float> alpha(TableSize);
  const int rows = independent ? components : 1;
  for (int c = 0; c < rows; ++c)
  {
    // Dependent: colour over component 0, opacity (function 0) over the last component.
    const int colourComponent = c;
    const int opacityComponent = independent ? c : components - 1;
    const double* colourRange = this->ComponentRanges[colourComponent];
    const double* opacityRange = this->ComponentRanges[opacityComponent];
    if (property->GetColorChannels(c) == 1)
    {
      property->GetGrayTransferFunction(c)->GetTable(
        colourRange[0], colourRange[1], TableSize, alpha.data());
      for (int i = 0; i < TableSize; ++i)
      {
        rgb[3 * i] = rgb[3 * i + 1] = rgb[3 * i + 2] = alpha[i];
      }
    }
    else
    {
      property->GetRGBTransferFunction(c)->GetTable(
        colourRange[0], colourRange[1], TableSize, rgb.data());
    }
    property->GetScalarOpacity(c)->GetTable(
      opacityRange[0], opacityRange[1], TableSize, alpha.data());
    float* row = &table[4 * static_cast<size_t>(TableSize) * c];
    for (int i = 0; i < TableSize; ++i)
    {
      std::copy(&rgb[3 * i], &rgb[3 * i] + 3, row + 4 * i);
      row[4 * i + 3] = alpha[i];
    }
  }
  this->ComponentTables->SetContext(window);
  this->ComponentTables->Create2DFromRaw(TableSize, 4, 4, VTK_FLOAT, table.data());
  this->ComponentTables->SetWrapS(vtkTextureObject::ClampToEdge);
  this->ComponentTables->SetWrapT(vtkTextureObject::ClampToEdge);
  this->ComponentTables->SetMinificationFilter(vtkTextureObject::Linear);
  this->ComponentTables->SetMagnificationFilter(vtkTextureObject::Linear);
  this->ComponentTableProperty = property;
  this->ComponentTableTime = newest;
  this->ComponentTableLayout = layout;
  this->ComponentTableVolumeTime = this->VolumeUploadTime.GetMTime();
}

bool vtkAccelVolumeSliceResources::PrepareImageTargets(
  vtkOpenGLRenderWindow* window, int width, int height, bool enable)
{
  this->Framebuffer->SaveCurrentBindingsAndBuffers();
  this->Framebuffer->Bind();
  if (!enable)
  {
    this->Framebuffer->RemoveColorAttachment(1);
    this->Framebuffer->RestorePreviousBindingsAndBuffers();
    return true;
  }
  bool ok = true;
  if (!this->FirstDepth->GetHandle() || static_cast<int>(this->FirstDepth->GetWidth()) != width ||
    static_cast<int>(this->FirstDepth->GetHeight()) != height)
  {
    this->FirstDepth->SetContext(window);
    this->FirstDepth->ResetFormatAndType();
    ok = this->FirstDepth->Create2D(width, height, 1, VTK_FLOAT, false);
    this->FirstDepth->SetMinificationFilter(vtkTextureObject::Nearest);
    this->FirstDepth->SetMagnificationFilter(vtkTextureObject::Nearest);
  }
  this->Framebuffer->RemoveColorAttachment(1);
  this->Framebuffer->AddColorAttachment(1, this->FirstDepth);
  this->Framebuffer->RestorePreviousBindingsAndBuffers();
  if (ok &&
    (!this->ImageColour->GetHandle() || static_cast<int>(this->ImageColour->GetWidth()) != width ||
      static_cast<int>(this->ImageColour->GetHeight()) != height))
  {
    this->ImageColour->SetContext(window);
    this->ImageColour->ResetFormatAndType();
    ok = this->ImageColour->Create2D(width, height, 4, VTK_UNSIGNED_CHAR, false);
    this->ImageFramebuffer->SetContext(window);
    this->ImageFramebuffer->SaveCurrentBindingsAndBuffers();
    this->ImageFramebuffer->Bind();
    this->ImageFramebuffer->RemoveColorAttachment(0);
    this->ImageFramebuffer->AddColorAttachment(0, this->ImageColour);
    this->ImageFramebuffer->RestorePreviousBindingsAndBuffers();
  }
  return ok;
}

bool vtkAccelVolumeSliceResources::PrepareExtraTargets(vtkOpenGLRenderWindow* window, int width,
  int height, bool auxiliaryDepth, bool secondAccumulation)
{
  const auto sized = [width, height](vtkTextureObject* texture)
  {
    return texture->GetHandle() && static_cast<int>(texture->GetWidth()) == width &&
      static_cast<int>(texture->GetHeight()) == height;
  };
  if (auxiliaryDepth && !sized(this->AuxiliaryDepth))
  {
    this->AuxiliaryDepth->SetContext(window);
    if (!this->AuxiliaryDepth->AllocateDepth(width, height, vtkTextureObject::Float32))
    {
      return false;
    }
    this->AuxiliaryDepth->SetMinificationFilter(vtkTextureObject::Nearest);
    this->AuxiliaryDepth->SetMagnificationFilter(vtkTextureObject::Nearest);
  }
  if (secondAccumulation && !sized(this->AccumulationSecond))
  {
    this->AccumulationSecond->SetContext(window);
    this->AccumulationSecond->ResetFormatAndType();
    if (!this->AccumulationSecond->Create2D(width, height, 4, VTK_FLOAT, false))
    {
      return false;
    }
    this->AccumulationSecond->SetMinificationFilter(vtkTextureObject::Nearest);
    this->AccumulationSecond->SetMagnificationFilter(vtkTextureObject::Nearest);
  }
  this->Framebuffer->SaveCurrentBindingsAndBuffers();
  this->Framebuffer->Bind();
  this->Framebuffer->RemoveColorAttachment(2);
  if (secondAccumulation)
  {
    this->Framebuffer->AddColorAttachment(2, this->AccumulationSecond);
  }
  this->Framebuffer->RestorePreviousBindingsAndBuffers();
  return true;
}

void vtkAccelVolumeSliceResources::AttachAuxiliaryDepth(bool auxiliary)
{
  this->Framebuffer->AddDepthAttachment(auxiliary ? this->AuxiliaryDepth : this->SceneDepth);
}

bool vtkAccelVolumeSliceResources::PrepareFullDepth(
  vtkOpenGLRenderWindow* window, int width, int height, int depthFormat)
{
  if (this->SceneDepthFull->GetHandle() && this->SceneDepthFullFormat == depthFormat &&
    static_cast<int>(this->SceneDepthFull->GetWidth()) == width &&
    static_cast<int>(this->SceneDepthFull->GetHeight()) == height)
  {
    return true;
  }
  this->SceneDepthFull->SetContext(window);
  if (!vtkAccelVolumeAllocateDepth(this->SceneDepthFull, width, height, depthFormat))
  {
    return false;
  }
  this->SceneDepthFullFormat = depthFormat;
  this->SceneDepthFull->SetMinificationFilter(vtkTextureObject::Nearest);
  this->SceneDepthFull->SetMagnificationFilter(vtkTextureObject::Nearest);
  this->DepthFramebuffer->SetContext(window);
  this->DepthFramebuffer->SaveCurrentBindingsAndBuffers();
  this->DepthFramebuffer->Bind();
  this->DepthFramebuffer->AddDepthAttachment(this->SceneDepthFull);
  this->DepthFramebuffer->RestorePreviousBindingsAndBuffers();
  return true;
}

void vtkAccelVolumeSliceResources::ReleaseGraphicsResources(vtkWindow* window)
{
  this->DepthFramebuffer->ReleaseGraphicsResources(window);
  this->SceneDepthFull->ReleaseGraphicsResources(window);
  this->ComponentVolume->ReleaseGraphicsResources(window);
  this->ComponentTables->ReleaseGraphicsResources(window);
  this->ComponentTableProperty = nullptr;
  this->FirstDepth->ReleaseGraphicsResources(window);
  this->AuxiliaryDepth->ReleaseGraphicsResources(window);
  this->AccumulationSecond->ReleaseGraphicsResources(window);
  this->ImageColour->ReleaseGraphicsResources(window);
  this->ImageFramebuffer->ReleaseGraphicsResources(window);
  this->Bricks.ReleaseGraphicsResources(window);
  this->TransferTable->ReleaseGraphicsResources(window);
  this->GradientOpacityTable->ReleaseGraphicsResources(window);
  this->EmptyLeaves->ReleaseGraphicsResources(window);
  this->EmptyBlocks->ReleaseGraphicsResources(window);
  this->TransferTable2D->ReleaseGraphicsResources(window);
  this->Gradients->ReleaseGraphicsResources(window);
  this->GradientScalars = nullptr;
  this->Table2DSource = nullptr;
  this->GradientTableRows = 0;
  this->GradientTableProperty = nullptr;
  this->Accumulation->ReleaseGraphicsResources(window);
  this->SceneDepth->ReleaseGraphicsResources(window);
  this->SceneDepthFormat = -2;
  this->SceneDepthFullFormat = -2;
  this->Framebuffer->ReleaseGraphicsResources(window);
  this->VertexBuffer->ReleaseGraphicsResources();
  this->SliceRecordBuffer->ReleaseGraphicsResources();
  this->Programs.clear(); // the window's shader cache releases them
  this->Compute.ReleaseGraphicsResources(window);
  this->Classifier.ReleaseGraphicsResources();
  for (auto& timer : this->FrameTimers)
  {
    if (timer)
    {
      timer->ReleaseGraphicsResources();
      timer.reset();
    }
  }
  this->RunningTimer = -1;
  this->SliceArray->ReleaseGraphicsResources();
  this->GeneratedSliceArray->ReleaseGraphicsResources();
  this->ResolveArray->ReleaseGraphicsResources();
  this->UploadedScalars = nullptr;
  this->TableProperty = nullptr;
  this->Context = nullptr;
}

vtkShaderProgram* vtkAccelVolumeSliceResources::ReadyProgram(vtkOpenGLRenderWindow* window,
  const char* vertex, const char* fragment, const std::string& prelude)
{
  vtkOpenGLShaderCache* cache = window->GetShaderCache();
  // The sources are the module's static strings: their addresses name them.
  const std::string key = std::to_string(reinterpret_cast<std::uintptr_t>(vertex)) + ' ' +
    std::to_string(reinterpret_cast<std::uintptr_t>(fragment)) + ' ' + prelude;
  const auto found = this->Programs.find(key);
  if (found != this->Programs.end() && found->second.Cache == cache)
  {
    return cache->ReadyShaderProgram(found->second.Program);
  }
  const std::string source =
    prelude.empty() ? std::string(fragment) : vtkAccelVolumeSliceAssembleShader(fragment, prelude);
  vtkShaderProgram* program = cache->ReadyShaderProgram(vertex, source.c_str(), "");
  if (program)
  {
    this->Programs[key] = CachedProgram{ cache, program };
  }
  return program;
}

void vtkAccelVolumeSliceResources::BeginFrameTimer()
{
  this->EndFrameTimer(); // one a failed frame left running
  if (!vtkOpenGLRenderTimer::IsSupported())
  {
    return;
  }
  // Harvest finished queries (Ready never blocks), then time this frame with an idle one; when
  // all are still in flight this frame goes untimed.
  for (int t = 0; t < 3; ++t)
  {
    std::unique_ptr<vtkOpenGLRenderTimer>& timer = this->FrameTimers[t];
    if (!timer)
    {
      timer.reset(new vtkOpenGLRenderTimer);
    }
    if (timer->Stopped() && timer->Ready())
    {
      this->LastGPUSeconds = timer->GetElapsedSeconds();
      timer->Reset();
    }
  }
  for (int t = 0; t < 3; ++t)
  {
    if (!this->FrameTimers[t]->Started())
    {
      this->FrameTimers[t]->Start();
      this->RunningTimer = t;
      return;
    }
  }
}

void vtkAccelVolumeSliceResources::EndFrameTimer()
{
  if (this->RunningTimer >= 0)
  {
    this->FrameTimers[this->RunningTimer]->Stop();
    this->RunningTimer = -1;
  }
}
