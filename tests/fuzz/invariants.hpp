#pragma once

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "core/config/quote.hpp"

namespace fatc::fuzz {

/// Stops the run as a finding, saying which promise was broken.
[[noreturn]] inline void broken(const char* promise, const std::string& detail) {
  std::fprintf(stderr, "broken promise: %s: %s\n", promise, detail.c_str());
  std::abort();
}

/// Every message is one printable line of bounded length: user text inside
/// is escaped and cut short (quote(), escape()).
inline void check_messages(const std::vector<std::string>& messages) {
  for (const std::string& message : messages) {
    if (message.empty()) broken("a message says something", "empty");
    if (message.size() > 1000) broken("a message is short", message.substr(0, 200));
    for (const char c : message) {
      const auto byte = static_cast<unsigned char>(c);
      if (byte < 0x20 || byte == 0x7F) broken("no control characters in a message", message);
    }
  }
}

/// Nothing a terminal acts on: no C0 control but tab and newline, no DEL, no
/// C1 control, no byte that is not UTF-8.
inline void check_terminal_safe(const std::string& text) {
  for (std::size_t at = 0; at < text.size();) {
    const auto byte = static_cast<unsigned char>(text[at]);
    if (byte < 0x80) {
      if ((byte < 0x20 && byte != '\t' && byte != '\n') || byte == 0x7F) {
        broken("no control character reaches the terminal", text.substr(0, 200));
      }
      ++at;
      continue;
    }
    char32_t code = 0;
    const std::size_t length = decode_utf8(text, at, code);
    if (length == 0 || code <= 0x9F)
      broken("only UTF-8 and no C1 control reaches the terminal", text.substr(0, 200));
    at += length;
  }
}

}  // namespace fatc::fuzz
