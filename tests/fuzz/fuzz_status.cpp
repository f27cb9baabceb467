// Any bytes as the status file --operator prints the component's words from,
// and as a line the command line prints: what reaches the terminal has no
// control character it would act on (C0 but tab and newline, DEL, C1, a byte
// that is not UTF-8). Never a crash, an exception, a leak or undefined behaviour.
#include <cstdint>
#include <string>

#include "cli/operator_watch.hpp"
#include "invariants.hpp"
#include "io/capped_lines.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  fatc::fuzz::check_terminal_safe(fatc::io::terminal_safe(text));
  const auto words = fatc::io::parse_status_words(text);
  if (!words) return 0;
  fatc::io::OperatorWatch watch({fatc::io::OperatorRequest::Action::load, 3}, true, 0);
  for (const std::string& line : watch.observe(words, {3, true, true, false}).lines) {
    if (line.find('\n') != std::string::npos) fatc::fuzz::broken("a message is one line", line);
    fatc::fuzz::check_terminal_safe(line);
  }
  return 0;
}
