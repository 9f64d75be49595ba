// Missing or limited OpenGL:
// - Render with a renderer in a render window that is not an OpenGL one (a mock), or in no
//   window at all: every mapper (slice, ray cast, shear-warp, smart) reports that it needs an
//   OpenGL render window (the CPU mappers need OpenGL only to show their image);
// - a volume wider than GL_MAX_3D_TEXTURE_SIZE (2049 x 3 x 2 on llvmpipe's 2048): the slice
//   mapper bricks it and draws it without a message, close to the ray caster's image; the smart
//   mapper asked for the slice mapper keeps it; the CPU mappers render it;
// - a context without compute shaders (forced with ACCELVOLUME_DISABLE_COMPUTE=1): the min-max
//   octree's GPU builder falls back to the CPU builder with a warning and gives the identical
//   octree; without the variable it builds on the GPU again (where OpenGL 4.3 is there).
#include "AccelVolumeBadInputSupport.h"
#include "vtkAccelVolumeMinMaxOctree.h"

#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkTextureObject.h"

#include <cstdlib>
#include <functional>
#include <memory>

namespace
{
using namespace accelvolume_test;

// A render window with no OpenGL behind it.
class MockRenderWindow : public vtkRenderWindow
{
public:
  static MockRenderWindow* New();
  vtkTypeMacro(MockRenderWindow, vtkRenderWindow);
};
vtkStandardNewMacro(MockRenderWindow);

bool NoOpenGLWindow(MapperKind kind)
{
  bool ok = true;
  for (bool mock : { true, false })
  {
    auto mapper = NewMapper(kind);
    vtkNew<ErrorRecorder> errors;
    mapper->AddObserver(vtkCommand::ErrorEvent, errors);
    mapper->SetInputData(BlockVolume(VTK_UNSIGNED_CHAR, 8, 8, 8, 0, 100));
    vtkNew<vtkVolume> volume;
    volume->SetMapper(mapper);
    vtkNew<vtkRenderer> renderer;
    renderer->AddVolume(volume);
    renderer->GetActiveCamera()->ParallelProjectionOn();
    vtkNew<MockRenderWindow> window;
    if (mock)
    {
      window->AddRenderer(renderer);
    }
    mapper->Render(renderer, volume); // what vtkVolume::RenderVolumetricGeometry does
    ok = CheckMessage(errors, "needs an OpenGL render window",
           std::string(MapperName(kind)) + (mock ? ", mock render window" : ", no render window") +
             ": error") &&
      ok;
    if (mock)
    {
      window->RemoveRenderer(renderer);
    }
  }
  return ok;
}

bool TooLargeForTextures()
{
  bool ok = true;
  auto wide = BlockVolume(VTK_UNSIGNED_CHAR, 2049, 3, 2, 0, 200);
  const double bounds[6] = { 0, 2048, 0, 2, 0, 1 };
  auto render = [&](MapperKind kind, const std::function<void(Probe&)>& configure)
  {
    auto probe = std::make_unique<Probe>(kind, wide);
    // The centre of the 2049-voxel axis, so that its 3-voxel height fills most of the window.
    probe->LookAt(bounds, 2, 0, 0);
    probe->Renderer->GetActiveCamera()->SetParallelScale(2.0);
    SetRampProperty(probe->Volume->GetProperty(), 0, 200);
    probe->Mapper->SetBlendModeToMaximumIntensity();
    if (configure)
    {
      configure(*probe);
    }
    probe->Render();
    return probe;
  };
  auto slice = render(MapperKind::Slice, nullptr);
  const int maximum = vtkTextureObject::GetMaximumTextureSize3D(
    vtkOpenGLRenderWindow::SafeDownCast(slice->Window.GetPointer()));
  if (maximum != 2048)
  {
    std::cout << "GL_MAX_3D_TEXTURE_SIZE is " << maximum << ", not 2048: part skipped\n";
    return true;
  }
  ok = CheckNoMessage(slice->Errors, slice->Name("2049x3x2: no error (bricked)")) && ok;
  ok = Check(vtkAccelVolumeSliceMapper::SafeDownCast(slice->Mapper)->GetLastNumberOfBricks() >= 2,
         slice->Name("2049x3x2: two bricks or more")) &&
    ok;
  auto rayCast = render(MapperKind::RayCast, nullptr);
  const std::vector<float> expected = ReadPixels(rayCast->Window);
  ok = CheckNoMessage(rayCast->Errors, rayCast->Name("2049x3x2: no error")) && ok;
  ok = Check(MaximumDifferenceFrom(expected, Background) > 0.1,
         rayCast->Name("2049x3x2: the volume is drawn")) &&
    ok;
  auto smart = render(MapperKind::Smart,
    [](Probe& p)
    { vtkAccelVolumeSmartMapper::SafeDownCast(p.Mapper)->SetRequestedRenderModeToSlice(); });
  auto* smartMapper = vtkAccelVolumeSmartMapper::SafeDownCast(smart->Mapper);
  // Slices and rays sample differently: the agreement tests' bound (2.5 grey levels mean).
  ok = Check(accelvolume_test::CompareImages(ReadPixels(slice->Window), expected, 0.1).mean <
             2.5 / 255.0,
         slice->Name("2049x3x2: close to the ray caster's image")) &&
    ok;
  ok = CheckNoMessage(smart->Errors, smart->Name("requested slice, 2049x3x2: no error")) && ok;
  ok = CheckNoMessage(smart->Warnings, smart->Name("requested slice, 2049x3x2: no warning")) && ok;
  ok = Check(smartMapper->GetLastRenderMode() == vtkAccelVolumeSmartMapper::SLICE_RENDER,
         smart->Name("requested slice, 2049x3x2: slice mapper used (bricks)"),
         smartMapper->GetLastChoiceReason()) &&
    ok;
  auto shearWarp = render(MapperKind::ShearWarp, nullptr);
  ok = CheckNoMessage(shearWarp->Errors, shearWarp->Name("2049x3x2: no error")) && ok;
  ok = Check(MaximumDifferenceFrom(ReadPixels(shearWarp->Window), Background) > 0.1,
         shearWarp->Name("2049x3x2: the volume is drawn")) &&
    ok;
  return ok;
}

bool SameOctrees(vtkAccelVolumeMinMaxOctree* a, vtkAccelVolumeMinMaxOctree* b)
{
  if (a->GetDepth() != b->GetDepth() || a->GetNumberOfNodes() != b->GetNumberOfNodes())
  {
    return false;
  }
  for (int level = 0; level <= a->GetDepth(); ++level)
  {
    for (vtkIdType node = 0;; ++node)
    {
      double ra[2], rb[2];
      const bool hasA = a->GetNodeRange(level, node, ra);
      const bool hasB = b->GetNodeRange(level, node, rb);
      if (hasA != hasB)
      {
        return false;
      }
      if (!hasA)
      {
        break;
      }
      if (ra[0] != rb[0] || ra[1] != rb[1])
      {
        return false;
      }
    }
  }
  return true;
}

bool ComputeFallback()
{
  bool ok = true;
  vtkNew<vtkRenderWindow> generic;
  vtkNew<vtkRenderer> renderer;
  generic->SetMultiSamples(0);
  generic->SetSize(8, 8);
  generic->AddRenderer(renderer);
  generic->Render();
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(generic);
  auto image = BlockVolume(VTK_SHORT, 37, 19, 23, -40, 900);
  vtkNew<vtkAccelVolumeMinMaxOctree> cpu;
  cpu->SetInputData(image);
  ok = Check(cpu->Update(), "CPU octree") && ok;
  vtkNew<vtkAccelVolumeMinMaxOctree> gpu;
  vtkNew<ErrorRecorder> errors;
  vtkNew<ErrorRecorder> warnings;
  gpu->AddObserver(vtkCommand::ErrorEvent, errors);
  gpu->AddObserver(vtkCommand::WarningEvent, warnings);
  gpu->SetInputData(image);
  gpu->SetBuilder(vtkAccelVolumeMinMaxOctree::BUILDER_GPU);
  gpu->SetRenderWindow(window);
  setenv("ACCELVOLUME_DISABLE_COMPUTE", "1", 1);
  const bool built = gpu->Update();
  unsetenv("ACCELVOLUME_DISABLE_COMPUTE");
  ok = Check(built, "GPU builder without compute shaders: Update succeeds") && ok;
  ok = CheckNoMessage(errors, "GPU builder without compute shaders: no error") && ok;
  ok = CheckMessage(warnings, "falling back to the CPU builder",
         "GPU builder without compute shaders: warning") &&
    ok;
  ok = Check(gpu->GetLastBuilder() == vtkAccelVolumeMinMaxOctree::BUILDER_CPU &&
           gpu->GetGPULevelBuffer(0) == 0,
         "GPU builder without compute shaders: built by the CPU builder") &&
    ok;
  ok = Check(SameOctrees(gpu, cpu), "GPU builder without compute shaders: identical octree") && ok;
  int major = 0, minor = 0;
  window->GetOpenGLVersion(major, minor);
  if (major > 4 || (major == 4 && minor >= 3))
  {
    image->Modified(); // rebuild, now with compute shaders
    ok = Check(gpu->Update() && gpu->GetLastBuilder() == vtkAccelVolumeMinMaxOctree::BUILDER_GPU &&
             gpu->GetGPULevelBuffer(0) != 0,
           "with compute shaders: built on the GPU") &&
      ok;
    ok = Check(SameOctrees(gpu, cpu), "with compute shaders: identical octree") && ok;
  }
  gpu->ReleaseGraphicsResources();
  return ok;
}
}

int TestAccelVolumeNoContext(int, char*[])
{
  bool ok = true;
  for (MapperKind kind : AllMappers)
  {
    ok = NoOpenGLWindow(kind) && ok;
  }
  ok = TooLargeForTextures() && ok;
  ok = ComputeFallback() && ok;
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
