// Headless render window: owns an EGL (surfaceless) or OSMesa context under VTK's generic window.
#include "vtkAccelVolumeHeadlessRenderWindow.h"

#include "vtkAccelVolumeObjectFactory.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLState.h"
#include "vtkRendererCollection.h"
#include "vtk_glew.h"

#if ACCELVOLUME_HAVE_EGL
#ifndef EGL_NO_X11
#define EGL_NO_X11
#endif
#ifndef MESA_EGL_NO_X11_HEADERS
#define MESA_EGL_NO_X11_HEADERS
#endif
#include <EGL/egl.h>
#include <EGL/eglext.h>
#endif

#if ACCELVOLUME_HAVE_OSMESA
// GLEW hides gl.h, which would define these for osmesa.h.
#ifndef GLAPI
#define GLAPI extern
#endif
#ifndef GLAPIENTRY
#define GLAPIENTRY
#endif
#include <GL/osmesa.h>

#include "vtkAccelVolumeOSMesaLoader.h"
#endif

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <string>
#include <vector>

namespace
{
// Debian's GLX-built glewInit() loads every GL entry point first, then fails in its GLX part
// (GLEW_ERROR_GLX_VERSION_11_ONLY = 3 or GLEW_ERROR_NO_GLX_DISPLAY = 4) because no X display
// exists; the GL entry points are valid for EGL/OSMesa contexts. Codes 1 and 2 are real GL
// failures.
constexpr GLenum FirstGLXOnlyGlewError = 3;

#if ACCELVOLUME_HAVE_EGL
// One EGL display for the process: terminating it would destroy every window's context.
struct EGLDisplayHolder
{
  EGLDisplay Display = EGL_NO_DISPLAY;
  bool Tried = false;
  std::mutex Mutex;
};

EGLDisplayHolder& SharedEGL()
{
  static EGLDisplayHolder holder;
  return holder;
}

bool HasExtension(const char* extensions, const char* name)
{
  if (!extensions)
  {
    return false;
  }
  const size_t length = std::strlen(name);
  for (const char* p = std::strstr(extensions, name); p; p = std::strstr(p + 1, name))
  {
    if ((p == extensions || p[-1] == ' ') && (p[length] == ' ' || p[length] == '\0'))
    {
      return true;
    }
  }
  return false;
}

EGLDisplay OpenEGLDisplay()
{
  EGLDisplayHolder& holder = SharedEGL();
  std::lock_guard<std::mutex> lock(holder.Mutex);
  if (holder.Tried)
  {
    return holder.Display;
  }
  holder.Tried = true;
  const char* clientExtensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  auto getPlatformDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
    eglGetProcAddress("eglGetPlatformDisplayEXT"));
  std::vector<EGLDisplay> candidates;
  if (getPlatformDisplay)
  {
    // NVIDIA: the first GPU device. Mesa: the surfaceless platform (no window system at all).
    if (HasExtension(clientExtensions, "EGL_EXT_platform_device"))
    {
      auto queryDevices =
        reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
      EGLDeviceEXT devices[8];
      EGLint count = 0;
      if (queryDevices && queryDevices(8, devices, &count) && count > 0)
      {
        for (EGLint i = 0; i < count; ++i)
        {
          candidates.push_back(getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr));
        }
      }
    }
    if (HasExtension(clientExtensions, "EGL_MESA_platform_surfaceless"))
    {
      candidates.insert(candidates.begin(),
        getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr));
    }
  }
  candidates.push_back(eglGetDisplay(EGL_DEFAULT_DISPLAY));
  for (EGLDisplay display : candidates)
  {
    EGLint major = 0;
    EGLint minor = 0;
    if (display != EGL_NO_DISPLAY && eglInitialize(display, &major, &minor) &&
      eglBindAPI(EGL_OPENGL_API))
    {
      holder.Display = display;
      break;
    }
  }
  return holder.Display;
}
#endif

std::string Lowercase(const char* text)
{
  std::string result = text ? text : "";
  std::transform(result.begin(), result.end(), result.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return result;
}
}

class vtkAccelVolumeHeadlessRenderWindow::vtkInternals
{
public:
#if ACCELVOLUME_HAVE_EGL
  EGLDisplay Display = EGL_NO_DISPLAY;
  EGLContext EGLContextHandle = EGL_NO_CONTEXT;
#endif
#if ACCELVOLUME_HAVE_OSMESA
  OSMesaContext OSMesaContextHandle = nullptr;
  std::vector<unsigned char> OSMesaBuffer;
  int OSMesaBufferSize[2] = { 0, 0 };
#endif
  std::string RendererString;
  bool CreationFailed = false;
};

vtkStandardNewMacro(vtkAccelVolumeHeadlessRenderWindow);

vtkAccelVolumeHeadlessRenderWindow::vtkAccelVolumeHeadlessRenderWindow()
  : Internals(new vtkInternals)
{
  this->SetOffScreenRendering(1);
  this->SetShowWindow(false);
  this->SetUseOffScreenBuffers(true);
  this->SetFrameBlitModeToNoBlit();
  this->SetMultiSamples(0);
  this->SetIsDirect(1);
  this->SetSupportsOpenGL(1);
  this->SetReadyForRendering(true);
  this->SetOwnContext(1);
  this->Size[0] = 300;
  this->Size[1] = 300;
  this->SetWindowName("AccelVolume headless");
}

vtkAccelVolumeHeadlessRenderWindow::~vtkAccelVolumeHeadlessRenderWindow()
{
  this->Finalize();
}

void vtkAccelVolumeHeadlessRenderWindow::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Backend: " << GetBackendName(this->Backend) << "\n";
  os << indent << "ActiveBackend: " << GetBackendName(this->ActiveBackend) << "\n";
}

const char* vtkAccelVolumeHeadlessRenderWindow::GetBackendName(int backend)
{
  switch (backend)
  {
    case BACKEND_EGL:
      return "egl";
    case BACKEND_OSMESA:
      return "osmesa";
    case BACKEND_X:
      return "x";
    default:
      return "automatic";
  }
}

int vtkAccelVolumeHeadlessRenderWindow::ParseBackendName(const char* name)
{
  const std::string value = Lowercase(name);
  if (value.empty() || value == "auto" || value == "automatic")
  {
    return BACKEND_AUTOMATIC;
  }
  if (value == "egl")
  {
    return BACKEND_EGL;
  }
  if (value == "osmesa")
  {
    return BACKEND_OSMESA;
  }
  if (value == "x" || value == "glx" || value == "x11")
  {
    return BACKEND_X;
  }
  return -1;
}

bool vtkAccelVolumeHeadlessRenderWindow::IsBackendAvailable(int backend)
{
  switch (backend)
  {
#if ACCELVOLUME_HAVE_EGL
    case BACKEND_EGL:
      return OpenEGLDisplay() != EGL_NO_DISPLAY;
#endif
#if ACCELVOLUME_HAVE_OSMESA
    case BACKEND_OSMESA:
      return true;
#endif
    case BACKEND_X:
    {
      const char* display = std::getenv("DISPLAY");
      return display && *display;
    }
    default:
      return false;
  }
}

int vtkAccelVolumeHeadlessRenderWindow::ResolveAutomaticBackend()
{
  const int requested = ParseBackendName(std::getenv("ACCELVOLUME_GL"));
  if (requested == BACKEND_EGL || requested == BACKEND_OSMESA)
  {
    return requested;
  }
  for (int candidate : { BACKEND_EGL, BACKEND_OSMESA })
  {
    if (IsBackendAvailable(candidate))
    {
      return candidate;
    }
  }
  return BACKEND_AUTOMATIC;
}

void vtkAccelVolumeHeadlessRenderWindow::InstallAsDefaultRenderWindow(int backend)
{
  vtkAccelVolumeObjectFactory::Install(backend);
}

int vtkAccelVolumeHeadlessRenderWindow::GetFactoryBackend()
{
  return vtkAccelVolumeObjectFactory::GetBackend();
}

void vtkAccelVolumeHeadlessRenderWindow::SetBackend(int backend)
{
  if (backend != BACKEND_AUTOMATIC && backend != BACKEND_EGL && backend != BACKEND_OSMESA)
  {
    vtkErrorMacro("Unsupported headless backend " << backend << " (use EGL, OSMesa or automatic)");
    return;
  }
  if (backend == this->Backend)
  {
    return;
  }
  this->Finalize();
  this->Backend = backend;
  this->Internals->CreationFailed = false;
  this->Modified();
}

bool vtkAccelVolumeHeadlessRenderWindow::CreateContext()
{
  vtkInternals& internals = *this->Internals;
  if (this->ActiveBackend != BACKEND_AUTOMATIC)
  {
    return true;
  }
  if (internals.CreationFailed)
  {
    return false;
  }
  const int backend =
    this->Backend == BACKEND_AUTOMATIC ? ResolveAutomaticBackend() : this->Backend;
#if ACCELVOLUME_HAVE_EGL
  if (backend == BACKEND_EGL)
  {
    internals.Display = OpenEGLDisplay();
    if (internals.Display == EGL_NO_DISPLAY)
    {
      vtkErrorMacro("EGL: no usable display (is libEGL with a Mesa or NVIDIA vendor installed?)");
      internals.CreationFailed = true;
      return false;
    }
    const EGLint configAttributes[] = { EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RED_SIZE, 8,
      EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8, EGL_ALPHA_SIZE, 8, EGL_DEPTH_SIZE, 24,
      EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE };
    EGLConfig config = nullptr;
    EGLint configCount = 0;
    if (!eglChooseConfig(internals.Display, configAttributes, &config, 1, &configCount) ||
      configCount < 1)
    {
      config = nullptr; // EGL_KHR_no_config_context: the context renders to FBOs only anyway
    }
    eglBindAPI(EGL_OPENGL_API);
    // Ask for the newest core version first: NVIDIA's EGL gives exactly the version asked
    // for (a 3.2 request yields 3.2, without compute shaders), Mesa the newest it has anyway.
    // VTK needs 3.2; 4.3 enables the GPU octree builder.
    static const EGLint coreVersions[][2] = { { 4, 6 }, { 4, 5 }, { 4, 3 }, { 3, 2 } };
    for (const auto& version : coreVersions)
    {
      const EGLint contextAttributes[] = { EGL_CONTEXT_MAJOR_VERSION, version[0],
        EGL_CONTEXT_MINOR_VERSION, version[1], EGL_CONTEXT_OPENGL_PROFILE_MASK,
        EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE };
      internals.EGLContextHandle =
        eglCreateContext(internals.Display, config, EGL_NO_CONTEXT, contextAttributes);
      if (internals.EGLContextHandle != EGL_NO_CONTEXT)
      {
        break;
      }
    }
    if (internals.EGLContextHandle == EGL_NO_CONTEXT)
    {
      vtkErrorMacro("EGL: could not create an OpenGL core context of version 3.2 or newer "
                    "(error 0x"
        << std::hex << eglGetError() << std::dec << ")");
      internals.CreationFailed = true;
      return false;
    }
    this->ActiveBackend = BACKEND_EGL;
    return true;
  }
#endif
#if ACCELVOLUME_HAVE_OSMESA
  if (backend == BACKEND_OSMESA)
  {
    const int attributes[] = { OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24,
      OSMESA_STENCIL_BITS, 8, OSMESA_ACCUM_BITS, 0, OSMESA_PROFILE, OSMESA_CORE_PROFILE,
      OSMESA_CONTEXT_MAJOR_VERSION, 3, OSMESA_CONTEXT_MINOR_VERSION, 2, 0 };
    internals.OSMesaContextHandle = OSMesaCreateContextAttribs(attributes, nullptr);
    if (!internals.OSMesaContextHandle)
    {
      vtkErrorMacro("OSMesa: could not create an OpenGL 3.2 core context");
      internals.CreationFailed = true;
      return false;
    }
    vtkAccelVolumeRegisterOSMesaContext(internals.OSMesaContextHandle, true);
    this->ActiveBackend = BACKEND_OSMESA;
    return true;
  }
#endif
  vtkErrorMacro("No headless OpenGL backend available (requested "
    << GetBackendName(this->Backend) << ", resolved " << GetBackendName(backend)
    << "); this build has EGL=" << ACCELVOLUME_HAVE_EGL << " OSMesa=" << ACCELVOLUME_HAVE_OSMESA);
  internals.CreationFailed = true;
  return false;
}

void vtkAccelVolumeHeadlessRenderWindow::DestroyContext()
{
  vtkInternals& internals = *this->Internals;
#if ACCELVOLUME_HAVE_EGL
  if (internals.EGLContextHandle != EGL_NO_CONTEXT)
  {
    if (eglGetCurrentContext() == internals.EGLContextHandle)
    {
      eglMakeCurrent(internals.Display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    }
    eglDestroyContext(internals.Display, internals.EGLContextHandle);
    internals.EGLContextHandle = EGL_NO_CONTEXT;
  }
#endif
#if ACCELVOLUME_HAVE_OSMESA
  if (internals.OSMesaContextHandle)
  {
    vtkAccelVolumeRegisterOSMesaContext(internals.OSMesaContextHandle, false);
    OSMesaDestroyContext(internals.OSMesaContextHandle);
    internals.OSMesaContextHandle = nullptr;
    internals.OSMesaBuffer.clear();
    internals.OSMesaBuffer.shrink_to_fit();
    internals.OSMesaBufferSize[0] = internals.OSMesaBufferSize[1] = 0;
  }
#endif
  this->ActiveBackend = BACKEND_AUTOMATIC;
  this->Initialized = false;
  this->GlewInitValid = false;
}

void vtkAccelVolumeHeadlessRenderWindow::MakeCurrent()
{
  if (!this->CreateContext())
  {
    return;
  }
  vtkInternals& internals = *this->Internals;
#if ACCELVOLUME_HAVE_EGL
  if (this->ActiveBackend == BACKEND_EGL)
  {
    if (eglGetCurrentContext() != internals.EGLContextHandle &&
      !eglMakeCurrent(
        internals.Display, EGL_NO_SURFACE, EGL_NO_SURFACE, internals.EGLContextHandle))
    {
      vtkErrorMacro(
        "EGL: eglMakeCurrent failed (error 0x" << std::hex << eglGetError() << std::dec << ")");
    }
    return;
  }
#endif
#if ACCELVOLUME_HAVE_OSMESA
  if (this->ActiveBackend == BACKEND_OSMESA)
  {
    // OSMesa needs a colour buffer of the window's size; VTK renders into its own FBOs.
    const int width = std::max(1, this->Size[0]);
    const int height = std::max(1, this->Size[1]);
    const bool resized =
      width != internals.OSMesaBufferSize[0] || height != internals.OSMesaBufferSize[1];
    if (resized)
    {
      internals.OSMesaBuffer.assign(static_cast<size_t>(width) * height * 4, 0);
      internals.OSMesaBufferSize[0] = width;
      internals.OSMesaBufferSize[1] = height;
    }
    if (resized || OSMesaGetCurrentContext() != internals.OSMesaContextHandle)
    {
      if (!OSMesaMakeCurrent(internals.OSMesaContextHandle, internals.OSMesaBuffer.data(),
            GL_UNSIGNED_BYTE, width, height))
      {
        vtkErrorMacro("OSMesa: OSMesaMakeCurrent failed");
      }
    }
  }
#endif
}

void vtkAccelVolumeHeadlessRenderWindow::ReleaseCurrent()
{
#if ACCELVOLUME_HAVE_EGL
  if (this->ActiveBackend == BACKEND_EGL && this->IsCurrent())
  {
    eglMakeCurrent(this->Internals->Display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  }
#endif
  // OSMesa cannot release a context without binding another one; nothing to do there.
}

bool vtkAccelVolumeHeadlessRenderWindow::IsCurrent()
{
#if ACCELVOLUME_HAVE_EGL
  if (this->ActiveBackend == BACKEND_EGL)
  {
    return this->Internals->EGLContextHandle != EGL_NO_CONTEXT &&
      eglGetCurrentContext() == this->Internals->EGLContextHandle;
  }
#endif
#if ACCELVOLUME_HAVE_OSMESA
  if (this->ActiveBackend == BACKEND_OSMESA)
  {
    return this->Internals->OSMesaContextHandle &&
      OSMesaGetCurrentContext() == this->Internals->OSMesaContextHandle;
  }
#endif
  return false;
}

void* vtkAccelVolumeHeadlessRenderWindow::GetGenericContext()
{
#if ACCELVOLUME_HAVE_EGL
  if (this->ActiveBackend == BACKEND_EGL)
  {
    return this->Internals->EGLContextHandle;
  }
#endif
#if ACCELVOLUME_HAVE_OSMESA
  if (this->ActiveBackend == BACKEND_OSMESA)
  {
    return this->Internals->OSMesaContextHandle;
  }
#endif
  return nullptr;
}

int vtkAccelVolumeHeadlessRenderWindow::GetColorBufferSizes(int* rgba)
{
  int total = this->Superclass::GetColorBufferSizes(rgba);
  vtkOpenGLFramebufferObject* framebuffer = this->GetRenderFramebuffer();
  if (rgba && total == 0 && this->Initialized && framebuffer && framebuffer->GetFBOIndex() != 0)
  {
    this->GetState()->PushDrawFramebufferBinding();
    framebuffer->Bind(GL_DRAW_FRAMEBUFFER);
    total = this->Superclass::GetColorBufferSizes(rgba);
    this->GetState()->PopDrawFramebufferBinding();
  }
  return total;
}

int vtkAccelVolumeHeadlessRenderWindow::SupportsOpenGL()
{
  this->MakeCurrent();
  return this->IsCurrent() ? 1 : 0;
}

void vtkAccelVolumeHeadlessRenderWindow::Initialize()
{
  this->MakeCurrent();
  if (this->IsCurrent())
  {
    this->OpenGLInit();
  }
}

void vtkAccelVolumeHeadlessRenderWindow::OpenGLInit()
{
  // vtkGenericOpenGLRenderWindow::Render() initialises GL before it asks for the context.
  this->MakeCurrent();
  if (!this->IsCurrent())
  {
    return;
  }
  this->Superclass::OpenGLInit();
}

void vtkAccelVolumeHeadlessRenderWindow::OpenGLInitContext()
{
  if (!this->Initialized)
  {
    const GLenum result = glewInit();
    if (result != GLEW_OK && result < FirstGLXOnlyGlewError)
    {
      vtkErrorMacro("GLEW could not be initialized: " << reinterpret_cast<const char*>(
                      glewGetErrorString(result)));
      return;
    }
    if (!GLEW_VERSION_3_2)
    {
      vtkErrorMacro("OpenGL 3.2 or later is required; the " << GetBackendName(this->ActiveBackend)
                                                            << " context offers less");
      return;
    }
    this->GlewInitValid = true;
    this->Initialized = true;
    const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    this->Internals->RendererString = renderer ? renderer : "";
  }
  this->Superclass::OpenGLInitContext();
}

void vtkAccelVolumeHeadlessRenderWindow::Render()
{
  if (!this->CreateContext())
  {
    return;
  }
  this->MakeCurrent();
  this->Superclass::Render();
}

void vtkAccelVolumeHeadlessRenderWindow::SetSize(int width, int height)
{
  if (width < 0 || height < 0)
  {
    vtkErrorMacro("Invalid window size " << width << "x" << height);
    return;
  }
  this->Superclass::SetSize(width, height);
}

const char* vtkAccelVolumeHeadlessRenderWindow::GetOpenGLRendererString()
{
  return this->Internals->RendererString.c_str();
}

void vtkAccelVolumeHeadlessRenderWindow::Finalize()
{
  if (this->ActiveBackend == BACKEND_AUTOMATIC)
  {
    return;
  }
  // Release every renderer's GL objects while our context is still alive.
  this->MakeCurrent();
  if (this->IsCurrent())
  {
    this->ReleaseGraphicsResources(this);
  }
  this->DestroyContext();
}
