// Private state of vtkAccelVolumeMinMaxOctree, shared with the module's mappers (not installed).
#ifndef vtkAccelVolumeMinMaxOctreeInternals_h
#define vtkAccelVolumeMinMaxOctreeInternals_h

#include "vtkAccelVolumeMinMaxOctree.h"

#include "skipping/MinMaxOctree.h"
#include "vtkAccelVolumeOctreeGPUBuilder.h"
#include "vtkImageData.h"
#include "vtkSmartPointer.h"
#include "vtkType.h"

#include <string>

class vtkDataArray;
class vtkPiecewiseFunction;

class vtkAccelVolumeMinMaxOctree::vtkInternals
{
public:
  /**
   * The core octree with every level on the CPU: a GPU-built octree is read back on first use
   * (timed apart from the build). nullptr when nothing was built or the read-back failed.
   */
  accelvolume::MinMaxOctree* GetCPUOctree();

  accelvolume::MinMaxOctree Octree;
  vtkSmartPointer<vtkImageData> Input;
  vtkOpenGLRenderWindow* Window = nullptr; // not reference counted (the header says why)
  vtkTextureObject* InputTexture = nullptr; // SetInputTexture's (not reference counted)
  vtkAccelVolumeOctreeGPUBuilder GPUBuilder;

  // What the last successful build saw, so that Update() knows when to rebuild.
  bool Built = false;
  bool LevelsOnCPU = false; // false after a GPU build until the read-back
  vtkImageData* BuiltImage = nullptr;
  vtkDataArray* BuiltScalars = nullptr;
  int BuiltLeafSize = 0;
  int BuiltBuilder = -1;
  int BuiltThreads = 0;
  int BuiltDimensions[3] = { 0, 0, 0 };
  std::string FallbackReason; // why the last GPU build fell back to the CPU builder
  double LastReadBackTime = 0.0;
  double LastUploadTime = 0.0; // GPU builder's share of LastBuildTime spent uploading

  // What the last classification saw.
  bool Classified = false;
  vtkPiecewiseFunction* ClassifiedFunction = nullptr;
  double ClassifiedRange[2] = { 0.0, 0.0 };
};

#endif
