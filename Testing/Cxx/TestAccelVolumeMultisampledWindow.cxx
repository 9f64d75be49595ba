// Every mapper in a multisampled window (VTK's windows default to 8 samples): the image matches
// the single-sampled one, with and without opaque geometry in the volume. A multisampled
// framebuffer can neither be copied nor read by glReadPixels, so before the depth was resolved
// by a blit the slice mapper drew nothing and the CPU mappers lost the geometry.
#include "AccelVolumeDropInScene.h"

#include "vtkActor.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkSphereSource.h"
#include "vtk_glew.h"

namespace
{
using namespace accelvolume_dropin;

// The draw framebuffer's sample buffers while the mapper renders (so the test cannot pass on a
// window that quietly ignored the multisample request).
void RecordSampleBuffers(vtkObject*, unsigned long, void* clientData, void*)
{
  GLint sampleBuffers = 0;
  glGetIntegerv(GL_SAMPLE_BUFFERS, &sampleBuffers);
  *static_cast<int*>(clientData) = sampleBuffers;
}

std::vector<float> RenderWith(
  Kind kind, vtkImageData* image, int blend, int samples, bool geometry, int& sampleBuffers)
{
  Scene scene(kind, image, blend);
  scene.Window->SetMultiSamples(samples);
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(image->GetCenter());
  sphere->SetRadius(9.0);
  sphere->SetThetaResolution(32);
  sphere->SetPhiResolution(32);
  vtkNew<vtkPolyDataMapper> sphereMapper;
  sphereMapper->SetInputConnection(sphere->GetOutputPort());
  vtkNew<vtkActor> actor;
  actor->SetMapper(sphereMapper);
  actor->GetProperty()->SetColor(0.9, 0.8, 0.2);
  if (geometry)
  {
    scene.Renderer->AddActor(actor);
  }
  vtkNew<vtkCallbackCommand> record;
  record->SetCallback(RecordSampleBuffers);
  record->SetClientData(&sampleBuffers);
  vtkVolumeMapper* observed = scene.Mapper;
  if (auto* smart = vtkAccelVolumeSmartMapper::SafeDownCast(scene.Mapper))
  {
    observed = smart->GetRayCastMapper();
  }
  observed->AddObserver(vtkCommand::StartEvent, record);
  return scene.Render();
}
}

int TestAccelVolumeMultisampledWindow(int, char*[])
{
  vtkSmartPointer<vtkImageData> image = Phantom();
  bool ok = true;
  for (Kind kind : accelvolume_test::AllMappers)
  {
    for (int blend : { vtkVolumeMapper::COMPOSITE_BLEND, vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND })
    {
      for (bool geometry : { false, true })
      {
        int singleBuffers = -1;
        int multiBuffers = -1;
        const std::vector<float> single =
          RenderWith(kind, image, blend, 0, geometry, singleBuffers);
        const std::vector<float> multi = RenderWith(kind, image, blend, 8, geometry, multiBuffers);
        const std::string what = std::string(Name(kind)) +
          (blend == vtkVolumeMapper::COMPOSITE_BLEND ? " composite" : " MIP") +
          (geometry ? " with a sphere" : "") + ", 8 samples vs none";
        if (multiBuffers != 1)
        {
          std::cout << "FAIL  " << what << ": the mapper rendered into a framebuffer with "
                    << multiBuffers << " sample buffers (expected 1)\n";
          ok = false;
          continue;
        }
        // Multisampling only changes the antialiased edges of the geometry.
        const auto d = CompareImages(multi, single, 16.0 / 255.0);
        const bool same = d.mean <= 1.5 / 255.0 && d.fractionAbove <= 0.02;
        std::cout << (same ? "ok    " : "FAIL  ") << what << ": mean |diff| " << d.mean
                  << " (limit " << 1.5 / 255.0 << "), pixels over 16/255 " << d.fractionAbove
                  << " (limit 0.02)\n";
        ok = Drawn(what, multi) && same && ok;
      }
    }
  }
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
