// What --check says of the keys with a unit that config.json left out.
#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "settings.hpp"
#include "reader.hpp"

namespace fatc {

using reading::format_number;

std::vector<std::string> defaulted_words(const Config& config) {
  const bool inch = config.units == Units::inch;
  // The default each key takes, and where it comes from: the same amount in
  // the other unit, so that a reader sees they agree, or the key it follows.
  struct Taken {
    const char* key;
    double value;
    bool feed;
    std::optional<UnitDefault> fallback;
    const char* follows;
  };
  std::vector<Taken> taken = {
      {"pocket_feed", config.pocket_feed, true, unit_default::pocket_feed, ""},
      {"probe_seek_feed", config.probe_seek_feed, true, unit_default::probe_seek_feed, ""},
      {"probe_latch_feed", config.probe_latch_feed, true, unit_default::probe_latch_feed, ""},
      {"probe_backoff", config.probe_backoff, false, unit_default::probe_backoff, ""},
      {"probe_check_tolerance", config.check_tolerance(), false,
       unit_default::probe_check_tolerance, ""},
      {"probe_window", config.window(), false, unit_default::probe_window, ""},
      {"rack_keepout_above", config.keepout_above(), false, unit_default::rack_keepout_above, ""},
      {"verify_feed", config.dry_run_feed(), true, std::nullopt, "pocket_feed"},
      {"rack_keepout_margin", config.keepout_margin(), false, std::nullopt,
       "half the side offset's length"}};
  if (config.rack_touch) {
    const RackTouch& touch = *config.rack_touch;
    taken.push_back({"rack_touch.bore_tolerance", touch.bore_tolerance, false,
                     unit_default::bore_tolerance, ""});
    taken.push_back({"rack_touch.search", touch.search, false, unit_default::touch_search, ""});
    taken.push_back({"rack_touch.clear", touch.clear, false, unit_default::touch_clear, ""});
    taken.push_back({"rack_touch.drift_tolerance", touch.drift_tolerance, false,
                     unit_default::touch_drift_tolerance, ""});
  }
  const auto amount = [](double value, bool feed, bool in_inch) {
    return format_number(value) + (feed ? (in_inch ? " in/min" : " mm/min")
                                        : (in_inch ? " inch" : " mm"));
  };
  std::vector<std::string> words;
  for (const Taken& key : taken) {
    if (std::find(config.defaulted.begin(), config.defaulted.end(), key.key) ==
        config.defaulted.end()) {
      continue;
    }
    words.push_back(std::string(key.key) + " " + amount(key.value, key.feed, inch) +
                    (key.fallback ? " (default; " +
                                        amount(key.fallback->in(inch ? Units::mm : Units::inch),
                                               key.feed, !inch) +
                                        (inch ? " in a mm config)" : " in an inch config)")
                                  : std::string(" (default: ") + key.follows + ")"));
  }
  return words;
}

}  // namespace fatc
