// Command-line parsing, usage text and validation of accelvolume_benchmark_cropping's options.
#include "BenchmarkCroppingOptions.h"

#include "BenchmarkCommon.h"

#include <cstdlib>
#include <iostream>

namespace accelvolume::benchmark
{
namespace
{
void Usage()
{
  std::cout
    << "Usage: accelvolume_benchmark_cropping [options]\n"
       "  --data DIR          folder of the volumes and datasets.json (default "
    << ACCELVOLUME_BENCHMARK_DATA_DIR
    << ")\n"
       "  --datasets A,B      dataset names (default cthead,cta_avm); a name maps to the file\n"
       "                      NAME_<X>x<Y>x<Z>_<type>.raw[.gz] in the data folder\n"
       "  --size W H          image size (default 512 512)\n"
       "  --frames N          timed frames per configuration (default 10)\n"
       "  --reference-frames N timed frames of the 8x reference (default 3)\n"
       "  --gl egl|osmesa|auto headless OpenGL backend (default egl)\n"
       "  --json FILE         machine-readable results (default benchmark_cropping.json)\n"
       "  --images DIR        save PNGs (and x8 difference images) of the first dataset\n"
       "  --crop LOW HIGH     crop box as fractions of every axis (default 0.2 0.8)\n"
       "  --band R            half-width in pixels of the outline band (default 2.5)\n"
       "  --zoom Z            camera zoom after fitting the crop box (default 1.0)\n"
       "  --window LOW HIGH   transfer-function window for every dataset (default: per dataset)\n";
}

} // namespace

bool ParseArguments(int argc, char* argv[], Options& options)
{
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    // True when `arg` is `name` and is followed by one value per field, which it then consumes.
    auto option = [&](const char* name, auto&... values)
    { return TakeOption(argc, argv, i, name, values...); };
    std::string datasets;
    if (arg == "--help" || arg == "-h")
    {
      Usage();
      std::exit(0);
    }
    else if (option("--datasets", datasets))
    {
      options.Datasets = SplitList(datasets);
    }
    else if (option("--window", options.Window[0], options.Window[1]))
    {
      options.HaveWindow = true;
    }
    else if (!(option("--data", options.DataDir) ||
               option("--size", options.Width, options.Height) ||
               option("--frames", options.Frames) ||
               option("--reference-frames", options.ReferenceFrames) ||
               option("--gl", options.GL) || option("--json", options.Json) ||
               option("--images", options.Images) ||
               option("--crop", options.CropLow, options.CropHigh) ||
               option("--zoom", options.Zoom) || option("--band", options.BandRadius)))
    {
      std::cerr << "unknown or incomplete option: " << arg << "\n";
      Usage();
      return false;
    }
  }
  if (options.Width < 16 || options.Height < 16 || options.Frames < 1 ||
    options.ReferenceFrames < 1 || options.Datasets.empty() ||
    !(options.CropLow >= 0 && options.CropLow < options.CropHigh && options.CropHigh <= 1) ||
    options.BandRadius <= 0 || options.Zoom <= 0 ||
    (options.HaveWindow && !(options.Window[0] < options.Window[1])))
  {
    std::cerr << "invalid option values\n";
    return false;
  }
  return true;
}

} // namespace accelvolume::benchmark
