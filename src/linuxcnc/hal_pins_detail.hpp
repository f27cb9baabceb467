#pragma once

#include <hal.h>

#include "hal_pins.hpp"

namespace fatc::linuxcnc {

struct HalPins {
  hal_s32_t* number;        ///< in: tool being prepared (iocontrol.0.tool-prep-number)
  hal_bit_t* tool_prepare;  ///< in: iocontrol.0.tool-prepare
  hal_bit_t* prepared;      ///< out: iocontrol.0.tool-prepared
  hal_bit_t* tool_change;   ///< in: iocontrol.0.tool-change
  hal_bit_t* changed;       ///< out: iocontrol.0.tool-changed; high until tool-change drops
  hal_bit_t* chuck;         ///< out: true opens the chuck
  hal_bit_t*
      chuck_held;    ///< out: a G-code release holds the chuck open: inhibit motion and spindle
  hal_bit_t* probe;  ///< in: the touch-off sensor
  hal_bit_t* spindle_stopped;    ///< in: the spindle stands still, as LinuxCNC commands it
  hal_bit_t* zero_speed;         ///< in: the spindle's zero-speed feedback (sensors.zero_speed)
  hal_bit_t* tool_present;       ///< in: a tool is clamped in the spindle (sensors.tool_present)
  hal_bit_t* drawbar_open;       ///< in: the drawbar is released (sensors.drawbar_open)
  hal_bit_t* drawbar_closed;     ///< in: the drawbar is clamped (sensors.drawbar_closed)
  hal_bit_t* air_pressure_ok;    ///< in: the drawbar has air (sensors.air_pressure)
  hal_bit_t* rack_cover_open;    ///< out: true opens the rack cover (`rack_cover`)
  hal_bit_t* rack_cover_opened;  ///< in: the cover reads open (rack_cover.opened_sensor)
  hal_bit_t* rack_cover_closed;  ///< in: the cover reads closed (rack_cover.closed_sensor)
  hal_bit_t* air_blast;          ///< out: cleans the spindle taper (`air_blast`)
  /// in: pocket-occupied-N, one per configured pocket, in the order of
  /// `pocket_tools` (sensors.pocket_occupancy); HAL memory, `pocket_count` long
  hal_bit_t** pocket_occupied;
  int* pocket_tools;
  int pocket_count;
  hal_bit_t* machine_on;      ///< in: machine on and out of estop
  hal_bit_t* all_homed;       ///< in: every joint homed
  hal_bit_t* clear_fault;     ///< in: rising edge clears a fault with the operator's confirmation
  hal_s32_t* confirm_tool;    ///< in: the spindle holds this tool (0 empty); -1: LinuxCNC's tool
  hal_s32_t* confirm_pocket;  ///< in: the cut-off pocket holds its tool: 1 yes, 0 no, -1 not said
  hal_s32_t* cut_off_pocket;  ///< out: the pocket a cut-off sequence involved, 0 none
  hal_bit_t* heartbeat;       ///< out: toggles every poll; gates the chuck in HAL
  hal_s32_t* linuxcnc_tool;   ///< in: iocontrol.0.tool-number
  hal_s32_t* state;  ///< out: the Phase: 0 not ready, 1 idle, 2 changing, ... 8 chuck (status.hpp)
  hal_bit_t* ready;  ///< out: idle and able to change tools
  hal_bit_t* busy;   ///< out: running a sequence
  hal_bit_t* fault;  ///< out: in fault
  hal_s32_t* tool_in_spindle;  ///< out: what the changer knows is in the spindle
  hal_bit_t* step_request;     ///< in: the executor asks for its next step (motion.digital-out-M)
  hal_float_t*
      executor_call;      ///< in: 1 the executor runs inside M6, 2 over MDI (motion.analog-out)
  hal_bit_t* abort;       ///< in: a rising edge aborts the running sequence
  hal_bit_t* step_ready;  ///< out: a step is on the step pins (motion.digital-in-N)
  hal_s32_t* step_kind;   ///< out: StepKind
  hal_s32_t* step_axes;   ///< out: 3 = XY, 4 = Z, 7 = XYZ
  hal_float_t* step_x;    ///< out: machine X of the move
  hal_float_t* step_y;
  hal_float_t* step_z;
  hal_float_t* step_feed;     ///< out: units per minute
  hal_s32_t* step_tool;       ///< out: tool of set-length, set-tool, done
  hal_float_t* step_value;    ///< out: tool length of set-length
  hal_bit_t* return_to_xy;    ///< in: after M6, go back over the XY where it was called
  hal_bit_t* units_inch;      ///< out: the config is in inches (the executor uses G20)
  hal_float_t* probe_z;       ///< in: machine Z where the probe move stopped (motion.analog-out)
  hal_float_t* probe_result;  ///< in: 1 touched, 0 missed, -1 already tripped (motion.analog-out)
  hal_s32_t* tool_number;     ///< in: the tool the operator buttons are about
  hal_bit_t* load;            ///< in: rising edge: load and probe tool-number
  hal_bit_t* unload;          ///< in: rising edge: unload tool-number
  hal_s32_t* pocket_number;   ///< in: the pocket load, teach-pocket and verify-pocket are about (0:
                              ///< load chooses)
  hal_bit_t* teach_pocket;    ///< in: rising edge: the machine position becomes pocket-number's
  hal_bit_t* teach_loading;   ///< in: rising edge: ... becomes `loading`
  hal_bit_t* teach_safe;      ///< in: rising edge: ... becomes `safe`
  hal_bit_t* teach_sensor;    ///< in: rising edge: its XY becomes the touch-off sensor's
  hal_bit_t* verify_pocket;   ///< in: rising edge: a dry run through pocket-number's approach
  hal_s32_t* pocket_served;   ///< out: the pocket a sequence serves now, 0 none
  hal_bit_t* measure_all;     ///< in: rising edge: measure the tools measure-which says
  hal_s32_t* measure_which;   ///< in: 0 every tool in the rack, 1 the unmeasured, 2 the program's
  hal_s32_t* batch_done;      ///< out: measure all: tools done so far
  hal_s32_t* batch_total;     ///< out: measure all: tools it measures, 0 none running
  hal_bit_t* continue_;       ///< in: rising edge: the operator is done (Continue)
  hal_bit_t* cancel;          ///< in: rising edge: the operator cancels
  hal_bit_t* waiting_for_operator;  ///< out: a prompt waits for Continue or Cancel
  hal_float_t* last_length;         ///< out: the last tool length measured
  hal_s32_t* step_number;  ///< out: the step of the sequence under way, as --plan numbers it
  hal_s32_t*
      awaiting;  ///< out: 0 nothing, 1 motion, 2 probe, 3 timer, 4 spindle, 5 operator, 6 sensor
  hal_bit_t* accepting;   ///< out: load and unload would be accepted now
  hal_bit_t* can_cancel;  ///< out: cancel would act now (an operator wait or a load-flow probe)
};

}  // namespace fatc::linuxcnc
