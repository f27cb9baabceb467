#include "teach.hpp"

#include <cmath>
#include <cstdio>
#include <vector>

#include "../config/json_text.hpp"
#include "../config/quote.hpp"
#include "sequence_check.hpp"

namespace fatc {
namespace {

using OrderedJson = nlohmann::ordered_json;

/// Lines are wrapped here, as .clang-format wraps the code.
constexpr std::size_t kColumns = 100;
/// Pockets named in "there is no pocket N (pockets: ...)"; a rack has a few dozen.
constexpr std::size_t kMaxPocketsNamed = 30;

bool is_container(const OrderedJson& value) { return value.is_object() || value.is_array(); }

/// Nothing but scalars inside: written on one line.
bool is_flat(const OrderedJson& value) {
  for (const auto& item : value) {
    if (is_container(item)) return false;
  }
  return true;
}

/// `value` of scalars from `column` on, wrapped under its first item when a
/// line would pass kColumns; `trailing` characters (a comma) follow it.
void write_flat(const OrderedJson& value, std::size_t column, std::size_t trailing,
                std::string& out) {
  std::vector<std::string> items;
  for (const auto& item : value.items()) {
    items.push_back(value.is_object() ? OrderedJson(item.key()).dump() + ": " + item.value().dump()
                                      : item.value().dump());
  }
  out += value.is_object() ? '{' : '[';
  const std::size_t start = ++column;
  for (std::size_t i = 0; i < items.size(); ++i) {
    const std::size_t tail = i + 1 == items.size() ? 1 + trailing : 1;  // "," or the bracket
    if (i > 0 && column + 2 + items[i].size() + tail > kColumns) {
      out += ",\n" + std::string(start, ' ');
      column = start;
    } else if (i > 0) {
      out += ", ";
      column += 2;
    }
    out += items[i];
    column += items[i].size();
  }
  out += value.is_object() ? '}' : ']';
}

void write_value(const OrderedJson& value, std::size_t indent, std::size_t column,
                 std::size_t trailing, std::string& out) {
  if (!is_container(value)) {
    out += value.dump();
    return;
  }
  if (is_flat(value)) {
    write_flat(value, column, trailing, out);
    return;
  }
  const std::string inner(indent + 2, ' ');
  out += value.is_object() ? "{\n" : "[\n";
  std::size_t left = value.size();
  for (const auto& item : value.items()) {
    const std::size_t comma = --left > 0 ? 1 : 0;
    std::string head = inner;
    if (value.is_object()) head += OrderedJson(item.key()).dump() + ": ";
    out += head;
    write_value(item.value(), indent + 2, head.size(), comma, out);
    out += comma ? ",\n" : "\n";
  }
  out += std::string(indent, ' ') + (value.is_object() ? "}" : "]");
}

/// A number as given, for the error line: "151.2", "-80", "nan", "1e+300".
std::string given(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.10g", value);
  return buffer;
}

/// A value as written, with the decimals of its units: "150.0000".
std::string fixed(double value, int decimals) {
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, std::fabs(value) < 1e15 ? "%.*f" : "%.*g", decimals, value);
  return buffer;
}

/// The value at `decimals`; -0 written as 0. Beyond a double's decimals it stays as it is.
double rounded(double value, int decimals) {
  const double scale = std::pow(10.0, decimals);
  const double result = std::round(value * scale) / scale;
  if (!std::isfinite(result)) return value;
  return result == 0.0 ? 0.0 : result;
}

template <typename Json>
Units units_of(const Json& root) {
  const auto units = root.find("units");
  return units != root.end() && *units == "inch" ? Units::inch : Units::mm;
}

/// The number at object[axis], if it is one.
std::optional<double> number_at(const OrderedJson* object, const char* axis) {
  if (!object || !object->is_object()) return std::nullopt;
  const auto found = object->find(axis);
  if (found == object->end() || !found->is_number()) return std::nullopt;
  return found->get<double>();
}

/// "pockets: 1, 2, 4", or "no pockets".
std::string pockets_named(const OrderedJson& root) {
  const auto pockets = root.find("pockets");
  if (pockets == root.end() || !pockets->is_object() || pockets->empty()) return "no pockets";
  std::string names = "pockets: ";
  std::size_t named = 0;
  for (const auto& item : pockets->items()) {
    if (named == kMaxPocketsNamed) return names + ", ...";
    names += (named++ > 0 ? ", " : "") + escape(item.key(), 20);
  }
  return names;
}

}  // namespace

std::optional<TeachTarget> parse_teach_target(const std::string& text) {
  using Kind = TeachTarget::Kind;
  if (text == "loading") return TeachTarget{Kind::loading, 0};
  if (text == "safe") return TeachTarget{Kind::safe, 0};
  if (text == "sensor") return TeachTarget{Kind::sensor, 0};
  if (text == "datum") return TeachTarget{Kind::datum, 0};
  const std::string prefix = "pocket:";
  if (text.rfind(prefix, 0) != 0) return std::nullopt;
  const auto number = tool_number_key(text.substr(prefix.size()));
  if (!number) return std::nullopt;
  return TeachTarget{Kind::pocket, *number};
}

std::string target_name(const TeachTarget& target) {
  switch (target.kind) {
    case TeachTarget::Kind::pocket:
      return "pocket " + std::to_string(target.pocket);
    case TeachTarget::Kind::loading:
      return "loading";
    case TeachTarget::Kind::safe:
      return "safe";
    case TeachTarget::Kind::datum:
      return "the rack datum";
    case TeachTarget::Kind::sensor:
      break;
  }
  return "sensor";
}

Units declared_units(const std::string& config_text) {
  const JsonText parsed = parse_json_text(config_text);
  if (!parsed.value || !parsed.value->is_object()) return Units::mm;
  return units_of(*parsed.value);
}

std::string format_config_json(const OrderedJson& root) {
  std::string out;
  write_value(root, 0, 0, 0, out);
  return out + "\n";
}

TeachResult teach(const std::string& config_text, const TeachTarget& target, const Point& at,
                  const std::optional<SoftLimits>& limits, const ToolLengths& lengths) {
  const bool sensor = target.kind == TeachTarget::Kind::sensor;
  const char* const axes[] = {"x", "y", "z"};
  const double values[] = {at.x, at.y, at.z};
  const int taught_axes = sensor ? 2 : 3;

  std::string position;
  for (int axis = 0; axis < taught_axes; ++axis) {
    position +=
        std::string(axis > 0 ? " " : "") + static_cast<char>('X' + axis) + given(values[axis]);
  }
  auto refuse = [&](const std::string& why) {
    TeachResult refused;
    refused.error = "teach " + target_name(target) + " at " + position + ": not written: " + why;
    return refused;
  };
  for (int axis = 0; axis < taught_axes; ++axis) {
    if (!std::isfinite(values[axis])) {
      return refuse(std::string(1, static_cast<char>('X' + axis)) + " is not a finite number");
    }
  }

  // Strict first: duplicate keys, depth and numbers beyond a double are
  // refused there, which nlohmann's own parser would let through.
  const JsonText strict = parse_json_text(config_text);
  if (!strict.value) return refuse(strict.errors.front());
  if (!strict.value->is_object()) {
    return refuse("config: expected a JSON object at the top, got " + describe(*strict.value));
  }
  OrderedJson root = OrderedJson::parse(config_text);

  OrderedJson* entry = nullptr;
  const OrderedJson* fallback = nullptr;  // where an axis the entry lacks comes from
  std::string path;
  if (target.kind == TeachTarget::Kind::pocket) {
    const auto pockets = root.find("pockets");
    if (pockets != root.end() && pockets->is_object()) {
      for (auto& item : pockets->items()) {
        if (tool_number_key(item.key()) == target.pocket) entry = &item.value();
      }
    }
    if (!entry) {
      return refuse("there is no pocket " + std::to_string(target.pocket) + " (" +
                    pockets_named(root) + "); teaching does not add pockets");
    }
    path = "pockets." + std::to_string(target.pocket);
    if (const auto defaults = root.find("pocket_default"); defaults != root.end()) {
      fallback = &*defaults;
    }
  } else if (target.kind == TeachTarget::Kind::datum) {
    // The datum's pocket is named by hand once; teaching writes where it was found.
    path = "rack_touch.datum";
    const auto touch = root.find("rack_touch");
    if (touch == root.end() || !touch->is_object() || !touch->contains("datum")) {
      return refuse("config.json has no rack_touch.datum: name the datum's pocket there first, "
                    "\"datum\": {\"pocket\": N}");
    }
    entry = &(*touch)["datum"];
  } else {
    path = target.kind == TeachTarget::Kind::loading ? "loading"
           : target.kind == TeachTarget::Kind::safe  ? "safe"
                                                     : "probe_limit";
    if (!root.contains(path)) root[path] = OrderedJson::object();
    entry = &root[path];
  }
  if (!entry->is_object()) {
    return refuse(path + ": expected an object, got " + describe(nlohmann::json(*entry)));
  }

  const int decimals = units_of(root) == Units::inch ? 5 : 4;
  TeachResult result;
  result.change = (sensor ? "sensor (probe_limit)" : target_name(target)) + ":";
  for (int axis = 0; axis < taught_axes; ++axis) {
    auto before = number_at(entry, axes[axis]);
    if (!before) before = number_at(fallback, axes[axis]);
    const double after = rounded(values[axis], decimals);
    const std::string now = fixed(after, decimals);
    result.change += std::string(axis > 0 ? "," : "") + " " + axes[axis] + " ";
    if (before && fixed(*before, decimals) == now) {
      result.change += now + " (unchanged)";
    } else {
      result.change += (before ? fixed(*before, decimals) : std::string("unset")) + " → " + now;
    }
    (*entry)[axes[axis]] = after;
  }
  if (sensor) {
    const auto z = number_at(entry, "z");
    result.change += "; z " + (z ? fixed(*z, decimals) : std::string("unset")) +
                     " kept (the lowest the probe may go)";
  }

  std::string text = format_config_json(root);
  const ConfigResult parsed = parse_config(text);
  if (!parsed.config) return refuse(parsed.errors.front());
  const SequencesChecked checked = check_sequences(*parsed.config, limits, lengths);
  if (!checked.violations.empty()) return refuse(describe(checked.violations.front()));
  result.text = std::move(text);
  return result;
}

}  // namespace fatc

namespace fatc {

TeachResult teach_all(const std::string& config_text, const std::vector<Taught>& taught,
                      const std::optional<SoftLimits>& limits, const ToolLengths& lengths) {
  TeachResult all;
  std::string text = config_text;
  for (const Taught& one : taught) {
    TeachResult result = teach(text, one.target, one.at, limits, lengths);
    if (!result.text) return result;
    text = std::move(*result.text);
    all.change += (all.change.empty() ? "" : "\n") + result.change;
  }
  all.text = std::move(text);
  return all;
}

}  // namespace fatc
