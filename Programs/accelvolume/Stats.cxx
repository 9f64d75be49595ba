// Stats: JSON output of accelvolume render --stats.
#include "Stats.h"

#include "JsonOutput.h"
#include "VolumeIO.h"

#include <vtkDataArray.h>
#include <vtkPointData.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>
#include <vector>

#ifndef ACCELVOLUME_VERSION
#define ACCELVOLUME_VERSION "unknown"
#endif

namespace accelvolume::cli
{
namespace
{

// [[g, a], ...] or null when no gradient opacity was set.
JsonDocument GradientOpacity(const AppliedTransferFunction& applied)
{
  if (applied.gradientOpacity.empty())
  {
    return nullptr;
  }
  JsonDocument points = JsonDocument::array();
  for (const auto& point : applied.gradientOpacity)
  {
    points.push_back({ JsonNumber(point[0]), JsonNumber(point[1]) });
  }
  return points;
}

JsonDocument Numbers(const double* values, int count)
{
  JsonDocument array = JsonDocument::array();
  for (int i = 0; i < count; ++i)
  {
    array.push_back(JsonNumber(values[i]));
  }
  return array;
}

struct FrameStatistics
{
  double median = 0, min = 0, max = 0, mean = 0;
};

FrameStatistics Statistics(std::vector<double> ms)
{
  FrameStatistics statistics;
  if (ms.empty())
  {
    return statistics;
  }
  std::sort(ms.begin(), ms.end());
  const std::size_t n = ms.size();
  statistics.median = n % 2 ? ms[n / 2] : (ms[n / 2 - 1] + ms[n / 2]) / 2;
  statistics.min = ms.front();
  statistics.max = ms.back();
  statistics.mean = std::accumulate(ms.begin(), ms.end(), 0.0) / n;
  return statistics;
}

// The "raycast" object: the ray caster's settings and last-frame counters, or null.
JsonDocument RayCastObject(const RenderResult& result)
{
  if (!result.rayCastUsed)
  {
    return nullptr;
  }
  const RayCastResult& r = result.rayCast;
  JsonDocument o;
  o["leap"] = LeapName(r.leap);
  o["cell_leap"] = r.cellLeap;
  o["threads"] = r.threads;
  o["octree_leaf_size"] = r.octreeLeafSize;
  o["image_sample_distance"] = JsonNumber(r.imageSampleDistance);
  o["rays"] = r.rays;
  o["samples"] = r.samples;
  o["leaped_octree"] = r.leapedOctree;
  o["leaped_distance_map"] = r.leapedDistanceMap;
  o["leaped_cell_table"] = r.leapedCellTable;
  o["transparent_cell_samples"] = r.transparentCellSamples;
  o["terminated_rays"] = r.terminatedRays;
  o["octree_leaps"] = r.octreeLeaps;
  o["distance_map_leaps"] = r.distanceMapLeaps;
  o["culled_pixels"] = r.culledPixels;
  o["packet_rays"] = r.packetRays;
  o["acceleration_bytes"] = r.accelerationBytes;
  o["render_ms"] = JsonNumber(r.renderMs);
  o["cast_ms"] = JsonNumber(r.castMs);
  o["prepare_ms"] = JsonNumber(r.prepareMs);
  o["first_prepare_ms"] = JsonNumber(r.firstPrepareMs);
  return o;
}

// The "shearwarp" object: the shear-warp mapper's settings, last-frame timings (rank 0's; band_ms
// holds every rank's bands) and counters (voxels, samples, skipped pixels summed over the ranks;
// stored voxels and encoded bytes per rank), or null.
JsonDocument ShearWarpObject(const RenderResult& result)
{
  if (!result.shearWarpUsed)
  {
    return nullptr;
  }
  const ShearWarpResult& w = result.shearWarp;
  static const char* const axes[] = { "x", "y", "z" };
  JsonDocument o;
  o["rle"] = w.runLengthEncoding;
  o["ert"] = w.earlyRayTermination;
  o["balance"] = w.balance;
  o["shading"] = w.phongShading ? "phong" : "table";
  o["warp"] = w.warpOnGPU ? "gpu" : "cpu";
  o["threads"] = w.threads;
  o["ranks"] = w.ranks;
  o["render_ms"] = JsonNumber(w.renderMs);
  o["encode_ms"] = JsonNumber(w.encodeMs);
  o["first_encode_ms"] = JsonNumber(w.firstEncodeMs);
  o["table_ms"] = JsonNumber(w.tableMs);
  o["composite_ms"] = JsonNumber(w.compositeMs);
  o["gather_ms"] = JsonNumber(w.gatherMs);
  o["warp_ms"] = JsonNumber(w.warpMs);
  o["imbalance"] = JsonNumber(w.imbalance);
  o["bands"] = w.bandMs.size();
  o["band_ms"] = Numbers(w.bandMs.data(), static_cast<int>(w.bandMs.size()));
  o["voxels"] = w.voxels;
  o["samples"] = w.samples;
  o["skipped_pixels"] = w.skippedPixels;
  o["principal_axis"] = w.principalAxis >= 0 && w.principalAxis < 3
    ? JsonDocument(axes[w.principalAxis])
    : JsonDocument(nullptr);
  o["stored_voxels"] = w.storedVoxels;
  o["encoded_bytes"] = w.encodedBytes;
  return o;
}

// The "slice" object: the slice mapper's last frame (its slice count, passes and skipping
// fractions are top-level keys), or null.
JsonDocument SliceObject(const RenderResult& result)
{
  if (!result.sliceUsed)
  {
    return nullptr;
  }
  const SliceResult& s = result.slice;
  JsonDocument o;
  o["render_ms"] = JsonNumber(s.renderMs);
  o["slices"] = result.slices;
  o["proxy_polygons"] = s.proxyPolygons;
  o["boundary_faces"] = s.boundaryFaces;
  o["termination_passes"] = result.terminationPasses;
  o["gpu_slices"] = result.slicesGenerated;
  o["half_float_target"] = result.halfFloatTarget;
  o["compositing"] = result.computeSlices ? "compute" : "raster";
  o["bricks"] = s.bricks;
  o["bricks_drawn"] = s.bricksDrawn;
  o["brick_uploads"] = s.brickUploads;
  o["uploaded_bytes"] = JsonNumber(s.uploadedBytes);
  o["resident_bytes"] = JsonNumber(s.residentBytes);
  return o;
}

// The "smart" object: the smart mapper's choice for the last frame, why, and its own time (the
// chosen mapper's counters are in its own object), or null.
JsonDocument SmartObject(const RenderResult& result)
{
  if (!result.smartUsed)
  {
    return nullptr;
  }
  JsonDocument o;
  o["mode"] = result.smart.mode;
  o["reason"] = result.smart.reason;
  o["render_ms"] = JsonNumber(result.smart.renderMs);
  return o;
}

std::string TypeName(vtkImageData* image)
{
  // DescribeVolume gives "XxYxZ type"; the type is the part after the space.
  const std::string description = DescribeVolume(image);
  const auto space = description.find(' ');
  return space == std::string::npos ? "unknown" : description.substr(space + 1);
}

} // namespace

void WriteStats(std::ostream& stream, const Options& options, vtkImageData* image,
  const RenderResult& result, int warnings)
{
  const FrameStatistics frames = Statistics(result.frameMs);
  int dims[3];
  image->GetDimensions(dims);
  const bool phantom = options.volume.inputPath.empty();
  const bool smart = options.mapper == MapperKind::Smart;
  const bool sampledImage =
    options.mapper == MapperKind::RayCast || options.mapper == MapperKind::VTKFixed || smart;
  const bool cpu = sampledImage || options.mapper == MapperKind::ShearWarp;
  const std::size_t listed = std::min<std::size_t>(result.frameMs.size(), 10000);
  const auto optional = [](bool present, const JsonDocument& value)
  { return present ? value : JsonDocument(nullptr); };
  JsonDocument d;
  d["tool"] = "accelvolume";
  d["version"] = ACCELVOLUME_VERSION;
  d["mapper"] = MapperName(options.mapper);
  d["blend"] = BlendName(options.blend);
  d["width"] = options.size[0];
  d["height"] = options.size[1];
  d["frames"] = options.frames;
  d["ms_per_frame"] = { { "median", JsonNumber(frames.median) }, { "min", JsonNumber(frames.min) },
    { "max", JsonNumber(frames.max) }, { "mean", JsonNumber(frames.mean) } };
  d["first_frame_ms"] = JsonNumber(result.firstFrameMs);
  d["mapper_render_ms"] = JsonNumber(result.mapperRenderMs);
  d["frame_ms"] = Numbers(result.frameMs.data(), static_cast<int>(listed));
  d["gl_renderer"] = result.glRenderer;
  d["gl_backend"] = result.glBackend;
  d["input"] = phantom ? options.volume.phantom : options.volume.inputPath;
  d["input_kind"] = phantom ? "phantom" : "file";
  d["dims"] = { dims[0], dims[1], dims[2] };
  d["type"] = TypeName(image);
  d["spacing"] = Numbers(image->GetSpacing(), 3);
  d["origin"] = Numbers(image->GetOrigin(), 3);
  d["scalar_range"] = Numbers(result.scalarRange, 2);
  d["window"] = Numbers(result.window, 2);
  d["raysum_unit"] =
    optional(options.mapper == MapperKind::Slice || options.mapper == MapperKind::RayCast || smart,
      JsonNumber(result.raysumUnit));
  d["sample_distance"] = JsonNumber(result.sampleDistance);
  d["sample_distance_source"] = result.sampleDistanceSource;
  d["slices"] = optional(result.slices >= 0, result.slices);
  d["ert"] = options.earlyRayTermination;
  d["ert_passes"] = result.terminationPasses;
  d["ess"] = options.emptySpaceSkipping;
  d["transparent_leaf_fraction"] = JsonNumber(result.transparentLeafFraction);
  d["slice_area_kept"] = JsonNumber(result.proxyAreaFraction);
  d["slab_samples"] = optional(result.slabSamples >= 0, result.slabSamples);
  d["boundary_rerender"] =
    optional(options.mapper == MapperKind::Slice || smart, options.boundaryRerender);
  d["tf"] = optional(!options.transferFunction.empty(), options.transferFunction);
  d["shade"] = result.transferFunction.shade;
  d["gradient_opacity"] = GradientOpacity(result.transferFunction);
  const AppliedTransferFunction& lighting = result.transferFunction;
  d["lighting"] = { { "ambient", JsonNumber(lighting.ambient) },
    { "diffuse", JsonNumber(lighting.diffuse) }, { "specular", JsonNumber(lighting.specular) },
    { "specular_power", JsonNumber(lighting.specularPower) } };
  d["crop"] = optional(options.haveCrop, Numbers(options.crop, 6));
  d["crop_planes"] = optional(options.haveCrop, Numbers(result.cropPlanes, 6));
  d["camera"] = { { "azimuth", JsonNumber(options.azimuth) },
    { "elevation", JsonNumber(options.elevation) }, { "roll", JsonNumber(options.roll) },
    { "zoom", JsonNumber(options.zoom) }, { "parallel", options.parallel },
    { "final_azimuth", JsonNumber(options.azimuth + 2.0 * (options.frames - 1)) } };
  d["background"] = Numbers(options.background, 3);
  d["out"] = optional(!options.outPath.empty(), options.outPath);
  d["threads"] = optional(cpu, options.threads);
  d["image_sample_distance"] = optional(sampledImage, JsonNumber(options.imageSampleDistance));
  d["raycast"] = RayCastObject(result);
  d["shearwarp"] = ShearWarpObject(result);
  d["slice"] = SliceObject(result);
  d["smart"] = SmartObject(result);
  d["vtk_warnings"] = warnings;
  WriteJsonDocument(stream, d);
}

std::string Summary(const Options& options, vtkImageData* image, const RenderResult& result)
{
  const FrameStatistics frames = Statistics(result.frameMs);
  std::ostringstream text;
  text.precision(4);
  text << MapperName(options.mapper) << " " << BlendName(options.blend) << " " << options.size[0]
       << "x" << options.size[1] << ", "
       << (options.volume.inputPath.empty() ? "phantom " + options.volume.phantom
                                            : options.volume.inputPath)
       << " " << DescribeVolume(image) << ": " << frames.median << " ms/frame (median of "
       << result.frameMs.size() << "; first " << result.firstFrameMs << " ms), sample distance "
       << result.sampleDistance;
  if (result.slices >= 0)
  {
    text << ", " << result.slices << " slices";
  }
  if (result.smartUsed)
  {
    text << ", chose " << result.smart.mode;
  }
  if (result.rayCastUsed)
  {
    text << ", leap " << LeapName(result.rayCast.leap) << ", cell leap "
         << (result.rayCast.cellLeap ? "on" : "off") << ", " << result.rayCast.samples
         << " samples";
  }
  if (result.shearWarpUsed)
  {
    const ShearWarpResult& w = result.shearWarp;
    text << ", axis "
         << "xyz?"[w.principalAxis >= 0 && w.principalAxis < 3 ? w.principalAxis : 3] << ", "
         << w.bandMs.size() << " bands on " << w.ranks << " rank" << (w.ranks == 1 ? "" : "s")
         << ", imbalance " << w.imbalance << ", " << w.samples << " samples";
  }
  text << ", " << result.glBackend << " / " << result.glRenderer;
  if (!options.outPath.empty())
  {
    text << " -> " << options.outPath;
  }
  return text.str();
}

} // namespace accelvolume::cli
