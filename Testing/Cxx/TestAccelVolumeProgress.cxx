// Progress events: every AccelVolume mapper's Render fires StartEvent, ProgressEvent values that
// never decrease, lie in [0, 1] and end at 1, then EndEvent, all on the calling (main) thread
// and never more than a hundred per render; progress observers leave the image byte-identical.
// Covered: slice, ray cast (several tile chunks), shear-warp (parallel), the smart mapper (its
// chosen mapper's progress forwarded, the forwarder removed afterwards) and the octree's build.
#include "AccelVolumeTestScene.h"
#include "vtkAccelVolumeMinMaxOctree.h"
#include "vtkAccelVolumeShearWarpMapper.h"
#include "vtkAccelVolumeSmartMapper.h"
#include "vtkCallbackCommand.h"

#include <cstdlib>
#include <iostream>
#include <string>
#include <thread>
#include <vector>

namespace
{
using namespace accelvolume_test;

// Every Start / Progress / End event of one object, with its value and thread.
struct EventLog
{
  struct Entry
  {
    unsigned long Event = 0;
    double Value = -1;
    bool MainThread = true;
  };
  std::vector<Entry> Entries;
  std::thread::id Main = std::this_thread::get_id();
  vtkNew<vtkCallbackCommand> Command;

  EventLog()
  {
    this->Command->SetClientData(this);
    this->Command->SetCallback(
      [](vtkObject*, unsigned long event, void* client, void* data)
      {
        auto* log = static_cast<EventLog*>(client);
        Entry entry;
        entry.Event = event;
        entry.MainThread = std::this_thread::get_id() == log->Main;
        if (event == vtkCommand::ProgressEvent && data)
        {
          entry.Value = *static_cast<double*>(data);
        }
        log->Entries.push_back(entry);
      });
  }
  void Attach(vtkObject* object)
  {
    for (unsigned long event :
      { vtkCommand::StartEvent, vtkCommand::ProgressEvent, vtkCommand::EndEvent })
    {
      object->AddObserver(event, this->Command);
    }
  }
};

// The log must hold exactly `renders` sequences Start, Progress..., End with the rules above;
// needIntermediate: some value strictly between 0 and 1 in every sequence (a chunked loop).
bool CheckLog(const EventLog& log, int renders, bool needIntermediate, const std::string& what)
{
  bool ok = true;
  const auto fail = [&](const std::string& message)
  {
    std::cerr << what << ": " << message << "\n";
    ok = false;
  };
  int sequences = 0;
  bool open = false;
  double last = -1;
  int progressEvents = 0;
  bool intermediate = false;
  for (const EventLog::Entry& entry : log.Entries)
  {
    if (!entry.MainThread)
    {
      fail("an event came from a worker thread");
    }
    if (entry.Event == vtkCommand::StartEvent)
    {
      if (open)
      {
        fail("StartEvent inside a render");
      }
      open = true;
      last = -1;
      progressEvents = 0;
      intermediate = false;
    }
    else if (entry.Event == vtkCommand::ProgressEvent)
    {
      if (!open)
      {
        fail("ProgressEvent outside StartEvent / EndEvent");
      }
      if (!(entry.Value >= 0.0 && entry.Value <= 1.0))
      {
        fail("progress " + std::to_string(entry.Value) + " outside [0, 1]");
      }
      if (entry.Value < last)
      {
        fail(
          "progress went back from " + std::to_string(last) + " to " + std::to_string(entry.Value));
      }
      intermediate = intermediate || (entry.Value > 0.0 && entry.Value < 1.0);
      last = entry.Value;
      ++progressEvents;
    }
    else if (entry.Event == vtkCommand::EndEvent)
    {
      if (!open)
      {
        fail("EndEvent without StartEvent");
      }
      if (last != 1.0)
      {
        fail("the last progress before EndEvent is " + std::to_string(last) + ", not 1");
      }
      if (progressEvents < 2 || progressEvents > 100)
      {
        fail(std::to_string(progressEvents) + " progress events in one render (2..100 expected)");
      }
      if (needIntermediate && !intermediate)
      {
        fail("no progress between 0 and 1");
      }
      open = false;
      ++sequences;
    }
  }
  if (open)
  {
    fail("a render without EndEvent");
  }
  if (sequences != renders)
  {
    fail(std::to_string(sequences) + " Start/End sequences for " + std::to_string(renders) +
      " renders");
  }
  return ok;
}

std::vector<unsigned char> WindowBytes(vtkRenderWindow* window)
{
  const int* size = window->GetSize();
  vtkNew<vtkUnsignedCharArray> pixels;
  window->GetPixelData(0, 0, size[0] - 1, size[1] - 1, 0, pixels);
  const unsigned char* data = pixels->GetPointer(0);
  return std::vector<unsigned char>(data, data + pixels->GetNumberOfValues());
}

// Composite with shading (gradients and leaping structures to build), parallel or perspective.
template <typename SceneType>
void Configure(SceneType& scene, bool parallel)
{
  scene.Mapper->SetBlendMode(vtkVolumeMapper::COMPOSITE_BLEND);
  scene.Volume->GetProperty()->ShadeOn();
  scene.Renderer->GetActiveCamera()->SetParallelProjection(parallel ? 1 : 0);
  scene.Renderer->ResetCamera();
}

// Two frames (the first builds the mapper's structures, the second turns the camera) with and
// without observers, on two scenes: both frames' images must be identical and the observed
// events well formed. Returns the observed scene's log check.
template <typename MapperType, typename Setup>
bool CheckMapper(const std::string& what, bool parallel, bool needIntermediate, Setup&& setup)
{
  // Under a sanitizer a 120x120 window: the same events on a sixth of the pixels.
  const int size = SanitizerSubset() ? 120 : 300;
  SceneOf<MapperType> plain("blobs", vtkVolumeMapper::COMPOSITE_BLEND, size);
  SceneOf<MapperType> observed("blobs", vtkVolumeMapper::COMPOSITE_BLEND, size);
  Configure(plain, parallel);
  Configure(observed, parallel);
  setup(plain.Mapper.GetPointer());
  setup(observed.Mapper.GetPointer());
  // A modified mapper's own (empty) pipeline pass fires a short Start / 0 / 1 / End sequence of
  // VTK's when vtkVolume next updates it: run it now, so the log holds the renders alone.
  plain.Mapper->Update();
  observed.Mapper->Update();
  EventLog log;
  log.Attach(observed.Mapper);
  bool ok = true;
  for (int frame = 0; frame < 2; ++frame)
  {
    if (frame > 0)
    {
      plain.Renderer->GetActiveCamera()->Azimuth(25);
      observed.Renderer->GetActiveCamera()->Azimuth(25);
    }
    plain.Window->Render();
    observed.Window->Render();
    if (WindowBytes(plain.Window) != WindowBytes(observed.Window))
    {
      std::cerr << what << ": frame " << frame << " differs with progress observers\n";
      ok = false;
    }
  }
  ok = CheckLog(log, 2, needIntermediate, what) && ok;
  std::cout << what << ": " << log.Entries.size() << " events in 2 renders"
            << (ok ? "" : " (FAILED)") << "\n";
  return ok;
}

bool CheckOctree()
{
  vtkSmartPointer<vtkImageData> image = MakePhantom("blobs", 64, 56, 48);
  vtkNew<vtkAccelVolumeMinMaxOctree> octree;
  octree->SetInputData(image);
  EventLog log;
  log.Attach(octree);
  bool ok = octree->Update() && octree->Update(); // the second reuses the build: no events
  ok = CheckLog(log, 1, false, "octree") && ok;
  image->GetPointData()->GetScalars()->Modified();
  ok = octree->Update() && CheckLog(log, 2, false, "octree rebuild") && ok;
  return ok;
}
}

int TestAccelVolumeProgress(int, char*[])
{
  bool ok = true;
  ok = CheckMapper<vtkAccelVolumeSliceMapper>("slice", false, true, [](auto*) {}) && ok;
  ok = CheckMapper<vtkAccelVolumeRayCastMapper>("raycast", false, true, [](auto*) {}) && ok;
  ok = CheckMapper<vtkAccelVolumeRayCastMapper>("raycast octree, 1 thread", false, true,
         [](vtkAccelVolumeRayCastMapper* mapper)
         {
           mapper->SetLeapMode(vtkAccelVolumeRayCastMapper::LEAP_OCTREE);
           mapper->SetNumberOfThreads(1);
         }) &&
    ok;
  ok = CheckMapper<vtkAccelVolumeShearWarpMapper>("shearwarp", true, true, [](auto*) {}) && ok;
  // The smart mapper on software GL: a still perspective frame goes to the ray caster, a
  // requested shear-warp render in parallel projection to the shear-warp mapper.
  ok = CheckMapper<vtkAccelVolumeSmartMapper>("smart (ray cast)", false, true, [](auto*) {}) && ok;
  ok = CheckMapper<vtkAccelVolumeSmartMapper>("smart (shear-warp)", true, true,
         [](vtkAccelVolumeSmartMapper* mapper) { mapper->SetRequestedRenderModeToShearWarp(); }) &&
    ok;
  {
    // The forwarder is attached only while an observed smart mapper renders.
    SceneOf<vtkAccelVolumeSmartMapper> scene(
      "blobs", vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND, SanitizerSubset() ? 120 : 300);
    EventLog log;
    log.Attach(scene.Mapper);
    scene.Window->Render();
    vtkVolumeMapper* owned[3] = { scene.Mapper->GetSliceMapper(), scene.Mapper->GetRayCastMapper(),
      scene.Mapper->GetShearWarpMapper() };
    for (vtkVolumeMapper* mapper : owned)
    {
      if (mapper->HasObserver(vtkCommand::ProgressEvent))
      {
        std::cerr << "smart: " << mapper->GetClassName() << " still has a progress observer\n";
        ok = false;
      }
    }
    ok = CheckLog(log, 1, true, "smart (forwarder)") && ok;
  }
  ok = CheckOctree() && ok;
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
