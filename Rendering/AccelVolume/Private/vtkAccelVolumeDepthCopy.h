// vtkAccelVolumeDepthCopy: copies of the scene depth the mappers read (private to the module).
// VTK's windows are multisampled by default (8 samples), and a multisampled framebuffer can be
// neither copied (glCopyTexSubImage) nor read (glReadPixels): its depth is resolved by a blit
// into a texture of the same depth format, as vtkGPUVolumeRayCastMapper does.
#ifndef vtkAccelVolumeDepthCopy_h
#define vtkAccelVolumeDepthCopy_h

#include "vtkNew.h" // For vtkNew

class vtkOpenGLFramebufferObject;
class vtkOpenGLRenderWindow;
class vtkTextureObject;
class vtkWindow;

/** GL_DEPTH24_STENCIL8, besides vtkTextureObject's depth formats. */
constexpr int vtkAccelVolumeDepthStencilFormat = 100;

/**
 * The depth format of the read framebuffer when it is multisampled (a vtkTextureObject depth
 * format or vtkAccelVolumeDepthStencilFormat), -1 when it is single-sampled (then any depth
 * texture can take a copy).
 */
int vtkAccelVolumeReadDepthFormat();

/** Allocates `texture` with `depthFormat` (-1: 32-bit float depth). */
bool vtkAccelVolumeAllocateDepth(vtkTextureObject* texture, int width, int height, int depthFormat);

/**
 * Copies the read framebuffer's depth in [x, x + width) x [y, y + height) to (0, 0) of
 * `texture`, the depth attachment of `framebuffer` (allocated with `depthFormat`, the read
 * framebuffer's vtkAccelVolumeReadDepthFormat(), when that is multisampled).
 */
void vtkAccelVolumeCopyReadDepth(vtkOpenGLRenderWindow* window, vtkTextureObject* texture,
  vtkOpenGLFramebufferObject* framebuffer, int depthFormat, int x, int y, int width, int height);

/** Reads the read framebuffer's depth into `depth` (width x height floats), multisampled or not. */
class vtkAccelVolumeDepthReader
{
public:
  vtkAccelVolumeDepthReader();
  ~vtkAccelVolumeDepthReader();
  bool Read(
    vtkOpenGLRenderWindow* window, const int lowerLeft[2], int width, int height, float* depth);
  void ReleaseGraphicsResources(vtkWindow* window);

private:
  vtkAccelVolumeDepthReader(const vtkAccelVolumeDepthReader&) = delete;
  void operator=(const vtkAccelVolumeDepthReader&) = delete;
  vtkNew<vtkTextureObject> Resolved;
  vtkNew<vtkOpenGLFramebufferObject> Framebuffer;
  int Format = -2;
};

/**
 * Makes `window`'s context current for the scope when it has one (and restores the previous
 * one after): a mapper releasing its objects for one window while another window's context is
 * current would otherwise delete that window's objects of the same names (VTK's
 * TestRemoveVolumeNonCurrentContext).
 */
class vtkAccelVolumeWindowContext
{
public:
  explicit vtkAccelVolumeWindowContext(vtkWindow* window);
  ~vtkAccelVolumeWindowContext();
  vtkAccelVolumeWindowContext(const vtkAccelVolumeWindowContext&) = delete;
  void operator=(const vtkAccelVolumeWindowContext&) = delete;

private:
  vtkOpenGLRenderWindow* Window = nullptr;
};

#endif
