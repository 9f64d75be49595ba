// Command-line parsing, usage text and validation of accelvolume_benchmark_memory's options.
#include "BenchmarkMemoryOptions.h"

#include "BenchmarkCommon.h"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <thread>

namespace accelvolume::benchmark::memory
{
namespace
{
void Usage()
{
  std::cout
    << "Usage: accelvolume_benchmark_memory [options]\n"
       "Peak resident memory of each mapper on each volume, every case in a fresh child process.\n"
       "  --data DIR          folder of the volumes and datasets.json (default "
    << ACCELVOLUME_BENCHMARK_DATA_DIR
    << ")\n"
       "  --volumes A,B       data-folder names (NAME_<X>x<Y>x<Z>_<type>.raw[.gz]) or "
       "'procedural'\n"
       "                      (default ct_chest_lidc0314,procedural)\n"
       "  --procedural-dims X Y Z  the generated uint16 volume (default 1024 1024 512: 1 GiB)\n"
       "  --mappers A,B       among slice, raycast-none, raycast-octree, raycast-dmap,\n"
       "                      shearwarp-1, shearwarp-all, vtk-fixed, vtk-gpu (default all)\n"
       "  --procedural-skip A,B  mappers not run on the procedural volume (default none)\n"
       "  --size N            square image size in pixels (default 256)\n"
       "  --tf tf1|tf2        transfer-function preset of `accelvolume render --tf` (default tf1)\n"
       "  --shade on|off      Phong shading (default on)\n"
       "  --threads N         'all threads' (default: hardware threads)\n"
       "  --case-timeout S    seconds before a case's process is killed (default 900)\n"
       "  --memory-limit MIB  address-space cap of each case's process (default 60 % of the\n"
       "                      machine's memory; -1: none): a mapper that needs more fails alone\n"
       "  --quick             smoke run: procedural 128x128x96, size 64 (unless given)\n"
       "  --gl egl|osmesa|auto headless OpenGL backend (default egl)\n"
       "  --json FILE         machine-readable results (default "
       "accelvolume_benchmark_memory.json)\n"
       "Exit code: 0 every case ran, 1 a case failed (error, crash, timeout) or a backend is\n"
       "missing, 2 bad options, 125 no case could run because the data is absent.\n";
}

bool Known(const std::string& id)
{
  const auto& ids = MapperIds();
  return std::find(ids.begin(), ids.end(), id) != ids.end();
}

} // namespace

double MachineMemoryMiB()
{
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  double kib = 0;
  while (meminfo >> key >> kib)
  {
    if (key == "MemTotal:")
    {
      return kib / 1024.0;
    }
    meminfo.ignore(1 << 10, '\n');
  }
  return 0;
}

const std::vector<std::string>& MapperIds()
{
  static const std::vector<std::string> ids = { "slice", "raycast-none", "raycast-octree",
    "raycast-dmap", "shearwarp-1", "shearwarp-all", "vtk-fixed", "vtk-gpu" };
  return ids;
}

bool ParseArguments(int argc, char* argv[], Options& options)
{
  bool haveSize = false, haveVolumes = false, haveDims = false;
  std::string shade = "on";
  options.Mappers = MapperIds();
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
    else if (arg == "--quick")
    {
      options.Quick = true;
    }
    else if (option("--child", options.ChildMapper, options.ChildVolume))
    {
      options.Child = true;
    }
    else if (option("--volumes", list))
    {
      options.Volumes = SplitList(list);
      haveVolumes = true;
    }
    else if (option("--mappers", list))
    {
      options.Mappers = SplitList(list);
    }
    else if (option("--procedural-skip", list))
    {
      options.ProceduralSkip = list == "none" ? std::vector<std::string>() : SplitList(list);
    }
    else if (option("--procedural-dims", options.ProceduralDims[0], options.ProceduralDims[1],
               options.ProceduralDims[2]))
    {
      haveDims = true;
    }
    else if (option("--size", options.Size))
    {
      haveSize = true;
    }
    else if (!(option("--data", options.DataDir) || option("--tf", options.Tf) ||
               option("--shade", shade) || option("--threads", options.Threads) ||
               option("--case-timeout", options.CaseTimeout) ||
               option("--memory-limit", options.MemoryLimit) || option("--gl", options.GL) ||
               option("--json", options.Json) || option("--child-fd", options.ChildFd)))
    {
      std::cerr << "unknown or incomplete option: " << arg << "\n";
      Usage();
      return false;
    }
  }
  if (options.Quick)
  {
    options.Size = haveSize ? options.Size : 64;
    if (!haveVolumes)
    {
      options.Volumes = { ProceduralName };
    }
    if (!haveDims)
    {
      options.ProceduralDims[0] = options.ProceduralDims[1] = 128;
      options.ProceduralDims[2] = 96;
    }
  }
  if (options.Threads == 0)
  {
    options.Threads = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  }
  if (options.MemoryLimit == 0)
  {
    options.MemoryLimit = 0.6 * MachineMemoryMiB();
  }
  options.Shade = shade == "on";
  bool mappersValid = !options.Mappers.empty();
  for (const std::string& id : options.Mappers)
  {
    mappersValid = mappersValid && Known(id);
  }
  for (const std::string& id : options.ProceduralSkip)
  {
    mappersValid = mappersValid && Known(id);
  }
  const int* d = options.ProceduralDims;
  const bool dimsValid = d[0] >= 2 && d[1] >= 2 && d[2] >= 2 && d[0] <= 4096 && d[1] <= 4096 &&
    d[2] <= 4096 && static_cast<double>(d[0]) * d[1] * d[2] <= 4.0 * 1024 * 1024 * 1024;
  if (options.Volumes.empty() || !mappersValid || !dimsValid || options.Size < 16 ||
    options.Size > 4096 || options.Threads < 1 || options.Threads > 1024 ||
    !(options.CaseTimeout > 0) || (options.Tf != "tf1" && options.Tf != "tf2") ||
    (shade != "on" && shade != "off") || (options.Child && options.ChildFd < 0))
  {
    std::cerr << "invalid option values (volumes non-empty, known mappers, procedural dims "
                 "2..4096 and at most 2^32 voxels, size 16..4096, threads 1..1024, case "
                 "timeout > 0, tf1|tf2, shade on|off)\n";
    return false;
  }
  return true;
}

std::vector<std::string> ChildArguments(
  const Options& options, const std::string& mapper, const std::string& volume, int resultFd)
{
  const int* d = options.ProceduralDims;
  return { "--child", mapper, volume, "--child-fd", std::to_string(resultFd), "--data",
    options.DataDir, "--procedural-dims", std::to_string(d[0]), std::to_string(d[1]),
    std::to_string(d[2]), "--size", std::to_string(options.Size), "--tf", options.Tf, "--shade",
    options.Shade ? "on" : "off", "--threads", std::to_string(options.Threads), "--gl", options.GL,
    "--memory-limit", std::to_string(options.MemoryLimit) };
}

} // namespace accelvolume::benchmark::memory
