// MapperSetup: creating and configuring the --mapper, and reading its timings and counters.
#include "MapperSetup.h"

#include <vtkAccelVolumeMPIExchange.h>
#include <vtkAccelVolumeRayCastMapper.h>
#include <vtkAccelVolumeShearWarpMapper.h>
#include <vtkAccelVolumeSliceMapper.h>
#include <vtkAccelVolumeSmartMapper.h>

#include <vtkCamera.h>
#include <vtkFixedPointVolumeRayCastMapper.h>
#include <vtkGPUVolumeRayCastMapper.h>
#include <vtkImageData.h>
#include <vtkMatrix3x3.h>
#include <vtkMatrix4x4.h>
#include <vtkNew.h>

#include <cmath>

namespace accelvolume::cli
{
namespace
{

void ConfigureSlice(
  vtkAccelVolumeSliceMapper* slice, const Options& options, const RenderResult& result)
{
  slice->SetAutoAdjustSampleDistances(0);
  slice->SetSampleDistance(result.sampleDistance);
  slice->SetNumberOfSlices(options.slices);
  slice->SetBoundaryRerendering(options.boundaryRerender);
  slice->SetEarlyRayTermination(options.earlyRayTermination);
  if (options.ertInterval > 0)
  {
    slice->SetEarlyRayTerminationInterval(options.ertInterval);
  }
  slice->SetEmptySpaceSkipping(options.emptySpaceSkipping);
  slice->SetPrecomputeGradients(options.precomputeGradients);
  slice->SetJittering(options.jitter);
  slice->SetGPUSliceGeneration(options.gpuSlices);
  slice->SetHalfFloatTarget(options.halfFloatTarget);
  slice->SetSliceCompositing(options.sliceCompositing);
  if (options.slabSamples > 0)
  {
    slice->SetSlabSamples(options.slabSamples);
  }
  slice->SetGPUMemoryBudget(static_cast<vtkIdType>(options.gpuBudgetMiB * 1024 * 1024));
  slice->SetMaximumBrickSize(options.maxBrick);
  slice->SetAdditiveUnitDistance(result.raysumUnit);
}

void ConfigureRayCast(
  vtkAccelVolumeRayCastMapper* rayCast, const Options& options, const RenderResult& result)
{
  // Deterministic frames: always the still-frame sample distances, whatever the frame time.
  rayCast->SetAutoAdjustSampleDistances(0);
  rayCast->SetSampleDistance(result.sampleDistance);
  rayCast->SetInteractiveSampleDistance(result.sampleDistance);
  rayCast->SetImageSampleDistance(options.imageSampleDistance);
  rayCast->SetEarlyRayTermination(options.earlyRayTermination);
  rayCast->SetAdditiveUnitDistance(result.raysumUnit);
  rayCast->SetNumberOfThreads(options.threads);
  // --leap and --cell-leap default to the mapper's own defaults (distance map, off).
  if (options.haveCellLeap)
  {
    rayCast->SetCellLeaping(options.cellLeap);
  }
  if (options.haveLeap)
  {
    rayCast->SetLeapMode(options.leap == LeapKind::None ? vtkAccelVolumeRayCastMapper::LEAP_NONE
        : options.leap == LeapKind::Octree              ? vtkAccelVolumeRayCastMapper::LEAP_OCTREE
                                           : vtkAccelVolumeRayCastMapper::LEAP_DISTANCE_MAP);
  }
}

void ConfigureShearWarp(
  vtkAccelVolumeShearWarpMapper* shearWarp, const Options& options, vtkAccelVolumeMPIExchange* mpi)
{
  shearWarp->SetNumberOfThreads(options.threads);
  shearWarp->SetEarlyRayTermination(options.earlyRayTermination);
  shearWarp->SetRunLengthEncoding(options.runLengthEncoding);
  shearWarp->SetLoadBalancing(options.balance);
  shearWarp->SetWarpOnGPU(options.warpOnGPU);
  shearWarp->SetBackgroundEncoding(options.backgroundEncoding);
  shearWarp->SetShadingMode(options.phongShading
      ? vtkAccelVolumeShearWarpMapper::SHADING_PHONG
      : vtkAccelVolumeShearWarpMapper::SHADING_LOOKUP_TABLE);
  if (mpi)
  {
    shearWarp->SetController(mpi->GetController());
    shearWarp->SetCommunicationTimeout(options.mpiTimeout);
  }
}

// The ray caster's settings as it holds them and its last frame's counters and timings.
void ReadRayCastResult(vtkAccelVolumeRayCastMapper* mapper, RenderResult& result)
{
  RayCastResult& out = result.rayCast;
  result.rayCastUsed = true;
  const int leap = mapper->GetLeapMode();
  out.leap = leap == vtkAccelVolumeRayCastMapper::LEAP_NONE  ? LeapKind::None
    : leap == vtkAccelVolumeRayCastMapper::LEAP_DISTANCE_MAP ? LeapKind::DistanceMap
                                                             : LeapKind::Octree;
  out.cellLeap = mapper->GetCellLeaping() != 0;
  out.threads = mapper->GetNumberOfThreads();
  out.octreeLeafSize = mapper->GetOctreeLeafSize();
  out.imageSampleDistance = mapper->GetLastImageSampleDistance();
  out.rays = mapper->GetLastNumberOfRays();
  out.samples = mapper->GetLastNumberOfSamples();
  out.leapedOctree = mapper->GetLastSamplesLeapedByOctree();
  out.leapedDistanceMap = mapper->GetLastSamplesLeapedByDistanceMap();
  out.leapedCellTable = mapper->GetLastSamplesLeapedByCellTable();
  out.transparentCellSamples = mapper->GetLastSamplesInTransparentCells();
  out.terminatedRays = mapper->GetLastNumberOfTerminatedRays();
  out.octreeLeaps = mapper->GetLastNumberOfOctreeLeaps();
  out.distanceMapLeaps = mapper->GetLastNumberOfDistanceMapLeaps();
  out.culledPixels = mapper->GetLastNumberOfCulledPixels();
  out.packetRays = mapper->GetLastNumberOfPacketRays();
  out.accelerationBytes = mapper->GetAccelerationBytes();
  out.renderMs = 1000 * mapper->GetLastRenderTime();
  out.castMs = 1000 * mapper->GetLastCastTime();
  out.prepareMs = 1000 * mapper->GetLastPrepareTime();
  result.sampleDistance = mapper->GetLastSampleDistance();
}

// World distance between shear-warp's samples along a ray: one sample per slice of the principal
// axis, so the ray length across one index step of that axis (0 when unknown).
double ShearWarpSliceDistance(vtkImageData* image, vtkCamera* camera, int axis)
{
  if (axis < 0 || axis > 2)
  {
    return 0;
  }
  double direction[3];
  camera->GetDirectionOfProjection(direction);
  vtkMatrix4x4* indexToWorld = image->GetIndexToPhysicalMatrix();
  vtkNew<vtkMatrix3x3> linear;
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      linear->SetElement(r, c, indexToWorld->GetElement(r, c));
    }
  }
  linear->Invert();
  double inIndex[3];
  linear->MultiplyPoint(direction, inIndex);
  return std::fabs(inIndex[axis]) > 1e-12 ? 1.0 / std::fabs(inIndex[axis]) : 0;
}

// The shear-warp mapper's settings as it holds them and its last frame's counters and timings.
void ReadShearWarpResult(vtkAccelVolumeShearWarpMapper* mapper, vtkImageData* image,
  vtkCamera* camera, vtkAccelVolumeMPIExchange* mpi, RenderResult& result)
{
  ShearWarpResult& out = result.shearWarp;
  result.shearWarpUsed = true;
  out.runLengthEncoding = mapper->GetRunLengthEncoding() != 0;
  out.earlyRayTermination = mapper->GetEarlyRayTermination() != 0;
  out.balance = mapper->GetLoadBalancing() != 0;
  out.warpOnGPU = mapper->GetWarpOnGPU() != 0;
  out.phongShading = mapper->GetShadingMode() == vtkAccelVolumeShearWarpMapper::SHADING_PHONG;
  out.threads = mapper->GetNumberOfThreads();
  out.ranks = mpi ? mpi->GetNumberOfRanks() : 1;
  out.renderMs = 1000 * mapper->GetLastRenderTime();
  out.encodeMs = 1000 * mapper->GetLastEncodeTime();
  out.tableMs = 1000 * mapper->GetLastTableTime();
  out.compositeMs = 1000 * mapper->GetLastCompositeTime();
  out.gatherMs = 1000 * mapper->GetLastGatherTime();
  out.warpMs = 1000 * mapper->GetLastWarpTime();
  out.imbalance = mapper->GetLastImbalance();
  out.bandMs.clear();
  for (int band = 0; band < mapper->GetLastNumberOfBands(); ++band)
  {
    out.bandMs.push_back(1000 * mapper->GetLastBandTime(band));
  }
  out.voxels = mapper->GetLastNumberOfVoxels();
  out.samples = mapper->GetLastNumberOfSamples();
  out.skippedPixels = mapper->GetLastNumberOfSkippedPixels();
  if (out.ranks > 1)
  {
    // The mapper counts this rank's bands; the stats report the whole frame (collective: every
    // rank reads its result).
    const long long local[3] = { out.voxels, out.samples, out.skippedPixels };
    long long total[3] = { 0, 0, 0 };
    mpi->Sum(local, total, 3, "frame counters");
    out.voxels = total[0];
    out.samples = total[1];
    out.skippedPixels = total[2];
  }
  out.principalAxis = mapper->GetLastPrincipalAxis();
  out.storedVoxels = mapper->GetLastNumberOfStoredVoxels();
  out.encodedBytes = mapper->GetEncodedBytes();
  result.sampleDistance = ShearWarpSliceDistance(image, camera, out.principalAxis);
  result.sampleDistanceSource = "slice-spacing";
}

// The slice mapper's last frame: its time, geometry and what the accelerations did.
void ReadSliceResult(vtkAccelVolumeSliceMapper* mapper, RenderResult& result)
{
  SliceResult& out = result.slice;
  result.sliceUsed = true;
  out.renderMs = 1000 * mapper->GetLastRenderTime();
  out.proxyPolygons = mapper->GetLastNumberOfProxyPolygons();
  out.boundaryFaces = mapper->GetLastNumberOfBoundaryFaces();
  out.bricks = mapper->GetLastNumberOfBricks();
  out.bricksDrawn = mapper->GetLastNumberOfBricksDrawn();
  out.brickUploads = mapper->GetLastNumberOfBrickUploads();
  out.uploadedBytes = static_cast<double>(mapper->GetLastUploadedBytes());
  out.residentBytes = static_cast<double>(mapper->GetLastResidentBytes());
  result.sampleDistance = mapper->GetLastSliceSpacing();
  result.slices = mapper->GetLastNumberOfSlices();
  result.slabSamples = mapper->GetSlabSamples();
  result.terminationPasses = mapper->GetLastNumberOfTerminationPasses();
  result.slicesGenerated = mapper->GetLastSlicesGenerated();
  result.halfFloatTarget = mapper->GetHalfFloatTarget() != 0;
  result.computeSlices =
    mapper->GetLastSliceCompositing() == vtkAccelVolumeSliceMapper::SLICE_COMPOSITING_COMPUTE;
  result.transparentLeafFraction = mapper->GetLastTransparentLeafFraction();
  result.proxyAreaFraction = mapper->GetLastProxyAreaFraction();
}

const char* SmartModeName(int mode)
{
  switch (mode)
  {
    case vtkAccelVolumeSmartMapper::SLICE_RENDER:
      return MapperName(MapperKind::Slice);
    case vtkAccelVolumeSmartMapper::RAYCAST_RENDER:
      return MapperName(MapperKind::RayCast);
    case vtkAccelVolumeSmartMapper::SHEARWARP_RENDER:
      return MapperName(MapperKind::ShearWarp);
    default:
      return "none";
  }
}

} // namespace

MapperSet CreateMapper(const Options& options, RenderResult& result, vtkAccelVolumeMPIExchange* mpi)
{
  MapperSet set;
  switch (options.mapper)
  {
    case MapperKind::Slice:
    {
      auto slice = vtkSmartPointer<vtkAccelVolumeSliceMapper>::New();
      ConfigureSlice(slice, options, result);
      set.Slice = slice;
      set.Mapper = slice;
      break;
    }
    case MapperKind::RayCast:
    {
      auto rayCast = vtkSmartPointer<vtkAccelVolumeRayCastMapper>::New();
      ConfigureRayCast(rayCast, options, result);
      set.RayCast = rayCast;
      set.Mapper = rayCast;
      break;
    }
    case MapperKind::VTKGPU:
    {
      auto gpu = vtkSmartPointer<vtkGPUVolumeRayCastMapper>::New();
      gpu->SetAutoAdjustSampleDistances(0);
      gpu->SetSampleDistance(static_cast<float>(result.sampleDistance));
      set.Mapper = gpu;
      break;
    }
    case MapperKind::VTKFixed:
    {
      auto fixed = vtkSmartPointer<vtkFixedPointVolumeRayCastMapper>::New();
      fixed->SetAutoAdjustSampleDistances(0);
      fixed->SetSampleDistance(static_cast<float>(result.sampleDistance));
      fixed->SetInteractiveSampleDistance(static_cast<float>(result.sampleDistance));
      fixed->SetImageSampleDistance(static_cast<float>(options.imageSampleDistance));
      if (options.threads > 0)
      {
        fixed->SetNumberOfThreads(options.threads);
      }
      set.Mapper = fixed;
      break;
    }
    case MapperKind::ShearWarp:
    {
      auto shearWarp = vtkSmartPointer<vtkAccelVolumeShearWarpMapper>::New();
      ConfigureShearWarp(shearWarp, options, mpi);
      result.sampleDistanceSource = "slice-spacing";
      set.ShearWarp = shearWarp;
      set.Mapper = shearWarp;
      break;
    }
    case MapperKind::Smart:
    {
      // Each owned mapper as its own --mapper would set it; the smart mapper picks one per
      // frame and forwards the blend mode, input and cropping.
      auto smart = vtkSmartPointer<vtkAccelVolumeSmartMapper>::New();
      ConfigureSlice(smart->GetSliceMapper(), options, result);
      ConfigureRayCast(smart->GetRayCastMapper(), options, result);
      ConfigureShearWarp(smart->GetShearWarpMapper(), options, nullptr);
      set.Slice = smart->GetSliceMapper();
      set.RayCast = smart->GetRayCastMapper();
      set.ShearWarp = smart->GetShearWarpMapper();
      set.Smart = smart;
      set.Mapper = smart;
      break;
    }
  }
  return set;
}

void ReadFirstFrame(const MapperSet& set, RenderResult& result)
{
  const int mode = set.Smart ? set.Smart->GetLastRenderMode() : -1;
  if (set.RayCast && (!set.Smart || mode == vtkAccelVolumeSmartMapper::RAYCAST_RENDER))
  {
    result.rayCast.firstPrepareMs = 1000 * set.RayCast->GetLastPrepareTime();
  }
  if (set.ShearWarp && (!set.Smart || mode == vtkAccelVolumeSmartMapper::SHEARWARP_RENDER))
  {
    result.shearWarp.firstEncodeMs = 1000 * set.ShearWarp->GetLastEncodeTime();
  }
}

void ReadMapperResults(const MapperSet& set, vtkImageData* image, vtkCamera* camera,
  vtkAccelVolumeMPIExchange* mpi, RenderResult& result)
{
  // The smart mapper's counters are those of the mapper its last frame used.
  const int mode = set.Smart ? set.Smart->GetLastRenderMode() : -1;
  const auto used = [&](const void* mapper, int smartMode)
  { return mapper && (!set.Smart || mode == smartMode); };
  if (set.Smart)
  {
    result.smartUsed = true;
    result.smart.mode = SmartModeName(mode);
    result.smart.reason = set.Smart->GetLastChoiceReason();
    result.smart.renderMs = 1000 * set.Smart->GetLastRenderTime();
  }
  if (used(set.Slice, vtkAccelVolumeSmartMapper::SLICE_RENDER))
  {
    ReadSliceResult(set.Slice, result);
  }
  if (used(set.RayCast, vtkAccelVolumeSmartMapper::RAYCAST_RENDER))
  {
    ReadRayCastResult(set.RayCast, result);
  }
  if (used(set.ShearWarp, vtkAccelVolumeSmartMapper::SHEARWARP_RENDER))
  {
    ReadShearWarpResult(set.ShearWarp, image, camera, mpi, result);
  }
  // The mapper's own time for its last Render (VTK's mappers: vtkAbstractMapper::TimeToDraw).
  if (set.Smart)
  {
    result.mapperRenderMs = result.smart.renderMs;
  }
  else if (result.sliceUsed)
  {
    result.mapperRenderMs = result.slice.renderMs;
  }
  else if (result.rayCastUsed)
  {
    result.mapperRenderMs = result.rayCast.renderMs;
  }
  else if (result.shearWarpUsed)
  {
    result.mapperRenderMs = result.shearWarp.renderMs;
  }
  else
  {
    result.mapperRenderMs = 1000 * set.Mapper->GetTimeToDraw();
  }
}

} // namespace accelvolume::cli
