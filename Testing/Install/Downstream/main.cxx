// Downstream smoke test of the AccelVolume package: the public headers compile outside the
// project, the library links and loads, auto-initialisation registers the module's object
// factory, and (with ACCELVOLUME_GL=egl|osmesa) vtkRenderWindow::New() is the headless window.
#include "vtkAccelVolumeHeadlessRenderWindow.h"
#include "vtkAccelVolumeSliceMapper.h"

#include "vtkNew.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"

#include <cstdlib>
#include <cstring>
#include <iostream>
#include <sstream>
#include <string>

int main()
{
  int failures = 0;

  vtkNew<vtkAccelVolumeSliceMapper> mapper;
  std::ostringstream printed;
  mapper->Print(printed);
  std::cout << printed.str();
  if (printed.str().find("vtkAccelVolumeSliceMapper") == std::string::npos)
  {
    std::cerr << "FAIL: PrintSelf does not name vtkAccelVolumeSliceMapper\n";
    ++failures;
  }

  vtkNew<vtkAccelVolumeHeadlessRenderWindow> headless;
  std::cout << "Headless window class: " << headless->GetClassName() << "\n";

  const char* gl = std::getenv("ACCELVOLUME_GL");
  const std::string backend = gl ? gl : "";
  std::cout << "ACCELVOLUME_GL=" << (gl ? gl : "(unset)") << "\n";
  if (backend == "osmesa" || backend == "egl")
  {
    vtkSmartPointer<vtkRenderWindow> window =
      vtkSmartPointer<vtkRenderWindow>::Take(vtkRenderWindow::New());
    std::cout << "vtkRenderWindow::New() gives " << window->GetClassName() << "\n";
    auto* asHeadless = vtkAccelVolumeHeadlessRenderWindow::SafeDownCast(window);
    if (!asHeadless)
    {
      std::cerr << "FAIL: vtkRenderWindow::New() is not a vtkAccelVolumeHeadlessRenderWindow "
                   "(object factory not auto-initialised?)\n";
      ++failures;
    }
    else
    {
      // One tiny frame proves the context, GLEW workaround and framebuffer work downstream.
      vtkNew<vtkRenderer> renderer;
      renderer->SetBackground(0.25, 0.5, 0.75);
      window->AddRenderer(renderer);
      window->SetSize(32, 32);
      window->SetMultiSamples(0);
      window->Render();
      const int active = asHeadless->GetActiveBackend();
      std::cout << "Active backend: " << vtkAccelVolumeHeadlessRenderWindow::GetBackendName(active)
                << ", renderer: "
                << (asHeadless->GetOpenGLRendererString() ? asHeadless->GetOpenGLRendererString()
                                                          : "(none)")
                << "\n";
      if (active != vtkAccelVolumeHeadlessRenderWindow::ParseBackendName(backend.c_str()))
      {
        std::cerr << "FAIL: active backend is not " << backend << "\n";
        ++failures;
      }
      unsigned char* pixels = window->GetPixelData(16, 16, 16, 16, 0, 0);
      // Background (0.25, 0.5, 0.75) -> (64, 127 or 128, 191), allowing rounding.
      if (!pixels || std::abs(pixels[0] - 64) > 1 || std::abs(pixels[1] - 128) > 1 ||
        std::abs(pixels[2] - 191) > 1)
      {
        std::cerr << "FAIL: unexpected background pixel";
        if (pixels)
        {
          std::cerr << " " << int(pixels[0]) << "," << int(pixels[1]) << "," << int(pixels[2]);
        }
        std::cerr << "\n";
        ++failures;
      }
      delete[] pixels;
    }
  }

  std::cout << (failures ? "Downstream check FAILED\n" : "Downstream check passed\n");
  return failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
