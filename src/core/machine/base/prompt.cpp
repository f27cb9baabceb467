#include "prompt.hpp"

#include <cctype>
#include <cstdio>

namespace fatc {
namespace {

/// An operator flow ends its executor run before it asks; inside M6 the
/// program holds, and Cancel stops it.
std::string handover_question(const Prompt& prompt, const std::string& what) {
  if (prompt.m6_tool) {
    return "M6 T" + std::to_string(*prompt.m6_tool) + ": " + what +
           ", then press Continue (Cancel stops the program)";
  }
  std::string text = what + ", then press Continue (Cancel to stop)";
  text[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(text[0])));
  return text;
}

}  // namespace

std::string waypoint_words(const std::string& waypoint, const Point& at, unsigned known_axes) {
  std::string words = waypoint + " (";
  const char* names[] = {"X", "Y", "Z"};
  const double values[] = {at.x, at.y, at.z};
  for (int axis = 0; axis < 3; ++axis) {
    if (!(known_axes & (1u << axis))) continue;
    char coordinate[48];
    std::snprintf(coordinate, sizeof coordinate, "%s%s=%.3f", words.back() == '(' ? "" : " ",
                  names[axis], values[axis]);
    words += coordinate;
  }
  return words + ")";
}

std::string words(const Prompt& prompt) {
  const std::string tool = "tool " + std::to_string(prompt.tool);
  switch (prompt.kind) {
    case Prompt::Kind::none:
      break;
    case Prompt::Kind::insert_tool:
      return handover_question(prompt, "insert " + tool + " into the spindle");
    case Prompt::Kind::remove_tool:
      return handover_question(prompt, "remove " + tool + " from the spindle");
    case Prompt::Kind::jog_to_sensor:
      return "Tool " + std::to_string(prompt.tool) +
             " is in the spindle. Jog it closer to the touch-off sensor if you like, then press "
             "Continue to probe (Cancel to stop)";
    case Prompt::Kind::verify_stop:
      return "Verify pocket " + std::to_string(prompt.pocket) + ", stop " +
             std::to_string(prompt.stop) + " of " + std::to_string(prompt.stops) + ": " +
             waypoint_words(prompt.waypoint, prompt.at, prompt.known_axes) +
             ". Look at the clearance, then press Continue (Cancel stops here)";
    case Prompt::Kind::step:
      return "Step by step, " + prompt.sequence + ", step " + std::to_string(prompt.stop) + ": " +
             prompt.action + " " +
             (prompt.known_axes != 0
                  ? waypoint_words(prompt.waypoint, prompt.at, prompt.known_axes)
                  : prompt.waypoint) +
             ". Press Continue to make it (Cancel aborts the sequence)";
    case Prompt::Kind::touch_found:
      return prompt.sequence + " found: " + prompt.action +
             ". Press Continue to write this into config.json (its backup is kept), Cancel to "
             "write nothing";
  }
  return "";
}

}  // namespace fatc
