#include "cli.hpp"

#include <ostream>
#include <vector>

#include "check.hpp"
#include "confirm.hpp"
#include "core/config/quote.hpp"
#include "core/machine/changer.hpp"
#include "io/capped_lines.hpp"
#include "io/files.hpp"
#include "lint.hpp"
#include "linuxcnc/offline/ini.hpp"
#include "plan.hpp"
#include "plot.hpp"
#include "teach.hpp"
#include "usage.hpp"

namespace fatc::io {
namespace {

/// A file given on the command line, as a message names it.
struct GivenFile {
  std::string name;  ///< "--plot \"rack.svg\"", "the backup \"config.json.bak\""
  std::string path;
};

}  // namespace

std::string written_onto_input(const Options& options) {
  std::vector<GivenFile> written;
  std::vector<GivenFile> inputs;
  switch (options.mode) {
    case Options::Mode::plot:
      written = {{"--plot " + quote(options.plot_path, 200), options.plot_path}};
      inputs = {{"--config", options.config_path}, {"--state", options.state_path}};
      break;
    case Options::Mode::teach: {
      const std::string backup = options.config_path + ".bak";
      written = {{"the backup " + quote(backup, 200), backup}};
      inputs = {{"--ini", options.ini_path.value_or("")}};
      break;
    }
    case Options::Mode::confirm:
    case Options::Mode::component:
      written = {{"--state " + quote(options.state_path, 200), options.state_path}};
      inputs = {{"--config", options.config_path}};
      break;
    default:
      break;
  }
  for (const GivenFile& output : written) {
    for (const GivenFile& input : inputs) {
      if (input.path.empty() || !same_file(output.path, input.path)) continue;
      return output.name + " is the file given as " + input.name + ": nothing written";
    }
  }
  return "";
}

Options with_state_of_ini(Options options) {
  const bool reads_it = options.mode == Options::Mode::check ||
                        options.mode == Options::Mode::lint ||
                        options.mode == Options::Mode::operator_request;
  if (!reads_it || options.state_given || !options.ini_path) return options;
  std::string error;
  const auto ini = IniFile::read(*options.ini_path, error);
  if (!ini) return options;  // the INI's own check says why
  if (const auto state = ini->get("FIXED_ATC_PROBE", "STATE"); state && !state->empty()) {
    options.state_path =
        (*state)[0] == '/' ? *state : folder_of(*options.ini_path) + "/" + *state;
  }
  return options;
}

namespace {

int run_mode(const Options& given, std::ostream& out, std::ostream& err) {
  const Options options = with_state_of_ini(given);
  if (const std::string refused = written_onto_input(options); !refused.empty()) {
    err << refused << "\n";
    return 2;
  }
  switch (options.mode) {
    case Options::Mode::check:
      return check(options, out, err);
    case Options::Mode::plan:
      return plan(options, out, err);
    case Options::Mode::dot:
      out << Changer::dot();
      return 0;
    case Options::Mode::confirm:
      return confirm(options, out, err);
    case Options::Mode::lint:
      return lint(options, out, err);
    case Options::Mode::teach:
      return teach_position(options, out, err);
    case Options::Mode::plot:
      return plot(options, out, err);
    case Options::Mode::help:
      out << usage();
      return 0;
    case Options::Mode::component:
    case Options::Mode::version:  // main's: the version is linked into the program alone
    case Options::Mode::operator_request:  // HAL's: src/cli/operator_command.cpp
      break;
  }
  return 2;
}

}  // namespace

int run_tool_mode(const Options& options, std::ostream& out, std::ostream& err) {
  // Graphviz and the usage are ours alone; every other line may hold a file's text.
  if (options.mode == Options::Mode::dot || options.mode == Options::Mode::help) {
    return run_mode(options, out, err);
  }
  CappedLines out_lines(out), err_lines(err);
  std::ostream capped_out(&out_lines), capped_err(&err_lines);
  const int code = run_mode(options, capped_out, capped_err);
  capped_out.flush();
  capped_err.flush();
  return code;
}

}  // namespace fatc::io
