#pragma once

#include <hal.h>

#include "core/config/sensor_list.hpp"
#include "core/rack/keepout.hpp"

namespace fatc::linuxcnc {

/// The pins' values in HAL memory; what each means is in pin_list.hpp.
struct HalPins {
  hal_s32_t* number;
  hal_bit_t* tool_prepare;
  hal_bit_t* prepared;
  hal_bit_t* tool_change;
  hal_bit_t* changed;
  hal_bit_t* chuck;
  hal_bit_t* chuck_held;
  hal_bit_t* probe_in_spindle;
  hal_bit_t* spindle_refused;
  hal_bit_t* probe;
  hal_bit_t* spindle_stopped;
  /// in: the optional sensors of core/config/sensor_list.hpp, by Sensor
  hal_bit_t* sensors[kSensorCount];
  hal_bit_t* rack_cover_open;
  hal_bit_t* air_blast;
  /// in: the pocket sensors, one per configured pocket, in the order of
  /// `pocket_tools` (sensors.pocket_occupancy); HAL memory, `pocket_count` long
  hal_bit_t** pocket_sensors;
  int* pocket_tools;
  int pocket_count;
  hal_bit_t* machine_on;
  hal_bit_t* all_homed;
  hal_bit_t* clear_fault;
  hal_s32_t* confirm_tool;
  hal_s32_t* confirm_pocket;
  hal_s32_t* cut_off_pocket;
  hal_bit_t* heartbeat;
  hal_s32_t* linuxcnc_tool;
  hal_s32_t* state;
  hal_bit_t* ready;
  hal_bit_t* busy;
  hal_bit_t* touching;
  hal_bit_t* changer_spindle;
  hal_bit_t* fault;
  hal_s32_t* tool_in_spindle;
  hal_bit_t* step_request;
  hal_float_t* executor_call;
  hal_bit_t* abort;
  hal_bit_t* step_ready;
  hal_s32_t* step_kind;
  hal_s32_t* step_axes;
  hal_float_t* step_x;
  hal_float_t* step_y;
  hal_float_t* step_z;
  hal_float_t* step_feed;
  hal_s32_t* step_tool;
  hal_float_t* step_value;
  hal_s32_t* step_via;
  hal_float_t* step_via_x;
  hal_float_t* step_via_y;
  hal_float_t* step_via_z;
  hal_float_t* step_blend;
  hal_bit_t* return_to_xy;
  hal_bit_t* units_inch;
  hal_float_t* probe_z;
  hal_float_t* probe_result;
  hal_s32_t* tool_number;
  hal_bit_t* load;
  hal_bit_t* unload;
  hal_s32_t* pocket_number;
  hal_bit_t* teach_pocket;
  hal_bit_t* teach_loading;
  hal_bit_t* teach_safe;
  hal_bit_t* teach_sensor;
  hal_bit_t* verify_pocket;
  hal_bit_t* air_run_change;
  hal_bit_t* air_run_load;
  hal_bit_t* air_run_unload;
  hal_bit_t* air_run_verify;
  hal_bit_t* touch_pockets;
  hal_bit_t* teach_datum;
  hal_bit_t* check_datum;
  hal_bit_t* clear_datum_drift;
  hal_s32_t* air_from_tool;
  hal_float_t* air_height;
  hal_float_t* air_feed;
  hal_s32_t* pocket_served;
  hal_bit_t* measure_all;
  hal_s32_t* measure_which;
  hal_s32_t* batch_done;
  hal_s32_t* batch_total;
  hal_bit_t* continue_;
  hal_bit_t* cancel;
  hal_bit_t* waiting_for_operator;
  hal_bit_t* step_by_step;
  hal_float_t* last_length;
  hal_s32_t* step_number;
  hal_s32_t* awaiting;
  hal_bit_t* accepting;
  hal_bit_t* can_cancel;
  hal_s32_t* rack_keepout;
  hal_bit_t* rack_keepout_lift;
  hal_bit_t* rack_keepout_enable;
  hal_float_t* rack_keepout_tool_length;
  hal_s32_t* rack_keepout_boxes;
  /// out: box N of the rack's volume for fatc-rack-guard, machine units
  hal_float_t* keepout_x_min[kGuardBoxes];
  hal_float_t* keepout_x_max[kGuardBoxes];
  hal_float_t* keepout_y_min[kGuardBoxes];
  hal_float_t* keepout_y_max[kGuardBoxes];
  hal_float_t* keepout_z_max[kGuardBoxes];
  hal_s32_t* rack_keepout_trips;
  hal_s32_t* rack_keepout_box;
  hal_float_t* rack_keepout_at_x;
  hal_float_t* rack_keepout_at_y;
  hal_float_t* rack_keepout_at_z;
  /// The I/O check (core/rack/io_check.hpp): one button per action of kIoActions.
  hal_bit_t* io_check_chuck_release;
  hal_bit_t* io_check_chuck_clamp;
  hal_bit_t* io_check_cover_open;
  hal_bit_t* io_check_cover_close;
  hal_bit_t* io_check_air_blast;
  hal_bit_t* io_check_holding_tool;
  hal_bit_t* io_check_held;
};

}  // namespace fatc::linuxcnc
