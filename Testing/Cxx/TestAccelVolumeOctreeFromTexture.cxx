// The slice mapper's skipping octree built on the GPU from its resident volume texture
// (SetOctreeBuilder BUILDER_GPU): byte-identical images to the CPU-built octree, for 8- and
// 16-bit scalars, with rasterised slices (the levels read back and classified on the CPU: the
// same transparent leaves) and compute slices (classified on the GPU, nothing read back), and
// again after the scalars change (a time-varying volume: the new step is uploaded once and the
// octree rebuilt from that upload). Directly: vtkAccelVolumeMinMaxOctree::SetInputTexture gives the
// CPU builder's node ranges. Skipped (125) without OpenGL 4.3 compute shaders.
#include "AccelVolumeTestUtilities.h"
#include "vtkAccelVolumeMinMaxOctree.h"
#include "vtkAccelVolumeSliceMapper.h"

#include "vtkDataArray.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkTesting.h"
#include "vtkTextureObject.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnsignedShortArray.h"

#include <cmath>
#include <cstdlib>

namespace
{
using Mapper = vtkAccelVolumeSliceMapper;
using Octree = vtkAccelVolumeMinMaxOctree;

// The phantom's values as 8- or 16-bit unsigned scalars (`shift` moves every value, as a new
// time step would).
vtkSmartPointer<vtkImageData> Quantised(vtkImageData* source, int type, double shift)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->CopyStructure(source);
  vtkDataArray* values = source->GetPointData()->GetScalars();
  vtkSmartPointer<vtkDataArray> out = type == VTK_UNSIGNED_CHAR
    ? vtkSmartPointer<vtkDataArray>(vtkSmartPointer<vtkUnsignedCharArray>::New())
    : vtkSmartPointer<vtkDataArray>(vtkSmartPointer<vtkUnsignedShortArray>::New());
  const double scale = type == VTK_UNSIGNED_CHAR ? 0.2 : 40.0;
  const double top = type == VTK_UNSIGNED_CHAR ? 255.0 : 65535.0;
  out->SetNumberOfTuples(values->GetNumberOfTuples());
  for (vtkIdType i = 0; i < values->GetNumberOfTuples(); ++i)
  {
    out->SetTuple1(i, std::min(top, std::max(0.0, std::round(values->GetTuple1(i) * scale + shift))));
  }
  image->GetPointData()->SetScalars(out);
  return image;
}

struct Frame
{
  std::vector<float> pixels;
  double leafFraction = -1.0;
  int compositing = -1;
  int builder = -1; // the octree builder of the frame's octree
};

class Scene
{
public:
  Scene(vtkImageData* image, int builder, int compositing)
  {
    this->Volume->SetMapper(this->SliceMapper);
    this->SliceMapper->SetInputData(image);
    this->SliceMapper->SetOctreeBuilder(builder);
    this->SliceMapper->SetSliceCompositing(compositing);
    this->SliceMapper->SetEarlyRayTermination(false);
    double range[2];
    image->GetPointData()->GetScalars()->GetRange(range);
    accelvolume_test::SetRampProperty(
      this->Volume->GetProperty(), range[0] + 0.3 * (range[1] - range[0]), range[1], true);
    this->Volume->GetProperty()->ShadeOn();
    this->Renderer->AddVolume(this->Volume);
    accelvolume_test::SetupObliqueView(this->Window, this->Renderer, 140, 35, -20, true);
  }
  Frame Render()
  {
    this->Window->Render();
    Frame frame;
    frame.pixels = accelvolume_test::ReadPixels(this->Window);
    frame.leafFraction = this->SliceMapper->GetLastTransparentLeafFraction();
    frame.compositing = this->SliceMapper->GetLastSliceCompositing();
    frame.builder = this->SliceMapper->GetLastOctreeBuilder();
    return frame;
  }
  void SetInput(vtkImageData* image) { this->SliceMapper->SetInputData(image); }
  // A new opacity ramp starting at `fraction` of the data range (a re-classification only).
  void SetRamp(vtkImageData* image, double fraction)
  {
    double range[2];
    image->GetPointData()->GetScalars()->GetRange(range);
    accelvolume_test::SetRampProperty(
      this->Volume->GetProperty(), range[0] + fraction * (range[1] - range[0]), range[1], true);
  }
  vtkRenderWindow* GetWindow() { return this->Window; }

private:
  vtkNew<Mapper> SliceMapper;
  vtkNew<vtkVolume> Volume;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkRenderWindow> Window;
};

// Compute slices classify a GPU-built octree on the GPU, by the transfer table's entries rather
// than the opacity function: the same images, a transparent fraction within the table's
// quantisation of the CPU one. Rasterised slices read the levels back: the CPU classification.
bool Same(const std::string& what, const Frame& gpu, const Frame& cpu)
{
  const auto d = accelvolume_test::CompareImages(gpu.pixels, cpu.pixels, 0.0);
  const bool gpuClassified = gpu.compositing == Mapper::SLICE_COMPOSITING_COMPUTE;
  const bool fractions = gpuClassified ? std::abs(gpu.leafFraction - cpu.leafFraction) <= 0.05
                                       : gpu.leafFraction == cpu.leafFraction;
  const bool ok = d.maximum == 0.0 && fractions && gpu.leafFraction > 0 &&
    cpu.leafFraction > 0 && gpu.builder == Octree::BUILDER_GPU && cpu.builder == Octree::BUILDER_CPU;
  std::cout << what << ": max |diff| " << d.maximum << ", transparent leaves "
            << gpu.leafFraction << " / " << cpu.leafFraction << ", builders " << gpu.builder
            << " / " << cpu.builder << (ok ? "" : "  FAILED") << "\n";
  return ok;
}

// Node ranges of an octree built from a texture the caller uploaded against the CPU build.
bool DirectInputTexture(vtkImageData* image, vtkOpenGLRenderWindow* window)
{
  int dims[3];
  image->GetDimensions(dims);
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  vtkNew<vtkTextureObject> texture;
  texture->SetContext(window);
  const bool made = texture->Create3DFromRaw(
    dims[0], dims[1], dims[2], 1, scalars->GetDataType(), scalars->GetVoidPointer(0));
  vtkNew<Octree> cpu;
  cpu->SetInputData(image);
  vtkNew<Octree> gpu;
  gpu->SetInputData(image);
  gpu->SetBuilder(Octree::BUILDER_GPU);
  gpu->SetRenderWindow(window);
  gpu->SetInputTexture(texture);
  bool ok = made && cpu->Update() && gpu->Update() && gpu->GetLastBuilder() == Octree::BUILDER_GPU;
  vtkIdType nodes = 0;
  for (int level = 0; ok && level <= cpu->GetDepth(); ++level)
  {
    for (vtkIdType node = 0; ok; ++node)
    {
      double a[2] = { 0, 0 };
      double b[2] = { 0, 0 };
      const bool inA = gpu->GetNodeRange(level, node, a);
      const bool inB = cpu->GetNodeRange(level, node, b);
      ok = inA == inB && (!inA || (a[0] == b[0] && a[1] == b[1]));
      if (!inA || !inB)
      {
        break;
      }
      ++nodes;
    }
  }
  ok = ok && nodes == cpu->GetNumberOfNodes();
  std::cout << "octree from a caller's texture vs CPU build: " << (ok ? "same" : "DIFFERENT")
            << " node ranges (" << nodes << " nodes)\n";
  gpu->ReleaseGraphicsResources();
  texture->ReleaseGraphicsResources(window);
  return ok;
}
}

int TestAccelVolumeOctreeFromTexture(int, char*[])
{
  auto phantom = accelvolume_test::MakePhantom("blobs", 70, 58, 46);
  bool ok = true;
  for (int type : { VTK_UNSIGNED_CHAR, VTK_UNSIGNED_SHORT })
  {
    auto first = Quantised(phantom, type, 0.0);
    auto second = Quantised(phantom, type, type == VTK_UNSIGNED_CHAR ? 25.0 : 3000.0);
    for (int compositing : { Mapper::SLICE_COMPOSITING_RASTER, Mapper::SLICE_COMPOSITING_AUTO })
    {
      Scene gpu(first, Octree::BUILDER_GPU, compositing);
      Scene cpu(first, Octree::BUILDER_CPU, compositing);
      const Frame a = gpu.Render();
      auto* window = vtkOpenGLRenderWindow::SafeDownCast(gpu.GetWindow());
      int major = 0;
      int minor = 0;
      window->GetOpenGLVersion(major, minor);
      if (major < 4 || (major == 4 && minor < 3))
      {
        std::cout << "OpenGL " << major << "." << minor << ": no compute shaders, skipped\n";
        return VTK_SKIP_RETURN_CODE;
      }
      const std::string name = std::string(type == VTK_UNSIGNED_CHAR ? "8-bit" : "16-bit") +
        (a.compositing == Mapper::SLICE_COMPOSITING_COMPUTE ? ", compute slices"
                                                            : ", raster slices");
      ok = Same(name, a, cpu.Render()) && ok;
      // A new transfer function: classified again, the octree kept.
      gpu.SetRamp(first, 0.5);
      cpu.SetRamp(first, 0.5);
      ok = Same(name + ", new transfer function", gpu.Render(), cpu.Render()) && ok;
      // A new time step: new scalars, uploaded by the frame and the octree rebuilt from them.
      gpu.SetInput(second);
      cpu.SetInput(second);
      ok = Same(name + ", next time step", gpu.Render(), cpu.Render()) && ok;
      if (type == VTK_UNSIGNED_SHORT && compositing == Mapper::SLICE_COMPOSITING_RASTER)
      {
        ok = DirectInputTexture(second, window) && ok;
      }
    }
  }
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
