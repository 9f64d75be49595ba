// GL entry-point loader shim for OSMesa under Debian's GLX-built GLEW.
//
// glewInit() resolves every GL function through glXGetProcAddressARB. With an OSMesa context
// current, GLX knows nothing about it, so this module interposes the symbol (it precedes
// libGLX in the executable's lookup order) and answers with OSMesaGetProcAddress; otherwise
// it forwards to the real GLX function. OSMesaGetCurrentContext() alone cannot tell: with Mesa's
// shared glapi it also reports GLX and EGL contexts, so only contexts this module created count.
#include "vtk_glew.h"

// GLEW hides gl.h, which would define these for osmesa.h.
#ifndef GLAPI
#define GLAPI extern
#endif
#ifndef GLAPIENTRY
#define GLAPIENTRY
#endif
#include <GL/osmesa.h>

#include "vtkAccelVolumeOSMesaLoader.h"

#include <dlfcn.h>

#include <algorithm>
#include <mutex>
#include <vector>

namespace
{
std::mutex ContextsMutex;
std::vector<void*> OwnContexts;

bool IsOwnContextCurrent()
{
  void* current = reinterpret_cast<void*>(OSMesaGetCurrentContext());
  if (!current)
  {
    return false;
  }
  std::lock_guard<std::mutex> lock(ContextsMutex);
  return std::find(OwnContexts.begin(), OwnContexts.end(), current) != OwnContexts.end();
}

using ProcAddress = void (*)();
using GLXLoader = ProcAddress (*)(const GLubyte*);

ProcAddress Resolve(const char* forwardName, const GLubyte* name)
{
  if (IsOwnContextCurrent())
  {
    return reinterpret_cast<ProcAddress>(OSMesaGetProcAddress(reinterpret_cast<const char*>(name)));
  }
  auto next = reinterpret_cast<GLXLoader>(dlsym(RTLD_NEXT, forwardName));
  return next ? next(name) : nullptr;
}
}

void vtkAccelVolumeRegisterOSMesaContext(void* context, bool registered)
{
  std::lock_guard<std::mutex> lock(ContextsMutex);
  OwnContexts.erase(
    std::remove(OwnContexts.begin(), OwnContexts.end(), context), OwnContexts.end());
  if (registered)
  {
    OwnContexts.push_back(context);
  }
}

extern "C"
{
  __attribute__((visibility("default"))) ProcAddress glXGetProcAddressARB(const GLubyte* name)
  {
    return Resolve("glXGetProcAddressARB", name);
  }

  __attribute__((visibility("default"))) ProcAddress glXGetProcAddress(const GLubyte* name)
  {
    return Resolve("glXGetProcAddress", name);
  }
}
