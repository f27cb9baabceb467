// What config.json says of single tools: `probe_after_change`, every tool's
// measuring rule, and `tools`, each tool's own kind, rule and feeds.

#include "tool_rules.hpp"

#include <algorithm>
#include <cstdio>
#include <utility>

namespace fatc {
namespace {

/// The words of a rule as config.json spells them; "measure" is the older
/// word for "always" (probe_after_change of the first versions).
constexpr std::pair<const char*, MeasureRule> kRuleWords[] = {
    {"off", MeasureRule::off},     {"always", MeasureRule::always},
    {"new", MeasureRule::when_new}, {"never", MeasureRule::never},
    {"check", MeasureRule::check}, {"measure", MeasureRule::always},
};
constexpr const char* kRuleList = "\"off\", \"always\", \"new\", \"never\", \"check\" or \"measure\"";

const ToolConfig* declared_tool(const Config& config, int tool) {
  const auto found = config.tools.find(tool);
  return found == config.tools.end() ? nullptr : &found->second;
}

}  // namespace

namespace reading {

std::optional<MeasureRule> read_rule(Reader& reader, const Json& object, const std::string& path,
                                     const char* key) {
  const auto given = object.find(key);
  if (given == object.end()) return std::nullopt;
  for (const auto& [word, rule] : kRuleWords) {
    if (*given == word) return rule;
  }
  reader.error(join_path(path, key), std::string("expected ") + kRuleList + ", got " +
                                         describe(*given));
  return std::nullopt;
}

void read_tools(Reader& reader, const Json& root, Config& config) {
  const Json* tools = reader.object(root, "", "tools", false);
  if (!tools) return;
  for (const auto& item : tools->items()) {
    const std::string here = join_path("tools", item.key());
    const auto number = tool_number_key(item.key());
    if (!number) {
      reader.error(here, "the key must be a tool number from 1 to 999999999, like \"7\"");
      continue;
    }
    if (!item.value().is_object()) {
      reader.error(here, "expected an object, got " + describe(item.value()));
      continue;
    }
    const Json& entry = item.value();
    reader.reject_unknown_keys(entry, here);
    ToolConfig tool;
    if (const auto kind = entry.find("kind"); kind != entry.end()) {
      if (*kind == "probe") {
        tool.kind = ToolKind::probe;
      } else if (*kind != "cutter") {
        reader.error(join_path(here, "kind"),
                     "expected \"cutter\" or \"probe\", got " + describe(*kind));
      }
    }
    tool.measure = read_rule(reader, entry, here, "measure");
    tool.check_tolerance = reader.declared(entry, here, "check_tolerance");
    tool.probe_feed = reader.declared(entry, here, "probe_feed");
    config.tools[*number] = tool;
  }
}

void check_tools(Reader& reader, const Config& config) {
  for (const auto& [number, tool] : config.tools) {
    const std::string here = "tools." + std::to_string(number);
    const MeasureRule rule = config.rule_of(number);
    if (tool.check_tolerance && rule != MeasureRule::check) {
      reader.error(here + ".check_tolerance",
                   std::string("only a tool checked at M6 uses it, and tool ") +
                       std::to_string(number) + "'s rule is \"" + rule_name(rule) +
                       "\": give \"measure\": \"check\" or drop the tolerance");
    } else if (tool.check_tolerance && *tool.check_tolerance >= config.window()) {
      reader.error(here + ".check_tolerance",
                   "must be smaller than probe_window (" + format_number(config.window()) +
                       "), got " + format_number(*tool.check_tolerance));
    }
    if (tool.probe_feed && *tool.probe_feed > config.probe_seek_feed) {
      reader.error(here + ".probe_feed", "must not be above probe_seek_feed (" +
                                             format_number(config.probe_seek_feed) +
                                             "): it caps both probing feeds, got " +
                                             format_number(*tool.probe_feed));
    } else if (tool.probe_feed && rule == MeasureRule::never) {
      reader.error(here + ".probe_feed", "tool " + std::to_string(number) +
                                             " is never measured (\"measure\": \"never\"): "
                                             "nothing would use its probe_feed");
    }
  }
}

}  // namespace reading

const char* rule_name(MeasureRule rule) {
  for (const auto& [word, value] : kRuleWords) {
    if (value == rule) return word;
  }
  return "?";
}

MeasureRule Config::rule_of(int tool) const {
  const ToolConfig* own = declared_tool(*this, tool);
  return own && own->measure ? *own->measure : probe_after_change;
}

bool Config::is_probe(int tool) const {
  const ToolConfig* own = declared_tool(*this, tool);
  return own && own->kind == ToolKind::probe;
}

namespace {
/// The cap of a tool's probing feeds: its own, a probe's the slow one.
std::optional<double> feed_cap(const Config& config, int tool) {
  const ToolConfig* own = declared_tool(config, tool);
  if (own && own->probe_feed) return own->probe_feed;
  if (config.is_probe(tool)) return config.probe_latch_feed;
  return std::nullopt;
}
}  // namespace

double Config::seek_feed_of(int tool) const {
  return std::min(probe_seek_feed, feed_cap(*this, tool).value_or(probe_seek_feed));
}

double Config::latch_feed_of(int tool) const {
  return std::min(probe_latch_feed, feed_cap(*this, tool).value_or(probe_latch_feed));
}

std::string rule_said(const Config& config, int tool) {
  const ToolConfig* own = declared_tool(config, tool);
  return (own && own->measure ? "tools." + std::to_string(tool) + ".measure"
                              : std::string("probe_after_change")) +
         " is \"" + rule_name(config.rule_of(tool)) + "\"";
}

std::vector<std::string> measuring_words(const Config& config) {
  std::vector<std::string> lines;
  for (const auto& [tool, own] : config.tools) {
    lines.push_back("T" + std::to_string(tool) + " " + rule_words(config, tool));
  }
  lines.push_back(std::string(config.tools.empty() ? "every tool " : "every other tool ") +
                  rule_words(config, 0) + " (probe_after_change)");
  return lines;
}

std::string spindle_held_refusal(int tool) {
  if (tool == 0) {
    return "spindle held: a probe was in the spindle when the changer stopped answering, so the "
           "spindle start was aborted";
  }
  const std::string t = std::to_string(tool);
  return "spindle held: tool " + t + " in the spindle is a probe (tools." + t +
         ".kind), so the spindle start was aborted; change to a cutter (M6) before M3 or M4";
}

bool uses_default_tolerance(const Config& config) {
  if (config.probe_after_change == MeasureRule::check) return true;  // every tool not listed
  for (const auto& [tool, own] : config.tools) {
    if (config.rule_of(tool) == MeasureRule::check && !own.check_tolerance) return true;
  }
  return false;
}

std::string rule_words(const Config& config, int tool) {
  std::string rule;
  switch (config.rule_of(tool)) {
    case MeasureRule::always:
      rule = "measured";
      break;
    case MeasureRule::when_new:
      rule = "measured if new";
      break;
    case MeasureRule::off:
      rule = "not measured at M6";
      break;
    case MeasureRule::never:
      rule = "never measured (tool table length)";
      break;
    case MeasureRule::check: {
      char tolerance[48];
      std::snprintf(tolerance, sizeof tolerance, "%g", config.check_tolerance_of(tool));
      rule = std::string("checked ±") + tolerance;
      break;
    }
  }
  return config.is_probe(tool) ? "probe, spindle held, " + rule : rule;
}

}  // namespace fatc
