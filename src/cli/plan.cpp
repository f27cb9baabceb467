#include "plan.hpp"

#include <ostream>

#include "check.hpp"
#include "core/dry_run/air_run.hpp"
#include "core/dry_run/sequence_check.hpp"
#include "core/dry_run/simulator.hpp"
#include "core/formatted.hpp"
#include "inputs.hpp"
#include "io/files.hpp"
#include "lint.hpp"
#include "plan_touch.hpp"
#include "linuxcnc/offline/ini.hpp"
#include "linuxcnc/offline/program_tools.hpp"

namespace fatc::io {
namespace {

/// The planned change's time on its path and on the other one, as --lint
/// estimates it (change_time), and the bound.
void print_estimate(const Options& options, const Config& config, const ToolState& tools, int to,
                    const Simulator& sim, std::ostream& out) {
  std::string error;
  const auto motion = machine_motion(options.ini_path, config, error);
  if (!motion) return;  // the INI was read already: this cannot fail now
  Config other = config;
  other.path = config.path == Path::direct ? Path::prototype : Path::direct;
  const Simulator other_sim = plan_change(other, tools, to, config.probe_limit.z);
  const ChangeTime time = change_time(sim, config.safe, motion->timing);
  const ChangeTime other_time = change_time(other_sim, config.safe, motion->timing);
  const char* name = config.path == Path::direct ? "direct" : "prototype";
  const char* other_name = config.path == Path::direct ? "prototype" : "direct";
  const std::string parts = formatted("(moves %.2f s, dwells %.2f s, %d step%s)", time.moves,
                                      time.dwells, time.steps, time.steps == 1 ? "" : "s");
  // Two lines: the figures, then how they were worked out (a line stays under 400 characters).
  out << "estimated " << seconds_text(time.seconds()) << " on the " << name << " path ("
      << seconds_text(other_time.seconds()) << " on the " << other_name << " path) " << parts
      << ", the operator not counted\n"
      << "  from safe: " << motion->source << ", " << estimate_costs_text(motion->timing) << "\n";
  if (config.blend_tolerance > 0.0) {
    out << "  blend_tolerance: a blended run counted as one step, its moves as exact stops; its "
           "rounded corners save more\n";
  }
  if (!options.ini_path) {
    out << "bound: --ini gives it (the machine's velocities and accelerations)\n";
    return;
  }
  const auto ini = IniFile::read(*options.ini_path, error);
  const auto limits = ini ? motion_limits(*ini, config.units, error) : std::nullopt;
  if (!limits) {
    out << "bound: not known: " << error << "\n";
    return;
  }
  const Simulator& direct = config.path == Path::direct ? sim : other_sim;
  const Simulator& prototype = config.path == Path::direct ? other_sim : sim;
  out << "bound " << seconds_text(limits_seconds(direct, config.safe, *limits))
      << ": the direct path's moves at the velocities and accelerations of "
      << shown_path(*options.ini_path) << ", each an exact stop, plus the dwells (the prototype "
      << "path's: " << seconds_text(limits_seconds(prototype, config.safe, *limits))
      << "; with each run of rapids as one move, more than blending could save: "
      << seconds_text(blended_seconds(direct, config.safe, *limits)) << ")\n";
  if (!config.move_while_spindle_stops) return;
  Config direct_config = config;
  direct_config.path = Path::direct;
  const Simulator running = plan_change_running_down(direct_config, tools, to, config.probe_limit.z);
  const double meanwhile = limits_seconds_while_running_down(running, config.safe, *limits);
  out << "while the spindle runs down: " << seconds_text(meanwhile)
      << " of the bound's moves (" << (config.rack_cover ? "up to safe Z" : "up to safe Z and across at it")
      << "), the rest "
      << seconds_text(limits_seconds(running, config.safe, *limits) - meanwhile)
      << " once it stands\n";
}

/// --plan --air: the change flown in the air, every move checked with the
/// tool `from` in the spindle all the way (nothing is taken or handed).
int plan_in_the_air(const Options& options, const Config& config, const ToolState& tools, int to,
                    const Loaded& loaded, std::ostream& out) {
  const AirSettings air{*options.air_height, options.air_feed.value_or(0.0)};
  const std::string name = "M6 T" + std::to_string(to) + " with " + spindle_words(tools.spindle);
  const AirPlan plan =
      plan_air_run(config, tools, {}, 0, [to](Changer& c) { c.tool_change(to); }, name, air,
                   tools.spindle, loaded.lengths.of(tools.spindle, tools.lengths).length);
  if (!plan.request) {
    out << plan.refused << "\n";
    return 1;
  }
  out << plan.request->name << ", " << rack_words(options) << "\n";
  std::vector<Step> route = plan.request->route;
  int number = 0;
  for (Step& step : route) {
    step.held = tools.spindle;
    out << formatted("%3d  ", ++number) << describe(step) << "\n";
  }
  std::vector<SequenceViolation> violations;
  const StepsFrom from{{}, 0, loaded.lengths, tools.lengths};
  for (const Violation& v : check_steps(config, route, loaded.limits, from)) {
    violations.push_back({"air run", v.step, route[v.step], v.what});
  }
  out << "the chuck, the probe, the operator's waits and LinuxCNC's tool commands left out: "
         "nothing is taken, handed or measured\n";
  return report(violations, out) != 0 ? 1 : 0;
}

}  // namespace

int plan(const Options& options, std::ostream& out, std::ostream& err) {
  const Loaded loaded = load(options, err);
  if (!loaded.config || loaded.problems > 0) return 1;
  if (options.touch) return plan_touch(options, loaded, out);
  const Config& config = *loaded.config;
  const int from = *options.from_tool;
  const int to = *options.to_tool;
  auto rack = rack_of(options, config, err);
  if (!rack) return 1;
  ToolState& tools = *rack;
  tools.put_in_spindle(from);
  if (options.air_height) return plan_in_the_air(options, config, tools, to, loaded, out);
  const Simulator sim = plan_change(config, tools, to, config.probe_limit.z);
  out << "M6 T" << to << " with " << spindle_words(from) << ", " << rack_words(options) << "\n";
  int number = 0;
  for (const auto& record : sim.records) {
    if (record.kind == Record::Kind::save) continue;
    out << formatted("%3d  ", ++number) << describe(record) << "\n";
  }
  const int violations =
      report(check_sequence("M6", config, sim, loaded.limits, {{}, 0, loaded.lengths, tools.lengths}),
             out);
  const bool refused = refusal(sim).has_value();
  if (!refused) print_estimate(options, config, tools, to, sim, out);
  return refused || violations != 0 ? 1 : 0;
}

}  // namespace fatc::io
