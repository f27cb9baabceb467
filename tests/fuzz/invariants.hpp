#pragma once

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

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

}  // namespace fatc::fuzz
