/**
 * @file    vtkAccelVolumeSlicePasses.h
 * @brief   The two OpenGL passes of vtkAccelVolumeSliceMapper (private to the module):
 *          accumulate the proxy slices and cut faces into the float target, then resolve
 *          the accumulated values into colours over the scene.
 */
#ifndef vtkAccelVolumeSlicePasses_h
#define vtkAccelVolumeSlicePasses_h

#include <array>
#include <string>
#include <vector>

class vtkAccelVolumeSliceResources;
class vtkMatrix4x4;
class vtkImageData;
class vtkOpenGLRenderWindow;
class vtkTextureObject;

// Everything one frame's passes need, computed by the mapper.
struct vtkAccelVolumeSliceFrame
{
  // A convex cell of the cropped volume: its index-space box and its vertex ranges.
  struct Cell
  {
    std::array<float, 3> Lower;
    std::array<float, 3> Upper;
    int SliceFirst = 0;
    int SliceCount = 0;
    int FaceFirst = 0;
    int FaceCount = 0;
  };
  // One brick's share of the frame: which texture, where it sits in the volume, the samples it
  // owns (the shaders discard the others) and its cells.
  struct BrickDraw
  {
    int Brick = 0; // index into the brick layout / cache
    float OwnedLower[3] = { 0, 0, 0 };
    float OwnedUpper[3] = { 0, 0, 0 };
    float TextureOrigin[3] = { 0, 0, 0 }; // index of the texture's first texel
    float TextureSize[3] = { 1, 1, 1 };
    std::vector<Cell> Cells;
    // Composite: the first vertex of each slice, and the end, so slices can be drawn in
    // batches for early ray termination.
    std::vector<int> SliceStarts;
  };
  static constexpr int MaximumClipPlanes = 8;
  // Floats per proxy vertex: index x, y, z, then the eye depth of the vertex's slice plane minus
  // ReferenceDepth (the same value for every vertex of a slice; unused by cut faces).
  static constexpr int VertexFloats = 4;

  int BlendMode = 0; // vtkVolumeMapper blend mode (MIP, MinIP, additive, average)
  int SlabSamples = 1;
  bool HalfFloatTarget = false; // accumulation targets in 16-bit floats
  int Width = 0; // accumulation target: the viewport, divided by the image sample distance
  int Height = 0;
  int ViewportWidth = 0; // the renderer's viewport in window pixels
  int ViewportHeight = 0;
  int LowerLeft[2] = { 0, 0 };     // the viewport in the read framebuffer (the scene depth)
  int DrawLowerLeft[2] = { 0, 0 }; // and where it is drawn: (0, 0) in a depth-peeling target
  float Dimensions[3] = { 1, 1, 1 };
  bool Linear = true;   // trilinear (else nearest) volume sampling
  bool Bricked = false; // several bricks: the shaders test sample ownership
  vtkMatrix4x4* IndexToClip = nullptr;
  vtkMatrix4x4* IndexToEye = nullptr;
  vtkMatrix4x4* EyeToIndex = nullptr;
  vtkMatrix4x4* Projection = nullptr; // eye -> clip
  vtkMatrix4x4* InverseProjection = nullptr;
  double ReferenceDepth = 0; // eye depth near the volume; slice depths are sent relative to it
  int ClipPlaneCount = 0;
  float ClipPlanes[MaximumClipPlanes][4] = {};
  float SliceSpacing = 1;
  float SlicePhase = 0;
  bool BoundaryRerendering = true;
  bool ClearSecondTarget = false; // depth peeling's first volumetric stage (see DepthPeeling.h)
  bool SlicePlane = false; // SLICE_BLEND: one classified sample on the plane, drawn as a face
  bool Parallel = false;
  float AdditiveScale = 1;
  float OpacityUnitDistance = 1; // composite: length the table opacities hold for
  // Composite shading / gradient opacity.
  bool Shade = false;
  bool GradientOpacity = false;
  float NormalMatrix[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 }; // row-major, index gradient -> eye
  float ScalarRangeWidth = 1;
  float GradientTableMaximum = 1;
  // Per index axis, index-step differences -> VTK's gradient magnitude (mean / axis spacing).
  float GradientAxisScale[3] = { 1, 1, 1 };
  // VTK's light model (common/Lighting.h), eye space.
  static constexpr int MaximumLights = 16;
  int LightCount = 0;
  int LightPositional[MaximumLights] = {};
  float LightAxis[MaximumLights][3] = {};
  float LightPosition[MaximumLights][3] = {};
  float LightAmbient[MaximumLights][3] = {};
  float LightDiffuse[MaximumLights][3] = {};
  float LightSpecular[MaximumLights][3] = {};
  float LightAttenuation[MaximumLights][3] = {};
  float LightCosCone[MaximumLights] = {};
  float LightExponent[MaximumLights] = {};
  bool TwoSidedLighting = true;
  bool HeadlightOnly = false;
  float Lighting[4] = { 0.1f, 0.7f, 0.2f, 10.0f }; // ambient, diffuse, specular, power
  float AverageRange[2] = { 0, 1 };
  float AverageLower[4] = { 0, 0, 0, 0 }; // per component (independent multi-component)
  float AverageUpper[4] = { 1, 1, 1, 1 };
  float ColourScale = 1; // FinalColorWindow / Level
  float ColourBias = 0;
  // ISOSURFACE_BLEND (drawn as composite): the property's iso-values normalised to the data
  // range, ascending.
  static constexpr int MaximumIsoSurfaces = 16;
  bool IsoSurface = false;
  // UseDepthPass (composite): 1 = the contour-depth stage, 2 = the accumulation after it (rays
  // start at the contour); the contour values are IsoSurfaceValues then. 0 = no depth pass.
  int DepthPassStage = 0;
  int IsoComponent = 0; // independent components: the one iso-surfaces are drawn of
  int IsoSurfaceCount = 0;
  float IsoSurfaceValues[MaximumIsoSurfaces] = {};
  // 2-4 component scalars: the resources' ComponentVolume and ComponentTables.
  int Components = 1;
  bool IndependentComponents = true;
  float ComponentWeights[4] = { 1, 1, 1, 1 };
  float ComponentUnitDistances[4] = { 1, 1, 1, 1 };
  float ComponentLighting[4][4] = {}; // per independent component: as Lighting
  // Mask input: 0 none, 1 binary, 2 label map (composite only); its texture and label table.
  int MaskMode = 0;
  bool MaskNeighbours = false; // ghost masks: a sample next to a hidden point is hidden (VTK)
  float MaskBlendFactor = 1;
  float MaskMaximum[3] = { 0, 0, 0 };
  vtkTextureObject* MaskTexture = nullptr;
  vtkTextureObject* LabelTable = nullptr;
  // RenderToImage: resolve into the resources' image target instead of the scene, and keep the
  // nearest contributing sample's depth; the images are read back into these (when set).
  bool RenderToImage = false;
  vtkImageData* ColourImage = nullptr;
  vtkImageData* DepthImage = nullptr; // float window depth, 1 where nothing contributes
  int SelectionMode = 0;              // vtkAccelVolumeSelectionMode
  float SelectionColour[3] = { 0, 0, 0 };
  // Composite early ray termination: every TerminationInterval slices, pixels whose alpha
  // reached TerminationThreshold are closed for later slices (counted across bricks).
  bool FrontToBack = true; // composite order (back to front uses "over")
  bool Jitter = false;     // composite: per-pixel sample offsets against wood-grain
  bool EarlyTermination = false;
  int TerminationInterval = 16;
  float TerminationThreshold = 0.99f;
  mutable int TerminationPasses = 0; // out: mark passes run

  // Composite empty-space skipping: per fragment (transparent samples skip the shading) and
  // by octree leaves (EmptyLeaves texture, 1 = transparent leaf).
  bool GradientTexture = false; // precomputed gradients instead of central differences
  float GradientTextureScale = 1;
  bool TransferFunction2D = false; // vtkVolumeProperty::TF_2D
  float Gradient2DMaximum = 1;     // gradient magnitude at the 2D table's top row
  bool SkipTransparentSamples = false;
  bool SkipEmptyLeaves = false;
  float LeafSize = 8;
  float LeafGridMaximum[3] = { 0, 0, 0 };
  float BlockGridMaximum[3] = { 0, 0, 0 }; // compute slices: EmptyBlocks' grid size - 1

  std::vector<BrickDraw> Bricks;                // in drawing order
  const std::vector<float>* Vertices = nullptr; // triangles, VertexFloats per vertex

  // Composite slices generated by the vertex stage: one instance per slice, SliceRecordFloats
  // floats each in SliceRecords (its depth minus ReferenceDepth, the box it is drawn across:
  // lower, upper, then padding); cells' SliceFirst / SliceCount and SliceStarts count slices.
  static constexpr int SliceRecordFloats = 8;
  static constexpr int GeneratedSliceVertices = 30;
  bool GeneratedSlices = false;
  const std::vector<float>* SliceRecords = nullptr;
  float DepthGradient[3] = { 0, 0, 1 }; // index space: depth - ReferenceDepth = g . p + offset
  float DepthOffset = 0;

  // Compute slices (composite, MIP, MinIP of one brick and one region): one compute dispatch
  // takes every slice's samples per pixel instead of drawing proxy slices. Bricks then holds
  // one brick with one cell (the region box) and no slices. Slice planes lie at relative depths
  // SliceBase + j * SliceSpacing (j integer).
  bool ComputeSlices = false;
  float SliceBase = 0;
  bool CountSamples = false;      // count the samples taken (a read-back that waits for the GPU)
  mutable long long Samples = -1; // out: samples taken (compute slices with CountSamples), or -1
};

/**
 * Runs both passes inside a saved/restored OpenGL state, uploading bricks as the frame needs
 * them. Returns false with `error` set when a shader did not compile, the targets could not be
 * allocated or a brick could not be uploaded (the scene is left untouched then).
 */
bool vtkAccelVolumeRenderSlicePasses(vtkOpenGLRenderWindow* window,
  vtkAccelVolumeSliceResources& resources, const vtkAccelVolumeSliceFrame& frame,
  std::string& error);

#endif
