/**
 * @class   vtkAccelVolumeBrickCache
 * @brief   The slice mapper's volume textures (private to the module): one 3D texture per
 *          brick of an accelvolume::BrickLayout, within a budget of bricks kept on the GPU.
 *
 * With room for every brick, each is uploaded once, the first time a frame needs it (bricks
 * that the octree finds empty are never uploaded). With room for fewer (a GPU memory budget
 * below the volume's size), the first `capacity - 1` bricks a frame needs stay resident for good
 * and the rest stream through the last slot, so a frame uploads only what the budget cannot
 * hold, in the order the frame draws (which compositing fixes). Uploads read the brick straight
 * out of the whole volume's encoded scalars (GL_UNPACK_ROW_LENGTH / IMAGE_HEIGHT): no
 * per-brick copy on the CPU.
 */
#ifndef vtkAccelVolumeBrickCache_h
#define vtkAccelVolumeBrickCache_h

#include "vtkAccelVolumeScalarEncoding.h"
#include "vtkSmartPointer.h"

#include "slicing/Bricking.h"

#include <cstdint>
#include <string>
#include <vector>

class vtkOpenGLRenderWindow;
class vtkTextureObject;
class vtkWindow;

class vtkAccelVolumeBrickCache
{
public:
  vtkAccelVolumeBrickCache();
  ~vtkAccelVolumeBrickCache();

  /**
   * New data or layout: forgets every brick (textures are kept for reuse). `encoded` must stay
   * valid until the next Reset; `capacity` is how many bricks may be resident at once.
   */
  void Reset(const accelvolume::BrickLayout& layout, const int dimensions[3],
    const vtkAccelVolumeEncodedScalars* encoded, int capacity);

  /** Counters of the frame start over. */
  void BeginFrame();

  /**
   * The texture holding brick `brick`, uploaded now if it is not resident. nullptr with `error`
   * set when the upload fails.
   */
  vtkTextureObject* Acquire(
    vtkOpenGLRenderWindow* window, int brick, bool linear, std::string& error);

  bool IsResident(int brick) const;
  /** True once every brick of the layout is resident (the encoded scalars are not needed). */
  bool AllResident() const;

  int GetCapacity() const { return this->Capacity; }
  int GetFrameUploads() const { return this->FrameUploads; }
  std::uint64_t GetFrameUploadedBytes() const { return this->FrameUploadedBytes; }
  std::uint64_t GetResidentBytes() const;

  void ReleaseGraphicsResources(vtkWindow* window);

private:
  vtkAccelVolumeBrickCache(const vtkAccelVolumeBrickCache&) = delete;
  void operator=(const vtkAccelVolumeBrickCache&) = delete;

  bool Upload(vtkOpenGLRenderWindow* window, int brick, vtkTextureObject* texture,
    std::string& error);

  accelvolume::BrickLayout Layout;
  int Dimensions[3] = { 0, 0, 0 };
  const vtkAccelVolumeEncodedScalars* Encoded = nullptr;
  int Capacity = 1;
  std::vector<vtkSmartPointer<vtkTextureObject>> Slots;
  std::vector<int> SlotBrick;  // brick held by each slot, -1 when free
  std::vector<int> BrickSlot;  // slot of each brick, -1 when not resident
  int FrameUploads = 0;
  std::uint64_t FrameUploadedBytes = 0;
};

#endif
