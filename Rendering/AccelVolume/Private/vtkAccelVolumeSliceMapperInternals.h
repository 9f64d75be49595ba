// vtkAccelVolumeSliceMapper's per-mapper state and per-frame view (private to the module),
// shared by its two source files.
#ifndef vtkAccelVolumeSliceMapperInternals_h
#define vtkAccelVolumeSliceMapperInternals_h

#include "vtkAccelVolumeMinMaxOctree.h"
#include "vtkAccelVolumeSliceGeometry.h"
#include "vtkAccelVolumeSliceMapper.h"
#include "vtkAccelVolumeSliceMask.h"
#include "vtkAccelVolumeSlicePasses.h"
#include "vtkAccelVolumeSliceResources.h"
#include "vtkImageData.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkSmartPointer.h"

#include "common/Geometry.h"

class vtkPiecewiseFunction;

#include <string>
#include <vector>

class vtkCamera;
class vtkDataArray;
class vtkOpenGLRenderWindow;
class vtkRenderer;
class vtkVolume;
class vtkVolumeProperty;

// The frame's view: its size, the matrices between index, eye and clip space, the clipped
// regions and the slices' spacing and depth.
struct vtkAccelVolumeSliceView
{
  vtkImageData* Input = nullptr;
  int Dimensions[3] = { 0, 0, 0 };
  int Width = 0;
  int Height = 0;
  int LowerLeft[2] = { 0, 0 };
  vtkCamera* Camera = nullptr;
  vtkMatrix4x4* View = nullptr;
  vtkNew<vtkMatrix4x4> IndexToWorld;
  vtkNew<vtkMatrix4x4> Projection;
  vtkNew<vtkMatrix4x4> IndexToEye;
  vtkNew<vtkMatrix4x4> IndexToClip;
  vtkNew<vtkMatrix4x4> EyeToIndex;
  vtkNew<vtkMatrix4x4> InverseProjection;
  accelvolume::Box VolumeBox;
  std::vector<accelvolume::Box> Regions;
  std::vector<accelvolume::HalfSpace> Clip;
  accelvolume::ViewRays Rays;
  double VoxelSpacing = 0;
  double ReferenceDepth = 0;
  double Spacing = 0;
};

// One classified input of the empty-leaf octree.
struct vtkAccelVolumeLeafSource
{
  vtkImageData* Image = nullptr;
  vtkPiecewiseFunction* Opacity = nullptr;
  double Range[2] = { 0, 1 };
};

// Per-mapper state kept out of the public header.
class vtkAccelVolumeSliceMapper::vtkInternals
{
public:
  vtkAccelVolumeSliceResources Resources;
  vtkAccelVolumeSliceMask Mask;
  vtkAccelVolumeSliceFrame Frame;
  vtkNew<vtkAccelVolumeMinMaxOctree> Octree;
  // Multi-component scalars: each component alone, as the octrees classify them (dependent:
  // the opacity component; independent: each weighted one), built on demand and refreshed
  // with the scalars; null where not needed.
  std::vector<vtkSmartPointer<vtkImageData>> ComponentImages;
  vtkDataArray* ComponentImagesSource = nullptr;
  vtkMTimeType ComponentImagesTime = 0;
  // The octrees of independent components after the first source (which uses Octree).
  std::vector<vtkSmartPointer<vtkAccelVolumeMinMaxOctree>> ComponentOctrees;
  // What the uploaded leaf texture reflects: per source its scalars' time, function's time
  // and range, then the leaf size.
  std::vector<double> LeavesKey;
  double LeavesTransparentFraction = 0.0;
  int LeafGrid[3] = { 0, 0, 0 };
  // The octree's merged non-empty boxes for that classification (slice culling).
  std::vector<accelvolume::Box> NonEmptyBoxes;
  bool HaveNonEmptyBoxes = false;
  std::string Renderer;
  // Whether the context runs compute slices (asked once per window).
  vtkOpenGLRenderWindow* ComputeWindow = nullptr;
  bool ComputeSupported = false;
  std::vector<float> Vertices;
  std::vector<float> SliceRecords; // generated slices (see vtkAccelVolumeSliceFrame)
  // Generated slices: the last frame's view, for GetLastProxyAreaFraction on demand.
  bool AreaFractionPending = false;
  vtkAccelVolumeSliceGeometryInput AreaInput;
  std::vector<accelvolume::Box> AreaRegions;
  std::vector<accelvolume::HalfSpace> AreaClip;
  // RenderToImage's last images (RGBA8 colour; float window depth, 1 = nothing).
  vtkNew<vtkImageData> ColourImage;
  vtkNew<vtkImageData> DepthImage;
  // Hidden points (ghost array) as a binary mask, combined with a binary mask input.
  vtkSmartPointer<vtkImageData> GhostMask;
  vtkMTimeType GhostMaskTime = 0;
  bool UsedGhostMask = false;

  // The mask the frame uses: the mask input, or the input's hidden points (ghost / blanking
  // array) as a binary mask, intersected with a binary mask input.
  vtkImageData* EffectiveMask(vtkAccelVolumeSliceMapper* self, vtkImageData* input);
  // ClampDepthToBackface: where no sample contributed, the depth image takes the depth at which
  // the pixel's ray starts in the volume (box and clip planes): what VTK 9.1's GPU mapper
  // writes under that name (its ray start, not the back face).
  void ClampDepthImageToBackface(const vtkAccelVolumeSliceView& view);
  bool ReportedError = false;

  // Uploads the volume and its transfer table; false (reported) when it cannot.
  bool UploadVolume(vtkAccelVolumeSliceMapper* self, vtkOpenGLRenderWindow* window,
    vtkImageData* input, vtkDataArray* scalars, vtkVolumeProperty* property, const double range[2]);
  // The frame's matrices, regions and clip planes; false when the viewport is empty.
  bool SetUpView(vtkAccelVolumeSliceMapper* self, vtkRenderer* renderer, vtkVolume* volume,
    vtkImageData* input, vtkAccelVolumeSliceView& view);
  // The slices' spacing and the rays' depth map.
  void ChooseSliceSpacing(vtkAccelVolumeSliceMapper* self, vtkVolume* volume, vtkAccelVolumeSliceView& view);
  // Proxy geometry: per brick (in drawing order), per region, its slices then its cut faces.
  void BuildProxyGeometry(vtkAccelVolumeSliceMapper* self, vtkOpenGLRenderWindow* window,
    vtkImageData* input, vtkDataArray* scalars, vtkVolumeProperty* property, const double range[2], const vtkAccelVolumeSliceView& view,
    bool& skipEmptyLeaves, vtkAccelVolumeSliceGeometryStats& stats);
  // Whether this frame's slices are composited by the compute pass (SliceCompositing, the
  // frame's inputs and the context).
  bool UseComputeSlices(vtkAccelVolumeSliceMapper* self, vtkOpenGLRenderWindow* window,
    const vtkAccelVolumeSliceView& view);
  // The frame's settings for the passes; false (reported) when the 2D table fails.
  bool FillFrame(vtkAccelVolumeSliceMapper* self, vtkRenderer* renderer,
    vtkOpenGLRenderWindow* window, vtkImageData* input, vtkDataArray* scalars,
    vtkVolumeProperty* property, const double range[2], const vtkAccelVolumeSliceView& view,
    bool skipEmptyLeaves);
  // One component of the multi-component scalars as an image of its own (cached).
  vtkImageData* ComponentImage(vtkImageData* input, vtkDataArray* scalars, int component);
  // What the octree classifies for this frame: the scalars (one component), the opacity
  // component (dependent) or each component of non-zero weight (independent, the AND of their
  // transparency: the weighted sum of their opacities is zero only where all are).
  std::vector<vtkAccelVolumeLeafSource> LeafSources(vtkImageData* input, vtkDataArray* scalars,
    vtkVolumeProperty* property, const double range[2]);
  // Builds / classifies the octrees of the sources, uploads their leaf transparency and keeps
  // the non-empty boxes; false if unavailable.
  bool UpdateEmptyLeaves(vtkAccelVolumeSliceMapper* self, vtkOpenGLRenderWindow* window,
    const std::vector<vtkAccelVolumeLeafSource>& sources, bool computeSlices);
  // Compute slices with OctreeBuilder GPU and one source: the octree built and classified on the
  // GPU into the skipping textures, nothing read back (no non-empty boxes: the rasterised
  // slices' culling needs the CPU path). False when that cannot run (the CPU path then does).
  bool ClassifyOnGPU(vtkAccelVolumeSliceMapper* self, vtkOpenGLRenderWindow* window,
    const vtkAccelVolumeLeafSource& source);
  // The octree of `image` set up for this frame's build: builder, window and (GPU builder, the
  // uploaded scalars in one brick) the resident texture to build from.
  void ConfigureOctree(vtkAccelVolumeSliceMapper* self, vtkOpenGLRenderWindow* window,
    vtkAccelVolumeMinMaxOctree* octree, vtkImageData* image);
  // The block texture of the leaf flags just classified (x fastest, 255 = transparent).
  bool UploadEmptyBlocks(
    vtkOpenGLRenderWindow* window, const std::vector<unsigned char>& leafFlags);
  // Components (weights, unit distances), masks (vtkAccelVolumeSliceFrameFill.cxx).
  void FillComponentsAndMasks(vtkAccelVolumeSliceMapper* self, vtkDataArray* scalars,
    vtkVolumeProperty* property, const vtkAccelVolumeSliceView& view);
  // Raysum and average scales: the additive unit, the average's scalar range normalised to
  // the data range and to each component's (vtkAccelVolumeSliceFrameFill.cxx).
  void FillProjectionScales(
    vtkAccelVolumeSliceMapper* self, vtkVolumeProperty* property, const double range[2]);
  // Lights, gradient units and tables (vtkAccelVolumeSliceFrameFill.cxx).
  void FillShadingAndGradients(vtkAccelVolumeSliceMapper* self, vtkRenderer* renderer,
    vtkOpenGLRenderWindow* window, vtkImageData* input, vtkDataArray* scalars,
    vtkVolumeProperty* property, const double range[2], const vtkAccelVolumeSliceView& view);
  // Issues the slice passes and records the frame's brick counters.
  bool DrawPasses(
    vtkAccelVolumeSliceMapper* self, vtkOpenGLRenderWindow* window, std::string& passError);
};


// Blend modes drawn by the composite passes (iso-surfaces and the slice plane too).
inline bool vtkAccelVolumeCompositeLike(int blendMode)
{
  return blendMode == vtkVolumeMapper::COMPOSITE_BLEND ||
    blendMode == vtkVolumeMapper::ISOSURFACE_BLEND || blendMode == vtkVolumeMapper::SLICE_BLEND;
}

#endif
