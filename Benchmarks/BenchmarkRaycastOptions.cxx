// Command-line parsing, usage text and validation of accelvolume_benchmark_raycast's options.
#include "BenchmarkRaycastOptions.h"

#include "BenchmarkCommon.h"

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <thread>

namespace accelvolume::benchmark::raycast
{
namespace
{
void Usage()
{
  std::cout
    << "Usage: accelvolume_benchmark_raycast [options]\n"
       "  --data DIR          folder of the volumes and datasets.json (default "
    << ACCELVOLUME_BENCHMARK_DATA_DIR
    << ")\n"
       "  --datasets A,B      dataset names (default "
       "cthead,aneurism,cta_avm,boston_teapot,engine,\n"
       "                      bonsai_hazeremoved); a name maps to the file\n"
       "                      NAME_<X>x<Y>x<Z>_<type>.raw[.gz] in the data folder\n"
       "  --tfs A,B           transfer-function presets of `accelvolume render --tf` (default\n"
       "                      tf2,tf1)\n"
       "  --size N            square image size in pixels (default 512)\n"
       "  --frames N          timed frames per configuration (default 10)\n"
       "  --threads N         threads of every mapper (default: hardware threads)\n"
       "  --sample-factor F   sample distance = F x smallest voxel spacing (default 1)\n"
       "  --reference-factor K  the quality reference samples K times more densely (default 4)\n"
       "  --view AZ EL        initial camera azimuth / elevation in degrees (default 30 20)\n"
       "  --turn DEG          azimuth turn per timed round (default 3)\n"
       "  --shade on|off      Phong shading (default on)\n"
       "  --quick             smoke run: size 128, 2 frames, engine, tf2 (unless given)\n"
       "  --gl egl|osmesa|auto headless OpenGL backend (default egl)\n"
       "  --json FILE         machine-readable results (default "
       "accelvolume_benchmark_raycast.json)\n"
       "  --images DIR        save PNGs of the fixed view (ours, VTK, reference)\n"
       "Exit code: 0 ok, 1 a dataset or backend missing, 2 bad options, 3 our six leaping\n"
       "configurations gave different images.\n";
}

} // namespace

bool ParseArguments(int argc, char* argv[], Options& options)
{
  bool haveSize = false, haveFrames = false, haveDatasets = false, haveTfs = false;
  std::string shade = "on";
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    // True when `arg` is `name` and is followed by one value per field, which it then consumes.
    auto option = [&](const char* name, auto&... values)
    { return TakeOption(argc, argv, i, name, values...); };
    std::string list;
    if (arg == "--help" || arg == "-h")
    {
      Usage();
      std::exit(0);
    }
    else if (arg == "--quick")
    {
      options.Quick = true;
    }
    else if (option("--datasets", list))
    {
      options.Datasets = SplitList(list);
      haveDatasets = true;
    }
    else if (option("--tfs", list))
    {
      options.TransferFunctions = SplitList(list);
      haveTfs = true;
    }
    else if (option("--size", options.Size))
    {
      haveSize = true;
    }
    else if (option("--frames", options.Frames))
    {
      haveFrames = true;
    }
    else if (!(option("--data", options.DataDir) || option("--threads", options.Threads) ||
               option("--sample-factor", options.SampleFactor) ||
               option("--reference-factor", options.ReferenceFactor) ||
               option("--view", options.Azimuth, options.Elevation) ||
               option("--turn", options.Turn) || option("--shade", shade) ||
               option("--gl", options.GL) || option("--json", options.Json) ||
               option("--images", options.Images)))
    {
      std::cerr << "unknown or incomplete option: " << arg << "\n";
      Usage();
      return false;
    }
  }
  if (options.Quick)
  {
    options.Size = haveSize ? options.Size : 128;
    options.Frames = haveFrames ? options.Frames : 2;
    if (!haveDatasets)
    {
      options.Datasets = { "engine" };
    }
    if (!haveTfs)
    {
      options.TransferFunctions = { "tf2" };
    }
  }
  if (options.Threads == 0)
  {
    options.Threads = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  }
  bool tfsValid = !options.TransferFunctions.empty();
  for (const std::string& tf : options.TransferFunctions)
  {
    tfsValid = tfsValid && (tf == "tf1" || tf == "tf2");
  }
  options.Shade = shade == "on";
  if (options.Frames < 1 || options.Datasets.empty() || options.Size < 16 || options.Size > 4096 ||
    options.Threads < 1 || options.Threads > 1024 || !(options.SampleFactor > 0) ||
    options.ReferenceFactor < 1 || !tfsValid || (shade != "on" && shade != "off"))
  {
    std::cerr << "invalid option values (frames >= 1, size 16..4096, threads 1..1024, "
                 "sample factor > 0, reference factor >= 1, tfs among tf1,tf2, shade on|off)\n";
    return false;
  }
  return true;
}

} // namespace accelvolume::benchmark::raycast
