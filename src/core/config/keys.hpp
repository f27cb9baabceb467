#pragma once

// config.json's keys, declared once: the reader takes the keys an object may
// have and the bounds of each number from here, and the config reference
// (docs/config.md) is generated from it (fatc_docs), so neither can drift.

#include <optional>
#include <string>
#include <vector>

#include "settings.hpp"

namespace fatc {

/// What a number may be (in the config's unit: a range holds in mm and inch alike).
struct Range {
  double min;
  double max;
  const char* unit;  ///< "length" (the config's unit), "seconds", "feed" (units/min), or ""
};

struct KeyDeclaration {
  /// The JSON path: "flush.pulses"; `N` stands for any pocket ("pockets.N.x");
  /// a last part "{x,y,z}" declares each of them alike.
  const char* path;
  std::string fallback;  ///< the default in words, or "required"
  std::optional<Range> bounds;
  /// The range in words where bounds do not say it all: choices, relations.
  const char* range;
  std::string doc;  ///< one line; `backticks` name keys, pins and values
  std::optional<double> inch_min = std::nullopt;  ///< a floor of its own in inches
};

/// Every key, in the order of the reference.
const std::vector<KeyDeclaration>& config_keys();
/// The declaration of `path` ("pockets.7.x" finds "pockets.N.{x,y,z}"); a
/// path not declared is a programming error (std::logic_error).
const KeyDeclaration& key(const std::string& path);
/// The names an object at `path` may hold ("" the top, "pockets.7" a pocket).
std::vector<std::string> keys_below(const std::string& path);
/// `key`'s bounds in `units`.
Range bounds_in(const KeyDeclaration& key, Units units);

/// The reference table of docs/config.md.
std::string config_markdown();

}  // namespace fatc
