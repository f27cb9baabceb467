#pragma once

#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "core/motion/point.hpp"
#include "core/dry_run/teach.hpp"
#include "operator_watch.hpp"

namespace fatc::io {

/// The component's command line.
struct Options {
  enum class Mode { component, check, plan, dot, help, version, confirm, lint, teach, plot,
                    operator_request };
  Mode mode = Mode::component;
  std::string config_path;
  std::string state_path;  ///< component, --check, --lint: CONFIG.state unless --state is given
  bool state_given = false;  ///< --state was given (not CONFIG.state)
  std::optional<std::string> ini_path;
  std::optional<int> from_tool;
  std::optional<int> to_tool;
  std::optional<int> spindle_tool;             ///< --confirm: what the spindle holds
  std::optional<bool> pocket_holds_tool;       ///< --confirm: the cut-off pocket holds its tool
  std::string program_path;                    ///< --lint PROGRAM
  std::optional<std::string> tool_table_path;  ///< --lint: LinuxCNC's tool table
  std::optional<std::string> subroutine_path;  ///< --lint: folders of subroutines, ':' between
  std::optional<TeachTarget> teach_target;     ///< --teach TARGET
  std::optional<Point> teach_at;               ///< --teach: --at X,Y,Z, machine coordinates
  std::string plot_path;                       ///< --plot FILE.svg
  std::optional<OperatorRequest> request;      ///< --operator ACTION
  std::optional<int> into_pocket;              ///< --operator load: --into P
  bool answer_yes = false;                     ///< --operator: --yes
  std::optional<double> timeout_seconds;       ///< --operator: --timeout SECONDS
};

/// Parses argv; nullopt and one line in `error` on a usage mistake: an
/// unknown, repeated or empty option, two modes at once, an option the mode
/// does not use.
std::optional<Options> parse_options(const std::vector<std::string>& args, std::string& error);

/// One line when a file the mode writes (--plot's drawing, the config's .bak
/// on --teach, the state file of --confirm and of the component) is one of the
/// files it reads, so that it would replace an input; empty otherwise.
std::string written_onto_input(const Options& options);

/// --check, --lint and --operator with --ini and no --state read the state
/// file the component reads: [FIXED_ATC_PROBE]STATE, from the INI's folder,
/// where LinuxCNC runs the HAL file that hands it to the component.
Options with_state_of_ini(Options options);

/// --confirm: 0 when the state file was rewritten with the operator's word.
/// --check: 0 when config, state and INI are valid and no planned move breaks
/// the keep-out or the soft limits, 1 otherwise. --plan: 0 printed, 1 refused or invalid. --dot: 0.
/// --lint: 0 clean, 1 problems found in the program, 2 an input it cannot read (see lint.hpp).
/// --teach: 0 written, 1 refused (nothing written), 2 the config or INI cannot be read or the
/// config cannot be written. --plot: 0 written, 1 the config or state is invalid or the
/// change refused, 2 the drawing cannot be written.
int run_tool_mode(const Options& options, std::ostream& out, std::ostream& err);

}  // namespace fatc::io
