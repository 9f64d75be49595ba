// Shared by the drop-in tests (TestAccelVolumeDropIn, TestAccelVolumeSliceDropIn): one small
// scene per mapper kind and the image checks they use.
#ifndef AccelVolumeDropInScene_h
#define AccelVolumeDropInScene_h

#include "AccelVolumeBadInputSupport.h"
#include "vtkAccelVolumeRayCastMapper.h"
#include "vtkAccelVolumeShearWarpMapper.h"
#include "vtkAccelVolumeSliceMapper.h"
#include "vtkAccelVolumeSmartMapper.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCellData.h"
#include "vtkColorTransferFunction.h"
#include "vtkCommand.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkGPUVolumeRayCastMapper.h"
#include "vtkHardwareSelector.h"
#include "vtkInformation.h"
#include "vtkLongLongArray.h"
#include "vtkPointData.h"
#include "vtkVolumeProperty.h"
#include "vtkRectilinearGrid.h"
#include "vtkSelection.h"
#include "vtkSelectionNode.h"
#include "vtkSmartVolumeMapper.h"
#include "vtkUniformGrid.h"
#include "vtkUnsignedIntArray.h"

#include <functional>
#include <iostream>
#include <string>


namespace accelvolume_dropin
{
using accelvolume_test::CompareImages;
using Kind = accelvolume_test::MapperKind;

inline const char* Name(Kind kind)
{
  return accelvolume_test::MapperName(kind);
}

// The mapper of a kind, with fixed sample distances where they would adapt to the frame time; the
// smart mapper renders with its ray caster.
inline vtkSmartPointer<vtkVolumeMapper> MakeMapper(Kind kind)
{
  vtkSmartPointer<vtkVolumeMapper> mapper = accelvolume_test::NewMapper(kind);
  if (auto* rayCast = vtkAccelVolumeRayCastMapper::SafeDownCast(mapper))
  {
    rayCast->SetAutoAdjustSampleDistances(0);
  }
  if (auto* smart = vtkAccelVolumeSmartMapper::SafeDownCast(mapper))
  {
    smart->SetRequestedRenderModeToRayCast();
    smart->GetRayCastMapper()->SetAutoAdjustSampleDistances(0);
  }
  return mapper;
}

// One scene: 160x160, parallel oblique view (shear-warp needs it), the phantom's ramp.
struct Scene
{
  vtkSmartPointer<vtkVolumeMapper> Mapper;
  vtkNew<vtkVolume> Volume;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkRenderWindow> Window;
  int Errors = 0;

  Scene(Kind kind, vtkDataSet* input, int blend)
  {
    this->Mapper = MakeMapper(kind);
    this->Mapper->SetInputData(input);
    this->Mapper->SetBlendMode(blend);
    this->Volume->SetMapper(this->Mapper);
    accelvolume_test::SetRampProperty(this->Volume->GetProperty(), 40.0, 900.0, true);
    this->Renderer->SetBackground(0.1, 0.1, 0.2);
    this->Renderer->AddVolume(this->Volume);
    accelvolume_test::SetupObliqueView(this->Window, this->Renderer, 160, 30, 20, false);
  }

  std::vector<float> Render()
  {
    this->Window->Render();
    return accelvolume_test::ReadPixels(this->Window);
  }
};

inline vtkSmartPointer<vtkImageData> Phantom()
{
  return accelvolume_test::MakePhantom("vessels", 40, 36, 32, 1.0, 1.0, 1.25);
}

inline bool Same(const std::string& what, const std::vector<float>& a, const std::vector<float>& b,
  double maximum = 0.0)
{
  const auto d = CompareImages(a, b, 1.0 / 255.0);
  const bool ok = d.maximum <= maximum + 1.0e-6;
  if (!ok)
  {
    static int dumped = 0;
    accelvolume_test::DumpImage("dropin-" + std::to_string(dumped) + "-got", a, 160, 160);
    accelvolume_test::DumpImage("dropin-" + std::to_string(dumped++) + "-expected", b, 160, 160);
  }
  std::cout << (ok ? "ok    " : "FAIL  ") << what << ": max |diff| " << d.maximum << " (limit "
            << maximum << "), mean " << d.mean << "\n";
  return ok;
}

inline bool Drawn(const std::string& what, const std::vector<float>& image)
{
  size_t covered = 0;
  for (size_t p = 0; p < image.size() / 3; ++p)
  {
    const double d = std::abs(image[3 * p] - 0.1) + std::abs(image[3 * p + 1] - 0.1) +
      std::abs(image[3 * p + 2] - 0.2);
    covered += d > 0.05 ? 1 : 0;
  }
  const bool ok = covered > image.size() / 3 / 20;
  std::cout << (ok ? "ok    " : "FAIL  ") << what << ": " << covered << " pixels drawn\n";
  return ok;
}
}

#endif
