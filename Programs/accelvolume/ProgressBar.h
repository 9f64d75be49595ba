// ProgressBar: a one-line progress bar on stderr for long runs (accelvolume render and octree,
// the benchmark programs). Plain C++: it is fed fractions, not VTK events, so any loop can
// drive it.
#ifndef accelvolume_cli_ProgressBar_h
#define accelvolume_cli_ProgressBar_h

#include <chrono>
#include <cstddef>
#include <string>

namespace accelvolume::cli
{

// --progress: Automatic shows the bar only when stderr is a terminal.
enum class ProgressMode
{
  Automatic,
  On,
  Off
};

// "auto", "on" or "off"; false (mode unchanged) for anything else.
bool ParseProgressMode(const std::string& text, ProgressMode& mode);

// Whether stderr is a terminal (isatty).
bool StderrIsTerminal();

// The bar: "label [#######.............]  35%  frame 2/6  name", redrawn in place with '\r' at
// most ten times a second (and whenever a task starts or the bar finishes), ended by Finish()
// with a newline. When it is not shown every call does nothing, so a run that is not on a
// terminal (or asked for --progress off) writes nothing at all.
class ProgressBar
{
public:
  ProgressBar(const std::string& label, ProgressMode mode);
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  bool IsShown() const { return this->Shown; }

  // Starts task `index` (0-based) of `count` (frames, builds, benchmark cases), optionally
  // named; the bar then covers (index + task fraction) / count.
  void BeginTask(int index, int count, const std::string& name = std::string());
  // The current task's fraction done, in [0, 1] (values below the last one are ignored).
  void Update(double fraction);
  // Draws the final state and ends the line; the next task or update starts a new line.
  void Finish();

private:
  void Draw(bool force);

  std::string Label;
  bool Shown = false;
  bool Drawn = false; // a line is open on the terminal
  int Index = 0;
  int Count = 1;
  std::string Name;
  double Fraction = 0;
  std::size_t LastLength = 0;
  std::chrono::steady_clock::time_point LastDraw;
};

} // namespace accelvolume::cli

#endif
