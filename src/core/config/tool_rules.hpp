#pragma once

// Reading what config.json says of single tools (tool_rules.cpp); the rules
// themselves are Config's (settings.hpp).

#include "reader.hpp"

namespace fatc::reading {

/// A measuring rule at object[key]: one of its words, one message otherwise.
std::optional<MeasureRule> read_rule(Reader& reader, const Json& object, const std::string& path,
                                     const char* key);
/// `tools`: each tool's kind, rule, check tolerance and probing feed.
void read_tools(Reader& reader, const Json& root, Config& config);
/// Relations of `tools` with the rest, once every key read cleanly.
void check_tools(Reader& reader, const Config& config);

}  // namespace fatc::reading
