// ExampleCommon.h: the few lines every technique example shares (a procedural volume, the
// command line, error capture and writing / checking the PNG), kept out of the examples so each
// one shows only its technique. Header-only on purpose: each example stays one translation unit.
#ifndef ExampleCommon_h
#define ExampleCommon_h

#include <vtkAbstractVolumeMapper.h>
#include <vtkCallbackCommand.h>
#include <vtkCamera.h>
#include <vtkCommand.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkObject.h>
#include <vtkPNGReader.h>
#include <vtkPNGWriter.h>
#include <vtkPointData.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkVolume.h>
#include <vtkVolumeProperty.h>
#include <vtkWindowToImageFilter.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace example
{
// The command line every example takes: [output.png] [--check] (ReadRealVolume: [--input FILE]).
struct Options
{
  std::string Output;
  std::string Input; // --input FILE (ReadRealVolume only)
  bool Check = false;
};

inline Options ParseArguments(int argc, char* argv[], const char* name)
{
  Options options;
  options.Output = std::string(name) + ".png";
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    if (arg == "--check")
    {
      options.Check = true; // re-read the PNG and fail if it holds only the background
    }
    else if (arg == "--input" && i + 1 < argc)
    {
      options.Input = argv[++i];
    }
    else if (arg == "-h" || arg == "--help")
    {
      std::printf("usage: %s [output.png] [--check]\n", name);
      std::exit(0);
    }
    else
    {
      options.Output = arg;
    }
  }
  return options;
}

// A 64^3 unsigned char volume: three Gaussian blobs and a thin torus, so MIP shows bright
// structures, composite shows shaded surfaces, and most of the box is empty (which is what the
// empty-space skipping examples skip). Procedural, so the examples need no data files.
inline vtkSmartPointer<vtkImageData> MakeVolume(int n = 64)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(n, n, n);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 1);
  auto* voxels = static_cast<unsigned char*>(image->GetScalarPointer());
  const double blobs[3][4] = { { 0.30, 0.35, 0.40, 0.12 }, { 0.70, 0.40, 0.55, 0.10 },
    { 0.50, 0.70, 0.35, 0.08 } }; // centre (x, y, z) and radius, in units of the box edge
  for (int z = 0; z < n; ++z)
  {
    for (int y = 0; y < n; ++y)
    {
      for (int x = 0; x < n; ++x)
      {
        const double p[3] = { (x + 0.5) / n, (y + 0.5) / n, (z + 0.5) / n };
        double value = 0.0;
        for (const auto& b : blobs)
        {
          const double d2 = (p[0] - b[0]) * (p[0] - b[0]) + (p[1] - b[1]) * (p[1] - b[1]) +
            (p[2] - b[2]) * (p[2] - b[2]);
          value += 255.0 * std::exp(-d2 / (b[3] * b[3]));
        }
        // Torus around the z axis through the centre: major radius 0.3, minor 0.04.
        const double ring = std::hypot(p[0] - 0.5, p[1] - 0.5) - 0.3;
        const double torus = std::hypot(ring, p[2] - 0.5);
        value += 200.0 * std::exp(-(torus * torus) / (0.04 * 0.04));
        *voxels++ = static_cast<unsigned char>(value > 255.0 ? 255.0 : value);
      }
    }
  }
  return image;
}

// Counts vtkErrorMacro reports of the objects it watches, so a failed render (no OpenGL
// context, an unsupported input) becomes a non-zero exit instead of a silently black PNG.
class ErrorWatch
{
public:
  ErrorWatch() { this->Callback->SetCallback(&ErrorWatch::Count); this->Callback->SetClientData(this); }
  void Watch(vtkObject* object) { object->AddObserver(vtkCommand::ErrorEvent, this->Callback); }
  int GetErrors() const { return this->Errors; }

private:
  static void Count(vtkObject*, unsigned long, void* self, void* message)
  {
    ++static_cast<ErrorWatch*>(self)->Errors;
    std::fprintf(stderr, "error: %s\n", message ? static_cast<const char*>(message) : "?");
  }
  vtkNew<vtkCallbackCommand> Callback;
  int Errors = 0;
};

// Writes the window's pixels to `path`. With `check`, reads the file back and requires the
// expected size and at least 1% of pixels away from the renderer's background (a blank or
// failed render would otherwise pass unnoticed). Returns 0 on success, 1 with a message.
inline int WritePNG(vtkRenderWindow* window, vtkRenderer* renderer, const std::string& path,
  bool check)
{
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff(); // the offscreen framebuffer has no front buffer
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(path.c_str());
  writer->SetInputConnection(grab->GetOutputPort());
  writer->Write();
  if (writer->GetErrorCode() != 0)
  {
    std::fprintf(stderr, "error: cannot write %s\n", path.c_str());
    return 1;
  }
  if (!check)
  {
    return 0;
  }
  vtkNew<vtkPNGReader> reader;
  if (!reader->CanReadFile(path.c_str()))
  {
    std::fprintf(stderr, "check failed: %s is not a readable PNG\n", path.c_str());
    return 1;
  }
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  const int* size = window->GetSize();
  int dims[3];
  image->GetDimensions(dims);
  auto* pixels = vtkUnsignedCharArray::SafeDownCast(image->GetPointData()->GetScalars());
  if (!pixels || dims[0] != size[0] || dims[1] != size[1] || pixels->GetNumberOfComponents() < 3)
  {
    std::fprintf(stderr, "check failed: %s is not a %dx%d RGB image\n", path.c_str(), size[0],
      size[1]);
    return 1;
  }
  double background[3];
  renderer->GetBackground(background);
  vtkIdType foreground = 0;
  for (vtkIdType i = 0; i < pixels->GetNumberOfTuples(); ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      if (std::abs(pixels->GetValue(i * pixels->GetNumberOfComponents() + c) -
            255.0 * background[c]) > 3.0)
      {
        ++foreground;
        break;
      }
    }
  }
  if (foreground * 100 < pixels->GetNumberOfTuples())
  {
    std::fprintf(stderr, "check failed: %s is blank (%lld pixels differ from the background)\n",
      path.c_str(), static_cast<long long>(foreground));
    return 1;
  }
  std::printf("check passed: %lld of %lld pixels show the volume\n",
    static_cast<long long>(foreground), static_cast<long long>(pixels->GetNumberOfTuples()));
  return 0;
}
// The scene every example shows: the volume in a renderer with the examples' background, in a
// 256x256 offscreen window from the module's factory (headless EGL / OSMesa without a display),
// with the mapper's and the window's errors counted.
struct Scene
{
  vtkNew<vtkVolume> Volume;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkRenderWindow> Window;
  ErrorWatch Errors;

  Scene(vtkAbstractVolumeMapper* mapper, vtkVolumeProperty* property, bool parallel = false)
  {
    this->Volume->SetMapper(mapper);
    this->Volume->SetProperty(property);
    this->Renderer->AddVolume(this->Volume);
    this->Renderer->SetBackground(0.1, 0.1, 0.2);
    this->Renderer->GetActiveCamera()->SetParallelProjection(parallel);
    this->Window->SetOffScreenRendering(1);
    this->Window->SetMultiSamples(0); // volume mappers draw into their own targets
    this->Window->SetSize(256, 256);
    this->Window->AddRenderer(this->Renderer);
    this->Errors.Watch(mapper);
    this->Errors.Watch(this->Window);
  }

  // Fits the camera to the volume, turns it and zooms in (the bounding sphere leaves a wide
  // margin).
  void Frame(double azimuth, double elevation, double zoom)
  {
    vtkCamera* camera = this->Renderer->GetActiveCamera();
    this->Renderer->ResetCamera();
    camera->Azimuth(azimuth);
    camera->Elevation(elevation);
    camera->OrthogonalizeViewUp();
    camera->Zoom(zoom);
    this->Renderer->ResetCameraClippingRange();
  }

  // Renders `frames` frames (turning by `turn` degrees before each when non-zero); false, with
  // "<name>: rendering failed", once the mapper or the window reported an error.
  bool Render(const char* name, int frames = 1, double turn = 0)
  {
    for (int frame = 0; frame < frames && this->Errors.GetErrors() == 0; ++frame)
    {
      if (turn != 0)
      {
        this->Renderer->GetActiveCamera()->Azimuth(turn);
        this->Renderer->ResetCameraClippingRange();
      }
      this->Window->Render();
    }
    if (this->Errors.GetErrors() > 0)
    {
      std::fprintf(stderr, "%s: rendering failed\n", name);
      return false;
    }
    return true;
  }

  int Write(const Options& options)
  {
    return WritePNG(this->Window, this->Renderer, options.Output, options.Check);
  }
};
} // namespace example

#endif
