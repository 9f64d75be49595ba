// OctreeStats: the JSON document and summary line of `accelvolume octree`.
#include "OctreeCommand.h"

#include "Stats.h"

#include <vtkAccelVolumeMinMaxOctree.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#ifndef ACCELVOLUME_VERSION
#define ACCELVOLUME_VERSION "unknown"
#endif

namespace accelvolume::cli
{
namespace
{

struct Spread
{
  double median = 0, min = 0, max = 0;
};

Spread SpreadOf(std::vector<double> values)
{
  Spread spread;
  if (!values.empty())
  {
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    spread.median = n % 2 ? values[n / 2] : (values[n / 2 - 1] + values[n / 2]) / 2;
    spread.min = values.front();
    spread.max = values.back();
  }
  return spread;
}

std::string Number(double value)
{
  if (!std::isfinite(value))
  {
    return "null";
  }
  std::ostringstream stream;
  stream.precision(10);
  stream << value;
  return stream.str();
}

} // namespace

const char* BuilderName(int builder)
{
  switch (builder)
  {
    case vtkAccelVolumeMinMaxOctree::BUILDER_REFERENCE:
      return "reference";
    case vtkAccelVolumeMinMaxOctree::BUILDER_GPU:
      return "gpu";
    default:
      return "cpu";
  }
}

void WriteOctreeStats(
  std::ostream& out, const OctreeOptions& options, vtkImageData* image, const OctreeResult& result)
{
  const Spread build = SpreadOf(result.buildMs);
  const Spread floor = SpreadOf(result.readFloorMs);
  const Spread classify = SpreadOf(result.classifyMs);
  int dims[3];
  image->GetDimensions(dims);
  const std::string description = DescribeVolume(image);
  const std::string type = description.substr(description.find(' ') + 1);
  std::string list;
  for (const double ms : result.buildMs)
  {
    list += (list.empty() ? "" : ", ") + Number(ms);
  }
  const bool phantom = options.volume.inputPath.empty();
  out << "{\n"
      << "  \"tool\": \"accelvolume octree\",\n"
      << "  \"version\": " << JsonString(ACCELVOLUME_VERSION) << ",\n"
      << "  \"builder\": " << JsonString(BuilderName(options.builder)) << ",\n"
      << "  \"threads\": " << result.threads << ",\n"
      << "  \"leaf\": " << options.leaf << ",\n"
      << "  \"input\": " << JsonString(phantom ? options.volume.phantom : options.volume.inputPath)
      << ",\n"
      << "  \"input_kind\": " << JsonString(phantom ? "phantom" : "file") << ",\n"
      << "  \"dims\": [" << dims[0] << ", " << dims[1] << ", " << dims[2] << "],\n"
      << "  \"type\": " << JsonString(type) << ",\n"
      << "  \"scalar_range\": [" << Number(result.range[0]) << ", " << Number(result.range[1])
      << "],\n"
      << "  \"repeat\": " << options.repeat << ",\n"
      << "  \"ms\": {\"median\": " << Number(build.median) << ", \"min\": " << Number(build.min)
      << ", \"max\": " << Number(build.max) << "},\n"
      << "  \"build_ms\": [" << list << "],\n"
      << "  \"nodes\": " << result.nodes << ",\n"
      << "  \"depth\": " << result.depth << ",\n"
      << "  \"leaf_grid\": [" << result.leafGrid[0] << ", " << result.leafGrid[1] << ", "
      << result.leafGrid[2] << "],\n"
      << "  \"bytes\": " << result.bytes << ",\n"
      << "  \"bytes_per_s\": " << Number(result.bytes / (build.median / 1000.0)) << ",\n"
      << "  \"read_floor_ms\": " << Number(floor.median) << ",\n"
      << "  \"ratio_to_floor\": " << Number(build.median / floor.median) << ",\n"
      << "  \"tf_low\": " << Number(result.tfLow) << ",\n"
      << "  \"tf_low_alternate\": " << Number(result.tfLowAlternate) << ",\n"
      << "  \"classify_ms\": {\"median\": " << Number(classify.median)
      << ", \"min\": " << Number(classify.min) << "},\n"
      << "  \"transparent_leaf_fraction\": " << Number(result.transparentLeafFraction) << ",\n"
      << "  \"gl_renderer\": "
      << (result.glRenderer.empty() ? "null" : JsonString(result.glRenderer)) << "\n"
      << "}\n";
}

std::string OctreeSummary(
  const OctreeOptions& options, vtkImageData* image, const OctreeResult& result)
{
  const Spread build = SpreadOf(result.buildMs);
  const Spread floor = SpreadOf(result.readFloorMs);
  const Spread classify = SpreadOf(result.classifyMs);
  std::ostringstream text;
  text.precision(4);
  const std::string where = !result.glRenderer.empty() ? result.glRenderer
    : result.threads == 1                              ? std::string("1 thread")
                          : std::to_string(result.threads) + " threads";
  text << "octree " << BuilderName(options.builder) << " (" << where << ") leaf " << options.leaf
       << ", "
       << (options.volume.inputPath.empty() ? "phantom " + options.volume.phantom
                                            : options.volume.inputPath)
       << " " << DescribeVolume(image) << ": " << build.median << " ms (median of "
       << result.buildMs.size() << ", min " << build.min << "), "
       << result.bytes / (build.median / 1000.0) / 1e9 << " GB/s, read floor " << floor.median
       << " ms (x" << build.median / floor.median << "), " << result.nodes << " nodes, depth "
       << result.depth << ", classify " << classify.median << " ms, "
       << 100.0 * result.transparentLeafFraction << "% leaves transparent";
  return text.str();
}

} // namespace accelvolume::cli
