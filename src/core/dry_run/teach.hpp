#pragma once

#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <vector>

#include "../config/config.hpp"
#include "../rack/geometry.hpp"
#include "../motion/point.hpp"

namespace fatc {

/// Where a taught position goes in config.json.
struct TeachTarget {
  enum class Kind {
    pocket,   ///< pockets."N": x, y and z
    loading,  ///< loading: x, y and z
    safe,     ///< safe: x, y and z
    sensor,  ///< the touch-off sensor, probe_limit: x and y; its z (how low the probe may go) stays
    datum,   ///< the rack datum, rack_touch.datum: x, y and z where its feature was found
  };
  Kind kind = Kind::pocket;
  int pocket = 0;  ///< for Kind::pocket: its number, the key in `pockets`
};

/// "pocket:3", "loading", "safe", "sensor" or "datum"; nullopt for anything else.
std::optional<TeachTarget> parse_teach_target(const std::string& text);
/// "pocket 3", "loading", "safe", "sensor", "the rack datum".
std::string target_name(const TeachTarget& target);

/// Either the new config.json text and what changed, or why nothing may be written.
struct TeachResult {
  std::optional<std::string> text;  ///< the whole new config.json
  std::string change;  ///< "pocket 3: x 150.0000 → 151.2000, y 20.0000 (unchanged), z ..."
  std::string error;   ///< "teach pocket 3 at X151.2 Y20 Z-80: not written: ..."
};

/// Puts the machine position `at` (G53, the config's units) into the config
/// text at `target`, rounded to 4 decimals (mm) or 5 (inch). Every other key,
/// known or not, keeps its value and its place. The new text must pass
/// parse_config and every planned sequence must keep out of the rack and
/// (given `limits`) within the soft limits, as `--check` demands; otherwise
/// `error` names the target, the position and the first problem. A pocket
/// that `pockets` does not have is refused: teaching does not add pockets.
/// The tools the sequences carry count as long as `lengths` says.
TeachResult teach(const std::string& config_text, const TeachTarget& target, const Point& at,
                  const std::optional<SoftLimits>& limits, const ToolLengths& lengths = {});

/// One position taught of several at once.
struct Taught {
  TeachTarget target;
  Point at;
};

/// Each of `taught` in turn, as teach() does one, into one text: all or
/// nothing. `change` holds one line per target; `error` the first refused.
TeachResult teach_all(const std::string& config_text, const std::vector<Taught>& taught,
                      const std::optional<SoftLimits>& limits, const ToolLengths& lengths = {});

/// The units the config text declares (`units`); mm when it says nothing or
/// cannot be read. The machine's soft limits are read in these.
Units declared_units(const std::string& config_text);

/// config.json as it is written by hand: 2-space indent, an object or array
/// of scalars on one line (wrapped at 100 columns), a newline at the end.
std::string format_config_json(const nlohmann::ordered_json& root);

}  // namespace fatc
