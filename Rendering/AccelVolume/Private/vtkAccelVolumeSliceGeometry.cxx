// The slice mapper's proxy geometry per brick, in drawing order.
#include "vtkAccelVolumeSliceGeometry.h"

#include "slicing/CompositeSlices.h"

#include <algorithm>

namespace
{
using Frame = vtkAccelVolumeSliceFrame;

// Appends a polygon as a triangle fan of proxy vertices (see Frame::VertexFloats); depth is the
// eye depth of the slice plane the polygon lies on minus the reference depth (0 for cut faces).
void AppendProxyPolygon(
  const accelvolume::Polygon& polygon, double depth, std::vector<float>& vertices)
{
  const float planeDepth = static_cast<float>(depth);
  for (size_t i = 1; i + 1 < polygon.size(); ++i)
  {
    for (const accelvolume::Vec3* v : { &polygon[0], &polygon[i], &polygon[i + 1] })
    {
      vertices.insert(vertices.end(),
        { static_cast<float>(v->x), static_cast<float>(v->y), static_cast<float>(v->z),
          planeDepth });
    }
  }
}

// `polygon` clipped to `box` (into `clipped`), or `polygon` itself without a box. Polygons are
// never copied here: a copy would instantiate std::vector<Vec3>'s copy in this library, whose
// symbols must not name Core types (Testing/Symbols).
const accelvolume::Polygon& ClippedToBox(
  const accelvolume::Polygon& polygon, const accelvolume::Box* box, accelvolume::Polygon& clipped)
{
  if (!box)
  {
    return polygon;
  }
  const accelvolume::Polygon* current = &polygon;
  for (const accelvolume::HalfSpace& half : accelvolume::BoxHalfSpaces(*box))
  {
    clipped = current->empty() ? accelvolume::Polygon() : accelvolume::ClipPolygon(*current, half);
    current = &clipped;
  }
  return clipped;
}

int VertexCount(const std::vector<float>& vertices)
{
  return static_cast<int>(vertices.size() / Frame::VertexFloats);
}

std::array<float, 3> ToFloats(const accelvolume::Vec3& v)
{
  return { { static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z) } };
}

accelvolume::Box Intersect(const accelvolume::Box& a, const accelvolume::Box& b)
{
  accelvolume::Box box;
  box.lower = { std::max(a.lower.x, b.lower.x), std::max(a.lower.y, b.lower.y),
    std::max(a.lower.z, b.lower.z) };
  box.upper = { std::min(a.upper.x, b.upper.x), std::min(a.upper.y, b.upper.y),
    std::min(a.upper.z, b.upper.z) };
  return box;
}

// The brick's draw record: its texture placement and the samples it owns (open towards the
// volume's outside, where the region and clip tests already bound the samples).
Frame::BrickDraw MakeBrickDraw(int index, const accelvolume::Brick& brick, bool bricked)
{
  constexpr float Far = 1.0e30f;
  Frame::BrickDraw draw;
  draw.Brick = index;
  for (int a = 0; a < 3; ++a)
  {
    draw.OwnedLower[a] = bricked && !brick.firstOnAxis[a] ? brick.pointLower[a] : -Far;
    draw.OwnedUpper[a] = bricked && !brick.lastOnAxis[a] ? brick.pointUpper[a] : Far;
    draw.TextureOrigin[a] = static_cast<float>(brick.textureOrigin[a]);
    draw.TextureSize[a] = static_cast<float>(brick.textureSize[a]);
  }
  return draw;
}

// The part of index space whose slices a brick draws: its owned box, grown by half a voxel
// towards its neighbours (their texels are in its texture too).
accelvolume::Box DrawnBox(const accelvolume::Brick& brick, const accelvolume::Box& volumeBox)
{
  accelvolume::Box box = accelvolume::BrickOwnedBox(brick, volumeBox);
  double* lower[3] = { &box.lower.x, &box.lower.y, &box.lower.z };
  double* upper[3] = { &box.upper.x, &box.upper.y, &box.upper.z };
  for (int a = 0; a < 3; ++a)
  {
    *lower[a] -= brick.firstOnAxis[a] ? 0.0 : 0.5;
    *upper[a] += brick.lastOnAxis[a] ? 0.0 : 0.5;
  }
  return box;
}

bool TouchesAny(const accelvolume::Box& box, const std::vector<accelvolume::Box>& boxes)
{
  return std::any_of(boxes.begin(), boxes.end(),
    [&box](const accelvolume::Box& other) { return !Intersect(box, other).IsEmpty(); });
}

// Composite slabs of one region, in compositing order: each fragment composites SlabSamples
// slice depths along its ray, so one blend stands for that many slices. Octree culling cuts
// each slab to the non-empty boxes' bounds over its depths.
void BuildCompositeSlabs(const vtkAccelVolumeSliceGeometryInput& input,
  const accelvolume::Box& region, Frame::BrickDraw& draw, std::vector<float>& vertices,
  vtkAccelVolumeSliceGeometryStats& stats)
{
  accelvolume::SlabStack slabs = accelvolume::ComputeSlabProxyPolygons(
    region, *input.Clip, input.Rays, input.Spacing, input.Phase, input.SlabSamples, input.NonEmpty);
  const int count = static_cast<int>(slabs.polygons.size());
  Frame::Cell cell;
  cell.Lower = ToFloats(region.lower);
  cell.Upper = ToFloats(region.upper);
  cell.SliceFirst = VertexCount(vertices);
  for (int n = 0; n < count; ++n)
  {
    const size_t slab = static_cast<size_t>(input.FrontToBack ? count - 1 - n : n);
    draw.SliceStarts.push_back(VertexCount(vertices));
    AppendProxyPolygon(slabs.polygons[slab], slabs.depths[slab] - input.ReferenceDepth, vertices);
  }
  draw.SliceStarts.push_back(VertexCount(vertices));
  cell.SliceCount = VertexCount(vertices) - cell.SliceFirst;
  cell.FaceFirst = VertexCount(vertices);
  stats.Slices += count * input.SlabSamples;
  stats.ProxyPolygons += count;
  if (cell.SliceCount > 0)
  {
    draw.Cells.push_back(cell);
  }
}

// Composite: one cell per brick, its slices depth-major.
void BuildCompositeBrick(const vtkAccelVolumeSliceGeometryInput& input,
  const std::vector<accelvolume::Box>& regions, Frame::BrickDraw& draw,
  std::vector<float>& vertices, vtkAccelVolumeSliceGeometryStats& stats, double& fullArea,
  double& keptArea)
{
  if (input.SlabSamples > 1 && regions.size() == 1)
  {
    BuildCompositeSlabs(input, regions.front(), draw, vertices, stats);
    return;
  }
  // Octree culling, geometry part: slices are clipped to the non-empty octree boxes' bounds at
  // their depth; what is cut lies in transparent leaves (image unchanged).
  const accelvolume::CompositeSlices composited =
    accelvolume::ComputeCompositeSlices(regions, *input.Clip, input.Rays.depthGradient,
      input.Rays.depthOffset, input.Spacing, input.Phase, input.FrontToBack, input.NonEmpty);
  fullArea += composited.fullArea;
  keptArea += composited.keptArea;
  Frame::Cell cell;
  cell.Lower = ToFloats(input.VolumeBox.lower);
  cell.Upper = ToFloats(input.VolumeBox.upper);
  cell.SliceFirst = VertexCount(vertices);
  for (const auto& slice : composited.slices)
  {
    draw.SliceStarts.push_back(VertexCount(vertices));
    AppendProxyPolygon(slice.second, slice.first - input.ReferenceDepth, vertices);
  }
  draw.SliceStarts.push_back(VertexCount(vertices));
  cell.SliceCount = VertexCount(vertices) - cell.SliceFirst;
  cell.FaceFirst = VertexCount(vertices);
  const int count = static_cast<int>(composited.slices.size());
  stats.Slices += count;
  stats.ProxyPolygons += count;
  if (cell.SliceCount > 0)
  {
    draw.Cells.push_back(cell);
  }
}

// Projection modes: one cell per cropping region, with its slices (or slab proxies) and, when
// asked, its cut faces. The cell keeps the whole region's box: the shaders weigh samples by the
// region's ray interval.
void BuildProjectionBrick(const vtkAccelVolumeSliceGeometryInput& input,
  const accelvolume::Box* drawn, const std::vector<std::vector<accelvolume::Polygon>>& faces,
  Frame::BrickDraw& draw, std::vector<float>& vertices, vtkAccelVolumeSliceGeometryStats& stats)
{
  const std::vector<accelvolume::Box>& regions = *input.Regions;
  for (size_t r = 0; r < regions.size(); ++r)
  {
    const accelvolume::Box part = drawn ? Intersect(regions[r], *drawn) : regions[r];
    if (part.IsEmpty())
    {
      continue;
    }
    Frame::Cell cell;
    cell.Lower = ToFloats(regions[r].lower);
    cell.Upper = ToFloats(regions[r].upper);
    cell.SliceFirst = VertexCount(vertices);
    // Each polygon with the depth of its plane: slab proxies lie on their (possibly raised)
    // front, slices on their depth.
    std::vector<accelvolume::Polygon> polygons;
    std::vector<double> depths;
    if (input.SlabSamples > 1)
    {
      accelvolume::SlabStack slabs = accelvolume::ComputeSlabProxyPolygons(
        part, *input.Clip, input.Rays, input.Spacing, input.Phase, input.SlabSamples);
      polygons = std::move(slabs.polygons);
      depths = std::move(slabs.depths);
    }
    else
    {
      accelvolume::SliceStack slices =
        accelvolume::ComputeViewAlignedSlices(part, *input.Clip, input.Rays.depthGradient,
          input.Rays.depthOffset, input.Spacing, input.Phase, accelvolume::SliceOrder::BackToFront);
      polygons = std::move(slices.polygons);
      depths = std::move(slices.depths);
    }
    for (size_t n = 0; n < polygons.size(); ++n)
    {
      AppendProxyPolygon(polygons[n], depths[n] - input.ReferenceDepth, vertices);
    }
    stats.ProxyPolygons += static_cast<int>(polygons.size());
    stats.Slices += static_cast<int>(polygons.size()) * input.SlabSamples;
    cell.SliceCount = VertexCount(vertices) - cell.SliceFirst;
    cell.FaceFirst = VertexCount(vertices);
    accelvolume::Polygon clipped;
    for (const accelvolume::Polygon& source : faces[r])
    {
      const accelvolume::Polygon& face = ClippedToBox(source, drawn, clipped);
      if (!face.empty())
      {
        AppendProxyPolygon(face, 0.0, vertices);
        ++stats.BoundaryFaces;
      }
    }
    cell.FaceCount = VertexCount(vertices) - cell.FaceFirst;
    if (cell.SliceCount + cell.FaceCount > 0)
    {
      draw.Cells.push_back(cell);
    }
  }
}

// Composite slices for the vertex stage to generate: per slice its depth and box.
void BuildGeneratedSlices(const vtkAccelVolumeSliceGeometryInput& input, Frame::BrickDraw& draw,
  std::vector<float>& records, vtkAccelVolumeSliceGeometryStats& stats)
{
  const std::vector<accelvolume::SliceBox> slices =
    accelvolume::ComputeSliceBoxes(input.Regions->front(), input.Rays.depthGradient,
      input.Rays.depthOffset, input.Spacing, input.Phase, input.FrontToBack, input.NonEmpty);
  records.resize(slices.size() * Frame::SliceRecordFloats);
  float* record = records.data();
  for (const accelvolume::SliceBox& slice : slices)
  {
    // The depth rounded as the CPU polygons' vertices carry it, so both sample alike.
    record[0] = static_cast<float>(slice.depth - input.ReferenceDepth);
    const std::array<float, 3> lower = ToFloats(slice.box.lower);
    const std::array<float, 3> upper = ToFloats(slice.box.upper);
    std::copy(lower.begin(), lower.end(), record + 1);
    std::copy(upper.begin(), upper.end(), record + 4);
    record[7] = 0.0f;
    record += Frame::SliceRecordFloats;
  }
  const int count = static_cast<int>(slices.size());
  Frame::Cell cell;
  cell.Lower = ToFloats(input.VolumeBox.lower);
  cell.Upper = ToFloats(input.VolumeBox.upper);
  cell.SliceFirst = 0;
  cell.SliceCount = count;
  cell.FaceFirst = 0;
  draw.SliceStarts.resize(static_cast<size_t>(count) + 1);
  for (int k = 0; k <= count; ++k)
  {
    draw.SliceStarts[static_cast<size_t>(k)] = k;
  }
  stats.Slices += count;
  stats.ProxyPolygons += count;
  if (count > 0)
  {
    draw.Cells.push_back(cell);
  }
}

// Compute slices: the brick and its region's cell, no geometry; the planes through the region.
void BuildComputeBrick(const vtkAccelVolumeSliceGeometryInput& input, Frame::BrickDraw& draw,
  vtkAccelVolumeSliceGeometryStats& stats)
{
  const accelvolume::Box& region = input.Regions->front();
  Frame::Cell cell;
  cell.Lower = ToFloats(region.lower);
  cell.Upper = ToFloats(region.upper);
  draw.Cells.push_back(cell);
  draw.SliceStarts.assign(2, 0);
  double minimumDepth = 0.0;
  double maximumDepth = 0.0;
  long long first = 0;
  long long last = -1;
  if (accelvolume::RegionDepthRange(region, *input.Clip, input.Rays.depthGradient,
        input.Rays.depthOffset, minimumDepth, maximumDepth))
  {
    accelvolume::SampleIndexRange(
      minimumDepth, maximumDepth, input.Phase, input.Spacing, first, last);
  }
  stats.Slices = static_cast<int>(std::max(0LL, last - first + 1));
}

bool CanGenerateSlices(const vtkAccelVolumeSliceGeometryInput& input)
{
  return input.GenerateSlices && input.Composite && !input.SlicePlane && input.Layout->Single() &&
    input.Regions->size() == 1 && input.Clip->empty() && input.SlabSamples <= 1;
}

// SLICE_BLEND: the plane's polygons as the brick's cut faces (no slices).
void BuildSlicePlaneBrick(const vtkAccelVolumeSliceGeometryInput& input,
  const accelvolume::Box* drawn, Frame::BrickDraw& draw, std::vector<float>& vertices,
  vtkAccelVolumeSliceGeometryStats& stats)
{
  Frame::Cell cell;
  cell.Lower = ToFloats(input.VolumeBox.lower);
  cell.Upper = ToFloats(input.VolumeBox.upper);
  cell.SliceFirst = VertexCount(vertices);
  draw.SliceStarts.assign(2, VertexCount(vertices));
  cell.FaceFirst = VertexCount(vertices);
  accelvolume::Polygon clipped;
  for (const accelvolume::Polygon& source : *input.SlicePlane)
  {
    const accelvolume::Polygon& face = ClippedToBox(source, drawn, clipped);
    if (!face.empty())
    {
      AppendProxyPolygon(face, 0.0, vertices);
      ++stats.BoundaryFaces;
      ++stats.ProxyPolygons;
      stats.Slices = 1;
    }
  }
  cell.FaceCount = VertexCount(vertices) - cell.FaceFirst;
  if (cell.FaceCount > 0)
  {
    draw.Cells.push_back(cell);
  }
}
}

void vtkAccelVolumeBuildSliceGeometry(const vtkAccelVolumeSliceGeometryInput& input,
  vtkAccelVolumeSliceFrame& frame, std::vector<float>& vertices, std::vector<float>& sliceRecords,
  vtkAccelVolumeSliceGeometryStats& stats)
{
  frame.Bricks.clear();
  vertices.clear();
  sliceRecords.clear();
  stats = vtkAccelVolumeSliceGeometryStats();
  const accelvolume::BrickLayout& layout = *input.Layout;
  frame.ComputeSlices = input.ComputeSlices; // the mapper checked one brick and one region
  if (frame.ComputeSlices)
  {
    frame.GeneratedSlices = false;
    frame.Bricked = false;
    Frame::BrickDraw draw = MakeBrickDraw(0, layout.bricks[0], false);
    BuildComputeBrick(input, draw, stats);
    frame.Bricks.push_back(std::move(draw));
    stats.KeptAreaFraction = -1.0;
    return;
  }
  frame.GeneratedSlices = CanGenerateSlices(input);
  if (frame.GeneratedSlices)
  {
    frame.Bricked = false;
    const accelvolume::Vec3& g = input.Rays.depthGradient;
    frame.DepthGradient[0] = static_cast<float>(g.x);
    frame.DepthGradient[1] = static_cast<float>(g.y);
    frame.DepthGradient[2] = static_cast<float>(g.z);
    frame.DepthOffset = static_cast<float>(input.Rays.depthOffset - input.ReferenceDepth);
    Frame::BrickDraw draw = MakeBrickDraw(0, layout.bricks[0], false);
    BuildGeneratedSlices(input, draw, sliceRecords, stats);
    if (!draw.Cells.empty())
    {
      frame.Bricks.push_back(std::move(draw));
    }
    stats.KeptAreaFraction = -1.0;
    return;
  }
  const bool bricked = !layout.Single();
  frame.Bricked = bricked;
  std::vector<std::vector<accelvolume::Polygon>> faces(input.Regions->size());
  if (!input.Composite && input.BoundaryFaces)
  {
    for (size_t r = 0; r < input.Regions->size(); ++r)
    {
      faces[r] = accelvolume::ComputeRegionBoundaryFaces((*input.Regions)[r], *input.Clip);
    }
  }
  std::vector<int> order = accelvolume::BrickVisibilityOrder(
    layout, input.Rays.perspective, input.Rays.eye, input.Rays.direction);
  if (input.Composite && !input.FrontToBack)
  {
    std::reverse(order.begin(), order.end());
  }
  double fullArea = 0.0;
  double keptArea = 0.0;
  for (int index : order)
  {
    const accelvolume::Brick& brick = layout.bricks[index];
    Frame::BrickDraw draw = MakeBrickDraw(index, brick, bricked);
    const accelvolume::Box drawn = DrawnBox(brick, input.VolumeBox);
    if (input.SlicePlane)
    {
      BuildSlicePlaneBrick(input, bricked ? &drawn : nullptr, draw, vertices, stats);
    }
    else if (input.Composite)
    {
      if (bricked && input.NonEmpty &&
        !TouchesAny(accelvolume::BrickOwnedBox(brick, input.VolumeBox), *input.NonEmpty))
      {
        continue; // every leaf in it is transparent: never drawn, never uploaded
      }
      std::vector<accelvolume::Box> regions;
      for (const accelvolume::Box& region : *input.Regions)
      {
        const accelvolume::Box part = bricked ? Intersect(region, drawn) : region;
        if (!part.IsEmpty())
        {
          regions.push_back(part);
        }
      }
      BuildCompositeBrick(input, regions, draw, vertices, stats, fullArea, keptArea);
    }
    else
    {
      BuildProjectionBrick(input, bricked ? &drawn : nullptr, faces, draw, vertices, stats);
    }
    if (!draw.Cells.empty())
    {
      frame.Bricks.push_back(std::move(draw));
    }
  }
  stats.KeptAreaFraction = fullArea > 0 ? keptArea / fullArea : 1.0;
}

double vtkAccelVolumeSliceKeptAreaFraction(const vtkAccelVolumeSliceGeometryInput& input)
{
  if (!input.Regions || !input.Clip)
  {
    return 1.0;
  }
  return accelvolume::ComputeCompositeSlices(*input.Regions, *input.Clip, input.Rays.depthGradient,
    input.Rays.depthOffset, input.Spacing, input.Phase, input.FrontToBack, input.NonEmpty)
    .keptAreaFraction;
}
