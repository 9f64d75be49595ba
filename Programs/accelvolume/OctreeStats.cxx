// OctreeStats: the JSON document and summary line of `accelvolume octree`.
#include "OctreeCommand.h"

#include "JsonOutput.h"
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
  const bool phantom = options.volume.inputPath.empty();
  JsonDocument buildMs = JsonDocument::array();
  for (const double ms : result.buildMs)
  {
    buildMs.push_back(JsonNumber(ms));
  }
  JsonDocument d;
  d["tool"] = "accelvolume octree";
  d["version"] = ACCELVOLUME_VERSION;
  d["builder"] = BuilderName(options.builder);
  d["threads"] = result.threads;
  d["leaf"] = options.leaf;
  d["input"] = phantom ? options.volume.phantom : options.volume.inputPath;
  d["input_kind"] = phantom ? "phantom" : "file";
  d["dims"] = { dims[0], dims[1], dims[2] };
  d["type"] = description.substr(description.find(' ') + 1);
  d["scalar_range"] = { JsonNumber(result.range[0]), JsonNumber(result.range[1]) };
  d["repeat"] = options.repeat;
  d["ms"] = { { "median", JsonNumber(build.median) }, { "min", JsonNumber(build.min) },
    { "max", JsonNumber(build.max) } };
  d["build_ms"] = buildMs;
  d["nodes"] = result.nodes;
  d["depth"] = result.depth;
  d["leaf_grid"] = { result.leafGrid[0], result.leafGrid[1], result.leafGrid[2] };
  d["bytes"] = result.bytes;
  d["bytes_per_s"] = JsonNumber(result.bytes / (build.median / 1000.0));
  d["read_floor_ms"] = JsonNumber(floor.median);
  d["ratio_to_floor"] = JsonNumber(build.median / floor.median);
  d["tf_low"] = JsonNumber(result.tfLow);
  d["tf_low_alternate"] = JsonNumber(result.tfLowAlternate);
  d["classify_ms"] = { { "median", JsonNumber(classify.median) },
    { "min", JsonNumber(classify.min) } };
  d["transparent_leaf_fraction"] = JsonNumber(result.transparentLeafFraction);
  d["gl_renderer"] = result.glRenderer.empty() ? JsonDocument(nullptr) : JsonDocument(result.glRenderer);
  WriteJsonDocument(out, d);
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
