// Option parsing, the printed table and the JSON file of accelvolume_benchmark_octree.
#include "BenchmarkOctreeReport.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace accelvolume::benchmark
{
namespace
{

void Usage()
{
  std::cout << "Usage: accelvolume_benchmark_octree [options]\n"
               "  --data DIR        folder of the volumes (default "
            << ACCELVOLUME_BENCHMARK_DATA_DIR
            << ")\n"
               "  --datasets A,B    file-name prefixes in DIR, 'vessels' = time-varying phantom\n"
               "                    (default cta_avm,aneurism,engine,ct_chest_lidc0314,vessels)\n"
               "  --repeat K        builds per builder, median reported (default 5; builds over\n"
               "                    2 s get fewer, said in the output)\n"
               "  --leaf L          leaf edge, power of two 2..64 (default 8)\n"
               "  --frames N        time-varying phantom frames (default 5)\n"
               "  --phantom-size N  its edge in voxels (default 256)\n"
               "  --gl egl|osmesa|auto  headless OpenGL backend (default egl)\n"
               "  --json FILE       results (default benchmark_octree.json)\n";
}

bool ParseInt(const char* text, int& value)
{
  char* end = nullptr;
  const long parsed = std::strtol(text, &end, 10);
  value = static_cast<int>(parsed);
  return *text && !*end && parsed >= 0 && parsed < (1 << 20);
}

std::string Quote(const std::string& text)
{
  std::string out = "\"";
  for (const char c : text)
  {
    out += c == '"' || c == '\\'             ? std::string("\\") + c
      : static_cast<unsigned char>(c) < 0x20 ? std::string(" ")
                                             : std::string(1, c);
  }
  return out + "\"";
}

std::string JsonList(const std::vector<double>& values)
{
  std::string text = "[";
  for (std::size_t i = 0; i < values.size(); ++i)
  {
    text += (i ? ", " : "") + Num(values[i], 4);
  }
  return text + "]";
}

const BuildResult* Find(const DatasetResult& d, const std::string& builder, bool oneThread)
{
  for (const BuildResult& b : d.Builds)
  {
    if (b.Builder == builder && (builder != "cpu" || b.AllThreads != oneThread))
    {
      return &b;
    }
  }
  return nullptr;
}

} // namespace

bool ParseArguments(int argc, char* argv[], Options& options)
{
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h")
    {
      Usage();
      std::exit(0);
    }
    if (i + 1 >= argc)
    {
      std::cerr << "unknown option or missing value: " << arg << "\n";
      return false;
    }
    const char* value = argv[++i];
    bool good = true;
    if (arg == "--data")
    {
      options.DataDir = value;
    }
    else if (arg == "--datasets")
    {
      options.Datasets.clear();
      std::stringstream list(value);
      for (std::string name; std::getline(list, name, ',');)
      {
        if (!name.empty())
        {
          options.Datasets.push_back(name);
        }
      }
      good = !options.Datasets.empty();
    }
    else if (arg == "--repeat" || arg == "--leaf" || arg == "--frames" || arg == "--phantom-size")
    {
      int& field = arg == "--repeat" ? options.Repeat
        : arg == "--leaf"            ? options.Leaf
        : arg == "--frames"          ? options.Frames
                                     : options.PhantomSize;
      good = ParseInt(value, field) && field >= 1;
    }
    else if (arg == "--gl")
    {
      options.GL = value;
    }
    else if (arg == "--json")
    {
      options.Json = value;
    }
    else
    {
      std::cerr << "unknown option: " << arg << "\n";
      Usage();
      return false;
    }
    if (!good)
    {
      std::cerr << "invalid value '" << value << "' for " << arg << "\n";
      return false;
    }
  }
  if (options.Leaf < 2 || options.Leaf > 64 || (options.Leaf & (options.Leaf - 1)) != 0)
  {
    std::cerr << "--leaf must be a power of two between 2 and 64\n";
    return false;
  }
  return true;
}

double Median(std::vector<double> values)
{
  if (values.empty())
  {
    return NAN;
  }
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : (values[n / 2 - 1] + values[n / 2]) / 2;
}

void PrintReport(const Machine& machine, const std::vector<DatasetResult>& results)
{
  std::cout << "\n"
            << std::left << std::setw(20) << "dataset" << std::setw(13) << "dims" << std::setw(8)
            << "type" << std::setw(11) << "builder" << std::right << std::setw(8) << "threads"
            << std::setw(11) << "median ms" << std::setw(8) << "GB/s" << std::setw(9) << "x ref"
            << std::setw(9) << "x floor"
            << "\n";
  for (const DatasetResult& d : results)
  {
    const std::string dims = d.Description.substr(0, d.Description.find(' '));
    const std::string type = d.Description.substr(d.Description.find(' ') + 1);
    const double floor = Median(d.ReadFloorMs);
    const BuildResult* reference = Find(d, "reference", true);
    auto row = [&](const std::string& builder, const std::string& threads, double ms,
                 const std::string& note)
    {
      std::cout << std::left << std::setw(20) << d.Name << std::setw(13) << dims << std::setw(8)
                << type << std::setw(11) << builder << std::right << std::setw(8) << threads
                << std::setw(11) << Num(ms, 2) << std::setw(8) << Num(d.Bytes / ms / 1e6, 2)
                << std::setw(9) << Num(reference ? SafeRatio(Median(reference->Ms), ms) : NAN, 2)
                << std::setw(9) << Num(SafeRatio(ms, floor), 2) << note << "\n";
    };
    row("read-floor", "1", floor, "");
    for (const BuildResult& b : d.Builds)
    {
      row(b.Builder, std::to_string(b.Threads), Median(b.Ms),
        b.ReducedRepeats ? "  (median of " + std::to_string(b.Ms.size()) + ": slow build)" : "");
    }
  }
  std::cout << "(x ref = reference ms / this ms: speed-up; x floor = this ms / read-floor ms)\n";

  std::cout << "\nratios and re-classification (targets: cpu <= 2x floor, cpu >= 5x reference, "
               "gpu faster than cpu, classify << 1 ms at 256^3):\n";
  for (const DatasetResult& d : results)
  {
    const BuildResult* reference = Find(d, "reference", true);
    const BuildResult* cpu = Find(d, "cpu", false);
    const BuildResult* cpu1 = Find(d, "cpu", true);
    const BuildResult* gpu = Find(d, "gpu", true);
    const double cpuMs = cpu ? Median(cpu->Ms) : NAN;
    std::cout << "  " << std::left << std::setw(20) << d.Name << std::right
              << "cpu(all) vs reference " << Num(SafeRatio(Median(reference->Ms), cpuMs), 2)
              << "x faster, cpu(1) vs reference "
              << Num(cpu1 ? SafeRatio(Median(reference->Ms), Median(cpu1->Ms)) : NAN, 2)
              << "x, cpu(all) / floor " << Num(SafeRatio(cpuMs, Median(d.ReadFloorMs)), 2)
              << ", gpu / cpu(all) " << (gpu ? Num(SafeRatio(Median(gpu->Ms), cpuMs), 2) : "n/a")
              << ", classify median " << Num(Median(d.ClassifyMs), 4) << " ms (min "
              << Num(*std::min_element(d.ClassifyMs.begin(), d.ClassifyMs.end()), 4) << "), "
              << d.Nodes << " nodes, depth " << d.Depth << ", "
              << Num(100 * d.TransparentLeafFraction, 1) << "% leaves transparent\n";
  }
  for (const DatasetResult& d : results)
  {
    if (d.Frames.FrameMs.empty())
    {
      continue;
    }
    const double frame = Median(d.Frames.FrameMs), rebuild = Median(d.Frames.RebuildMs);
    std::cout << "\ntime-varying " << d.Name << " " << d.Description << ", "
              << d.Frames.FrameMs.size() << " frames (t += 0.05), medians: data copy + Modified "
              << Num(Median(d.Frames.CopyMs), 1) << " ms, octree rebuild (cpu, all threads) "
              << Num(rebuild, 1) << " ms, slice-mapper MIP 512x512 (incl. texture upload) "
              << Num(Median(d.Frames.RenderMs), 1) << " ms; frame " << Num(frame, 1)
              << " ms -> rebuild = " << Num(100 * rebuild / frame, 1)
              << "% of the frame (phantom generation " << Num(Median(d.Frames.GenerateMs), 0)
              << " ms, outside the frame)\n";
  }
  if (!machine.GPUNote.empty())
  {
    std::cout << "\ngpu builder not run: " << machine.GPUNote << "\n";
  }
}

void WriteJson(
  const Options& options, const Machine& machine, const std::vector<DatasetResult>& results)
{
  std::ofstream out(options.Json);
  out << "{\n  \"benchmark\": \"accelvolume_benchmark_octree\",\n  \"leaf\": " << options.Leaf
      << ",\n  \"repeat\": " << options.Repeat << ",\n  \"threads\": " << machine.Threads
      << ",\n  \"smp_backend\": " << Quote(machine.SMPBackend)
      << ",\n  \"gl_backend\": " << Quote(machine.GLBackend)
      << ",\n  \"gl_renderer\": " << Quote(machine.GLRenderer)
      << ",\n  \"gl_version\": " << Quote(machine.GLVersion)
      << ",\n  \"gpu_note\": " << (machine.GPUNote.empty() ? "null" : Quote(machine.GPUNote))
      << ",\n  \"datasets\": [";
  for (std::size_t i = 0; i < results.size(); ++i)
  {
    const DatasetResult& d = results[i];
    const double floor = Median(d.ReadFloorMs);
    const BuildResult* reference = Find(d, "reference", true);
    out << (i ? "," : "") << "\n    {\"name\": " << Quote(d.Name)
        << ", \"file\": " << (d.File.empty() ? "null" : Quote(d.File))
        << ", \"volume\": " << Quote(d.Description) << ", \"bytes\": " << d.Bytes
        << ", \"load_s\": " << Num(d.LoadSeconds, 3) << ", \"read_floor_ms\": " << Num(floor, 4)
        << ", \"nodes\": " << d.Nodes << ", \"depth\": " << d.Depth
        << ", \"classify_ms\": {\"median\": " << Num(Median(d.ClassifyMs), 5)
        << ", \"all\": " << JsonList(d.ClassifyMs)
        << "}, \"transparent_leaf_fraction\": " << Num(d.TransparentLeafFraction, 5)
        << ",\n     \"builds\": [";
    for (std::size_t b = 0; b < d.Builds.size(); ++b)
    {
      const BuildResult& r = d.Builds[b];
      const double ms = Median(r.Ms);
      out << (b ? "," : "") << "\n       {\"builder\": " << Quote(r.Builder)
          << ", \"threads\": " << r.Threads << ", \"median_ms\": " << Num(ms, 4)
          << ", \"ms\": " << JsonList(r.Ms)
          << ", \"reduced_repeats\": " << (r.ReducedRepeats ? "true" : "false")
          << ", \"gb_per_s\": " << Num(d.Bytes / ms / 1e6, 4)
          << ", \"x_reference\": " << Num(reference ? SafeRatio(Median(reference->Ms), ms) : NAN, 4)
          << ", \"x_floor\": " << Num(SafeRatio(ms, floor), 4) << "}";
    }
    out << "]";
    if (!d.Frames.FrameMs.empty())
    {
      const FrameResult& f = d.Frames;
      out << ",\n     \"frames\": {\"generate_ms\": " << JsonList(f.GenerateMs)
          << ", \"copy_ms\": " << JsonList(f.CopyMs)
          << ", \"rebuild_ms\": " << JsonList(f.RebuildMs)
          << ", \"render_ms\": " << JsonList(f.RenderMs)
          << ", \"frame_ms\": " << JsonList(f.FrameMs) << ", \"rebuild_percent_of_frame\": "
          << Num(100 * Median(f.RebuildMs) / Median(f.FrameMs), 3) << "}";
    }
    out << "}";
  }
  out << "\n  ]\n}\n";
  if (!out)
  {
    std::cerr << "could not write " << options.Json << "\n";
  }
}

} // namespace accelvolume::benchmark
