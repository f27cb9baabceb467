#pragma once

#include <optional>
#include <string>

#include "../../motion/point.hpp"

namespace fatc {

/// A question to the operator, as data: what to do, with which tool, where.
/// Its words come from words() alone, so an adapter or a simulated operator
/// acts on the fields and nothing reads the English back.
struct Prompt {
  enum class Kind {
    none,           ///< nothing asked yet
    insert_tool,    ///< put `tool` into the spindle at `loading`
    remove_tool,    ///< take `tool` out of the spindle at `loading`
    jog_to_sensor,  ///< `tool` is in: jog closer to the touch-off sensor if wanted, then probe
    verify_stop,    ///< a dry run of `pocket` holds at `stop` of `stops`, at `waypoint`
    step,           ///< step by step: step `stop` of `sequence`, `action` `waypoint` at `at`
    touch_found,    ///< `sequence` touched: `action` is what it found, old beside new; write it?
  };
  Kind kind = Kind::none;
  int tool = 0;
  int pocket = 0;
  /// Inserting or removing inside M6 T<n>: the program holds until the answer.
  std::optional<int> m6_tool;
  int stop = 0;          ///< verify_stop: 1 for the first stop
  int stops = 0;         ///< verify_stop: how many stops the run has
  std::string waypoint;  ///< verify_stop: the waypoint reached, as --plan names it
  Point at;              ///< verify_stop: where the spindle stands (the axes of `known_axes`)
  unsigned known_axes = 0;
  /// step: the sequence ("M6 T3") and what its step does ("rapid to",
  /// "feed at F300 to", "open the chuck"), `waypoint` where ("safe Z", "at
  /// pocket 3"); `at` is its target on the axes it moves (a move) or where
  /// the spindle stands (a chuck action), on the axes known.
  std::string sequence;
  std::string action;
};

/// What the operator reads: "Insert tool 3 into the spindle, then press
/// Continue (Cancel to stop)", inside M6 "M6 T3: insert tool 3 into the
/// spindle, then press Continue (Cancel stops the program)", and so on.
std::string words(const Prompt& prompt);

/// "side of pocket 3 (X=120.000 Y=40.000 Z=-50.000)": a waypoint and where
/// the spindle stands there (the axes known), as --plan writes it.
std::string waypoint_words(const std::string& waypoint, const Point& at, unsigned known_axes);

}  // namespace fatc
