#include "interpreter_inputs.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <optional>
#include <set>
#include <string_view>

#include "../formatted.hpp"

namespace fatc::program {

InterpreterTable interpreter_table(const ToolTable& table, double length_scale) {
  InterpreterTable result;
  result.tool_of_row.push_back(0);
  for (const auto& [tool, entry] : table.tools) {
    // Row 0 is the spindle's: a T0 line would shift every row after it.
    if (tool <= 0) continue;
    std::string line;
    for (const std::string& field : entry.fields) {
      const char letter = static_cast<char>(std::toupper(static_cast<unsigned char>(field[0])));
      if (std::string_view("XYZUVWD").find(letter) != std::string_view::npos) {
        line += formatted("%c%.9g", letter, std::strtod(field.c_str() + 1, nullptr) * length_scale);
      } else {
        line += field;
      }
      line += ' ';
    }
    if (!line.empty()) line.back() = '\n';
    result.text += line;
    result.tool_of_row.push_back(tool);
  }
  return result;
}

namespace {

/// Whether parameter `number` holds a length of a stored position or offset:
/// X Y Z and U V W of G28 (5161), G30 (5181), G92 (5211) and the nine
/// coordinate systems (5221, 20 apart); not A B C, nor a system's rotation.
bool holds_length(long number) {
  for (const long base : {5161L, 5181L, 5211L}) {
    const long axis = number - base;
    if ((axis >= 0 && axis <= 2) || (axis >= 6 && axis <= 8)) return true;
  }
  if (number < 5221 || number > 5221 + 8 * 20 + 8) return false;
  const long axis = (number - 5221) % 20;
  return (axis >= 0 && axis <= 2) || (axis >= 6 && axis <= 8);
}

}  // namespace

std::string interpreter_parameters(std::string_view text, double length_scale) {
  std::string result;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    end = end == std::string_view::npos ? text.size() : end + 1;
    const std::string line(text.substr(start, end - start));
    start = end;
    // LinuxCNC reads each line with sscanf("%d %lf").
    char* after = nullptr;
    const long number = std::strtol(line.c_str(), &after, 10);
    char* value_end = nullptr;
    const double value = after == line.c_str() ? 0.0 : std::strtod(after, &value_end);
    if (after == line.c_str() || value_end == after || !holds_length(number)) {
      result += line;
      continue;
    }
    result += formatted("%ld\t%.9g\n", number, value * length_scale);
  }
  return result;
}

InterpreterTable any_tool_table() {
  InterpreterTable result;
  result.tool_of_row.push_back(0);
  for (int tool = 1; tool <= kToolsWithoutTable; ++tool) {
    result.text += "T" + std::to_string(tool) + " P" + std::to_string(tool) + "\n";
    result.tool_of_row.push_back(tool);
  }
  return result;
}

namespace {

std::string upper(std::string_view text) {
  std::string result;
  for (const char c : text) result.push_back(static_cast<char>(std::toupper(static_cast<unsigned char>(c))));
  return result;
}

std::string_view trimmed(std::string_view text) {
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.front()))) text.remove_prefix(1);
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.remove_suffix(1);
  return text;
}

/// The value of a `REMAP = ...` row; nullopt for any other row.
std::optional<std::string_view> remap_value(std::string_view row) {
  row = trimmed(row);
  if (row.substr(0, 5) != "REMAP") return std::nullopt;
  const std::string_view rest = trimmed(row.substr(5));
  if (rest.empty() || rest.front() != '=') return std::nullopt;
  return trimmed(rest.substr(1));
}

/// The code a REMAP value remaps, upper case: "M6".
std::string remapped_code(std::string_view remap) {
  return upper(remap.substr(0, remap.find_first_of(" \t")));
}

constexpr const char* kStandInM6 = "fixed_atc_probe_preflight_m6";

}  // namespace

bool is_own_m6_remap(std::string_view remap) {
  const std::string words = upper(remap);
  return remapped_code(remap) == "M6" && words.find("NGC=FIXED_ATC_PROBE_M6") != std::string::npos;
}

std::vector<StandIn> preflight_stand_ins() {
  auto sub = [](const std::string& name, const std::string& body) {
    return StandIn{name, "o<" + name + "> sub\n" + body + "o<" + name + "> endsub\nM2\n"};
  };
  // The remap stops the spindle before it asks for the change, whatever
  // TOOL_CHANGE_WITH_SPINDLE_ON; after it the spindle stays stopped (M72
  // restores what M70 saved after the M5).
  return {sub(kStandInM6, "M5\nM6\nG43\n")};
}

std::string user_m_code_module(const std::vector<int>& codes,
                               const std::optional<std::string>& own_toplevel) {
  std::string list;
  for (const int code : codes) list += std::to_string(code) + ", ";
  // A Python string of any path: each byte as \xNN.
  auto literal = [](const std::string& text) {
    std::string quoted = "b'";
    char hex[8];
    for (const unsigned char c : text) {
      std::snprintf(hex, sizeof hex, "\\x%02x", c);
      quoted += hex;
    }
    return quoted + "'.decode('utf-8', 'surrogateescape')";
  };
  std::string text =
      "# fixed_atc_probe --lint: LinuxCNC's task runs the INI's user M-codes, not its\n"
      "# interpreter, and tells the interpreter of each (USER_DEFINED_FUNCTION); rs274\n"
      "# is told the same, each a function that does nothing.\n"
      "import ctypes as _fatc_ctypes\n"
      "try:\n"
      "    _fatc_user_m = _fatc_ctypes.CFUNCTYPE(None, _fatc_ctypes.c_int, _fatc_ctypes.c_double,\n"
      "                                          _fatc_ctypes.c_double)(lambda code, p, q: None)\n"
      "    _fatc_table = (_fatc_ctypes.c_void_p * 100).in_dll(_fatc_ctypes.CDLL(None),\n"
      "                                                       'USER_DEFINED_FUNCTION')\n"
      "    for _fatc_code in (" + list + "):\n"
      "        _fatc_table[_fatc_code - 100] = _fatc_ctypes.cast(_fatc_user_m, _fatc_ctypes.c_void_p).value\n"
      "except (AttributeError, ValueError, OSError):\n"
      "    pass  # an rs274 that does not show the table: the codes stay unknown to it\n";
  if (own_toplevel) {
    // The INI's own TOPLEVEL, run as the plugin runs it: into the same namespace.
    text += "_fatc_own = " + literal(*own_toplevel) +
            "\nexec(compile(open(_fatc_own).read(), _fatc_own, 'exec'))\n";
  }
  return text;
}

std::string ini_for_preflight(std::string_view ini_text, const std::string& folders,
                              const std::string& python_toplevel) {
  // One folder a line: LinuxCNC reads at most LINELEN (255) characters of
  // one, and joins a line ending in a backslash with the next.
  std::string path;
  for (const char c : folders) path += c == ':' ? std::string(":\\\n") : std::string(1, c);
  const std::string rs274ngc_lines =
      "HAL_PIN_VARS = 0\n" + (folders.empty() ? "" : "SUBROUTINE_PATH = " + path + "\n");
  std::vector<std::string_view> rows;
  for (std::size_t start = 0; start < ini_text.size();) {
    std::size_t end = ini_text.find('\n', start);
    end = end == std::string_view::npos ? ini_text.size() : end + 1;
    rows.push_back(ini_text.substr(start, end - start));
    start = end;
  }
  auto is_section = [](std::string_view row) { return trimmed(row).substr(0, 1) == "["; };
  auto section_is = [](std::string_view row, std::string_view name) {
    return trimmed(row).substr(0, name.size()) == name;
  };
  // The lines go first in their section, where LinuxCNC takes the first of a key.
  struct Insert {
    std::string_view section;
    std::string lines;
    bool done = false;
  };
  std::vector<Insert> inserts = {{"[RS274NGC]", rs274ngc_lines}};
  if (!python_toplevel.empty()) inserts.push_back({"[PYTHON]", "TOPLEVEL = " + python_toplevel + "\n"});
  std::string text;
  bool in_rs274ngc = false;
  for (const std::string_view row : rows) {
    if (is_section(row)) in_rs274ngc = section_is(row, "[RS274NGC]");
    const auto remap = remap_value(row);
    if (in_rs274ngc && remap && is_own_m6_remap(*remap)) {
      const std::size_t ngc = upper(*remap).find("NGC=") + 4;
      const std::size_t name_end = std::min(remap->find_first_of(" \t", ngc), remap->size());
      text += "REMAP = " + std::string(remap->substr(0, ngc)) + kStandInM6 +
              std::string(remap->substr(name_end)) + "\n";
      continue;
    }
    text += row;
    for (Insert& insert : inserts) {
      if (insert.done || !is_section(row) || !section_is(row, insert.section)) continue;
      if (text.back() != '\n') text += '\n';
      text += insert.lines;
      insert.done = true;
    }
  }
  for (const Insert& insert : inserts) {
    if (insert.done) continue;
    if (!text.empty() && text.back() != '\n') text += '\n';
    text += std::string(insert.section) + "\n" + insert.lines;
  }
  return text;
}

}  // namespace fatc::program
