// vtkAccelVolumeImageDisplay: draws a CPU-rendered premultiplied RGBA float image over the
// renderer's viewport (blended "over" the scene). Not installed.
#ifndef vtkAccelVolumeImageDisplay_h
#define vtkAccelVolumeImageDisplay_h

#include "vtkAccelVolumeDepthCopy.h" // For vtkAccelVolumeDepthReader
#include "vtkNew.h"                  // For vtkNew

#include <vector> // For std::vector

class vtkOpenGLRenderWindow;
class vtkOpenGLVertexArrayObject;
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

  void ReleaseGraphicsResources(vtkWindow* window);

private:
  vtkAccelVolumeImageDisplay(const vtkAccelVolumeImageDisplay&) = delete;
  void operator=(const vtkAccelVolumeImageDisplay&) = delete;

  vtkNew<vtkTextureObject> Image;
  std::vector<unsigned short> Pixels;
  vtkNew<vtkOpenGLVertexArrayObject> Array;
  vtkAccelVolumeDepthReader DepthReader;
};

#endif
