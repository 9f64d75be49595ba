/**
 * @file    vtkAccelVolumeSliceGeometry.h
 * @brief   Proxy geometry of vtkAccelVolumeSliceMapper (private to the module): the view-aligned
 *          slices and cut faces of every cropping region, per volume brick, in drawing order.
 *
 * One brick: the regions' slices exactly as they are. Several bricks: each brick draws the
 * slices of (region box ∩ its owned box grown by half a voxel inside the volume) and the
 * shaders discard samples outside the owned box, so every sample point of the unbricked slices
 * is taken once, by one brick, at the same position; the grown box only keeps rasterisation
 * from missing pixels at a brick face. Composite draws bricks front to back (or back to front)
 * and each brick depth-major, which keeps every ray's samples in order; bricks that the octree
 * finds empty get no geometry (and so are never uploaded).
 */
#ifndef vtkAccelVolumeSliceGeometry_h
#define vtkAccelVolumeSliceGeometry_h

#include "vtkAccelVolumeSlicePasses.h"

#include "common/Geometry.h"
#include "slicing/Bricking.h"
#include "slicing/SlabProxy.h"

#include <vector>

struct vtkAccelVolumeSliceGeometryInput
{
  const std::vector<accelvolume::Box>* Regions = nullptr; // cropping cells
  const std::vector<accelvolume::HalfSpace>* Clip = nullptr;
  accelvolume::Box VolumeBox;
  accelvolume::ViewRays Rays; // depth(p) and the rays, in index space
  double ReferenceDepth = 0;  // slice depths are stored relative to it
  double Spacing = 1;
  double Phase = 0;
  bool Composite = false;
  bool FrontToBack = true;
  int SlabSamples = 1;                                     // projection modes, one brick only
  bool BoundaryFaces = false;                              // projection modes
  const std::vector<accelvolume::Box>* NonEmpty = nullptr; // composite octree culling
  const accelvolume::BrickLayout* Layout = nullptr;
  // SLICE_BLEND: the slice function's plane inside each cropping region (and the clip
  // planes); each brick draws them as cut faces instead of slices.
  const std::vector<accelvolume::Polygon>* SlicePlane = nullptr;
};

struct vtkAccelVolumeSliceGeometryStats
{
  int Slices = 0; // sample planes (slab polygons times their samples)
  int ProxyPolygons = 0;
  int BoundaryFaces = 0;
  double KeptAreaFraction = 1.0; // composite: slice area left by octree culling
};

/** Fills frame.Bricks (drawing order) and the vertices they index. */
void vtkAccelVolumeBuildSliceGeometry(const vtkAccelVolumeSliceGeometryInput& input,
  vtkAccelVolumeSliceFrame& frame, std::vector<float>& vertices,
  vtkAccelVolumeSliceGeometryStats& stats);

#endif
