#pragma once

// Reading config.json: the reader that checks each key against its
// declaration (keys.cpp) and collects every problem with its JSON path.

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "settings.hpp"
#include "json_text.hpp"
#include "keys.hpp"

namespace fatc::reading {

using Json = nlohmann::json;

inline std::string format_number(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

/// Most problems listed; the rest are only counted (a file of 100,000
/// unknown keys gets 20 lines, at once).
constexpr std::size_t kMaxErrors = 20;
/// Unknown keys longer than this get no "did you mean".
constexpr std::size_t kMaxSuggestedKeyLength = 64;

/// How many single-character edits turn `a` into `b`: for "did you mean".
std::size_t edit_distance(const std::string& a, const std::string& b);

/// Reads values out of the parsed JSON, collecting one message per problem.
class Reader {
 public:
  std::vector<std::string> errors;
  std::size_t unlisted = 0;  ///< problems past kMaxErrors
  Units units = Units::mm;

  void error(const std::string& path, const std::string& what) {
    if (errors.size() >= kMaxErrors) {
      ++unlisted;
      return;
    }
    errors.push_back((path.empty() ? std::string("config") : path) + ": " + what);
  }
  bool full() const { return errors.size() >= kMaxErrors; }
  std::size_t count() const { return errors.size() + unlisted; }

  /// One message for each key the object at `path` holds that keys.cpp does not declare there.
  void reject_unknown_keys(const Json& object, const std::string& path) {
    const std::vector<std::string> known = keys_below(path);
    for (const auto& item : object.items()) {
      const std::string& key = item.key();
      if (std::find(known.begin(), known.end(), key) != known.end()) continue;
      if (full()) {
        ++unlisted;
        continue;
      }
      std::string best;
      std::size_t best_distance = std::numeric_limits<std::size_t>::max();
      for (const std::string& candidate : known) {
        if (key.size() > kMaxSuggestedKeyLength) break;
        const std::size_t d = edit_distance(key, candidate);
        if (d < best_distance) {
          best_distance = d;
          best = candidate;
        }
      }
      std::string message = "unknown key";
      if (best_distance <= std::max<std::size_t>(2, key.size() / 3)) {
        message += ", did you mean \"" + best + "\"?";
      }
      error(join_path(path, key), message);
    }
  }

  /// The number at object[key]; nullopt and one message when it is missing
  /// (and required), not a number, or not finite.
  std::optional<double> number(const Json& object, const std::string& path, const char* key,
                               bool required) {
    const std::string here = join_path(path, key);
    const auto found = object.find(key);
    if (found == object.end()) {
      if (required) error(here, "missing");
      return std::nullopt;
    }
    if (!found->is_number()) {
      error(here, "expected a number, got " + describe(*found));
      return std::nullopt;
    }
    const double value = found->get<double>();
    if (!std::isfinite(value)) {
      error(here, "expected a finite number, got " + found->dump());
      return std::nullopt;
    }
    return value;
  }

  std::string unit_of(const Range& range) const {
    const std::string unit = range.unit;
    if (unit == "length") return std::string(" ") + units_name(units);
    if (unit == "feed") return std::string(" ") + units_name(units) + "/min";
    if (unit.empty()) return "";
    return " " + unit;
  }

  /// number() within `range`; nullopt and one message naming the range otherwise.
  std::optional<double> ranged(const Json& object, const std::string& path, const char* key,
                               const Range& range, bool required) {
    const auto value = number(object, path, key, required);
    if (!value) return std::nullopt;
    if (*value < range.min || *value > range.max) {
      error(join_path(path, key), "must be from " + format_number(range.min) + " to " +
                                      format_number(range.max) + unit_of(range) + ", got " +
                                      format_number(*value));
      return std::nullopt;
    }
    return value;
  }

  /// The number at object[key] within the bounds keys.cpp declares for it,
  /// required when declared so.
  std::optional<double> declared(const Json& object, const std::string& path, const char* key) {
    const KeyDeclaration& declaration = fatc::key(join_path(path, key));
    return ranged(object, path, key, bounds_in(declaration, units),
                  std::string(declaration.fallback) == "required");
  }

  /// declared() into `target`, left as it was (its default) when absent or refused.
  void read(const Json& object, const std::string& path, const char* key, double& target) {
    if (const auto value = declared(object, path, key)) target = *value;
  }

  const Json* object(const Json& parent, const std::string& path, const char* key, bool required) {
    const auto found = parent.find(key);
    if (found == parent.end()) {
      if (required) error(join_path(path, key), "missing");
      return nullptr;
    }
    if (!found->is_object()) {
      error(join_path(path, key), "expected an object, got " + describe(*found));
      return nullptr;
    }
    return &*found;
  }

  /// A point whose axes may each be absent (pocket entries, pocket_default).
  struct PartialPoint {
    std::optional<double> x, y, z;
  };

  /// The caller rejects the keys it does not know (pocket entries have more).
  PartialPoint partial_point(const Json& object, const std::string& path) {
    return {declared(object, path, "x"), declared(object, path, "y"), declared(object, path, "z")};
  }

  std::optional<Point> point(const Json& parent, const std::string& path, const char* key) {
    const Json* object = this->object(parent, path, key, true);
    if (!object) return std::nullopt;
    const std::string here = join_path(path, key);
    reject_unknown_keys(*object, here);
    const auto x = declared(*object, here, "x");
    const auto y = declared(*object, here, "y");
    const auto z = declared(*object, here, "z");
    if (!x || !y || !z) return std::nullopt;
    return Point{*x, *y, *z};
  }
};

}  // namespace fatc::reading
