// ProgressBar: terminal detection and drawing of the stderr progress bar.
#include "ProgressBar.h"

#include <algorithm>
#include <cstdio>
#include <iomanip>
#include <sstream>

#include <sys/ioctl.h>
#include <unistd.h>

namespace accelvolume::cli
{
namespace
{
// Redraws closer together than this only flicker (and cost writes on long --frames runs).
constexpr std::chrono::milliseconds RedrawInterval(100);

int TerminalColumns()
{
  winsize size{};
  if (ioctl(STDERR_FILENO, TIOCGWINSZ, &size) == 0 && size.ws_col >= 20)
  {
    return size.ws_col;
  }
  return 80; // not a terminal (--progress on into a file) or an unknown width
}
}

bool ParseProgressMode(const std::string& text, ProgressMode& mode)
{
  if (text == "auto")
  {
    mode = ProgressMode::Automatic;
  }
  else if (text == "on")
  {
    mode = ProgressMode::On;
  }
  else if (text == "off")
  {
    mode = ProgressMode::Off;
  }
  else
  {
    return false;
  }
  return true;
}

bool StderrIsTerminal()
{
  return isatty(STDERR_FILENO) == 1;
}

ProgressBar::ProgressBar(const std::string& label, ProgressMode mode)
  : Label(label)
  , Shown(mode == ProgressMode::On || (mode == ProgressMode::Automatic && StderrIsTerminal()))
{
}

ProgressBar::~ProgressBar()
{
  this->Finish();
}

void ProgressBar::BeginTask(int index, int count, const std::string& name)
{
  this->Count = std::max(count, 1);
  this->Index = std::min(std::max(index, 0), this->Count - 1);
  this->Name = name;
  this->Fraction = 0;
  this->Draw(true);
}

void ProgressBar::Update(double fraction)
{
  fraction = std::min(std::max(fraction, 0.0), 1.0);
  if (fraction <= this->Fraction)
  {
    return;
  }
  this->Fraction = fraction;
  this->Draw(false);
}

void ProgressBar::Finish()
{
  if (!this->Drawn)
  {
    return;
  }
  this->Draw(true);
  std::fputc('\n', stderr);
  std::fflush(stderr);
  this->Drawn = false;
  this->LastLength = 0;
}

void ProgressBar::Draw(bool force)
{
  if (!this->Shown)
  {
    return;
  }
  const auto now = std::chrono::steady_clock::now();
  if (!force && this->Drawn && now - this->LastDraw < RedrawInterval)
  {
    return;
  }
  this->LastDraw = now;
  const double overall = (this->Index + this->Fraction) / this->Count;
  std::ostringstream tail;
  tail << " " << std::setw(3) << static_cast<int>(overall * 100.0) << "%";
  if (this->Count > 1)
  {
    tail << "  " << this->Index + 1 << "/" << this->Count;
  }
  if (!this->Name.empty())
  {
    tail << "  " << this->Name;
  }
  // A bar of fixed width for the terminal (so it does not jump as the text after it changes),
  // leaving room for that text; one column spare so the line never wraps.
  const int columns = TerminalColumns() - 1;
  const int width = std::max(10, std::min(40, columns - static_cast<int>(this->Label.size()) - 40));
  const int filled = static_cast<int>(overall * width);
  std::string line = this->Label + " [" + std::string(static_cast<std::size_t>(filled), '#') +
    std::string(static_cast<std::size_t>(width - filled), '.') + "]" + tail.str();
  if (static_cast<int>(line.size()) > columns)
  {
    line.resize(static_cast<std::size_t>(std::max(columns, 1)));
  }
  const std::size_t length = line.size();
  if (length < this->LastLength)
  {
    line.append(this->LastLength - length, ' '); // clear what the last line left
  }
  this->LastLength = length;
  std::fputc('\r', stderr);
  std::fputs(line.c_str(), stderr);
  std::fflush(stderr);
  this->Drawn = true;
}

} // namespace accelvolume::cli
