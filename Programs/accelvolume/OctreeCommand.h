// OctreeCommand: `accelvolume octree`, times min-max octree builds and re-classification.
#ifndef accelvolume_cli_OctreeCommand_h
#define accelvolume_cli_OctreeCommand_h

#include "ProgressBar.h"
#include "VolumeIO.h"

#include <vtkAccelVolumeHeadlessRenderWindow.h>
#include <vtkAccelVolumeMinMaxOctree.h>
#include <vtkImageData.h>

#include <cstddef>
#include <ostream>
#include <string>
#include <vector>

namespace CLI
{
class App;
}

namespace accelvolume::cli
{

struct OctreeOptions
{
  VolumeRequest volume;
  int leaf = 8;
  int builder = vtkAccelVolumeMinMaxOctree::BUILDER_CPU;
  int threads = 0;
  int repeat = 5;
  bool haveTfLow = false;
  double tfLow = 0;
  int glBackend = vtkAccelVolumeHeadlessRenderWindow::BACKEND_AUTOMATIC;
  std::string statsPath;
  bool quiet = false;
  ProgressMode progress = ProgressMode::Automatic; // --progress: a bar on stderr
};

struct OctreeResult
{
  std::vector<double> buildMs;
  std::vector<double> readFloorMs;
  std::vector<double> classifyMs;
  int threads = 0;
  vtkIdType nodes = 0;
  int depth = 0;
  int leafGrid[3] = { 0, 0, 0 };
  std::size_t bytes = 0;
  double range[2] = { 0, 0 };
  double tfLow = 0, tfLowAlternate = 0;
  double transparentLeafFraction = 0;
  std::string glRenderer;
};

// "reference", "cpu" or "gpu".
const char* BuilderName(int builder);

// The --stats JSON (keys: see the code and README) and the one-line summary.
void WriteOctreeStats(
  std::ostream& out, const OctreeOptions& options, vtkImageData* image, const OctreeResult& result);
std::string OctreeSummary(
  const OctreeOptions& options, vtkImageData* image, const OctreeResult& result);

// The octree flags of `accelvolume octree` (help groups "Octree" and "Output"; the input flags
// are Options.h's AddInputFlags) and the checks after parsing (CheckInput first).
void AddOctreeFlags(CLI::App& command, OctreeOptions& options);
void CheckOctree(const OctreeOptions& options);

// Runs `accelvolume octree` with parsed options. Returns the exit code; throws CliError for
// runtime failures (1).
int RunOctreeCommand(const OctreeOptions& options);

} // namespace accelvolume::cli

#endif
