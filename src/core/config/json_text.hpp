#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace fatc {

/// Deepest nesting a config or state file may have; config.json needs 3.
constexpr std::size_t kMaxJsonDepth = 64;

/// Either the parsed JSON or what is wrong with the text, one line each:
/// "line 3, column 7: invalid JSON: ..." for syntax, numbers beyond a double,
/// NUL bytes and nesting deeper than kMaxJsonDepth; "pockets.2: appears twice"
/// for a key an object already had (nlohmann would silently keep the last).
struct JsonText {
  std::optional<nlohmann::json> value;
  std::vector<std::string> errors;
};

/// Parses without recursion, in time linear in the text.
JsonText parse_json_text(const std::string& text);

/// "parent.key", the key escaped and cut short (see escape()).
std::string join_path(const std::string& parent, const std::string& key);

/// A JSON value for a message: null, true, an object, an array, a quoted and
/// shortened string, or the number.
std::string describe(const nlohmann::json& value);

/// The tool number a key names ("7"), or nullopt ("07", "-3", "1.5", "x").
std::optional<int> tool_number_key(const std::string& key);

/// An integer JSON value from 1 to 999999999.
bool is_tool_number(const nlohmann::json& value);

}  // namespace fatc
