// New/PrintSelf smoke test of every public class.
#include "vtkAccelVolumeHeadlessRenderWindow.h"
#include "vtkAccelVolumeSliceMapper.h"
#include "vtkNew.h"

#include <cstdlib>
#include <sstream>

int TestAccelVolumeObjects(int, char*[])
{
  std::ostringstream text;
  vtkNew<vtkAccelVolumeSliceMapper> mapper;
  mapper->Print(text);
  vtkNew<vtkAccelVolumeHeadlessRenderWindow> window;
  window->Print(text);
  const std::string printed = text.str();
  const bool ok = printed.find("BoundaryRerendering") != std::string::npos &&
    printed.find("Backend") != std::string::npos;
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
