#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "../config/config.hpp"
#include "../config/rack_volume.hpp"
#include "../motion/point.hpp"

namespace fatc {

/// Where the length the keep-out counts for a tool comes from.
enum class LengthSource {
  none,      ///< the spindle is empty
  table,     ///< LinuxCNC's tool table: its Z is a length below the nose
  measured,  ///< the changer's own measurement (the table's Z is none)
  longest,   ///< neither: the longest tool the config allows
};

/// How long a tool hangs below the spindle nose, as the keep-out counts it.
struct KeepoutLength {
  double length = 0.0;
  LengthSource source = LengthSource::none;
};

/// The tool lengths the keep-out knows of: what every move is checked with,
/// the changer's own as much as the guard's.
struct ToolLengths {
  /// Z of LinuxCNC's tool table, by tool, in the config's units.
  std::map<int, double> table;
  /// The longest tool the config allows (longest_carried in dry_run/sequence_check.hpp).
  double longest = 0.0;

  /// `tool`'s length: the table's Z where it is a length below the nose
  /// (above 0), the changer's own measurement where that is longer or the
  /// table gives none, else `longest`. A negative or missing Z (tables
  /// written relative to a master tool) never lowers the boundary.
  KeepoutLength of(int tool, const std::map<int, double>& measured) const;
};

/// What the operator is told, once, of a tool whose table Z the keep-out
/// does not take: "T5: LinuxCNC's tool table gives Z-12.000 mm, no length
/// below the spindle nose; the rack keep-out counts it as 40.000 mm (the
/// longest tool the config allows)". Empty where the table's Z is taken.
std::string keepout_length_words(const Config& config, const ToolLengths& lengths, int tool,
                                 const std::map<int, double>& measured);

/// Where a move of the spindle nose first enters the rack's volume with a
/// tool `tool_length` long hanging below it (the volume raised by that length);
/// none for a move that starts inside (it leaves, or entered before).
struct RackEntry {
  int pocket = 0;  ///< the pocket of the part entered nearest to where it is entered
  Point nose;      ///< where the nose is as the tool's tip enters
};
std::optional<RackEntry> rack_entry(const std::vector<RackPart>& volume, const Point& from,
                                    const Point& to, double tool_length);


/// The keep-out of every motion, as the `rack-keepout` pin and the panel show it.
enum class KeepoutState {
  off = 0,                 ///< rack_keepout_all_motion is false
  armed = 1,               ///< every motion is kept out
  lifted_for_changer = 2,  ///< the changer's own moves run
  lifted_by_operator = 3,  ///< the operator jogs into the rack to teach
  not_armed = 4,           ///< the machine is not on and homed, or its status not read
};

struct KeepoutInputs {
  bool machine_ready = false;    ///< on, out of estop, homed
  bool status_read = false;      ///< LinuxCNC's status (units, tool length) is known
  bool changer_busy = false;     ///< a changer sequence runs
  bool operator_lifts = false;   ///< rack-keepout-lift
};
KeepoutState keepout_state(const Config& config, const KeepoutInputs& in);
/// The state in words, for the panel and messages.
const char* keepout_words(KeepoutState state);

/// "with T1 (length 30.0000 mm)", "with an empty spindle": the tool the
/// spindle holds as a keep-out message names it.
std::string held_words(const Config& config, int tool, double tool_length);

/// What the operator is told when the guard stopped a motion: `what` moved
/// ("program line 12", "an MDI command", "a jog").
std::string keepout_refusal(const Config& config, const std::string& what, int pocket, int tool,
                            double tool_length, const Point& at);

}  // namespace fatc
