#pragma once

// Whether the changer can take a request now: the rules every flow shares.
// Each flow's own rule is its why_not, in the flow's own .cpp (flows/NAME.cpp).

#include <optional>
#include <string>
#include <vector>

#include "context.hpp"

namespace fatc {

/// "tool 3", in a refusal.
std::string tool_name(int tool);
/// Why nothing can start: the machine not ready, or what the spindle holds uncertain.
std::optional<std::string> why_not_ready(const Context& ctx);
/// why_not_ready, or a chuck a G-code release left open.
std::optional<std::string> why_not_busy(const Context& ctx);
/// The spindle still turns (LinuxCNC's, or its own feedback where wired):
/// nothing the operator asks for may start.
std::optional<std::string> why_spindle_turning(const Context& ctx);
/// Every sequence opens the chuck: no air, no start (the legs check again
/// before each opening).
std::optional<std::string> why_no_air(const Context& ctx);
/// The rack datum (rack_touch) refuses a change to `tool`: its last check
/// found the rack moved, or a check is due (every check_every_changes, or
/// once each start with check_at_start) and `tool` is not the probe that
/// would make it.
std::optional<std::string> why_datum_refuses(const Context& ctx, int tool);
/// The tool in the spindle must be able to go home before anything else; a
/// manual tool only can when M6 may hand it out at `loading` (`hand_out`).
std::optional<std::string> why_spindle_cannot_be_emptied(const Context& ctx, bool hand_out);
/// "X20.000 Y150.000 Z-10.000 mm", machine coordinates.
std::string position_words(const Config& config, const Point& at);
/// A chuck atom left the chuck released: no other work until it is clamped.
std::optional<std::string> why_chuck_held_open(const Context& ctx);
/// How close to `loading` the machine must stand for a release with a tool
/// in the spindle: 0.05 mm, or 0.002 inch.
double loading_tolerance(const Config& config);
/// Why a taught config cannot be taken now (ConfigChanged), or nothing if it
/// can: only while `idle`, with task free and the chuck clamped; while the
/// idle changer compares its sensors (`comparing_sensors`), it says what it waits for.
std::optional<std::string> why_not_reconfigure(const Context& ctx, bool idle,
                                               bool comparing_sensors);

/// The pocket a load of `tool` puts it in: `asked` if given, else its own
/// pocket, else its first-start pocket if free, else the free pocket nearest
/// to `loading`. 0 and `why` when there is none (load_flow.cpp).
struct LoadPocket {
  int pocket = 0;
  std::string why;
};
LoadPocket choose_load_pocket(const Context& ctx, int tool, int asked);
/// The tools of `asked` that measure all can fetch (in the rack, or in the
/// spindle with a pocket to go to), in order, once each; `never` names those
/// whose rule is "never", `skipped` the others (measure_all_flow.cpp).
std::vector<int> measurable_tools(const Context& ctx, const std::vector<int>& asked,
                                  std::string& skipped, std::string& never);

}  // namespace fatc
