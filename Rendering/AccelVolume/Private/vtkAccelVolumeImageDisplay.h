// vtkAccelVolumeImageDisplay: draws a CPU-rendered premultiplied RGBA float image over the
// renderer's viewport (blended "over" the scene). Not installed.
#ifndef vtkAccelVolumeImageDisplay_h
#define vtkAccelVolumeImageDisplay_h

#include "vtkAccelVolumeDepthCopy.h" // For vtkAccelVolumeDepthReader
#include "vtkNew.h"                  // For vtkNew
#include "vtkSmartPointer.h"         // For vtkSmartPointer
#include "vtkWeakPointer.h"          // For vtkWeakPointer

#include <vector> // For std::vector

class vtkOpenGLBufferObject;
class vtkOpenGLRenderWindow;
class vtkOpenGLVertexArrayObject;
class vtkShaderProgram;
class vtkTextureObject;
class vtkWindow;

class vtkAccelVolumeImageDisplay
{
public:
  vtkAccelVolumeImageDisplay();
  ~vtkAccelVolumeImageDisplay();

  // rgba: imageWidth x imageHeight premultiplied pixels (4 floats, rows from the bottom),
  // stretched over the viewport (lowerLeft, width x height); only image pixels
  // rectangle = [x0, x1] x [y0, y1] (inclusive) are uploaded and drawn, the rest being
  // transparent. Colours are shown as rgb * colourScale + colourBias * alpha (FinalColorWindow /
  // Level); selectionMode (vtkAccelVolumeSelectionMode) replaces them for vtkHardwareSelector.
  // False if GL fails.
  bool Draw(vtkOpenGLRenderWindow* window, const int lowerLeft[2], int width, int height,
    int imageWidth, int imageHeight, const float* rgba, const int rectangle[4],
    float colourScale = 1.0f, float colourBias = 0.0f, int selectionMode = 0,
    const float selectionColour[3] = nullptr, bool clearSecondTarget = false);

  // The viewport's window depth in [0, 1] (rows from the bottom), width * height values.
  bool ReadDepth(
    vtkOpenGLRenderWindow* window, const int lowerLeft[2], int width, int height, float* depth);

  // Shear-warp's intermediate image (size[0] x size[1] premultiplied pixels, 4 floats) and its
  // warp (row-major 2 x 3): forward maps intermediate coordinates (pixel i at i) to image
  // positions (pixel x's centre at x + 0.5), inverse the other way (ShearWarpFactorization's
  // warp and inverseWarp).
  struct Warp
  {
    const float* image;
    int size[2];
    const double (*forward)[3];
    const double (*inverse)[3];
    // The image converted already (ShearWarpDisplayPixels: (size[0] + 1) x (size[1] + 1) 16-bit
    // pixels, the last column and row zero, and each row's first and last visible pixel), or
    // null: DrawWarped converts `image` itself.
    const unsigned short* converted = nullptr;
    const int* rowFirst = nullptr;
    const int* rowLast = nullptr;
  };

  // The intermediate image warped by the GPU into the image of imageWidth x imageHeight pixels
  // over the viewport, sampled bilinearly with zero outside, as ShearWarpRenderer::Warp. Only
  // image pixels in `rectangle` are drawn; the other arguments as Draw. False if GL fails or the
  // intermediate image exceeds the texture size limit (the caller then warps on the CPU).
  bool DrawWarped(vtkOpenGLRenderWindow* window, const int lowerLeft[2], int width, int height,
    int imageWidth, int imageHeight, const Warp& warp, const int rectangle[4], float colourScale,
    float colourBias, int selectionMode, const float selectionColour[3], bool clearSecondTarget);

  // A frame's intermediate image shown while it composites (plain frames of the lean shader:
  // no selection, no depth peeling). BeginWarpedFrame forgets an earlier frame's rows;
  // DrawWarpedRows uploads the rows [0, rowsReady) not uploaded yet, draws the footprint bands
  // they complete and flushes, so that the OpenGL driver draws them while the caller goes on;
  // DrawWarped then draws the rest. The image is the one DrawWarped draws alone. False if GL
  // fails or the image exceeds the texture size limit (nothing drawn: DrawWarped draws it all).
  void BeginWarpedFrame();
  // Draw calls that showed the last image (DrawWarpedRows' parts and DrawWarped's rest; Draw: 1).
  int GetLastNumberOfParts() const { return this->LastParts; }
  bool DrawWarpedRows(vtkOpenGLRenderWindow* window, const int lowerLeft[2], int width,
    int height, const Warp& warp, int rowsReady, float colourScale, float colourBias);

  void ReleaseGraphicsResources(vtkWindow* window);

private:
  vtkAccelVolumeImageDisplay(const vtkAccelVolumeImageDisplay&) = delete;
  void operator=(const vtkAccelVolumeImageDisplay&) = delete;

  struct Placement; // where and how the texture's pixels land (ImageDisplay.cxx)
  // A warp texture with room for uploadWidth x uploadHeight texels (zero border); false past
  // the texture size limit or if GL fails.
  bool PrepareWarpTexture(vtkOpenGLRenderWindow* window, vtkTextureObject* texture,
    int uploadWidth, int uploadHeight);
  vtkTextureObject* PartTexture(int part); // made on first use
  vtkShaderProgram* ReadyLeanProgram(vtkOpenGLRenderWindow* window); // bound, or null
  bool Show(vtkOpenGLRenderWindow* window, vtkTextureObject* texture, const Placement& placement);
  // The general shader's warp uniforms.
  void SetWarpUniforms(
    vtkShaderProgram* program, vtkTextureObject* texture, const Placement& placement);
  // The lean shader's geometry: the parallelogram's bands of intermediate rows that hold
  // visible pixels, each cut to their columns (FootprintVertices, then the buffer), drawn.
  void DrawFootprint(
    vtkShaderProgram* program, vtkTextureObject* texture, const Placement& placement);

  vtkNew<vtkTextureObject> Image;
  vtkNew<vtkTextureObject> Intermediate; // shear-warp's, with room to spare (DrawWarped)
  std::vector<unsigned short> Pixels;
  // DrawWarped's own conversion: each intermediate row's first and last pixel that is not zero
  // (first > last: none); and the footprint's triangles (x, y in normalized device coordinates, s, t).
  std::vector<int> RowFirst, RowLast;
  std::vector<float> FootprintVertices;
  vtkNew<vtkOpenGLVertexArrayObject> Array;
  vtkNew<vtkOpenGLVertexArrayObject> FootprintArray;
  vtkNew<vtkOpenGLBufferObject> FootprintBuffer;
  vtkAccelVolumeDepthReader DepthReader;
  // The frame drawn in parts (DrawWarpedRows): parts and footprint bands drawn, and each
  // part's texture (its rows from the first line of its bands).
  int DrawnParts = 0;
  int LastParts = 0;
  int DrawnBands = 0;
  std::vector<vtkSmartPointer<vtkTextureObject>> PartTextures;
  int WarpTextureSize[2] = { 0, 0 }; // every warp texture's (PrepareWarpTexture)
  vtkWeakPointer<vtkShaderProgram> LeanProgram;
  vtkWeakPointer<vtkOpenGLRenderWindow> LeanProgramWindow;
};

#endif
