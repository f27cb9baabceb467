// Any bytes as the saved tool state: either a state that writes back to the
// same state, or one printable line. Never a crash, an exception, a leak or
// undefined behaviour.
#include <cstdint>
#include <string>

#include "core/rack/tool_state.hpp"
#include "invariants.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const fatc::ToolStateResult result = fatc::tool_state_from_json(text);
  if (result.state.has_value() == !result.error.empty()) {
    fatc::fuzz::broken("a state or an error, never both or neither", text.substr(0, 200));
  }
  if (!result.state) {
    fatc::fuzz::check_messages({result.error});
    return 0;
  }
  const fatc::ToolStateResult again = fatc::tool_state_from_json(fatc::to_json(*result.state));
  if (!again.state || !(*again.state == *result.state)) {
    fatc::fuzz::broken("what is read is written back the same", again.error);
  }
  return 0;
}
