#pragma once

#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "../config/config.hpp"

namespace fatc {

/// A sequence under way, saved before the motion it describes, so that a
/// restart after a crash knows what may have happened and where.
struct InProgress {
  std::string sequence;  ///< "M6 T3", "load of tool 4", "unload of tool 4"
  std::string step;      ///< "returning tool 1 to pocket 1"
  int pocket = 0;        ///< the pocket involved, 0 if none
  bool operator==(const InProgress& other) const {
    return sequence == other.sequence && step == other.step && pocket == other.pocket;
  }
};

/// One pocket of the rack as the changer knows it.
struct PocketState {
  int tool = 0;        ///< the tool that belongs in it, 0: the pocket is free
  bool holds = false;  ///< that tool sits in it now (if not: in the spindle, or lost after a fault)
  bool operator==(const PocketState& other) const {
    return tool == other.tool && holds == other.holds;
  }
};

/// The rack datum's watch (rack_touch.datum): how many changes since it was
/// last touched, and what the last check found beyond its tolerance. Kept in
/// the state file, so a restart neither forgets a rack that moved nor counts
/// from zero again.
struct DatumWatch {
  int changes = 0;    ///< changes made since the datum was last checked or taught
  std::string drift;  ///< the last check's words where the rack moved: M6 is refused meanwhile
  bool operator==(const DatumWatch& other) const {
    return changes == other.changes && drift == other.drift;
  }
};

/// What the changer knows about where the tools are. Saved after every change.
struct ToolState {
  int spindle = 0;         ///< tool in the spindle, 0 = empty
  bool uncertain = false;  ///< an interrupted sequence: `spindle` is the last known, not a fact
  std::map<int, PocketState> pockets;     ///< by pocket number, every pocket of the config
  std::map<int, double> lengths;          ///< measured tool lengths, in the config's units
  std::optional<InProgress> in_progress;  ///< a sequence was under way when this was saved
  DatumWatch datum;

  /// First start: every pocket holds its first-start tool (`tool`), the spindle is empty.
  static ToolState fresh(const Config& config);

  bool operator==(const ToolState& other) const;

  /// The pocket `tool` belongs in, if any.
  std::optional<int> home_of(int tool) const;
  /// The pocket that holds `tool` now, if any.
  std::optional<int> pocket_holding(int tool) const;
  /// The tool that belongs in pocket `number`, 0 if it is free (or unknown).
  int tool_of(int number) const;
  /// Pocket `number` holds the tool that belongs in it.
  bool holds(int number) const;
  /// The tools sitting in their pockets, in pocket order.
  std::vector<int> rack_tools() const;
  /// `tool` is in the spindle (0: it is empty); its pocket, if any, no longer holds it.
  void put_in_spindle(int tool);
  /// Pockets no tool belongs in, in order.
  std::vector<int> free_pockets() const;

  /// The operator's word after a fault or a cut-off sequence: the spindle
  /// holds `spindle_tool` (0 empty) and, when a sequence was cut off at a
  /// pocket, whether that pocket holds its tool. Clears the uncertainty.
  void confirm(int spindle_tool, std::optional<bool> pocket_holds_tool);
  /// Why that word cannot be what is in the rack, or nothing: the cut-off
  /// pocket's own tool said to be in the spindle and in its pocket, or a
  /// pocket no tool belongs in said to hold its tool.
  std::optional<std::string> contradiction(int spindle_tool,
                                           std::optional<bool> pocket_holds_tool) const;
};

/// The pocket `tool` goes to when it leaves the spindle: its own, or, for a
/// tool from outside the rack, its first-start pocket if that is free.
std::optional<int> return_pocket(const ToolState& tools, const Config& config, int tool);

/// The probe (`tools.N.kind`) in the spindle, or, after a cut-off sequence,
/// one not known to sit in its pocket (out of it, in the pocket the sequence
/// was cut off at, or with no pocket), which may be: the spindle is held. 0: none.
int spindle_probe(const Config& config, const ToolState& tools);

/// "pockets 2, 5", "pocket 4" or "no pocket", for messages.
std::string pocket_list(const std::vector<int>& numbers);

struct ToolStateResult {
  std::optional<ToolState> state;
  std::string error;  ///< names the JSON path, empty on success
  /// The file's format: 1 (pocket N was tool N's, no `pockets`) or 2.
  int version = 2;
};

std::string to_json(const ToolState& state);
ToolStateResult tool_state_from_json(const std::string& text);

/// Makes a state read from a file fit the config it runs with; the error
/// names the pocket or tool, empty on success. A pocket the config does not
/// have may not hold a tool; a pocket the state does not know is new: it
/// holds its first-start tool, as at first start (version 1: pocket N is
/// tool N's and holds it only if the file said so).
std::string fit_to_config(ToolState& state, const Config& config, int version);

}  // namespace fatc
