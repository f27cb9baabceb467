#pragma once

#include <string>
#include <vector>

#include "../../rack/tool_state.hpp"

namespace fatc {

/// What measure all measures, as the `measure-which` pin asks.
struct MeasureChoice {
  enum class Kind {
    tools,          ///< `tools`: 0 every tool in the rack, 1 those with no length yet
    program_tools,  ///< 2: the tools of the program loaded in LinuxCNC, which its interpreter
                    ///< works out (never on the poll thread: it may take seconds)
    refused,        ///< any other value; `refusal` is the message
  };
  Kind kind = Kind::refused;
  std::vector<int> tools;
  std::string refusal;
};

/// `which` as the pin gives it, on the rack as `tools` records it.
MeasureChoice measure_which(int which, const ToolState& tools);

/// "measure all refused: <why>".
std::string measure_refused(const std::string& why);

}  // namespace fatc
