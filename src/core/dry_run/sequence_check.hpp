#pragma once

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "../config/config.hpp"
#include "../rack/geometry.hpp"
#include "simulator.hpp"
#include "../motion/step.hpp"

namespace fatc {

/// One move of a planned sequence that breaks the rack keep-out or the soft limits.
struct SequenceViolation {
  std::string sequence;  ///< "M6 T3 from empty", "load T3"
  std::size_t step = 0;  ///< index into the sequence's steps
  Step move;
  std::string what;
};

/// "M6 T3 from empty, step 5 (rapid to side of pocket 3): passes through the rack at pocket 4".
std::string describe(const SequenceViolation& violation);

/// The violations of one planned sequence, named `sequence`, from where it
/// starts and with the lengths of the tools its moves carry (`from`).
std::vector<SequenceViolation> check_sequence(const std::string& sequence, const Config& config,
                                              const Simulator& planned,
                                              const std::optional<SoftLimits>& limits,
                                              const StepsFrom& from = {});

/// Where a pocket's sequences leave the least room below the nose for the
/// tool they carry (tip_room): the longest tool they can carry.
struct SequenceRoom {
  double length = 0.0;
  std::string sequence;
  std::size_t step = 0;
  Step move;
  int holder = 0;  ///< the pocket whose holder that tool's tip would enter
};

/// "M6 T3 from empty (pocket 3), step 9 (rapid to safe Z) over pocket 4".
std::string describe(const SequenceRoom& room);

struct SequencesChecked {
  int sequences = 0;
  std::vector<SequenceViolation> violations;
  /// By pocket, where its sequences carry a tool over a holder (a pocket
  /// whose sequences never do is not in it).
  std::map<int, SequenceRoom> room;
};

/// Plans every sequence the changer can run through each pocket (M6 to it
/// with an empty spindle, M6 T0 from it, load, unload, measure, verify),
/// each from `safe`, where the sequence before left the spindle, and
/// checks each move against the keep-out and the soft limits, each tool
/// carried with its length in `lengths` and the changer's `measured` ones
/// (ToolLengths::of; none given: 0): what `--check`
/// reports and what a taught position must pass.
SequencesChecked check_sequences(const Config& config, const std::optional<SoftLimits>& limits,
                                 const ToolLengths& lengths = {},
                                 const std::map<int, double>& measured = {});

/// The longest tool the config allows: the least room any pocket's
/// sequences leave (`checked`), and no longer than the tool that crosses
/// the holders with the nose at above-clearance
/// (pocket_above_clearance_offset_z - pocket_above_chuck_offset_z).
double longest_carried(const Config& config, const SequencesChecked& checked);

/// What --check says of each tool of `lengths`' table, one line each: what
/// a Z of no length counts as, and which pockets' sequences cannot carry the
/// tool across their holders (where the room is least); last, how many fit
/// every pocket. A tool too long for the pocket it starts in is a violation
/// already; one too long for another pocket can still be loaded elsewhere or
/// handed over as a manual tool.
std::vector<std::string> carried_tools(const Config& config, const ToolLengths& lengths,
                                       const std::map<int, double>& measured,
                                       const SequencesChecked& checked);

/// What --check notes when `loading` is not over the touch-off sensor
/// (`probe_limit`'s X, Y, within 1 mm or 0.04 inch): a load measures straight
/// down from where the operator put the tool in, so each load would need a
/// jog over the sensor first. Nothing when it is.
std::optional<std::string> loading_note(const Config& config);

/// The tool lengths of the tool table `table` (by tool), with the longest
/// the config allows for those it gives no length of.
ToolLengths carried_lengths(const Config& config, const std::optional<SoftLimits>& limits,
                            std::map<int, double> table);

}  // namespace fatc
