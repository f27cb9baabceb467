#include "interpreter_inputs.hpp"

#include <cctype>
#include <cstdio>
#include <cstdlib>

namespace fatc::program {

InterpreterTable interpreter_table(const ToolTable& table, double diameter_scale) {
  InterpreterTable result;
  result.tool_of_row.push_back(0);
  for (const auto& [tool, entry] : table.tools) {
    // Row 0 is the spindle's: a T0 line would shift every row after it.
    if (tool <= 0) continue;
    std::string line;
    for (const std::string& field : entry.fields) {
      const char letter = static_cast<char>(std::toupper(static_cast<unsigned char>(field[0])));
      if (letter == 'D') {
        char scaled[64];
        std::snprintf(scaled, sizeof scaled, "D%.9g", std::strtod(field.c_str() + 1, nullptr) *
                                                          diameter_scale);
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
