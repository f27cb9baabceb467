#include "pin_reference.hpp"

#include <algorithm>

#include "io/man_text.hpp"
#include "pin_list.hpp"

namespace fatc::linuxcnc {
namespace {

std::string start_value(const PinDeclaration& pin) {
  if (std::string(pin.name) == "heartbeat") return "*";  // it toggles
  if (std::string(type_name(pin)) == "bit") return pin.start ? "TRUE" : "FALSE";
  return std::to_string(pin.start);
}

}  // namespace

std::string pins_markdown() {
  std::string out =
      "| pin | type | dir | meaning |\n"
      "| --- | --- | --- | --- |\n";
  for (const PinDeclaration& pin : kPins) {
    out += "| `" + std::string(pin.name) + "` | " + type_name(pin) + " | " + dir_name(pin) +
           " | " + pin.doc + " |\n";
  }
  return out;
}

std::string pins_man() {
  std::string out;
  for (const PinDeclaration& pin : kPins) {
    std::string name = pin.name;
    if (const auto n = name.rfind("-N"); n != std::string::npos && n + 2 == name.size()) {
      name = name.substr(0, n + 1) + "\\fIN\\fB";
    } else if (const auto m = name.find("-N-"); m != std::string::npos) {
      name = name.substr(0, m + 1) + "\\fIN\\fB" + name.substr(m + 2);
    }
    out += ".TP\n.B fixed_atc_probe." + name + " \\fR" + type_name(pin) + " " + dir_name(pin) +
           "\n" + io::man_text(pin.doc) + "\n";
  }
  return out;
}

std::string pins_golden(const std::vector<int>& pockets) {
  std::vector<std::pair<std::string, std::string>> lines;  // name, line
  for (const PinDeclaration& pin : kPins) {
    const std::string dir = pin.dir == HAL_IN ? "IN" : "OUT";
    const std::string head = std::string(type_name(pin)) + " " + dir + " " + start_value(pin) + " ";
    if (pin.type == PinDeclaration::Type::bit_per_pocket) {
      for (const int pocket : pockets) {
        const std::string name = "fixed_atc_probe." + pocket_pin(pocket);
        lines.emplace_back(name, head + name);
      }
    } else if (pin.type == PinDeclaration::Type::real_per_box) {
      for (std::size_t box = 0; box < kGuardBoxes; ++box) {
        const std::string name = "fixed_atc_probe." + box_pin_name(pin, box);
        lines.emplace_back(name, head + name);
      }
    } else {
      const std::string name = "fixed_atc_probe." + std::string(pin.name);
      lines.emplace_back(name, head + name);
    }
  }
  std::sort(lines.begin(), lines.end());
  std::string out;
  for (const auto& line : lines) out += line.second + "\n";
  return out;
}

}  // namespace fatc::linuxcnc
