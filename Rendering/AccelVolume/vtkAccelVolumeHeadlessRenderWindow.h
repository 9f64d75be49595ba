/**
 * @class   vtkAccelVolumeHeadlessRenderWindow
 * @brief   Offscreen OpenGL render window on OSMesa or EGL (surfaceless), for builds of VTK
 *          that have neither (such as Debian's VTK 9.1).
 *
 * The window owns its OpenGL 3.2 core context and renders into VTK's own offscreen
 * framebuffers, so no display or window system is needed:
 * - EGL: Mesa's surfaceless platform (llvmpipe here, the GPU driver on NVIDIA machines),
 *   falling back to the default EGL display where the surfaceless extension is absent.
 * - OSMesa: Mesa's software off-screen rasteriser.
 *
 * The backend is chosen by SetBackend(); BACKEND_AUTOMATIC reads the environment variable
 * `ACCELVOLUME_GL` (`egl`, `osmesa`) and otherwise prefers EGL, then OSMesa.
 * The module's object factory makes `vtkRenderWindow::New()` return this window when
 * `ACCELVOLUME_GL` is `egl` or `osmesa`, or when it is unset and no X display is available;
 * `ACCELVOLUME_GL=x` keeps VTK's X window (see InstallAsDefaultRenderWindow()).
 *
 * Debian's GLEW is built for GLX: glewInit() reports GLEW_ERROR_NO_GLX_DISPLAY after it has
 * loaded every GL entry point. This class accepts that code instead of failing, so VTK does
 * not print "GLEW could not be initialized" on every render.
 *
 * Several windows (contexts) may live in one process; each MakeCurrent() switches to its own.
 */

#ifndef vtkAccelVolumeHeadlessRenderWindow_h
#define vtkAccelVolumeHeadlessRenderWindow_h

#include "vtkGenericOpenGLRenderWindow.h"
#include "vtkRenderingAccelVolumeModule.h" // For export macro

#include <memory> // For std::unique_ptr

class VTKRENDERINGACCELVOLUME_EXPORT vtkAccelVolumeHeadlessRenderWindow
  : public vtkGenericOpenGLRenderWindow
{
public:
  static vtkAccelVolumeHeadlessRenderWindow* New();
  vtkTypeMacro(vtkAccelVolumeHeadlessRenderWindow, vtkGenericOpenGLRenderWindow);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum Backends
  {
    BACKEND_AUTOMATIC = 0,
    BACKEND_EGL = 1,
    BACKEND_OSMESA = 2,
    BACKEND_X = 3 ///< only meaningful for the object factory: VTK's own X window
  };

  ///@{
  /**
   * Requested backend (default BACKEND_AUTOMATIC). Must be set before the first render;
   * changing it later finalizes the current context.
   */
  void SetBackend(int backend);
  vtkGetMacro(Backend, int);
  ///@}

  /**
   * The backend in use once the context exists (BACKEND_AUTOMATIC before that, or when
   * context creation failed).
   */
  vtkGetMacro(ActiveBackend, int);

  /** "automatic", "egl", "osmesa" or "x". */
  static const char* GetBackendName(int backend);

  /** Parses "egl", "osmesa", "x", "auto"/"automatic"/"" (case-insensitive); -1 if unknown. */
  static int ParseBackendName(const char* name);

  /** Whether this build and machine can create a context for the backend. */
  static bool IsBackendAvailable(int backend);

  /**
   * What BACKEND_AUTOMATIC means here: `ACCELVOLUME_GL` if set and valid, else EGL when it
   * works, else OSMesa. Returns BACKEND_AUTOMATIC when no headless backend works.
   */
  static int ResolveAutomaticBackend();

  /**
   * Makes vtkRenderWindow::New() return a headless window using `backend`
   * (BACKEND_EGL/BACKEND_OSMESA/BACKEND_AUTOMATIC), or restores VTK's X window (BACKEND_X).
   * The module's auto-initialisation calls this once with the environment's choice.
   */
  static void InstallAsDefaultRenderWindow(int backend);

  /** The default backend for windows created through the object factory. */
  static int GetFactoryBackend();

  /** Renderer string of the current context (e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"). */
  const char* GetOpenGLRendererString();

  ///@{
  /** vtkRenderWindow / vtkOpenGLRenderWindow API implemented on the owned context. */
  void Initialize() override;
  void Finalize() override;
  void MakeCurrent() override;
  void ReleaseCurrent() override;
  bool IsCurrent() override;
  void Render() override;
  void SetSize(int width, int height) override;
  void SetSize(int size[2]) override { this->SetSize(size[0], size[1]); }
  void* GetGenericContext() override;
  int SupportsOpenGL() override;
  /**
   * The colour bits of the framebuffer VTK renders into. A surfaceless EGL or OSMesa default
   * framebuffer has no colour attachment, so VTK's query reported 0 bits and
   * vtkHardwareSelector (picking) refused the window; the render framebuffer is asked instead.
   */
  int GetColorBufferSizes(int* rgba) override;
  vtkTypeBool IsDirect() override { return 1; }
  ///@}

protected:
  vtkAccelVolumeHeadlessRenderWindow();
  ~vtkAccelVolumeHeadlessRenderWindow() override;

  void OpenGLInit() override;
  void OpenGLInitContext() override;

  int Backend = BACKEND_AUTOMATIC;
  int ActiveBackend = BACKEND_AUTOMATIC;

private:
  vtkAccelVolumeHeadlessRenderWindow(const vtkAccelVolumeHeadlessRenderWindow&) = delete;
  void operator=(const vtkAccelVolumeHeadlessRenderWindow&) = delete;

  bool CreateContext();
  void DestroyContext();

  class vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
};

#endif
