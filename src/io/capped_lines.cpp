#include "capped_lines.hpp"

#include <cstdio>

namespace fatc::io {

std::string terminal_safe(std::string_view line) {
  std::string out;
  char buffer[16];
  for (std::size_t at = 0; at < line.size();) {
    const unsigned char c = static_cast<unsigned char>(line[at]);
    if (c == '\n' || c == '\t' || (c >= 0x20 && c < 0x7F)) {
      out += static_cast<char>(c);
      ++at;
      continue;
    }
    char32_t code = c;
    const std::size_t length = c < 0x80 ? 1 : decode_utf8(line, at, code);
    if (c == '\r') {
      out += "\\r";
    } else if (length == 0 || c < 0x80) {
      std::snprintf(buffer, sizeof buffer, "\\x%02x", c);
      out += buffer;
    } else if (code <= 0x9F) {
      std::snprintf(buffer, sizeof buffer, "\\u{%04x}", static_cast<unsigned>(code));
      out += buffer;
    } else {
      out.append(line.substr(at, length));
    }
    at += length == 0 ? 1 : length;
  }
  return out;
}

void print_capped(std::ostream& out, const std::vector<std::string>& lines) {
  for (std::size_t i = 0; i < lines.size() && i < kMaxListedLines; ++i) {
    out << "  " << lines[i] << "\n";
  }
  if (lines.size() > kMaxListedLines) {
    out << "  ... and " << lines.size() - kMaxListedLines << " more\n";
  }
}

}  // namespace fatc::io
