#include <stdexcept>

#include "hal_pins_detail.hpp"

namespace fatc::linuxcnc {
namespace {

void check(int result, const std::string& prefix, const char* name) {
  if (result != 0) throw std::runtime_error("cannot create pin " + prefix + "." + name);
}
void make(int id, hal_pin_dir_t dir, hal_bit_t** pin, const std::string& prefix, const char* name) {
  check(hal_pin_bit_newf(dir, pin, id, "%s.%s", prefix.c_str(), name), prefix, name);
}
void make(int id, hal_pin_dir_t dir, hal_s32_t** pin, const std::string& prefix, const char* name) {
  check(hal_pin_s32_newf(dir, pin, id, "%s.%s", prefix.c_str(), name), prefix, name);
}
void make(int id, hal_pin_dir_t dir, hal_float_t** pin, const std::string& prefix,
          const char* name) {
  check(hal_pin_float_newf(dir, pin, id, "%s.%s", prefix.c_str(), name), prefix, name);
}

}  // namespace

HalPins* create_pins(const std::string& name, int& id, const std::vector<int>& pockets) {
  id = hal_init(name.c_str());
  if (id < 0) throw std::runtime_error("hal_init failed: is LinuxCNC (or halrun) running?");
  auto* p = static_cast<HalPins*>(hal_malloc(sizeof(HalPins)));
  if (!p) throw std::runtime_error("hal_malloc failed");
  const std::string& n = name;
  // iocontrol's tool handshake, mirrored.
  make(id, HAL_IN, &p->number, n, "number");
  make(id, HAL_IN, &p->tool_prepare, n, "tool-prepare");
  make(id, HAL_OUT, &p->prepared, n, "prepared");
  make(id, HAL_IN, &p->tool_change, n, "tool-change");
  make(id, HAL_OUT, &p->changed, n, "changed");
  // The rack.
  make(id, HAL_OUT, &p->chuck, n, "chuck");
  make(id, HAL_IN, &p->probe, n, "probe");
  make(id, HAL_IN, &p->spindle_stopped, n, "spindle-stopped");
  // The optional sensors: read only where config.json's `sensors` says they are wired.
  make(id, HAL_IN, &p->zero_speed, n, "zero-speed");
  make(id, HAL_IN, &p->tool_present, n, "tool-present");
  make(id, HAL_IN, &p->drawbar_open, n, "drawbar-open");
  make(id, HAL_IN, &p->drawbar_closed, n, "drawbar-closed");
  make(id, HAL_IN, &p->air_pressure_ok, n, "air-pressure-ok");
  // What the rack may need around it: each driven only where config.json names it.
  make(id, HAL_OUT, &p->rack_cover_open, n, "rack-cover-open");
  make(id, HAL_IN, &p->rack_cover_opened, n, "rack-cover-opened");
  make(id, HAL_IN, &p->rack_cover_closed, n, "rack-cover-closed");
  make(id, HAL_OUT, &p->air_blast, n, "air-blast");
  p->pocket_count = static_cast<int>(pockets.size());
  p->pocket_occupied =
      static_cast<hal_bit_t**>(hal_malloc(sizeof(hal_bit_t*) * (pockets.size() + 1)));
  p->pocket_tools = static_cast<int*>(hal_malloc(sizeof(int) * (pockets.size() + 1)));
  if (!p->pocket_occupied || !p->pocket_tools) throw std::runtime_error("hal_malloc failed");
  for (std::size_t i = 0; i < pockets.size(); ++i) {
    const std::string pin = "pocket-occupied-" + std::to_string(pockets[i]);
    p->pocket_tools[i] = pockets[i];
    make(id, HAL_IN, &p->pocket_occupied[i], n, pin.c_str());
  }
  make(id, HAL_IN, &p->machine_on, n, "machine-on");
  make(id, HAL_IN, &p->all_homed, n, "all-homed");
  make(id, HAL_IN, &p->clear_fault, n, "clear-fault");
  make(id, HAL_IN, &p->confirm_tool, n, "confirm-tool");
  make(id, HAL_IN, &p->confirm_pocket, n, "confirm-pocket");
  make(id, HAL_OUT, &p->cut_off_pocket, n, "cut-off-pocket");
  make(id, HAL_OUT, &p->heartbeat, n, "heartbeat");
  make(id, HAL_OUT, &p->chuck_held, n, "chuck-held");
  // Until a GUI says otherwise: the spindle holds LinuxCNC's tool, the pocket is not asked.
  *p->confirm_tool = -1;
  *p->confirm_pocket = -1;
  make(id, HAL_IN, &p->linuxcnc_tool, n, "linuxcnc-tool");
  // What the changer is doing.
  make(id, HAL_OUT, &p->state, n, "state");
  make(id, HAL_OUT, &p->ready, n, "ready");
  make(id, HAL_OUT, &p->busy, n, "busy");
  make(id, HAL_OUT, &p->fault, n, "fault");
  make(id, HAL_OUT, &p->tool_in_spindle, n, "tool-in-spindle");
  // The step executor's handshake.
  make(id, HAL_IN, &p->step_request, n, "step-request");
  make(id, HAL_IN, &p->executor_call, n, "executor-call");
  make(id, HAL_IN, &p->abort, n, "abort");
  make(id, HAL_OUT, &p->step_ready, n, "step-ready");
  make(id, HAL_OUT, &p->step_kind, n, "step-kind");
  make(id, HAL_OUT, &p->step_axes, n, "step-axes");
  make(id, HAL_OUT, &p->step_x, n, "step-x");
  make(id, HAL_OUT, &p->step_y, n, "step-y");
  make(id, HAL_OUT, &p->step_z, n, "step-z");
  make(id, HAL_OUT, &p->step_feed, n, "step-feed");
  make(id, HAL_OUT, &p->step_tool, n, "step-tool");
  make(id, HAL_OUT, &p->step_value, n, "step-value");
  make(id, HAL_OUT, &p->units_inch, n, "units-inch");
  make(id, HAL_IN, &p->return_to_xy, n, "return-to-xy");
  make(id, HAL_IN, &p->probe_z, n, "probe-z");
  make(id, HAL_IN, &p->probe_result, n, "probe-result");
  // The operator's buttons, from the GUI panel or any HAL source.
  make(id, HAL_IN, &p->tool_number, n, "tool-number");
  make(id, HAL_IN, &p->load, n, "load");
  make(id, HAL_IN, &p->unload, n, "unload");
  make(id, HAL_IN, &p->pocket_number, n, "pocket-number");
  make(id, HAL_IN, &p->teach_pocket, n, "teach-pocket");
  make(id, HAL_IN, &p->teach_loading, n, "teach-loading");
  make(id, HAL_IN, &p->teach_safe, n, "teach-safe");
  make(id, HAL_IN, &p->teach_sensor, n, "teach-sensor");
  make(id, HAL_IN, &p->verify_pocket, n, "verify-pocket");
  make(id, HAL_OUT, &p->pocket_served, n, "pocket-served");
  make(id, HAL_IN, &p->measure_all, n, "measure-all");
  make(id, HAL_IN, &p->measure_which, n, "measure-which");
  make(id, HAL_OUT, &p->batch_done, n, "batch-done");
  make(id, HAL_OUT, &p->batch_total, n, "batch-total");
  make(id, HAL_IN, &p->continue_, n, "continue");
  make(id, HAL_IN, &p->cancel, n, "cancel");
  make(id, HAL_OUT, &p->waiting_for_operator, n, "waiting-for-operator");
  make(id, HAL_OUT, &p->last_length, n, "last-length");
  // What a panel needs to show and to enable only the buttons that can act.
  make(id, HAL_OUT, &p->awaiting, n, "awaiting");
  make(id, HAL_OUT, &p->step_number, n, "step-number");
  make(id, HAL_OUT, &p->accepting, n, "accepting");
  make(id, HAL_OUT, &p->can_cancel, n, "can-cancel");
  return p;
}

}  // namespace fatc::linuxcnc
