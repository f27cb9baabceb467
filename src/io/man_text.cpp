#include "man_text.hpp"

namespace fatc::io {

std::string man_text(const std::string& text) {
  std::string out;
  bool bold = false;
  for (const char c : text) {
    if (c == '`') {
      out += bold ? "\\fR" : "\\fB";
      bold = !bold;
    } else {
      out += c == '\\' ? std::string("\\e") : std::string(1, c);
    }
  }
  return out;
}

}  // namespace fatc::io
