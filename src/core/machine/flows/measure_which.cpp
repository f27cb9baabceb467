#include "measure_which.hpp"

#include <algorithm>

namespace fatc {

MeasureChoice measure_which(int which, const ToolState& tools) {
  MeasureChoice choice;
  switch (which) {
    case 0:
    case 1:
      choice.kind = MeasureChoice::Kind::tools;
      choice.tools = tools.rack_tools();
      if (which == 1) {
        auto& asked = choice.tools;
        asked.erase(std::remove_if(asked.begin(), asked.end(),
                                   [&](int tool) { return tools.lengths.count(tool) != 0; }),
                    asked.end());
      }
      return choice;
    case 2:
      choice.kind = MeasureChoice::Kind::program_tools;
      return choice;
    default:
      choice.refusal = measure_refused(
          "measure-which must be 0 (every tool in the rack), 1 (the unmeasured) or 2 (the "
          "program's), got " +
          std::to_string(which));
      return choice;
  }
}

std::string measure_refused(const std::string& why) { return "measure all refused: " + why; }

}  // namespace fatc
