// Stats: JSON output of accelvolume render --stats.
#include "Stats.h"

#include "VolumeIO.h"

#include <vtkDataArray.h>
#include <vtkPointData.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
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

std::string Number(double value)
{
  if (!std::isfinite(value))
  {
    return "null";
  }
  std::ostringstream stream;
  stream.precision(12);
  stream << value;
  return stream.str();
}

std::string Array(const double* values, int count)
{
  std::string text = "[";
  for (int i = 0; i < count; ++i)
  {
    text += (i ? ", " : "") + Number(values[i]);
  }
  return text + "]";
}

// [[g, a], ...] or null when no gradient opacity was set.
std::string GradientOpacity(const AppliedTransferFunction& applied)
{
  if (applied.gradientOpacity.empty())
  {
    return "null";
  }
  std::string text = "[";
  for (const auto& point : applied.gradientOpacity)
  {
    text += (text.size() > 1 ? ", " : "") + Array(point.data(), 2);
  }
  return text + "]";
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
std::string RayCastObject(const RenderResult& result)
{
  if (!result.rayCastUsed)
  {
    return "null";
  }
  const RayCastResult& r = result.rayCast;
  std::ostringstream text;
  text << "{\"leap\": " << JsonString(LeapName(r.leap))
       << ", \"cell_leap\": " << (r.cellLeap ? "true" : "false") << ", \"threads\": " << r.threads
       << ", \"octree_leaf_size\": " << r.octreeLeafSize
       << ", \"image_sample_distance\": " << Number(r.imageSampleDistance)
       << ",\n    \"rays\": " << r.rays << ", \"samples\": " << r.samples
       << ", \"leaped_octree\": " << r.leapedOctree
       << ", \"leaped_distance_map\": " << r.leapedDistanceMap
       << ", \"leaped_cell_table\": " << r.leapedCellTable
       << ", \"transparent_cell_samples\": " << r.transparentCellSamples
       << ", \"terminated_rays\": " << r.terminatedRays
       << ", \"octree_leaps\": " << r.octreeLeaps
       << ", \"distance_map_leaps\": " << r.distanceMapLeaps
       << ", \"acceleration_bytes\": " << r.accelerationBytes
       << ",\n    \"render_ms\": " << Number(r.renderMs) << ", \"cast_ms\": " << Number(r.castMs)
       << ", \"prepare_ms\": " << Number(r.prepareMs)
       << ", \"first_prepare_ms\": " << Number(r.firstPrepareMs) << "}";
  return text.str();
}

// The "shearwarp" object: the shear-warp mapper's settings, last-frame timings (rank 0's; band_ms
// holds every rank's bands) and counters (voxels, samples, skipped pixels summed over the ranks;
// stored voxels and encoded bytes per rank), or null.
std::string ShearWarpObject(const RenderResult& result)
{
  if (!result.shearWarpUsed)
  {
    return "null";
  }
  const ShearWarpResult& w = result.shearWarp;
  std::string bands;
  for (std::size_t i = 0; i < w.bandMs.size(); ++i)
  {
    bands += (i ? ", " : "") + Number(w.bandMs[i]);
  }
  static const char* const axes[] = { "x", "y", "z" };
  std::ostringstream text;
  text << "{\"rle\": " << (w.runLengthEncoding ? "true" : "false")
       << ", \"ert\": " << (w.earlyRayTermination ? "true" : "false")
       << ", \"balance\": " << (w.balance ? "true" : "false")
       << ", \"shading\": " << JsonString(w.phongShading ? "phong" : "table")
       << ", \"threads\": " << w.threads << ", \"ranks\": " << w.ranks
       << ",\n    \"render_ms\": " << Number(w.renderMs) << ", \"encode_ms\": " << Number(w.encodeMs)
       << ", \"first_encode_ms\": " << Number(w.firstEncodeMs)
       << ", \"table_ms\": " << Number(w.tableMs) << ", \"composite_ms\": " << Number(w.compositeMs)
       << ", \"gather_ms\": " << Number(w.gatherMs) << ", \"warp_ms\": " << Number(w.warpMs)
       << ",\n    \"imbalance\": " << Number(w.imbalance) << ", \"bands\": " << w.bandMs.size()
       << ", \"band_ms\": [" << bands << "]"
       << ",\n    \"voxels\": " << w.voxels << ", \"samples\": " << w.samples
       << ", \"skipped_pixels\": " << w.skippedPixels << ", \"principal_axis\": "
       << (w.principalAxis >= 0 && w.principalAxis < 3 ? JsonString(axes[w.principalAxis])
                                                       : std::string("null"))
       << ", \"stored_voxels\": " << w.storedVoxels << ", \"encoded_bytes\": " << w.encodedBytes
       << "}";
  return text.str();
}

// The "slice" object: the slice mapper's last frame (its slice count, passes and skipping
// fractions are top-level keys), or null.
std::string SliceObject(const RenderResult& result)
{
  if (!result.sliceUsed)
  {
    return "null";
  }
  const SliceResult& s = result.slice;
  std::ostringstream text;
  text << "{\"render_ms\": " << Number(s.renderMs) << ", \"slices\": " << result.slices
       << ", \"proxy_polygons\": " << s.proxyPolygons
       << ", \"boundary_faces\": " << s.boundaryFaces
       << ", \"termination_passes\": " << result.terminationPasses
       << ", \"bricks\": " << s.bricks << ", \"bricks_drawn\": " << s.bricksDrawn
       << ", \"brick_uploads\": " << s.brickUploads
       << ", \"uploaded_bytes\": " << Number(s.uploadedBytes)
       << ", \"resident_bytes\": " << Number(s.residentBytes) << "}";
  return text.str();
}

// The "smart" object: the smart mapper's choice for the last frame, why, and its own time (the
// chosen mapper's counters are in its own object), or null.
std::string SmartObject(const RenderResult& result)
{
  if (!result.smartUsed)
  {
    return "null";
  }
  const SmartResult& s = result.smart;
  std::ostringstream text;
  text << "{\"mode\": " << JsonString(s.mode) << ", \"reason\": " << JsonString(s.reason)
       << ", \"render_ms\": " << Number(s.renderMs) << "}";
  return text.str();
}

std::string TypeName(vtkImageData* image)
{
  // DescribeVolume gives "XxYxZ type"; the type is the part after the space.
  const std::string description = DescribeVolume(image);
  const auto space = description.find(' ');
  return space == std::string::npos ? "unknown" : description.substr(space + 1);
}

} // namespace

std::string JsonString(const std::string& text)
{
  std::string out = "\"";
  for (const char c : text)
  {
    switch (c)
    {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\r':
        out += "\\r";
        break;
      case '\t':
        out += "\\t";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20)
        {
          char escape[8];
          std::snprintf(escape, sizeof(escape), "\\u%04x", static_cast<unsigned char>(c));
          out += escape;
        }
        else
        {
          out += c;
        }
    }
  }
  return out + "\"";
}

void WriteStats(std::ostream& stream, const Options& options, vtkImageData* image,
  const RenderResult& result, int warnings)
{
  const FrameStatistics frames = Statistics(result.frameMs);
  int dims[3];
  image->GetDimensions(dims);
  const double dimsDouble[3] = { double(dims[0]), double(dims[1]), double(dims[2]) };
  const bool phantom = options.volume.inputPath.empty();
  const std::string input = phantom ? options.volume.phantom : options.volume.inputPath;
  const bool smart = options.mapper == MapperKind::Smart;
  const bool sampledImage =
    options.mapper == MapperKind::RayCast || options.mapper == MapperKind::VTKFixed || smart;
  const bool cpu = sampledImage || options.mapper == MapperKind::ShearWarp;
  std::string frameList;
  for (std::size_t i = 0; i < result.frameMs.size() && i < 10000; ++i)
  {
    frameList += (i ? ", " : "") + Number(result.frameMs[i]);
  }
  stream << "{\n"
         << "  \"tool\": \"accelvolume\",\n"
         << "  \"version\": " << JsonString(ACCELVOLUME_VERSION) << ",\n"
         << "  \"mapper\": " << JsonString(MapperName(options.mapper)) << ",\n"
         << "  \"blend\": " << JsonString(BlendName(options.blend)) << ",\n"
         << "  \"width\": " << options.size[0] << ",\n"
         << "  \"height\": " << options.size[1] << ",\n"
         << "  \"frames\": " << options.frames << ",\n"
         << "  \"ms_per_frame\": {\"median\": " << Number(frames.median)
         << ", \"min\": " << Number(frames.min) << ", \"max\": " << Number(frames.max)
         << ", \"mean\": " << Number(frames.mean) << "},\n"
         << "  \"first_frame_ms\": " << Number(result.firstFrameMs) << ",\n"
         << "  \"mapper_render_ms\": " << Number(result.mapperRenderMs) << ",\n"
         << "  \"frame_ms\": [" << frameList << "],\n"
         << "  \"gl_renderer\": " << JsonString(result.glRenderer) << ",\n"
         << "  \"gl_backend\": " << JsonString(result.glBackend) << ",\n"
         << "  \"input\": " << JsonString(input) << ",\n"
         << "  \"input_kind\": " << JsonString(phantom ? "phantom" : "file") << ",\n"
         << "  \"dims\": " << Array(dimsDouble, 3) << ",\n"
         << "  \"type\": " << JsonString(TypeName(image)) << ",\n"
         << "  \"spacing\": " << Array(image->GetSpacing(), 3) << ",\n"
         << "  \"origin\": " << Array(image->GetOrigin(), 3) << ",\n"
         << "  \"scalar_range\": " << Array(result.scalarRange, 2) << ",\n"
         << "  \"window\": " << Array(result.window, 2) << ",\n"
         << "  \"raysum_unit\": "
         << (options.mapper == MapperKind::Slice || options.mapper == MapperKind::RayCast || smart
                ? Number(result.raysumUnit)
                : "null")
         << ",\n"
         << "  \"sample_distance\": " << Number(result.sampleDistance) << ",\n"
         << "  \"sample_distance_source\": " << JsonString(result.sampleDistanceSource) << ",\n"
         << "  \"slices\": " << (result.slices >= 0 ? std::to_string(result.slices) : "null")
         << ",\n"
         << "  \"ert\": " << (options.earlyRayTermination ? "true" : "false") << ",\n"
         << "  \"ert_passes\": " << result.terminationPasses << ",\n"
         << "  \"ess\": " << options.emptySpaceSkipping << ",\n"
         << "  \"transparent_leaf_fraction\": " << Number(result.transparentLeafFraction) << ",\n"
         << "  \"slice_area_kept\": " << Number(result.proxyAreaFraction) << ",\n"
         << "  \"slab_samples\": "
         << (result.slabSamples >= 0 ? std::to_string(result.slabSamples) : "null") << ",\n"
         << "  \"boundary_rerender\": "
         << (options.mapper == MapperKind::Slice || smart
                ? (options.boundaryRerender ? "true" : "false")
                : "null")
         << ",\n"
         << "  \"tf\": "
         << (options.transferFunction.empty() ? "null" : JsonString(options.transferFunction))
         << ",\n"
         << "  \"shade\": " << (result.transferFunction.shade ? "true" : "false") << ",\n"
         << "  \"gradient_opacity\": " << GradientOpacity(result.transferFunction) << ",\n"
         << "  \"lighting\": {\"ambient\": " << Number(result.transferFunction.ambient)
         << ", \"diffuse\": " << Number(result.transferFunction.diffuse)
         << ", \"specular\": " << Number(result.transferFunction.specular)
         << ", \"specular_power\": " << Number(result.transferFunction.specularPower) << "},\n"
         << "  \"crop\": " << (options.haveCrop ? Array(options.crop, 6) : "null") << ",\n"
         << "  \"crop_planes\": " << (options.haveCrop ? Array(result.cropPlanes, 6) : "null")
         << ",\n"
         << "  \"camera\": {\"azimuth\": " << Number(options.azimuth)
         << ", \"elevation\": " << Number(options.elevation)
         << ", \"roll\": " << Number(options.roll) << ", \"zoom\": " << Number(options.zoom)
         << ", \"parallel\": " << (options.parallel ? "true" : "false")
         << ", \"final_azimuth\": " << Number(options.azimuth + 2.0 * (options.frames - 1))
         << "},\n"
         << "  \"background\": " << Array(options.background, 3) << ",\n"
         << "  \"out\": " << (options.outPath.empty() ? "null" : JsonString(options.outPath))
         << ",\n"
         << "  \"threads\": " << (cpu ? std::to_string(options.threads) : "null") << ",\n"
         << "  \"image_sample_distance\": " << (sampledImage ? Number(options.imageSampleDistance) : "null")
         << ",\n"
         << "  \"raycast\": " << RayCastObject(result) << ",\n"
         << "  \"shearwarp\": " << ShearWarpObject(result) << ",\n"
         << "  \"slice\": " << SliceObject(result) << ",\n"
         << "  \"smart\": " << SmartObject(result) << ",\n"
         << "  \"vtk_warnings\": " << warnings << "\n"
         << "}\n";
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
    text << ", axis " << "xyz?"[w.principalAxis >= 0 && w.principalAxis < 3 ? w.principalAxis : 3]
         << ", " << w.bandMs.size() << " bands on " << w.ranks << " rank"
         << (w.ranks == 1 ? "" : "s") << ", imbalance " << w.imbalance << ", " << w.samples
         << " samples";
  }
  text << ", " << result.glBackend << " / " << result.glRenderer;
  if (!options.outPath.empty())
  {
    text << " -> " << options.outPath;
  }
  return text.str();
}

} // namespace accelvolume::cli
