#include "hal_pins_view.hpp"

#include <cmath>

#include "hal_pins_detail.hpp"

namespace fatc::linuxcnc {

SensorReadings read_sensors(const HalPins& pins, const Config& config) {
  const SensorConfig& wired = config.sensors;
  SensorReadings sensors;
  for (const SensorDeclaration& sensor : kSensors) {
    if (wired.wired(sensor.sensor)) sensors.set(sensor.sensor, *pins.sensors[index(sensor.sensor)]);
  }
  for (int i = 0; i < pins.pocket_count; ++i) {
    const int pocket = pins.pocket_tools[i];
    if (wired.pocket(pocket)) sensors.pockets[pocket] = *pins.pocket_sensors[i];
  }
  return sensors;
}

LinkInputs read_link(const HalPins& pins, std::optional<bool> interpreter_idle) {
  LinkInputs in;
  in.step_request = *pins.step_request;
  in.call = static_cast<int>(std::lround(*pins.executor_call));
  in.number = *pins.number;
  in.probe_result = *pins.probe_result;
  in.probe_z = *pins.probe_z;
  in.tool_prepare = *pins.tool_prepare;
  in.tool_change = *pins.tool_change;
  in.interpreter_idle = interpreter_idle;
  return in;
}

void write_link(HalPins& pins, const LinkOutputs& out) {
  *pins.step_kind = static_cast<int>(out.step.kind);
  *pins.step_axes = static_cast<int>(out.step.axes);
  *pins.step_x = out.step.target.x;
  *pins.step_y = out.step.target.y;
  *pins.step_z = out.step.target.z;
  *pins.step_feed = out.step.feed;
  *pins.step_tool = out.step.tool;
  *pins.step_value = out.step.value;
  // A run of rapids: up to safe Z and across at it before the step's own move.
  *pins.step_via = static_cast<int>(via_of(out.step));
  Point via = out.step.target;
  for (const Step& move : out.step.before) via = moved_to(via, move);
  *pins.step_via_x = via.x;
  *pins.step_via_y = via.y;
  *pins.step_via_z = via.z;
  *pins.step_blend = out.step.blend;
  *pins.step_ready = out.step_ready;
  *pins.prepared = out.prepared;
  *pins.changed = out.changed;
}

void write_status(HalPins& pins, const Status& status, const Changer& changer,
                  bool executor_attached, bool linuxcnc_task) {
  *pins.state = static_cast<int>(status.phase);
  *pins.ready = status.phase == Phase::idle && !status.chuck_held;
  *pins.chuck_held = status.chuck_held;
  *pins.probe_in_spindle = status.spindle_probe != 0;
  *pins.fault = status.phase == Phase::fault;
  *pins.busy = status.busy();
  *pins.touching = status.phase == Phase::touching;
  *pins.changer_spindle = status.turns_spindle;
  *pins.tool_in_spindle = changer.tools().spindle;
  *pins.awaiting = static_cast<int>(status.awaiting);
  *pins.step_number = status.step_number;
  *pins.pocket_served = status.pocket;
  *pins.accepting = status.accepting;
  if (status.last_length) *pins.last_length = *status.last_length;
  // An operator flow waits for the operator once its executor run has ended
  // (the GUI and jogging are then free); M6 holds its program meanwhile.
  const bool waiting = status.awaits_operator() && (!executor_attached || status.holds_program);
  // can-cancel first: a reader that sees the operator awaited sees the prompt
  // cancellable too.
  *pins.can_cancel = waiting || (status.probe_cancellable && linuxcnc_task) ||
                     status.phase == Phase::measuring;
  *pins.waiting_for_operator = waiting;
  // After can-cancel: a reader that sees a batch under way sees it cancellable.
  *pins.batch_done = status.batch_done;
  *pins.batch_total = status.batch_total;
  const auto& cut_off = changer.cut_off();
  // Only a pocket with a tool of its own has a question to answer.
  *pins.cut_off_pocket =
      cut_off && status.phase == Phase::fault && changer.tools().tool_of(cut_off->pocket) != 0
          ? cut_off->pocket
          : 0;
  *pins.heartbeat = !*pins.heartbeat;
}

}  // namespace fatc::linuxcnc
