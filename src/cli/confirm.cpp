#include "confirm.hpp"

#include <sys/stat.h>

#include <cerrno>
#include <ostream>

#include "io/files.hpp"

namespace fatc::io {
namespace {

/// Why the operator's answer cannot be what is in the rack, or empty: the
/// record's own contradictions (ToolState::contradiction, as the clear-fault
/// pin refuses them), or --pocket where no sequence was cut off at a pocket.
/// (The state file was read against the config: the cut-off pocket is one of its.)
std::string contradiction(const ToolState& tools, int pocket, const Options& options) {
  if (!options.pocket_holds_tool) return "";
  const std::string said = "--spindle " + std::to_string(*options.spindle_tool) + " --pocket " +
                           (*options.pocket_holds_tool ? "yes" : "no") + ": ";
  if (pocket == 0) return said + "no sequence was cut off at a pocket";
  if (const auto why = tools.contradiction(*options.spindle_tool, options.pocket_holds_tool)) {
    return said + *why;
  }
  return "";
}

}  // namespace

/// The recovery of a fault without LinuxCNC: the operator's word into the
/// state file, as the clear-fault pin would record it. Nothing moves.
int confirm(const Options& options, std::ostream& out, std::ostream& err) {
  const auto config = load_config_file(options.config_path);
  if (!config.config) {
    for (const auto& error : config.errors) err << error << "\n";
    return 1;
  }
  // A fault leaves a state file (a first start writes one at once): none there is a wrong path,
  // which would otherwise be written anew while the real one stays uncertain.
  struct stat st;
  if (::stat(options.state_path.c_str(), &st) != 0 && errno == ENOENT) {
    err << shown_path(options.state_path) << ": no such state file, so nothing to confirm and "
        << "nothing written (is it the --state the component was given?)\n";
    return 1;
  }
  auto state = load_state_file(options.state_path, *config.config);
  if (!state.state) {
    err << state.error << "\n";
    return 1;
  }
  ToolState& tools = *state.state;
  const int pocket = tools.in_progress ? tools.in_progress->pocket : 0;
  if (const std::string why = contradiction(tools, pocket, options); !why.empty()) {
    err << shown_path(options.state_path) << ": " << why << "\n";
    return 1;
  }
  tools.confirm(*options.spindle_tool, options.pocket_holds_tool);
  try {
    save_state_file(options.state_path, tools, kCommandLineWait);
  } catch (const std::exception& e) {
    err << e.what() << "\n";
    return 1;
  }
  out << shown_path(options.state_path) << ": the spindle holds "
      << (tools.spindle == 0 ? std::string("nothing") : "tool " + std::to_string(tools.spindle));
  if (pocket != 0) {
    out << "; pocket " << pocket << (tools.holds(pocket) ? " holds" : " does not hold") << " tool "
        << tools.tool_of(pocket);
  }
  out << "; nothing is uncertain now\n";
  return 0;
}

}  // namespace fatc::io
