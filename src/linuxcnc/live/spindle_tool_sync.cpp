#include "spindle_tool_sync.hpp"

#include "nml_link.hpp"

namespace fatc::linuxcnc {

void SpindleToolSync::poll(Clock::time_point now, int linuxcnc_tool, const Changer& changer,
                           NmlLink& nml, Ports& ports) {
  if (!wanted_ || changer.status().phase != Phase::idle) return;
  const int tool = changer.tools().spindle;
  if (linuxcnc_tool == tool) {
    wanted_ = false;  // done only when LinuxCNC says so: task may refuse an MDI
    return;
  }
  if (sent_ && now - *sent_ < std::chrono::seconds(5)) return;
  sent_ = now;
  if (!nml.run_mdi("M61 Q" + std::to_string(tool))) return;  // again in 5 s
  ports.tell(MessageKind::info,
             "told LinuxCNC the spindle holds " +
                 (tool == 0 ? std::string("nothing") : "tool " + std::to_string(tool)) +
                 ", as the changer recorded it");
}

}  // namespace fatc::linuxcnc
