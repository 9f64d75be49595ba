/**
 * @class   vtkAccelVolumeSliceResources
 * @brief   GPU resources of vtkAccelVolumeSliceMapper: the 3D volume texture, the transfer
 *          table, the float accumulation target, the scene depth copy and the proxy geometry
 *          buffers. Private to the module (not wrapped, not installed).
 */
#ifndef vtkAccelVolumeSliceResources_h
#define vtkAccelVolumeSliceResources_h

#include "vtkAccelVolumeBrickCache.h"
#include "vtkAccelVolumeGPUClassifier.h"
#include "vtkAccelVolumeSliceCompute.h"
#include "vtkAccelVolumeScalarEncoding.h"
#include "vtkNew.h"
#include "vtkTimeStamp.h"

#include "slicing/Bricking.h"

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

class vtkDataArray;
class vtkImageData;
class vtkOpenGLBufferObject;
class vtkOpenGLFramebufferObject;
class vtkOpenGLRenderTimer;
class vtkOpenGLRenderWindow;
class vtkOpenGLShaderCache;
class vtkOpenGLVertexArrayObject;
class vtkShaderProgram;
class vtkTextureObject;
class vtkVolumeProperty;
class vtkWindow;

class vtkAccelVolumeSliceResources
{
public:
  vtkAccelVolumeSliceResources();
  ~vtkAccelVolumeSliceResources();

  /** Makes `window` the context; releases what another context held. True when it changed. */
  bool UseContext(vtkOpenGLRenderWindow* window);

  /**
   * Encodes the scalars and lays out their bricks when the scalars, the range, the context or
   * the limits changed (a brick axis may span at most `maximumBrickSize` texels, 0 for
   * GL_MAX_3D_TEXTURE_SIZE; `budgetBytes` caps the bricks resident at once, 0 for none). The
   * textures are uploaded by Bricks.Acquire when a frame first needs them. Sets ScalarScale /
   * ScalarBias so that texel * scale + bias is the scalar normalised to `range`. False with
   * `error` set on failure.
   */
  bool PrepareVolume(vtkOpenGLRenderWindow* window, vtkImageData* image, vtkDataArray* scalars,
    const double range[2], std::uint64_t budgetBytes, int maximumBrickSize, std::string& error);

  /**
   * 2-4 component scalars: one float texture with each component normalised to its finite
   * range (ComponentRanges), as one brick. `colourComponents` (dependent RGBA): components 0-2
   * are colours as VTK's GPU mapper reads them instead, the value over the type's maximum for
   * 8- and 16-bit integers, as is for floating types (wider integers keep their range). False
   * with `error` set when the volume would need bricks (larger than GL_MAX_3D_TEXTURE_SIZE) or
   * the texture cannot be created.
   */
  bool PrepareMultiComponentVolume(vtkOpenGLRenderWindow* window, vtkImageData* image,
    vtkDataArray* scalars, bool colourComponents, std::string& error);
  /**
   * The per-component tables of 2-4 component scalars, rows 0..3 over ComponentRanges:
   * independent: colour and opacity of component c; dependent: row 0 holds the colour over
   * component 0 and the opacity over the last component.
   */
  void UpdateComponentTables(
    vtkOpenGLRenderWindow* window, vtkVolumeProperty* property, int components, bool independent);
  vtkNew<vtkTextureObject> ComponentVolume;
  vtkNew<vtkTextureObject> ComponentTables;
  double ComponentRanges[4][2] = {};
  bool UploadedColourComponents = false;
  // What ComponentTables reflects (the ranges come with the volume upload).
  vtkVolumeProperty* ComponentTableProperty = nullptr;
  vtkMTimeType ComponentTableTime = 0;
  vtkMTimeType ComponentTableVolumeTime = 0;
  int ComponentTableLayout = 0; // components, negative when dependent

  /** The one-component scalars the bricks hold (PrepareVolume's), or null. */
  vtkDataArray* GetUploadedScalars() const { return this->UploadedScalars; }

  /** The bricks of the prepared volume (one brick when it fits a texture and the budget). */
  const accelvolume::BrickLayout& GetBrickLayout() const { return this->Layout; }

  /**
   * Frees the encoded copy of the scalars (int, float, double and signed data) once every brick
   * is resident; it is rebuilt if a brick has to be uploaded again.
   */
  void ReleaseEncodedScalarsIfResident();

  /** Rebuilds the RGBA transfer table (colour + scalar opacity over `range`) when needed. */
  void UpdateTransferTable(
    vtkOpenGLRenderWindow* window, vtkVolumeProperty* property, const double range[2]);

  /**
   * Rebuilds the gradient-opacity table when a function or maximum changed: row r (of `rows`,
   * 1-4: one per independent component) holds 1024 entries of the property's gradient opacity
   * r over [0, maxima[r]] gradient magnitude.
   */
  void UpdateGradientOpacityTable(
    vtkOpenGLRenderWindow* window, vtkVolumeProperty* property, const double* maxima, int rows);

  /**
   * Uploads the property's 2D transfer function (an RGBA float vtkImageData, x: scalar,
   * y: gradient magnitude) when it changed. False (with error) for a malformed image.
   */
  bool UpdateTransferFunction2D(
    vtkOpenGLRenderWindow* window, vtkImageData* function, std::string& error);

  /**
   * Precomputes central-difference gradients of the normalized scalars (the paper's
   * 4-channel texture) when the volume changed. Call after UploadVolume.
   */
  bool UpdateGradients(vtkOpenGLRenderWindow* window, vtkImageData* image, vtkDataArray* scalars,
    const double range[2]);

  /**
   * Sizes the accumulation target (`channels` float channels: 1 for MIP/MinIP, 2 for the
   * integrating modes) and the scene depth copy to the viewport.
   */
  /**
   * depthFormat: vtkAccelVolumeReadDepthFormat()'s (-1: 32-bit float depth); halfFloat: 16-bit
   * float channels instead of 32-bit.
   */
  bool PrepareTargets(vtkOpenGLRenderWindow* window, int width, int height, int channels,
    int depthFormat, bool halfFloat);
  /** Sizes the full-viewport depth copy a reduced target (image sample distance > 1) needs. */
  bool PrepareFullDepth(vtkOpenGLRenderWindow* window, int width, int height, int depthFormat);
  /**
   * RenderToImage targets: the depth attachment 1 of the accumulation framebuffer (or its
   * removal when `enable` is false) and the colour image framebuffer, both width x height.
   */
  bool PrepareImageTargets(vtkOpenGLRenderWindow* window, int width, int height, bool enable);
  /**
   * Extra targets, width x height: `auxiliaryDepth` sizes a 32-bit float depth buffer
   * (AttachAuxiliaryDepth: dependent MIP / MinIP test their last component against it, the
   * depth pass keeps its contour there); `secondAccumulation` sizes and attaches (colour
   * attachment 2) the target of components 2-3 of an independent average, else removes it.
   */
  bool PrepareExtraTargets(vtkOpenGLRenderWindow* window, int width, int height,
    bool auxiliaryDepth, bool secondAccumulation);
  /** The accumulation framebuffer (bound) tests depth against AuxiliaryDepth, or SceneDepth. */
  void AttachAuxiliaryDepth(bool auxiliary);

  void ReleaseGraphicsResources(vtkWindow* window);

  /**
   * The program of (vertex source, fragment source, prelude from
   * vtkAccelVolumeSliceShaderPrelude, "" for none), made through the window's shader cache on
   * its first use and only bound after that: the cache would otherwise substitute and hash the
   * whole source on every call, every frame. Null when it does not compile.
   */
  vtkShaderProgram* ReadyProgram(vtkOpenGLRenderWindow* window, const char* vertex,
    const char* fragment, const std::string& prelude);

  vtkAccelVolumeBrickCache Bricks;
  vtkNew<vtkTextureObject> TransferTable;
  vtkNew<vtkTextureObject> GradientOpacityTable;
  vtkNew<vtkTextureObject> EmptyLeaves;     // R8 over the octree's leaf grid, 1 = transparent
  vtkNew<vtkTextureObject> EmptyBlocks;     // R8 over blocks of LeafBlock^3 leaves, 1 = all are
  static constexpr int LeafBlock = 4;       // leaves per block edge (AccelVolumeSliceCS)
  /** EmptyBlocks' size for a leaf grid (whole blocks over it). */
  static void BlockGridOf(const int leaves[3], int blocks[3])
  {
    for (int a = 0; a < 3; ++a)
    {
      blocks[a] = (leaves[a] + LeafBlock - 1) / LeafBlock;
    }
  }
  vtkNew<vtkTextureObject> TransferTable2D; // RGBA over (scalar, gradient magnitude)
  vtkNew<vtkTextureObject> Gradients;       // RGBA16: index-space gradient (rgb), value (a)
  float GradientScale = 1.0f;               // decoded gradient = (rgb * 2 - 1) * GradientScale
  bool AccumulationHalfFloat = false;
  vtkNew<vtkTextureObject> Accumulation;
  vtkNew<vtkTextureObject> SceneDepth;
  vtkNew<vtkTextureObject> SceneDepthFull;             // viewport-sized, for a reduced target only
  vtkNew<vtkOpenGLFramebufferObject> DepthFramebuffer; // SceneDepthFull as its depth
  int SceneDepthFormat = -2;     // what SceneDepth was allocated with (PrepareTargets)
  int SceneDepthFullFormat = -2; // and SceneDepthFull
  // RenderToImage: the nearest contributing depth (second accumulation target, R32F), and the
  // resolved colour (RGBA8) with its framebuffer.
  vtkNew<vtkTextureObject> FirstDepth;
  vtkNew<vtkTextureObject> AuxiliaryDepth;     // float depth: MIP / MinIP sample, contour
  vtkNew<vtkTextureObject> AccumulationSecond; // independent average: components 2-3
  vtkNew<vtkTextureObject> ImageColour;
  vtkNew<vtkOpenGLFramebufferObject> ImageFramebuffer;
  vtkNew<vtkOpenGLFramebufferObject> Framebuffer;
  vtkNew<vtkOpenGLBufferObject> VertexBuffer;
  vtkNew<vtkOpenGLBufferObject> SliceRecordBuffer; // generated slices' depths and boxes
  vtkNew<vtkOpenGLVertexArrayObject> SliceArray;
  vtkNew<vtkOpenGLVertexArrayObject> GeneratedSliceArray; // instanced slice records
  vtkNew<vtkOpenGLVertexArrayObject> ResolveArray;
  vtkAccelVolumeSliceCompute Compute; // compute slices' programs
  vtkAccelVolumeGPUClassifier Classifier; // skipping textures from a GPU-built octree

  static constexpr int TableSize = 1024;

  /**
   * GPU time of the frames, from GL timer queries read only once the GPU has them (the render
   * path never waits): BeginFrameTimer / EndFrameTimer around a frame's GL work; the seconds of
   * the latest frame whose result came in, or -1 before any did (or without timer queries).
   */
  void BeginFrameTimer();
  void EndFrameTimer();
  double GetLastGPUSeconds() const { return this->LastGPUSeconds; }

private:
  std::unique_ptr<vtkOpenGLRenderTimer> FrameTimers[3];
  int RunningTimer = -1;
  double LastGPUSeconds = -1.0;

  struct CachedProgram
  {
    vtkOpenGLShaderCache* Cache = nullptr;
    vtkShaderProgram* Program = nullptr;
  };
  std::map<std::string, CachedProgram> Programs;

public:
  float ScalarScale = 1.0f;
  float ScalarBias = 0.0f;
  int Dimensions[3] = { 0, 0, 0 };

private:
  vtkAccelVolumeSliceResources(const vtkAccelVolumeSliceResources&) = delete;
  void operator=(const vtkAccelVolumeSliceResources&) = delete;

  vtkTimeStamp VolumeUploadTime;
  vtkAccelVolumeEncodedScalars Encoded;
  bool EncodedReleased = false;
  accelvolume::BrickLayout Layout;
  std::uint64_t LayoutBudget = 0;
  int LayoutMaximumBrickSize = 0;
  vtkTimeStamp TableBuildTime;
  vtkTimeStamp GradientTableBuildTime;
  vtkTimeStamp Table2DBuildTime;
  vtkTimeStamp GradientBuildTime;
  vtkDataArray* GradientScalars = nullptr;
  vtkImageData* Table2DSource = nullptr;
  double GradientTableMaxima[4] = { -1.0, -1.0, -1.0, -1.0 };
  int GradientTableRows = 0;
  vtkVolumeProperty* GradientTableProperty = nullptr;
  vtkDataArray* UploadedScalars = nullptr;
  double UploadedRange[2] = { 0.0, 0.0 };
  double TableRange[2] = { 0.0, 0.0 };
  vtkVolumeProperty* TableProperty = nullptr;
  vtkWindow* Context = nullptr;
};

#endif
