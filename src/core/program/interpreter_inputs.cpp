#include "interpreter_inputs.hpp"

#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <string_view>

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
        char scaled[64];
        std::snprintf(scaled, sizeof scaled, "%c%.9g", letter,
                      std::strtod(field.c_str() + 1, nullptr) * length_scale);
        line += scaled;
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
    char scaled[80];
    std::snprintf(scaled, sizeof scaled, "%ld\t%.9g\n", number, value * length_scale);
    result += scaled;
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

std::string ini_for_preflight(std::string_view ini_text, const std::string& folders) {
  // One folder a line: LinuxCNC reads at most LINELEN (255) characters of
  // one, and joins a line ending in a backslash with the next.
  std::string path;
  for (const char c : folders) path += c == ':' ? std::string(":\\\n") : std::string(1, c);
  const std::string line =
      "HAL_PIN_VARS = 0\n" + (folders.empty() ? "" : "SUBROUTINE_PATH = " + path + "\n");
  std::size_t start = 0;
  while (start < ini_text.size()) {
    std::size_t end = ini_text.find('\n', start);
    end = end == std::string_view::npos ? ini_text.size() : end + 1;
    std::string_view row = ini_text.substr(start, end - start);
    while (!row.empty() && std::isspace(static_cast<unsigned char>(row.front()))) {
      row.remove_prefix(1);
    }
    if (row.rfind("[RS274NGC]", 0) == 0) {
      std::string text(ini_text.substr(0, end));
      if (text.back() != '\n') text += '\n';
      return text + line + std::string(ini_text.substr(end));
    }
    start = end;
  }
  std::string text(ini_text);
  if (!text.empty() && text.back() != '\n') text += '\n';
  return text + "[RS274NGC]\n" + line;
}

}  // namespace fatc::program
