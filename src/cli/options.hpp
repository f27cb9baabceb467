#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/dry_run/teach.hpp"
#include "core/motion/point.hpp"
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
  bool holding_tool = false;                   ///< --operator io:chuck-release: --holding-tool
  bool step_by_step = false;                   ///< --operator: --step
  std::optional<double> timeout_seconds;       ///< --operator: --timeout SECONDS
  std::optional<double> air_height;            ///< --plan: --air HEIGHT, the change flown in the air
  std::optional<double> air_feed;              ///< --plan --air: --air-feed FEED
  /// --plan --touch POCKETS: which features the touch path goes to.
  struct Touched {
    bool all = false;         ///< "all": every pocket
    bool datum = false;       ///< "datum": the rack datum's
    std::vector<int> pockets;  ///< "3,5"
  };
  std::optional<Touched> touch;
};

}  // namespace fatc::io
