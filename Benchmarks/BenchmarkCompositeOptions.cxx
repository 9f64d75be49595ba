// Command-line parsing, usage text and validation of accelvolume_benchmark_composite's options.
#include "BenchmarkCompositeOptions.h"

#include "BenchmarkCommon.h"

#include <cstdlib>
#include <iostream>

namespace accelvolume::benchmark::composite
{
namespace
{
void Usage()
{
  std::cout
    << "Usage: accelvolume_benchmark_composite [options]\n"
       "  --data DIR          folder of the volumes and datasets.json (default "
    << ACCELVOLUME_BENCHMARK_DATA_DIR
    << ")\n"
       "  --datasets A,B      dataset names (default engine,cthead,bonsai_hazeremoved); a name\n"
       "                      maps to the file NAME_<X>x<Y>x<Z>_<type>.raw[.gz] in the data "
       "folder\n"
       "  --tfs A,B           transfer-function presets of `accelvolume render --tf` (default "
       "tf1,tf2)\n"
       "  --sizes A,B         square image sizes (default 256,512)\n"
       "  --frames N          timed frames per configuration (default 5)\n"
       "  --large-frames N    timed frames at sizes above 256 (default 3; 0 = --frames)\n"
       "  --view AZ EL        camera azimuth / elevation in degrees (default 30 20)\n"
       "  --gl egl|osmesa|auto headless OpenGL backend (default egl)\n"
       "  --json FILE         machine-readable results (default benchmark_composite.json)\n"
       "  --images DIR        save PNGs of the quality-check view (base, ERT+both, VTK)\n";
}

} // namespace

bool ParseArguments(int argc, char* argv[], Options& options)
{
  bool sizesValid = true;
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
    else if (option("--datasets", list))
    {
      options.Datasets = SplitList(list);
    }
    else if (option("--tfs", list))
    {
      options.TransferFunctions = SplitList(list);
    }
    else if (option("--sizes", list))
    {
      options.Sizes.clear();
      for (const std::string& size : SplitList(list))
      {
        const int value = std::atoi(size.c_str());
        sizesValid = sizesValid && value >= 16 && value <= 4096;
        options.Sizes.push_back(value);
      }
    }
    else if (!(option("--data", options.DataDir) || option("--frames", options.Frames) ||
               option("--large-frames", options.LargeFrames) ||
               option("--view", options.Azimuth, options.Elevation) || option("--gl", options.GL) ||
               option("--json", options.Json) || option("--images", options.Images)))
    {
      std::cerr << "unknown or incomplete option: " << arg << "\n";
      Usage();
      return false;
    }
  }
  bool tfsValid = !options.TransferFunctions.empty();
  for (const std::string& tf : options.TransferFunctions)
  {
    tfsValid = tfsValid && (tf == "tf1" || tf == "tf2");
  }
  if (options.Frames < 1 || options.LargeFrames < 0 || options.Datasets.empty() ||
    options.Sizes.empty() || !sizesValid || !tfsValid)
  {
    std::cerr << "invalid option values (frames >= 1, sizes 16..4096, tfs among tf1,tf2)\n";
    return false;
  }
  return true;
}

} // namespace accelvolume::benchmark::composite
