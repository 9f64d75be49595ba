// The slice mapper's brick textures: resident bricks within a budget, the rest streamed.
#include "vtkAccelVolumeBrickCache.h"

#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkTextureObject.h"
#include "vtkType.h"
#include "vtk_glew.h"

#include <algorithm>

namespace
{
size_t TexelBytes(int textureType)
{
  return textureType == VTK_UNSIGNED_CHAR ? 1 : (textureType == VTK_UNSIGNED_SHORT ? 2 : 4);
}
}

vtkAccelVolumeBrickCache::vtkAccelVolumeBrickCache() = default;
vtkAccelVolumeBrickCache::~vtkAccelVolumeBrickCache() = default;

void vtkAccelVolumeBrickCache::Reset(const accelvolume::BrickLayout& layout,
  const int dimensions[3], const vtkAccelVolumeEncodedScalars* encoded, int capacity)
{
  this->Layout = layout;
  std::copy(dimensions, dimensions + 3, this->Dimensions);
  this->Encoded = encoded;
  const int bricks = static_cast<int>(layout.bricks.size());
  this->Capacity = std::max(1, std::min(capacity, bricks));
  // Textures already created are reused (re-specified by the next upload); extra ones go.
  this->Slots.resize(static_cast<size_t>(this->Capacity));
  this->SlotBrick.assign(this->Slots.size(), -1);
  this->BrickSlot.assign(static_cast<size_t>(bricks), -1);
}

void vtkAccelVolumeBrickCache::BeginFrame()
{
  this->FrameUploads = 0;
  this->FrameUploadedBytes = 0;
}

bool vtkAccelVolumeBrickCache::IsResident(int brick) const
{
  return brick >= 0 && brick < static_cast<int>(this->BrickSlot.size()) &&
    this->BrickSlot[brick] >= 0;
}

bool vtkAccelVolumeBrickCache::AllResident() const
{
  return std::all_of(
    this->BrickSlot.begin(), this->BrickSlot.end(), [](int slot) { return slot >= 0; });
}

std::uint64_t vtkAccelVolumeBrickCache::GetResidentBytes() const
{
  std::uint64_t bytes = 0;
  const size_t texel = this->Encoded ? TexelBytes(this->Encoded->TextureType) : 0;
  for (int brick : this->SlotBrick)
  {
    bytes += brick >= 0 ? this->Layout.bricks[brick].TexelCount() * texel : 0;
  }
  return bytes;
}

vtkTextureObject* vtkAccelVolumeBrickCache::Acquire(
  vtkOpenGLRenderWindow* window, int brick, bool linear, std::string& error)
{
  if (brick < 0 || brick >= static_cast<int>(this->BrickSlot.size()))
  {
    error = "no such brick";
    return nullptr;
  }
  int slot = this->BrickSlot[brick];
  if (slot < 0)
  {
    // A free slot becomes this brick's for good; once all are taken, the last one streams.
    const auto free = std::find(this->SlotBrick.begin(), this->SlotBrick.end(), -1);
    slot = free != this->SlotBrick.end() ? static_cast<int>(free - this->SlotBrick.begin())
                                         : this->Capacity - 1;
    if (this->SlotBrick[slot] >= 0)
    {
      this->BrickSlot[this->SlotBrick[slot]] = -1;
      this->SlotBrick[slot] = -1;
    }
    if (!this->Slots[slot])
    {
      this->Slots[slot] = vtkSmartPointer<vtkTextureObject>::New();
    }
    if (!this->Upload(window, brick, this->Slots[slot], error))
    {
      return nullptr;
    }
    this->SlotBrick[slot] = brick;
    this->BrickSlot[brick] = slot;
  }
  vtkTextureObject* texture = this->Slots[slot];
  const int filter = linear ? vtkTextureObject::Linear : vtkTextureObject::Nearest;
  texture->SetMinificationFilter(filter);
  texture->SetMagnificationFilter(filter);
  return texture;
}

bool vtkAccelVolumeBrickCache::Upload(
  vtkOpenGLRenderWindow* window, int brick, vtkTextureObject* texture, std::string& error)
{
  if (!this->Encoded || !this->Encoded->Data)
  {
    error = "the volume's scalars are no longer available for upload";
    return false;
  }
  const accelvolume::Brick& b = this->Layout.bricks[brick];
  const size_t texel = TexelBytes(this->Encoded->TextureType);
  const size_t first = (static_cast<size_t>(b.textureOrigin[2]) * this->Dimensions[1] +
                         static_cast<size_t>(b.textureOrigin[1])) *
      this->Dimensions[0] +
    static_cast<size_t>(b.textureOrigin[0]);
  const auto* data = static_cast<const unsigned char*>(this->Encoded->Data) + first * texel;
  texture->SetContext(window);
  // A reused texture keeps the format of its first upload unless told: the data may have
  // changed type (uchar -> short -> float) since.
  texture->ResetFormatAndType();
  window->GetState()->vtkglPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  // The brick is a box inside the whole volume: GL steps over the rest of each row and slice.
  glPixelStorei(GL_UNPACK_ROW_LENGTH, this->Dimensions[0]);
  glPixelStorei(GL_UNPACK_IMAGE_HEIGHT, this->Dimensions[1]);
  const bool created = texture->Create3DFromRaw(b.textureSize[0], b.textureSize[1],
    b.textureSize[2], 1, this->Encoded->TextureType, const_cast<unsigned char*>(data));
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
  glPixelStorei(GL_UNPACK_IMAGE_HEIGHT, 0);
  if (!created)
  {
    error = "could not create a " + std::to_string(b.textureSize[0]) + "x" +
      std::to_string(b.textureSize[1]) + "x" + std::to_string(b.textureSize[2]) +
      " 3D texture (out of GPU memory? set a smaller GPU memory budget)";
    return false;
  }
  texture->SetWrapS(vtkTextureObject::ClampToEdge);
  texture->SetWrapT(vtkTextureObject::ClampToEdge);
  texture->SetWrapR(vtkTextureObject::ClampToEdge);
  ++this->FrameUploads;
  this->FrameUploadedBytes += b.TexelCount() * texel;
  return true;
}

void vtkAccelVolumeBrickCache::ReleaseGraphicsResources(vtkWindow* window)
{
  for (auto& texture : this->Slots)
  {
    if (texture)
    {
      texture->ReleaseGraphicsResources(window);
    }
  }
  this->SlotBrick.assign(this->SlotBrick.size(), -1);
  this->BrickSlot.assign(this->BrickSlot.size(), -1);
}
