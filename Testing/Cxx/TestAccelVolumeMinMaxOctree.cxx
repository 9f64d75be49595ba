// vtkAccelVolumeMinMaxOctree: builders agree, timestamps, classification, GPU build, bad input.
#include "AccelVolumeTestUtilities.h"
#include "skipping/MinMaxOctree.h"
#include "vtkAccelVolumeMinMaxOctree.h"

#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkSMPTools.h"
#include "vtkTimerLog.h"

#include <cstdint>
#include <limits>
#include <sstream>

namespace
{
// Exposes the protected timestamps so the test can tell a rebuild from a no-op.
class OctreeProbe : public vtkAccelVolumeMinMaxOctree
{
public:
  static OctreeProbe* New() { VTK_STANDARD_NEW_BODY(OctreeProbe); }
  vtkTypeMacro(OctreeProbe, vtkAccelVolumeMinMaxOctree);
  vtkMTimeType GetBuildStamp() const { return this->BuildTime.GetMTime(); }
  vtkMTimeType GetClassifyStamp() const { return this->ClassifyTime.GetMTime(); }
};

bool Check(bool condition, const std::string& what)
{
  if (!condition)
  {
    std::cerr << "FAILED: " << what << "\n";
  }
  return condition;
}

// A phantom (values in [0, 1000]) converted to `type`: scaled to use the type's range, with
// negative values for the signed types and a fractional offset for float.
vtkSmartPointer<vtkImageData> MakeTypedPhantom(const char* name, int nx, int ny, int nz, int type)
{
  vtkSmartPointer<vtkImageData> source = accelvolume_test::MakePhantom(name, nx, ny, nz);
  vtkDataArray* values = source->GetPointData()->GetScalars();
  vtkSmartPointer<vtkDataArray> typed = vtk::TakeSmartPointer(vtkDataArray::CreateDataArray(type));
  typed->SetNumberOfTuples(values->GetNumberOfTuples());
  for (vtkIdType i = 0; i < values->GetNumberOfTuples(); ++i)
  {
    const double v = values->GetTuple1(i);
    switch (type)
    {
      case VTK_UNSIGNED_CHAR:
        typed->SetTuple1(i, std::floor(v * 0.255));
        break;
      case VTK_SHORT:
        typed->SetTuple1(i, std::floor(v * 30.0) - 12000.0);
        break;
      case VTK_UNSIGNED_SHORT:
        typed->SetTuple1(i, std::floor(v * 65.0));
        break;
      default:
        typed->SetTuple1(i, v - 123.375);
    }
  }
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(nx, ny, nz);
  image->GetPointData()->SetScalars(typed);
  return image;
}

// Every node's range, level by level (GetNodeRange fails past a level's end).
std::vector<std::vector<std::pair<double, double>>> AllRanges(vtkAccelVolumeMinMaxOctree* octree)
{
  std::vector<std::vector<std::pair<double, double>>> levels(octree->GetDepth() + 1);
  for (int level = 0; level <= octree->GetDepth(); ++level)
  {
    double range[2];
    for (vtkIdType i = 0; octree->GetNodeRange(level, i, range); ++i)
    {
      levels[level].emplace_back(range[0], range[1]);
    }
  }
  return levels;
}

// Equal ranges: exactly for tolerance 0; else within tolerance and never narrower than `b`.
bool SameRanges(vtkAccelVolumeMinMaxOctree* a, vtkAccelVolumeMinMaxOctree* b, double tolerance,
  const std::string& what)
{
  const auto first = AllRanges(a);
  const auto second = AllRanges(b);
  if (first.size() != second.size())
  {
    return Check(false, what + ": depth differs");
  }
  size_t nodes = 0;
  for (size_t level = 0; level < first.size(); ++level)
  {
    if (first[level].size() != second[level].size())
    {
      return Check(false, what + ": level " + std::to_string(level) + " length differs");
    }
    nodes += first[level].size();
    for (size_t i = 0; i < first[level].size(); ++i)
    {
      const auto& x = first[level][i];
      const auto& y = second[level][i];
      const bool same = tolerance == 0
        ? x == y
        : (x == y ||
            (x.first <= y.first && x.second >= y.second && y.first - x.first <= tolerance &&
              x.second - y.second <= tolerance));
      if (!same)
      {
        std::ostringstream message;
        message << what << ": level " << level << " node " << i << " [" << x.first << ", "
                << x.second << "] vs [" << y.first << ", " << y.second << "]";
        return Check(false, message.str());
      }
    }
  }
  return Check(nodes == static_cast<size_t>(a->GetNumberOfNodes()), what + ": node count");
}

// Brute force: each leaf's range is the min/max over voxels [i*L, (i+1)*L] clamped.
bool LeavesMatchVoxels(vtkAccelVolumeMinMaxOctree* octree, vtkImageData* image, int leafSize)
{
  int dims[3];
  image->GetDimensions(dims);
  int grid[3];
  octree->GetLeafGridSize(grid);
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  for (int k = 0; k < grid[2]; ++k)
    for (int j = 0; j < grid[1]; ++j)
      for (int i = 0; i < grid[0]; ++i)
      {
        double low = std::numeric_limits<double>::infinity();
        double high = -low;
        for (int z = k * leafSize; z <= std::min((k + 1) * leafSize, dims[2] - 1); ++z)
          for (int y = j * leafSize; y <= std::min((j + 1) * leafSize, dims[1] - 1); ++y)
            for (int x = i * leafSize; x <= std::min((i + 1) * leafSize, dims[0] - 1); ++x)
            {
              const double v = scalars->GetTuple1(x + dims[0] * (y + dims[1] * z));
              low = std::min(low, v);
              high = std::max(high, v);
            }
        double range[2];
        const vtkIdType index = static_cast<vtkIdType>(accelvolume::MortonEncode(i, j, k));
        if (!octree->GetNodeRange(0, index, range) || range[0] != low || range[1] != high)
        {
          return Check(false,
            "leaf (" + std::to_string(i) + "," + std::to_string(j) + "," + std::to_string(k) +
              ") differs from its voxels");
        }
      }
  return true;
}

// With opacity 0 up to `threshold` and rising after it, a leaf is transparent iff its max is
// below the threshold (checked away from the table's resolution), and a parent iff all its
// children are.
bool ClassificationConsistent(vtkAccelVolumeMinMaxOctree* octree, double threshold, double step)
{
  bool ok = true;
  double range[2];
  for (vtkIdType i = 0; octree->GetNodeRange(0, i, range); ++i)
  {
    const bool transparent = octree->IsNodeTransparent(0, i);
    if (range[0] > range[1])
    {
      ok = Check(transparent, "padding leaf is transparent") && ok;
    }
    else if (range[1] < threshold - step)
    {
      ok = Check(transparent, "leaf below the threshold is transparent") && ok;
    }
    else if (range[1] > threshold + step)
    {
      ok = Check(!transparent, "leaf above the threshold is visible") && ok;
    }
  }
  for (int level = 1; level <= octree->GetDepth(); ++level)
  {
    for (vtkIdType p = 0; octree->GetNodeRange(level, p, range); ++p)
    {
      bool all = true;
      for (vtkIdType c = 8 * p; c < 8 * p + 8 && octree->GetNodeRange(level - 1, c, range); ++c)
      {
        all = all && octree->IsNodeTransparent(level - 1, c);
      }
      ok = Check(octree->IsNodeTransparent(level, p) == all, "parent flag = all children") && ok;
    }
  }
  return ok;
}

bool TestCPUBuilders()
{
  bool ok = true;
  const int shapes[][3] = { { 37, 19, 53 }, { 1, 7, 30 } };
  for (int type : { VTK_UNSIGNED_CHAR, VTK_SHORT, VTK_FLOAT })
  {
    for (const auto& shape : shapes)
    {
      auto image = MakeTypedPhantom("blobs", shape[0], shape[1], shape[2], type);
      for (int leafSize : { 4, 8, 16 })
      {
        const std::string what = std::string(vtkImageScalarTypeNameMacro(type)) + " " +
          std::to_string(shape[0]) + "x" + std::to_string(shape[1]) + "x" +
          std::to_string(shape[2]) + " L" + std::to_string(leafSize);
        vtkNew<vtkAccelVolumeMinMaxOctree> reference;
        vtkNew<vtkAccelVolumeMinMaxOctree> one;
        vtkNew<vtkAccelVolumeMinMaxOctree> two;
        reference->SetBuilder(vtkAccelVolumeMinMaxOctree::BUILDER_REFERENCE);
        one->SetNumberOfThreads(1);
        two->SetNumberOfThreads(2);
        const int processThreads = vtkSMPTools::GetEstimatedNumberOfThreads();
        for (vtkAccelVolumeMinMaxOctree* octree :
          { reference.GetPointer(), one.GetPointer(), two.GetPointer() })
        {
          octree->SetInputData(image);
          octree->SetLeafSize(leafSize);
          ok = Check(octree->Update(), what + ": Update") && ok;
        }
        // A thread limit on one octree must not change the process's vtkSMPTools setting.
        ok = Check(vtkSMPTools::GetEstimatedNumberOfThreads() == processThreads,
               what + ": thread count restored after a limited build") &&
          ok;
        ok = LeavesMatchVoxels(reference, image, leafSize) && ok;
        ok = SameRanges(reference, one, 0, what + " reference vs CPU 1 thread") && ok;
        ok = SameRanges(one, two, 0, what + " CPU 1 vs 2 threads") && ok;
      }
    }
  }
  return ok;
}

bool TestTimestampsAndClassification()
{
  bool ok = true;
  auto image = MakeTypedPhantom("blobs", 37, 19, 53, VTK_SHORT);
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  vtkNew<OctreeProbe> octree;
  octree->SetInputData(image);
  ok = Check(octree->Update(), "first Update") && ok;
  const vtkMTimeType built = octree->GetBuildStamp();
  ok = Check(octree->Update() && octree->GetBuildStamp() == built, "no change, no rebuild") && ok;
  scalars->Modified();
  ok = Check(octree->Update() && octree->GetBuildStamp() > built, "Modified scalars rebuild") && ok;
  vtkMTimeType stamp = octree->GetBuildStamp();
  octree->SetLeafSize(4);
  ok = Check(octree->Update() && octree->GetBuildStamp() > stamp, "LeafSize rebuilds") && ok;
  stamp = octree->GetBuildStamp();
  octree->SetBuilder(vtkAccelVolumeMinMaxOctree::BUILDER_REFERENCE);
  ok = Check(octree->Update() && octree->GetBuildStamp() > stamp, "Builder rebuilds") && ok;

  double range[2];
  scalars->GetRange(range);
  const double step = (range[1] - range[0]) / (accelvolume_test::TableSize - 1);
  const double threshold = range[0] + 0.4 * (range[1] - range[0]);
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(range[0], 0.0);
  opacity->AddPoint(threshold, 0.0);
  opacity->AddPoint(range[1], 1.0);
  ok = Check(octree->Classify(opacity, range), "Classify") && ok;
  ok = ClassificationConsistent(octree, threshold, 2 * step) && ok;
  const double fraction = octree->GetTransparentLeafFraction();
  ok = Check(fraction > 0 && fraction < 1, "some leaves transparent, some not") && ok;
  const vtkMTimeType classified = octree->GetClassifyStamp();
  ok = Check(octree->Classify(opacity, range) && octree->GetClassifyStamp() == classified,
         "no change, no re-classification") &&
    ok;
  // A lower threshold: re-classified, fewer transparent leaves, still consistent.
  const double lower = range[0] + 0.1 * (range[1] - range[0]);
  opacity->RemoveAllPoints();
  opacity->AddPoint(range[0], 0.0);
  opacity->AddPoint(lower, 0.0);
  opacity->AddPoint(range[1], 1.0);
  ok = Check(octree->Classify(opacity, range) && octree->GetClassifyStamp() > classified,
         "function change re-classifies") &&
    ok;
  ok = ClassificationConsistent(octree, lower, 2 * step) && ok;
  ok = Check(octree->GetTransparentLeafFraction() < fraction, "fewer transparent leaves") && ok;
  std::cout << "transparent leaves: " << fraction << " -> " << octree->GetTransparentLeafFraction()
            << " (classify " << octree->GetLastClassifyTime() << " s)\n";

  // Distance queries at the extremes: all transparent -> t1; nothing transparent -> t0.
  const double origin[3] = { -5.0, 9.0, 26.0 };
  const double direction[3] = { 1.0, 0.0, 0.0 };
  opacity->RemoveAllPoints();
  opacity->AddPoint(range[0], 0.0);
  opacity->AddPoint(range[1], 0.0);
  octree->Classify(opacity, range);
  ok = Check(octree->NextNonEmpty(origin, direction, 0.0, 50.0) == 50.0, "empty ray -> t1") && ok;
  opacity->AddPoint(range[0], 1.0);
  opacity->AddPoint(range[1], 1.0);
  octree->Classify(opacity, range);
  const double t = octree->NextNonEmpty(origin, direction, 0.0, 50.0);
  ok =
    Check(std::abs(t - 5.0) < 1e-9, "opaque volume entered at t = 5, got " + std::to_string(t)) &&
    ok;
  std::ostringstream printed;
  octree->Print(printed);
  ok = Check(printed.str().find("LeafSize: 4") != std::string::npos, "PrintSelf") && ok;
  return ok;
}

// GPU builds against the CPU builder; skipped (not failed) without OpenGL 4.3.
bool TestGPUBuilder()
{
  vtkNew<vtkRenderWindow> generic;
  vtkNew<vtkRenderer> renderer;
  generic->SetMultiSamples(0);
  generic->SetSize(16, 16);
  generic->AddRenderer(renderer);
  generic->Render();
  vtkOpenGLRenderWindow* window = vtkOpenGLRenderWindow::SafeDownCast(generic);
  int major = 0;
  int minor = 0;
  if (window)
  {
    window->GetOpenGLVersion(major, minor);
  }
  if (!window || major < 4 || (major == 4 && minor < 3))
  {
    std::cout << "OpenGL " << major << "." << minor << ": no compute shaders, GPU part skipped\n";
    return true;
  }
  std::cout << "GPU builder in " << window->GetClassName() << ", OpenGL " << major << "." << minor
            << "\n";
  bool ok = true;
  const int shapes[][3] = { { 37, 19, 53 }, { 1, 7, 30 }, { 64, 48, 40 } };
  for (int type : { VTK_UNSIGNED_CHAR, VTK_SHORT, VTK_UNSIGNED_SHORT, VTK_FLOAT })
  {
    for (const auto& shape : shapes)
    {
      auto image = MakeTypedPhantom("vessels", shape[0], shape[1], shape[2], type);
      double range[2];
      image->GetPointData()->GetScalars()->GetRange(range);
      // Floats go through a texture normalised to the data range: 1e-5 of that range.
      const double tolerance = type == VTK_FLOAT ? 1e-5 * (range[1] - range[0]) : 0.0;
      for (int leafSize : { 4, 8, 16 })
      {
        const std::string what = std::string("GPU ") + vtkImageScalarTypeNameMacro(type) + " " +
          std::to_string(shape[0]) + "x" + std::to_string(shape[1]) + "x" +
          std::to_string(shape[2]) + " L" + std::to_string(leafSize);
        vtkNew<vtkAccelVolumeMinMaxOctree> cpu;
        vtkNew<vtkAccelVolumeMinMaxOctree> gpu;
        cpu->SetInputData(image);
        cpu->SetLeafSize(leafSize);
        gpu->SetInputData(image);
        gpu->SetLeafSize(leafSize);
        gpu->SetBuilder(vtkAccelVolumeMinMaxOctree::BUILDER_GPU);
        gpu->SetRenderWindow(window);
        ok = Check(cpu->Update() && gpu->Update(), what + ": Update") && ok;
        ok = Check(gpu->GetGPULevelBuffer(0) != 0 && cpu->GetGPULevelBuffer(0) == 0,
               what + ": level buffers") &&
          ok;
        ok = SameRanges(gpu, cpu, tolerance, what) && ok;
      }
    }
  }
  // Timings (informational): a 256^3 unsigned short phantom.
  auto big = MakeTypedPhantom("blobs", 256, 256, 256, VTK_UNSIGNED_SHORT);
  double seconds[3] = { 0, 0, 0 };
  vtkNew<vtkAccelVolumeMinMaxOctree> builders[3];
  for (int b = 0; b < 3; ++b)
  {
    builders[b]->SetInputData(big);
    builders[b]->SetBuilder(b);
    builders[b]->SetRenderWindow(window);
    ok = Check(builders[b]->Update(), "256^3 build") && ok;
    seconds[b] = builders[b]->GetLastBuildTime();
  }
  vtkNew<vtkTimerLog> timer;
  timer->StartTimer();
  double range[2];
  builders[2]->GetNodeRange(0, 0, range); // the first CPU query reads the levels back
  timer->StopTimer();
  ok = SameRanges(builders[2], builders[1], 0, "256^3 GPU vs CPU") && ok;
  std::cout << "256^3 ushort, leaf 8: reference " << seconds[0] << " s, CPU (vtkSMPTools, "
            << vtkSMPTools::GetEstimatedNumberOfThreads() << " threads) " << seconds[1]
            << " s, GPU " << seconds[2] << " s (upload included), read-back "
            << timer->GetElapsedTime() << " s\n";
  // The GPU build's upload share is only in PrintSelf (no public getter).
  std::ostringstream printed;
  builders[2]->Print(printed);
  const std::string text = printed.str();
  const size_t at = text.find("LastUploadTime");
  std::cout << "  GPU " << text.substr(at, text.find('\n', at) - at) << "\n";
  // Classification of read-back GPU levels matches the CPU build's.
  big->GetPointData()->GetScalars()->GetRange(range);
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(range[0], 0.0);
  opacity->AddPoint(0.5 * (range[0] + range[1]), 0.0);
  opacity->AddPoint(range[1], 1.0);
  ok = Check(builders[1]->Classify(opacity, range) && builders[2]->Classify(opacity, range) &&
           builders[1]->GetTransparentLeafFraction() == builders[2]->GetTransparentLeafFraction(),
         "GPU and CPU classification agree") &&
    ok;
  // Released buffers are rebuilt by the next Update().
  builders[2]->ReleaseGraphicsResources();
  ok = Check(builders[2]->GetGPULevelBuffer(0) == 0, "buffers released") && ok;
  ok = Check(builders[2]->Update() && builders[2]->GetGPULevelBuffer(0) != 0, "GPU rebuild") && ok;
  return ok;
}

bool ExpectError(const char* what, vtkAccelVolumeMinMaxOctree* octree, const char* expected)
{
  vtkNew<accelvolume_test::ErrorRecorder> recorder;
  octree->AddObserver(vtkCommand::ErrorEvent, recorder);
  const bool updated = octree->Update();
  const bool reported = recorder->Messages.find(expected) != std::string::npos;
  std::cout << what << ": " << (reported ? "reported" : "NOT reported") << " -> "
            << recorder->Messages;
  return Check(!updated && reported, what);
}

bool TestBadInput()
{
  bool ok = true;
  vtkNew<vtkAccelVolumeMinMaxOctree> none;
  ok = ExpectError("no input", none, "No input") && ok;
  vtkNew<vtkImageData> rgb;
  rgb->SetDimensions(4, 4, 4);
  rgb->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  vtkNew<vtkAccelVolumeMinMaxOctree> components;
  components->SetInputData(rgb);
  ok = ExpectError("three components", components, "single-component") && ok;
  vtkNew<vtkImageData> wide;
  wide->SetDimensions(4, 4, 4);
  wide->AllocateScalars(VTK_UNSIGNED_INT, 1);
  vtkNew<vtkAccelVolumeMinMaxOctree> unsupported;
  unsupported->SetInputData(wide);
  ok = ExpectError("unsigned int scalars", unsupported, "Unsupported scalar type") && ok;
  vtkNew<vtkAccelVolumeMinMaxOctree> windowless;
  windowless->SetInputData(MakeTypedPhantom("blobs", 8, 8, 8, VTK_UNSIGNED_CHAR));
  windowless->SetBuilder(vtkAccelVolumeMinMaxOctree::BUILDER_GPU);
  ok = ExpectError("GPU builder without window", windowless, "SetRenderWindow") && ok;
  windowless->SetLeafSize(3);
  windowless->SetBuilder(vtkAccelVolumeMinMaxOctree::BUILDER_CPU);
  ok = ExpectError("leaf size 3", windowless, "failed") && ok;
  return ok;
}
}

int TestAccelVolumeMinMaxOctree(int, char*[])
{
  bool ok = TestCPUBuilders();
  ok = TestTimestampsAndClassification() && ok;
  ok = TestBadInput() && ok;
  ok = TestGPUBuilder() && ok;
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
