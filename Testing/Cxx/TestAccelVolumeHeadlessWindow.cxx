// Headless windows: both backends, several contexts in one process, resize, factory override.
#include "vtkAccelVolumeHeadlessRenderWindow.h"

#include "vtkActor.h"
#include "vtkNew.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkUnsignedCharArray.h"

#include <cstdlib>
#include <iostream>

namespace
{
// Renders a red sphere on blue and checks the centre and corner pixels.
bool RenderSphere(vtkRenderWindow* window, int width, int height)
{
  vtkNew<vtkSphereSource> sphere;
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(sphere->GetOutputPort());
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(1, 0, 0);
  actor->GetProperty()->SetAmbient(1);
  actor->GetProperty()->SetDiffuse(0);
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  renderer->SetBackground(0, 0, 1);
  window->AddRenderer(renderer);
  window->SetSize(width, height);
  window->Render();
  vtkNew<vtkUnsignedCharArray> pixels;
  window->GetRGBACharPixelData(0, 0, width - 1, height - 1, 0, pixels);
  const unsigned char* centre = pixels->GetPointer(4 * ((height / 2) * width + width / 2));
  const unsigned char* corner = pixels->GetPointer(0);
  const bool ok = centre[0] > 200 && centre[2] < 50 && corner[2] > 200 && corner[0] < 50;
  if (!ok)
  {
    std::cerr << "unexpected pixels " << width << "x" << height << ": centre " << int(centre[0])
              << "," << int(centre[1]) << "," << int(centre[2]) << " corner " << int(corner[0])
              << "," << int(corner[1]) << "," << int(corner[2]) << "\n";
  }
  window->RemoveRenderer(renderer);
  return ok;
}
}

int TestAccelVolumeHeadlessWindow(int, char*[])
{
  bool ok = true;
  int backends = 0;
  for (int backend : { vtkAccelVolumeHeadlessRenderWindow::BACKEND_EGL,
         vtkAccelVolumeHeadlessRenderWindow::BACKEND_OSMESA })
  {
    if (!vtkAccelVolumeHeadlessRenderWindow::IsBackendAvailable(backend))
    {
      std::cout << vtkAccelVolumeHeadlessRenderWindow::GetBackendName(backend)
                << " not available here\n";
      continue;
    }
    ++backends;
    // Two live contexts at once, used alternately, then a resize.
    vtkNew<vtkAccelVolumeHeadlessRenderWindow> first;
    vtkNew<vtkAccelVolumeHeadlessRenderWindow> second;
    first->SetBackend(backend);
    second->SetBackend(backend);
    ok = RenderSphere(first, 64, 48) && ok;
    ok = RenderSphere(second, 50, 50) && ok;
    ok = RenderSphere(first, 120, 90) && ok;
    if (first->GetActiveBackend() != backend)
    {
      std::cerr << "backend not active\n";
      ok = false;
    }
    std::cout << vtkAccelVolumeHeadlessRenderWindow::GetBackendName(backend) << ": "
              << first->GetOpenGLRendererString() << "\n";
  }
  if (backends == 0)
  {
    std::cerr << "no headless backend available\n";
    return EXIT_FAILURE;
  }
  // vtkRenderWindow::New() goes through the module's factory (ACCELVOLUME_GL picks it).
  vtkNew<vtkRenderWindow> generic;
  if (!vtkAccelVolumeHeadlessRenderWindow::SafeDownCast(generic))
  {
    std::cerr << "vtkRenderWindow::New() returned " << generic->GetClassName() << "\n";
    ok = false;
  }
  else
  {
    ok = RenderSphere(generic, 40, 30) && ok;
  }
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
