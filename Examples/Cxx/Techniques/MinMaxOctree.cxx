// MinMaxOctree: builds the min-max octree of Lim and Shin 2009 with the parallel Morton-order
// CPU builder, classifies it with a transfer function, prints what it found, then renders the
// volume with the slice mapper, whose octree empty-space skipping uses the same structure
// (built by the mapper itself, with the same leaf size, so the transparent fractions match).
//
//   MinMaxOctree [output.png] [--check]
#include "ExampleCommon.h"

#include <vtkAccelVolumeMinMaxOctree.h>
#include <vtkAccelVolumeSliceMapper.h>
#include <vtkColorTransferFunction.h>
#include <vtkNew.h>
#include <vtkPiecewiseFunction.h>
#include <vtkVolumeProperty.h>

#include <cstdio>

int main(int argc, char* argv[])
{
  const example::Options options = example::ParseArguments(argc, argv, "MinMaxOctree");
  auto image = example::MakeVolume(64);

  // Opacity 0 below 60: leaves whose maximum is below 60 are transparent and can be skipped.
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0, 0.0);
  opacity->AddPoint(60, 0.0);
  opacity->AddPoint(255, 0.8);

  vtkNew<vtkAccelVolumeMinMaxOctree> octree;
  octree->SetInputData(image);
  octree->SetLeafSize(8); // 8^3-voxel leaves, as in the paper
  octree->SetBuilder(vtkAccelVolumeMinMaxOctree::BUILDER_CPU);
  // The classification maps the opacity function over the range the mapper uses: the
  // scalar range of the data.
  double range[2];
  image->GetScalarRange(range);
  if (!octree->Update() || !octree->Classify(opacity, range))
  {
    std::fprintf(stderr, "MinMaxOctree: octree build failed\n");
    return 1;
  }
  int leaves[3];
  octree->GetLeafGridSize(leaves);
  double root[2];
  octree->GetNodeRange(octree->GetDepth(), 0, root);
  std::printf("octree: %dx%dx%d leaves, depth %d, %lld nodes, root range [%g, %g], built in "
              "%.2f ms, classified in %.3f ms, %.0f%% of leaves transparent\n",
    leaves[0], leaves[1], leaves[2], octree->GetDepth(),
    static_cast<long long>(octree->GetNumberOfNodes()), root[0], root[1],
    1000.0 * octree->GetLastBuildTime(), 1000.0 * octree->GetLastClassifyTime(),
    100.0 * octree->GetTransparentLeafFraction());

  // Render with octree skipping only, to show the octree's effect alone.
  vtkNew<vtkAccelVolumeSliceMapper> mapper;
  mapper->SetInputData(image);
  mapper->SetBlendModeToComposite();
  mapper->SetEmptySpaceSkipping(vtkAccelVolumeSliceMapper::SKIP_OCTREE);
  mapper->SetOctreeLeafSize(octree->GetLeafSize());

  vtkNew<vtkColorTransferFunction> color;
  color->AddRGBPoint(60, 0.2, 0.5, 0.9);
  color->AddRGBPoint(255, 1.0, 1.0, 0.8);
  vtkNew<vtkVolumeProperty> property;
  property->SetColor(color);
  property->SetScalarOpacity(opacity);
  property->SetInterpolationTypeToLinear();
  property->ShadeOn();

  example::Scene scene(mapper, property);
  scene.Frame(-40, 25, 1.5);
  if (!scene.Render("MinMaxOctree"))
  {
    return 1;
  }
  if (scene.Write(options) != 0)
  {
    return 1;
  }
  std::printf("MinMaxOctree: slice mapper with octree skipping, %.0f%% of leaves skipped, %.0f%% "
              "of slice area drawn, %.1f ms -> %s\n",
    100.0 * mapper->GetLastTransparentLeafFraction(), 100.0 * mapper->GetLastProxyAreaFraction(),
    1000.0 * mapper->GetLastRenderTime(), options.Output.c_str());
  return 0;
}
