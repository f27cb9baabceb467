#pragma once

#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "../config/config.hpp"
#include "../rack/keepout.hpp"
#include "../rack/tool_state.hpp"
#include "coordinate_system.hpp"
#include "interpreter_output.hpp"
#include "preflight.hpp"
#include "tool_use.hpp"

namespace fatc {

struct KeepoutCheckInput {
  const Config* config = nullptr;
  std::string program;  ///< as messages show it
  ToolState tools;      ///< at the program's start: the spindle, and each tool's pocket
  /// LinuxCNC's tool table: each tool's length (Z) in the config's units;
  /// nullopt without a table.
  std::optional<std::map<int, double>> lengths;
  /// The longest tool the config allows (longest_carried), asked once a tool
  /// needs it: with a table, a tool whose Z is 0 or below or missing counts
  /// as its measured length (`tools`), else as that, as the guard counts it.
  std::function<double()> longest;
  std::string table_name;     ///< as messages show it
  bool return_to_xy = false;  ///< [FIXED_ATC_PROBE]RETURN_TO_XY: M6 ends over where it was called
};

/// The static layer of the rack keep-out: follows the canonical calls of a
/// program as LinuxCNC's interpreter (rs274) prints them, the spindle nose in
/// machine coordinates and the tool below it, and names every line whose
/// motion would enter the rack's volume (rack_volume, the one the realtime
/// guard holds) raised by the length of the tool then in the spindle, and
/// every chuck release the changer would refuse.
/// Keeps nothing of a move once it is checked.
class KeepoutCheck : public program::CallListener {
 public:
  explicit KeepoutCheck(KeepoutCheckInput input);

  void call(int line, bool numbered, std::string_view call) override;
  void tool_use(const program::ToolUse& use) override;

  /// Each line whose motion enters the rack, once, in the order met; beyond
  /// program::kMaxErrors lines, one more finding counts the rest.
  std::vector<program::Finding> problems() const;
  /// What the check could not know: a tool with no length, a spline's path.
  const std::vector<program::Finding>& unknowns() const { return unknowns_; }
  /// The lengths the program set (G10 L1, L10, L11), for the preflight's
  /// check of the changes after them: the last of a tool between two tool uses.
  const std::vector<LengthSet>& lengths_set() const { return lengths_set_; }

 private:
  void move(int line, bool numbered, const char* code, const Point& program_to);
  void arc(int line, bool numbered, const std::vector<double>& args);
  void probe(int line, bool numbered, const Point& program_to);
  void rigid_tap(int line, bool numbered, const Point& program_to);
  void change(const program::ToolUse& use);
  /// A chuck release (fixed_atc_probe_chuck_release) run from `line`, by
  /// itself or through a subroutine: refused while the spindle turns, or
  /// with a tool in it away from loading.
  void chuck_release(int line);
  /// Puts the nose where the last change ends, once a move needs it.
  void settle();
  /// Checks the nose's straight way `from` → `to`; false once the line is named.
  bool check(int line, bool numbered, const char* code, const Point& from, const Point& to);
  /// The nose's machine position for the program's `to`, and which of its axes are known.
  std::pair<Point, unsigned> target(const Point& program_to);
  /// The length of the tool in the spindle as the guard counts it
  /// (ToolLengths::of); without a table, 0 (said once, at `line`).
  double tool_length(int line);
  /// The table's length of `tool`; nullopt when the table has none.
  std::optional<double> table_length(int tool) const;
  std::optional<Point> change_end(int from, int to);
  void unknown(int line, const std::string& text);

  KeepoutCheckInput in_;
  std::vector<RackPart> volume_;
  /// The coordinate system as rs274 has it: the machine's (its M6 runs the
  /// stand-in that ends in G43 as the machine's remap does,
  /// program::preflight_stand_ins).
  program::CoordinateSystem rs274_;
  Point rs274_at_;           ///< where rs274 takes the nose to be (it starts at machine 0)
  Point nose_;               ///< where the machine's nose is, on the axes of `known_`
  unsigned known_ = 0;       ///< axes (1 X, 2 Y, 4 Z) of nose_ known
  unsigned out_of_step_ = 7; ///< axes where rs274's position is not the machine's
  int plane_ = 17;           ///< G17, G18, G19
  std::optional<int> spindle_;  ///< the tool in the spindle; nullopt: not known
  bool turning_ = false;        ///< the spindle is on (M3, M4 until M5)
  /// Lengths the program set (G10 L1, L10, L11), by tool, in the config's
  /// units: they stand for the table's from that line on.
  std::map<int, double> set_lengths_;
  std::vector<LengthSet> lengths_set_;
  std::size_t uses_told_ = 0;  ///< tool uses told so far (tool_use)
  /// An M6 whose end no move has needed yet.
  struct PendingChange {
    int line = 0;  ///< where the lint shows the change: its T word's line
    std::optional<int> from, to;
    Point called_at;  ///< the nose when it was called, on the axes of `known`
    unsigned known = 0;
  };
  std::optional<PendingChange> pending_;
  std::map<std::pair<int, int>, std::optional<Point>> change_ends_;
  std::set<int> named_;  ///< lines named, at most program::kMaxErrors
  std::size_t more_ = 0; ///< lines beyond those
  std::vector<program::Finding> problems_;
  std::vector<program::Finding> unknowns_;
  std::set<int> said_no_length_;  ///< tools said to have no length in the table
  std::optional<double> longest_;  ///< in_.longest's, once asked
  bool said_no_table_ = false;
  bool said_unknown_tool_ = false;
  bool said_spline_ = false;
};

}  // namespace fatc
