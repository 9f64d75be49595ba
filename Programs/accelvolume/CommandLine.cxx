// CommandLine: the accelvolume command line (CLI11): the program, its `render` and `octree`
// subcommands, the help layout, and one-line usage errors.
#include "OctreeCommand.h"
#include "Options.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <memory>
#include <regex>
#include <sstream>

namespace accelvolume::cli
{
namespace
{

CliError Usage(const std::string& message)
{
  return CliError(ExitUsage, message);
}

// Help, version: what a request flag asks for; thrown from its callback to stop parsing there.
struct Request
{
  Options::Action Action;
};

void AddHelpFlag(CLI::App& command, Options::Action action, const std::string& group)
{
  AddSwitch(command, "-h,--help", "this text", [action]() { throw Request{ action }; })
    ->group(group);
}

// CLI11's help with the usage line first, then the description (a subcommand's first line is its
// entry in the program's list), one blank line before each option group, then the footer.
class HelpFormatter : public CLI::Formatter
{
public:
  std::string make_help(
    const CLI::App* app, std::string name, CLI::AppFormatMode mode) const override
  {
    return this->make_usage(app, name) + "\n" + this->make_description(app) + "\n" +
      this->make_groups(app, mode) + this->make_subcommands(app, mode) + "\n" +
      this->make_footer(app);
  }
  std::string make_group(
    std::string group, bool positional, std::vector<const CLI::Option*> options) const override
  {
    return this->CLI::Formatter::make_group(group, positional, options).substr(1);
  }
  std::string make_subcommand(const CLI::App* command) const override
  {
    const std::string& description = command->get_description();
    std::ostringstream out;
    CLI::detail::format_help(out, command->get_name(),
      description.substr(0, description.find('\n')), this->get_column_width());
    return out.str();
  }
};

// The whole command line: the program, `render` and `octree`, bound to the options they fill.
class CommandLine
{
public:
  CommandLine(Options& render, OctreeOptions& octree)
  {
    auto formatter = std::make_shared<HelpFormatter>();
    formatter->column_width(29);
    this->App.formatter(formatter);
    this->App.set_help_flag();
    this->App.allow_extras();
    this->App.require_subcommand(0, 1);
    const std::string exitCodes = "Exit codes: 0 success, 1 runtime failure, 2 usage error.";
    const std::string commands =
      "The flags of each command: accelvolume render --help, accelvolume octree --help.\n";
    this->App.footer(commands + exitCodes);
    AddHelpFlag(this->App, Options::Action::MainHelp, "Options");
    AddSwitch(this->App, "--version", "print the version and exit",
      []() { throw Request{ Options::Action::Version }; });

    this->Render = this->App.add_subcommand("render", "render a volume file or a built-in phantom");
    this->Render->allow_extras();
    AddRenderFlags(*this->Render, render);
    AddHelpFlag(*this->Render, Options::Action::RenderHelp, "View and output");
    this->Render->footer(
      "The flags of one mapper are usage errors with the others. Shear-warp renders parallel\n"
      "projections only (the default for it; --perspective is a usage error) and takes no\n"
      "--crop, --sample-distance, --slices, --raysum-unit, additive or average blends.\n" +
      exitCodes);

    this->Octree = this->App.add_subcommand("octree",
      "time min-max octree builds\n\n"
      "Builds the min-max octree (Lim and Shin 2009: Morton-order min/max blocks for empty-space\n"
      "skipping) of a volume --repeat times, each time as if the data had changed, and\n"
      "reports the build time against a one-thread streaming read of the volume (the floor)\n"
      "and the re-classification time after a transfer-function change.");
    this->Octree->footer(exitCodes);
    this->Octree->allow_extras();
    AddInputFlags(*this->Octree, octree.volume);
    AddOctreeFlags(*this->Octree, octree);
    AddHelpFlag(*this->Octree, Options::Action::OctreeHelp, "Output");
  }

  CLI::App App{ "Renders a volume file or a built-in phantom with AccelVolume's slice mapper, "
                "its CPU\nray caster (--mapper raycast: octree / distance-map and cell leaping), "
                "its shear-warp\nrenderer (--mapper shearwarp: threads and MPI ranks) or one of "
                "VTK's volume mappers,\nheadless by default, and writes a PNG and/or JSON timings.",
    "accelvolume" };
  CLI::App* Render = nullptr;
  CLI::App* Octree = nullptr;
};

// Arguments CLI11 did not take: an unknown flag or a stray word is a usage error.
void CheckLeftOver(const CLI::App& command, const std::string& name)
{
  const std::vector<std::string> left = command.remaining();
  if (!left.empty())
  {
    const std::string& first = left.front();
    throw Usage(first.compare(0, 1, "-") == 0
        ? "unknown flag '" + first + "' (see accelvolume " + name + " --help)"
        : "unexpected argument '" + first + "'");
  }
}

// One line for CLI11's own parse errors; a flag cut short at the end says how many values it takes.
std::string ParseErrorLine(const CLI::ParseError& error)
{
  std::string message = error.what();
  std::replace(message.begin(), message.end(), '\n', ' ');
  std::smatch match;
  if (std::regex_match(message, match, std::regex("(\\S+): ([0-9]+) required .* missing")))
  {
    const std::string count = match[2];
    return match[1].str() + " expects " + count + " value" + (count == "1" ? "" : "s");
  }
  return message;
}

} // namespace

CLI::Option* AddFlag(CLI::App& command, const std::string& flag, int count, const std::string& text,
  const std::string& help, std::function<void(const FlagValues&)> take, bool anyValue)
{
  auto callback = [flag, count, anyValue, take = std::move(take)](const CLI::results_t& values)
  {
    for (const std::string& value : values)
    {
      if (!anyValue && value.size() > 2 && value.compare(0, 2, "--") == 0)
      {
        throw Usage(
          flag + " expects " + std::to_string(count) + " value" + (count == 1 ? "" : "s"));
      }
    }
    take(values);
    return true;
  };
  // One item of count strings: CLI11 then reads count arguments whatever they look like (as
  // "-30" or "-" must be read), and callback sees each occurrence on its own.
  return command.add_option(flag, CLI::callback_t(callback), help)
    ->type_size(count)
    ->expected(1)
    ->option_text(text)
    ->trigger_on_parse();
}

CLI::Option* AddSwitch(
  CLI::App& command, const std::string& flag, const std::string& help, std::function<void()> take)
{
  return command.add_flag_callback(flag, std::move(take), help)->trigger_on_parse();
}

Options::Action ParseCommandLine(
  const std::vector<std::string>& arguments, Options& render, OctreeOptions& octree)
{
  CommandLine line(render, octree);
  std::vector<const char*> argv;
  for (const std::string& argument : arguments)
  {
    argv.push_back(argument.c_str());
  }
  try
  {
    line.App.parse(static_cast<int>(argv.size()), argv.data());
  }
  catch (const Request& request)
  {
    return request.Action;
  }
  catch (const CLI::ParseError& error)
  {
    throw Usage(ParseErrorLine(error));
  }
  const std::vector<std::string> left = line.App.remaining(false);
  if (!left.empty())
  {
    if (left.front() == "help")
    {
      return Options::Action::MainHelp;
    }
    throw Usage((left.front().compare(0, 1, "-") == 0 ? "unknown flag '" : "unknown command '") +
      left.front() + "' (expected 'render' or 'octree'; try accelvolume --help)");
  }
  if (line.Render->parsed())
  {
    CheckLeftOver(*line.Render, "render");
    CheckRender(render);
    return Options::Action::Render;
  }
  if (line.Octree->parsed())
  {
    CheckLeftOver(*line.Octree, "octree");
    CheckInput(octree.volume);
    CheckOctree(octree);
    return Options::Action::Octree;
  }
  throw Usage("no command given (try accelvolume --help)");
}

std::string MainHelp()
{
  Options render;
  OctreeOptions octree;
  return CommandLine(render, octree).App.help();
}

std::string RenderHelp()
{
  Options render;
  OctreeOptions octree;
  return CommandLine(render, octree).Render->help("accelvolume");
}

std::string OctreeHelp()
{
  Options render;
  OctreeOptions octree;
  return CommandLine(render, octree).Octree->help("accelvolume");
}

} // namespace accelvolume::cli
