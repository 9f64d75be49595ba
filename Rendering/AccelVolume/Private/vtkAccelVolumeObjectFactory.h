/**
 * @class   vtkAccelVolumeObjectFactory
 * @brief   Object factory of the AccelVolume module: makes vtkRenderWindow::New() return a
 *          vtkAccelVolumeHeadlessRenderWindow when rendering headless.
 *
 * Private to the module. Registered by the module's auto-initialisation
 * (vtk_module_autoinit with VTK::RenderingAccelVolume) or explicitly through
 * vtkAccelVolumeHeadlessRenderWindow::InstallAsDefaultRenderWindow().
 */
#ifndef vtkAccelVolumeObjectFactory_h
#define vtkAccelVolumeObjectFactory_h

#include "vtkObjectFactory.h"
#include "vtkRenderingAccelVolumeModule.h" // For export macro

class VTKRENDERINGACCELVOLUME_NO_EXPORT vtkAccelVolumeObjectFactory : public vtkObjectFactory
{
public:
  static vtkAccelVolumeObjectFactory* New();
  vtkTypeMacro(vtkAccelVolumeObjectFactory, vtkObjectFactory);
  const char* GetVTKSourceVersion() override;
  const char* GetDescription() override { return "AccelVolume headless render windows"; }

  /**
   * Registers the factory once and routes vtkRenderWindow::New() to the given backend
   * (a vtkAccelVolumeHeadlessRenderWindow::Backends value; BACKEND_X restores VTK's window).
   */
  static void Install(int backend);
  /** The backend windows made by the factory use. */
  static int GetBackend();
  /** The backend the environment asks for: ACCELVOLUME_GL, else X when DISPLAY is set, else
   * headless. */
  static int BackendFromEnvironment();

protected:
  vtkAccelVolumeObjectFactory();
  ~vtkAccelVolumeObjectFactory() override = default;

private:
  vtkAccelVolumeObjectFactory(const vtkAccelVolumeObjectFactory&) = delete;
  void operator=(const vtkAccelVolumeObjectFactory&) = delete;
};

#endif
