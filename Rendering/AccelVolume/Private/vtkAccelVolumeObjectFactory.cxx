// Object factory routing vtkRenderWindow::New() to the headless window, plus module auto-init.
#include "vtkAccelVolumeObjectFactory.h"

#include "vtkAccelVolumeHeadlessRenderWindow.h"
#include "vtkVersion.h"

#include <cstdlib>
#include <iostream>
#include <mutex>

namespace
{
int FactoryBackend = vtkAccelVolumeHeadlessRenderWindow::BACKEND_AUTOMATIC;

vtkObject* CreateHeadlessRenderWindow()
{
  auto* window = vtkAccelVolumeHeadlessRenderWindow::New();
  window->SetBackend(FactoryBackend);
  return window;
}

// Unregisters the factory at exit so VTK's leak check does not count it.
struct FactoryRegistration
{
  vtkAccelVolumeObjectFactory* Factory = nullptr;
  ~FactoryRegistration()
  {
    if (this->Factory)
    {
      vtkObjectFactory::UnRegisterFactory(this->Factory);
      this->Factory->Delete();
    }
  }
};
FactoryRegistration Registration;
std::mutex RegistrationMutex;
}

vtkStandardNewMacro(vtkAccelVolumeObjectFactory);

vtkAccelVolumeObjectFactory::vtkAccelVolumeObjectFactory()
{
  this->RegisterOverride("vtkRenderWindow", "vtkAccelVolumeHeadlessRenderWindow",
    "AccelVolume headless (EGL/OSMesa) render window", 1, CreateHeadlessRenderWindow);
}

const char* vtkAccelVolumeObjectFactory::GetVTKSourceVersion()
{
  return VTK_SOURCE_VERSION;
}

int vtkAccelVolumeObjectFactory::GetBackend()
{
  return FactoryBackend;
}

int vtkAccelVolumeObjectFactory::BackendFromEnvironment()
{
  const char* requested = std::getenv("ACCELVOLUME_GL");
  if (requested && *requested)
  {
    const int backend = vtkAccelVolumeHeadlessRenderWindow::ParseBackendName(requested);
    if (backend >= 0 && backend != vtkAccelVolumeHeadlessRenderWindow::BACKEND_AUTOMATIC)
    {
      return backend;
    }
    if (backend < 0)
    {
      std::cerr << "AccelVolume: ignoring ACCELVOLUME_GL=" << requested
                << " (use egl, osmesa, x or auto)\n";
    }
  }
  const char* display = std::getenv("DISPLAY");
  return (display && *display) ? vtkAccelVolumeHeadlessRenderWindow::BACKEND_X
                               : vtkAccelVolumeHeadlessRenderWindow::BACKEND_AUTOMATIC;
}

void vtkAccelVolumeObjectFactory::Install(int backend)
{
  std::lock_guard<std::mutex> lock(RegistrationMutex);
  if (!Registration.Factory)
  {
    Registration.Factory = vtkAccelVolumeObjectFactory::New();
    vtkObjectFactory::RegisterFactory(Registration.Factory);
  }
  const bool useX = backend == vtkAccelVolumeHeadlessRenderWindow::BACKEND_X;
  FactoryBackend = useX ? vtkAccelVolumeHeadlessRenderWindow::BACKEND_AUTOMATIC : backend;
  Registration.Factory->SetEnableFlag(
    useX ? 0 : 1, "vtkRenderWindow", "vtkAccelVolumeHeadlessRenderWindow");
  // VTK's own X window comes from RenderingOpenGL2's factory, which may be registered first.
  vtkObjectFactory::SetAllEnableFlags(useX ? 1 : 0, "vtkRenderWindow", "vtkXOpenGLRenderWindow");
}

// Called by VTK's auto-initialisation of modules that implement VTK::RenderingCore.
VTKRENDERINGACCELVOLUME_EXPORT void vtkRenderingAccelVolume_AutoInit_Construct()
{
  vtkAccelVolumeObjectFactory::Install(vtkAccelVolumeObjectFactory::BackendFromEnvironment());
}
