// vtkAccelVolumeSmartMapper picks the mapper the class documentation's table names and renders
// exactly what that mapper renders alone: window pixels byte-identical to a direct render of
// the same scene. On the tests' headless software GL (llvmpipe): perspective composite -> ray
// cast; parallel composite in an interactive frame -> shear-warp; a requested slice render ->
// slice; a requested shear-warp render with additive blending falls back with one warning;
// no input or bad scalars -> a clear error, no crash; a choice reason after every render.
#include "AccelVolumeTestScene.h"
#include "vtkAccelVolumeShearWarpMapper.h"
#include "vtkAccelVolumeSmartMapper.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <sstream>
#include <string>

namespace
{
using namespace accelvolume_test;
using SmartScene = SceneOf<vtkAccelVolumeSmartMapper>;

std::vector<unsigned char> WindowBytes(vtkRenderWindow* window)
{
  const int* size = window->GetSize();
  vtkNew<vtkUnsignedCharArray> pixels;
  window->GetPixelData(0, 0, size[0] - 1, size[1] - 1, 0, pixels);
  const unsigned char* data = pixels->GetPointer(0);
  return std::vector<unsigned char>(data, data + pixels->GetNumberOfValues());
}

// Pixels that differ from the background (the volume is actually drawn).
int DrawnPixels(const std::vector<unsigned char>& rgb, const std::vector<unsigned char>& bg)
{
  int count = 0;
  for (size_t i = 0; i + 2 < rgb.size(); i += 3)
  {
    count += (rgb[i] != bg[0] || rgb[i + 1] != bg[1] || rgb[i + 2] != bg[2]) ? 1 : 0;
  }
  return count;
}

struct Setup
{
  int Blend = vtkVolumeMapper::COMPOSITE_BLEND;
  bool Parallel = false;
  double DesiredUpdateRate = 0.0; // 0: VTK's default (still frames)
};

template <typename SceneType>
void Configure(SceneType& scene, const Setup& setup)
{
  scene.Mapper->SetBlendMode(setup.Blend);
  scene.Renderer->GetActiveCamera()->SetParallelProjection(setup.Parallel ? 1 : 0);
  scene.Renderer->ResetCamera();
  if (setup.DesiredUpdateRate > 0)
  {
    scene.Window->SetDesiredUpdateRate(setup.DesiredUpdateRate);
  }
}

// Renders the scene with MapperType directly; the window's bytes.
template <typename MapperType>
std::vector<unsigned char> DirectRender(const Setup& setup)
{
  SceneOf<MapperType> scene("vessels", setup.Blend);
  Configure(scene, setup);
  scene.Window->Render();
  return WindowBytes(scene.Window);
}

std::vector<unsigned char> DirectRender(int mode, const Setup& setup)
{
  switch (mode)
  {
    case vtkAccelVolumeSmartMapper::SLICE_RENDER:
      return DirectRender<vtkAccelVolumeSliceMapper>(setup);
    case vtkAccelVolumeSmartMapper::SHEARWARP_RENDER:
      return DirectRender<vtkAccelVolumeShearWarpMapper>(setup);
    default:
      return DirectRender<vtkAccelVolumeRayCastMapper>(setup);
  }
}

bool Contains(const std::string& text, const std::string& part)
{
  return text.find(part) != std::string::npos;
}

// Recorded messages for the log, without the "ERROR: " that ctest's fail pattern matches.
std::string Quiet(std::string text)
{
  for (size_t at = text.find("ERROR: "); at != std::string::npos; at = text.find("ERROR: "))
  {
    text.replace(at, 7, "error: ");
  }
  return text;
}

// One smart render: the mode it used must be `expected`, the reason must mention `because`, and
// the window must equal the direct render of the expected mapper byte for byte.
bool CheckCase(const char* what, const Setup& setup, int requested, int expected,
  const std::string& because, int expectedWarnings = 0)
{
  SmartScene scene("vessels", setup.Blend);
  vtkNew<ErrorRecorder> errors;
  vtkNew<ErrorRecorder> warnings;
  scene.Mapper->AddObserver(vtkCommand::ErrorEvent, errors);
  scene.Mapper->AddObserver(vtkCommand::WarningEvent, warnings);
  scene.Mapper->SetRequestedRenderMode(requested);
  Configure(scene, setup);
  scene.Window->Render();
  const std::vector<unsigned char> smart = WindowBytes(scene.Window);
  const int used = scene.Mapper->GetLastRenderMode();
  const std::string reason = scene.Mapper->GetLastChoiceReason();
  // A second frame: same choice, no repeated warning.
  scene.Window->Render();
  const bool stable = scene.Mapper->GetLastRenderMode() == used &&
    reason == scene.Mapper->GetLastChoiceReason() && smart == WindowBytes(scene.Window);

  const std::vector<unsigned char> direct = DirectRender(expected, setup);
  const std::vector<unsigned char> background = { static_cast<unsigned char>(0.1 * 255 + 0.5),
    static_cast<unsigned char>(0.1 * 255 + 0.5), static_cast<unsigned char>(0.2 * 255 + 0.5) };
  const int drawn = DrawnPixels(smart, background);
  const bool ok = used == expected && !reason.empty() && Contains(reason, because) &&
    smart == direct && drawn > 1000 && stable && errors->Count == 0 &&
    warnings->Count == expectedWarnings;
  std::cout << (ok ? "ok    " : "FAIL  ") << what << ": used "
            << vtkAccelVolumeSmartMapper::GetRenderModeAsString(used) << " (expected "
            << vtkAccelVolumeSmartMapper::GetRenderModeAsString(expected) << "), reason \""
            << reason << "\", " << (smart == direct ? "identical to" : "DIFFERENT from")
            << " the direct render, " << drawn << " pixels drawn, "
            << (stable ? "stable" : "NOT stable") << " over two frames, " << errors->Count
            << " errors, " << warnings->Count << " warnings (expected " << expectedWarnings
            << ")\n";
  if (!errors->Messages.empty() || !warnings->Messages.empty())
  {
    std::cout << "      messages: " << Quiet(errors->Messages + warnings->Messages);
  }
  return ok;
}

// Bad inputs: an error on the smart mapper, no crash, nothing drawn.
bool CheckErrors()
{
  bool ok = true;
  {
    vtkNew<vtkAccelVolumeSmartMapper> mapper;
    vtkNew<ErrorRecorder> errors;
    mapper->AddObserver(vtkCommand::ErrorEvent, errors);
    vtkNew<vtkVolume> volume;
    volume->SetMapper(mapper);
    SetRampProperty(volume->GetProperty(), 0, 1000);
    vtkNew<vtkRenderer> renderer;
    renderer->AddVolume(volume);
    vtkNew<vtkRenderWindow> window;
    window->SetSize(64, 64);
    window->SetMultiSamples(0);
    window->AddRenderer(renderer);
    window->Render();
    mapper->Render(renderer, volume); // called directly too: still an error, no crash
    const bool reported = Contains(errors->Messages, "No input");
    const bool undefined =
      mapper->GetLastRenderMode() == vtkAccelVolumeSmartMapper::UNDEFINED_RENDER;
    const bool reason = std::string(mapper->GetLastChoiceReason()).size() > 0;
    const bool pass = reported && undefined && reason;
    std::cout << (pass ? "ok    " : "FAIL  ") << "no input: " << errors->Count
              << " error(s), last mode "
              << vtkAccelVolumeSmartMapper::GetRenderModeAsString(mapper->GetLastRenderMode())
              << ", reason \"" << mapper->GetLastChoiceReason() << "\"\n      "
              << Quiet(errors->Messages);
    ok = pass && ok;
  }
  {
    // An image without scalars: the chosen mapper's error comes back as the smart mapper's.
    SmartScene scene("vessels", vtkVolumeMapper::COMPOSITE_BLEND);
    vtkNew<vtkImageData> image;
    image->SetDimensions(8, 8, 8);
    scene.Mapper->SetInputData(image);
    vtkNew<ErrorRecorder> errors;
    scene.Mapper->AddObserver(vtkCommand::ErrorEvent, errors);
    scene.Window->Render();
    const bool pass = Contains(errors->Messages, "no point scalars") &&
      Contains(errors->Messages, "Mapper: ") &&
      std::string(scene.Mapper->GetLastChoiceReason()).size() > 0;
    std::cout << (pass ? "ok    " : "FAIL  ") << "no scalars: relayed error(s): "
              << Quiet(errors->Messages);
    ok = pass && ok;
  }
  return ok;
}

bool IsSoftware(std::string name)
{
  std::transform(name.begin(), name.end(), name.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return Contains(name, "llvmpipe") || Contains(name, "softpipe") || Contains(name, "swrast");
}
}

int TestAccelVolumeSmartMapper(int, char*[])
{
  using Smart = vtkAccelVolumeSmartMapper;
  bool ok = true;

  // (c) Requested slice: the slice mapper, whatever the GL. Also tells which GL the tests have.
  Setup slice;
  slice.Blend = vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND;
  ok = CheckCase("requested slice, MIP, perspective", slice, Smart::SLICE_RENDER,
         Smart::SLICE_RENDER, "requested slice") &&
    ok;
  std::string glRenderer;
  {
    SmartScene probe("vessels", vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND);
    probe.Mapper->SetRequestedRenderModeToSlice();
    probe.Window->Render();
    glRenderer = probe.Mapper->GetSliceMapper()->GetOpenGLRenderer();
  }
  const bool software = IsSoftware(glRenderer);
  std::cout << "OpenGL renderer: " << glRenderer << (software ? " (software)" : " (hardware)")
            << "\n";

  // (a) Default, perspective composite: the ray caster on software GL.
  Setup perspective;
  ok = CheckCase("default, composite, perspective", perspective, Smart::DEFAULT_RENDER,
         software ? Smart::RAYCAST_RENDER : Smart::SLICE_RENDER,
         software ? "perspective camera" : "hardware OpenGL") &&
    ok;

  // (b) Default, parallel composite, interactive frame (10 fps wanted): shear-warp.
  Setup interactive;
  interactive.Parallel = true;
  interactive.DesiredUpdateRate = 10.0;
  ok = CheckCase("default, composite, parallel, interactive", interactive, Smart::DEFAULT_RENDER,
         software ? Smart::SHEARWARP_RENDER : Smart::SLICE_RENDER,
         software ? "interactive frame -> shear-warp" : "hardware OpenGL") &&
    ok;

  // The same scene as a still frame: the exact ray caster.
  Setup still = interactive;
  still.DesiredUpdateRate = 0.0;
  ok = CheckCase("default, composite, parallel, still", still, Smart::DEFAULT_RENDER,
         software ? Smart::RAYCAST_RENDER : Smart::SLICE_RENDER,
         software ? "still frame" : "hardware OpenGL") &&
    ok;

  // (d) Requested shear-warp with additive blending: refused, one warning, another mapper.
  Setup additive;
  additive.Blend = vtkVolumeMapper::ADDITIVE_BLEND;
  additive.Parallel = true;
  ok = CheckCase("requested shear-warp, additive", additive, Smart::SHEARWARP_RENDER,
         software ? Smart::RAYCAST_RENDER : Smart::SLICE_RENDER, "additive blend", 1) &&
    ok;

  // A requested shear-warp render it can do.
  Setup mip;
  mip.Blend = vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND;
  mip.Parallel = true;
  ok = CheckCase("requested shear-warp, MIP, parallel", mip, Smart::SHEARWARP_RENDER,
         Smart::SHEARWARP_RENDER, "requested shear-warp") &&
    ok;

  // (e) Errors.
  ok = CheckErrors() && ok;

  // PrintSelf prints the settings and the last choice.
  vtkNew<Smart> printed;
  std::ostringstream text;
  printed->Print(text);
  if (!Contains(text.str(), "RequestedRenderMode: Default") ||
    !Contains(text.str(), "LastChoiceReason"))
  {
    std::cout << "FAIL  PrintSelf:\n" << text.str();
    ok = false;
  }
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
