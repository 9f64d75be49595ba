// Command-line parsing, usage text and validation of accelvolume_benchmark_shearwarp's options.
#include "BenchmarkShearWarpOptions.h"

#include "BenchmarkCommon.h"

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <thread>

namespace accelvolume::benchmark::shearwarp
{
namespace
{
void Usage()
{
  std::cout
    << "Usage: accelvolume_benchmark_shearwarp [options]\n"
       "  --data DIR          folder of the volumes and datasets.json (default "
    << ACCELVOLUME_BENCHMARK_DATA_DIR
    << ")\n"
       "  --datasets A,B      dataset names (default mri_t1_head,cthead,ct_chest_lidc0314); a "
       "name\n"
       "                      maps to the file NAME_<X>x<Y>x<Z>_<type>.raw[.gz] in the data "
       "folder\n"
       "  --skip-large        drop volumes over 32 Mi voxels (the 512x512x275 CT)\n"
       "  --sizes A,B         square final image sizes (default 256,512)\n"
       "  --tfs A,B           transfer-function presets of `accelvolume render --tf` (default\n"
       "                      tf2,tf1: opaque surfaces, then semi-transparent)\n"
       "  --shade on|off|both shaded, unshaded or both (default on)\n"
       "  --frames N          timed frames per configuration (default 10)\n"
       "  --threads N         the \"all threads\" count (default: hardware threads)\n"
       "  --view AZ EL        initial camera azimuth / elevation in degrees (default 30 20)\n"
       "  --turn DEG          azimuth turn per timed frame (default 1, as the paper)\n"
       "  --mpi-ranks A,B     rank counts of the MPI rows (default 1,2)\n"
       "  --no-mpi            skip the MPI rows (no mpiexec launch)\n"
       "  --no-volpack        skip the VolPack rows\n"
       "  --volpack-grey      VolPack in luminance mode (grey = mean of the transfer function's\n"
       "                      R, G, B: one colour channel) instead of RGB like the mapper\n"
       "  --gl egl|osmesa|auto headless OpenGL backend (default $ACCELVOLUME_GL, else egl)\n"
       "  --json FILE         machine-readable results (default "
       "accelvolume_benchmark_shearwarp.json)\n"
       "  --images DIR        save PNGs of the fixed view (ours (3) 1 thread, VolPack)\n"
       "Exit code: 0 ok, 1 a dataset, backend or MPI run failed, 2 bad options, 3 the image\n"
       "checks failed (thread counts / balancing not byte-identical, or no RLE vs RLE beyond the\n"
       "early-termination bound).\n";
}

std::vector<int> IntList(const std::string& list)
{
  std::vector<int> values;
  for (const std::string& item : SplitList(list))
  {
    values.push_back(std::atoi(item.c_str()));
  }
  return values;
}

std::string JoinInts(const std::vector<int>& values)
{
  std::ostringstream out;
  for (size_t i = 0; i < values.size(); ++i)
  {
    out << (i ? "," : "") << values[i];
  }
  return out.str();
}

} // namespace

bool ParseArguments(int argc, char* argv[], Options& options)
{
  if (const char* gl = std::getenv("ACCELVOLUME_GL"))
  {
    const std::string value = gl;
    if (value == "egl" || value == "osmesa" || value == "auto")
    {
      options.GL = value;
    }
  }
  std::string shade = "on";
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    auto option = [&](const char* name, auto&... values)
    { return TakeOption(argc, argv, i, name, values...); };
    std::string list;
    if (arg == "--help" || arg == "-h")
    {
      Usage();
      std::exit(0);
    }
    else if (arg == "--skip-large")
    {
      options.SkipLarge = true;
    }
    else if (arg == "--no-mpi")
    {
      options.Mpi = false;
    }
    else if (arg == "--no-volpack")
    {
      options.VolPack = false;
    }
    else if (arg == "--volpack-grey")
    {
      options.VolPackGrey = true;
    }
    else if (arg == "--mpi-worker")
    {
      options.MpiWorker = true;
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
      options.Sizes = IntList(list);
    }
    else if (option("--mpi-ranks", list))
    {
      options.MpiRanks = IntList(list);
    }
    else if (!(option("--data", options.DataDir) || option("--threads", options.Threads) ||
               option("--frames", options.Frames) ||
               option("--view", options.Azimuth, options.Elevation) ||
               option("--turn", options.Turn) || option("--shade", shade) ||
               option("--gl", options.GL) || option("--json", options.Json) ||
               option("--images", options.Images) || option("--mpi-dir", options.MpiDir)))
    {
      std::cerr << "unknown or incomplete option: " << arg << "\n";
      Usage();
      return false;
    }
  }
  if (options.Threads == 0)
  {
    options.Threads = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  }
  bool valid = !options.TransferFunctions.empty() && !options.Sizes.empty() &&
    !options.Datasets.empty() && !options.MpiRanks.empty();
  for (const std::string& tf : options.TransferFunctions)
  {
    valid = valid && (tf == "tf1" || tf == "tf2");
  }
  for (int size : options.Sizes)
  {
    valid = valid && size >= 16 && size <= 4096;
  }
  for (int ranks : options.MpiRanks)
  {
    valid = valid && ranks >= 1 && ranks <= 256;
  }
  if (shade == "on" || shade == "off")
  {
    options.Shades = { shade == "on" };
  }
  else if (shade == "both")
  {
    options.Shades = { true, false };
  }
  else
  {
    valid = false;
  }
  if (!valid || options.Frames < 1 || options.Threads < 1 || options.Threads > 1024 ||
    (options.MpiWorker && options.MpiDir.empty()))
  {
    std::cerr << "invalid option values (frames >= 1, sizes 16..4096, threads 1..1024, tfs among "
                 "tf1,tf2, shade on|off|both, MPI ranks 1..256)\n";
    return false;
  }
  return true;
}

std::vector<std::string> WorkerArguments(
  const Options& options, const std::string& dataset, const std::string& mpiDir)
{
  std::string tfs;
  for (const std::string& tf : options.TransferFunctions)
  {
    tfs += (tfs.empty() ? "" : ",") + tf;
  }
  const std::string shade = options.Shades.size() == 2 ? "both" : options.Shades[0] ? "on" : "off";
  std::ostringstream azimuth, elevation, turn;
  azimuth.precision(17);
  elevation.precision(17);
  turn.precision(17);
  azimuth << options.Azimuth;
  elevation << options.Elevation;
  turn << options.Turn;
  return { "--mpi-worker", "--mpi-dir", mpiDir, "--data", options.DataDir, "--datasets", dataset,
    "--sizes", JoinInts(options.Sizes), "--tfs", tfs, "--shade", shade, "--frames",
    std::to_string(options.Frames), "--view", azimuth.str(), elevation.str(), "--turn", turn.str(),
    "--gl", options.GL };
}

} // namespace accelvolume::benchmark::shearwarp
