// New/PrintSelf smoke test of every public class, and the defaults a drop-in replacement for
// VTK's mappers must share with them (a default-constructed VTK volume mapper composites).
#include "vtkAccelVolumeHeadlessRenderWindow.h"
#include "vtkAccelVolumeMinMaxOctree.h"
#include "vtkAccelVolumeRayCastMapper.h"
#include "vtkAccelVolumeShearWarpMapper.h"
#include "vtkAccelVolumeSliceMapper.h"
#include "vtkAccelVolumeSmartMapper.h"
#include "vtkNew.h"

#include <cstdlib>
#include <iostream>
#include <sstream>

namespace
{
bool ComposesByDefault(vtkVolumeMapper* mapper)
{
  const bool ok = mapper->GetBlendMode() == vtkVolumeMapper::COMPOSITE_BLEND;
  std::cout << mapper->GetClassName() << " default blend mode " << mapper->GetBlendMode()
            << (ok ? "" : "  FAILED (VTK's mappers default to composite)") << "\n";
  return ok;
}
}

int TestAccelVolumeObjects(int, char*[])
{
  std::ostringstream text;
  vtkNew<vtkAccelVolumeSliceMapper> slice;
  vtkNew<vtkAccelVolumeRayCastMapper> rayCast;
  vtkNew<vtkAccelVolumeShearWarpMapper> shearWarp;
  vtkNew<vtkAccelVolumeSmartMapper> smart;
  vtkNew<vtkAccelVolumeMinMaxOctree> octree;
  vtkNew<vtkAccelVolumeHeadlessRenderWindow> window;
  slice->Print(text);
  rayCast->Print(text);
  shearWarp->Print(text);
  smart->Print(text);
  octree->Print(text);
  window->Print(text);
  const std::string printed = text.str();
  bool ok = printed.find("BoundaryRerendering") != std::string::npos &&
    printed.find("Backend") != std::string::npos && printed.find("LeapMode") != std::string::npos;
  for (vtkVolumeMapper* mapper : { static_cast<vtkVolumeMapper*>(slice),
         static_cast<vtkVolumeMapper*>(rayCast), static_cast<vtkVolumeMapper*>(shearWarp),
         static_cast<vtkVolumeMapper*>(smart) })
  {
    ok = ComposesByDefault(mapper) && ok;
  }
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
