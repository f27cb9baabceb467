// What the component writes on the executor's pins for a blended run
// (nc_files/fixed_atc_probe_execute.ngc reads them).
#include <gtest/gtest.h>

#include "core/protocol/executor_link.hpp"
#include "linuxcnc/live/hal_pins_detail.hpp"
#include "linuxcnc/live/hal_pins_view.hpp"

namespace fatc::linuxcnc {
namespace {

/// The link's pins, each pointing at storage of its own.
struct LinkPins {
  hal_bit_t ready = 0, prepared = 0, changed = 0;
  hal_s32_t kind = 0, axes = 0, tool = 0, via = 0;
  hal_float_t x = 0, y = 0, z = 0, feed = 0, value = 0, via_x = 0, via_y = 0, via_z = 0, blend = 0;
  HalPins pins{};
  LinkPins() {
    pins.step_ready = &ready;
    pins.prepared = &prepared;
    pins.changed = &changed;
    pins.step_kind = &kind;
    pins.step_axes = &axes;
    pins.step_tool = &tool;
    pins.step_via = &via;
    pins.step_x = &x;
    pins.step_y = &y;
    pins.step_z = &z;
    pins.step_feed = &feed;
    pins.step_value = &value;
    pins.step_via_x = &via_x;
    pins.step_via_y = &via_y;
    pins.step_via_z = &via_z;
    pins.step_blend = &blend;
  }
};

Step rapid(unsigned axes, Point target) {
  Step step;
  step.kind = StepKind::rapid;
  step.axes = axes;
  step.target = target;
  return step;
}

TEST(HalPinsView, shouldPutABlendedRunsWayUpAndAcrossOnTheViaPins) {
  LinkPins link;
  LinkOutputs out;
  out.step_ready = true;
  out.step = rapid(axis_z, {100, 20, -60});
  out.step.before = {rapid(axis_z, {0, 0, -5}), rapid(axis_xy, {100, 20, 0})};
  out.step.blend = 10;
  write_link(link.pins, out);
  EXPECT_EQ(link.via, static_cast<int>(Via::up_and_across));
  EXPECT_EQ(link.via_x, 100.0);
  EXPECT_EQ(link.via_y, 20.0);
  EXPECT_EQ(link.via_z, -5.0);
  EXPECT_EQ(link.blend, 10.0);
  EXPECT_EQ(link.z, -60.0);
  EXPECT_EQ(link.axes, static_cast<int>(axis_z));

  // Across only: the run is already at safe Z.
  out.step.before = {rapid(axis_xy, {50, 60, 0})};
  write_link(link.pins, out);
  EXPECT_EQ(link.via, static_cast<int>(Via::across));
  EXPECT_EQ(link.via_x, 50.0);
  EXPECT_EQ(link.via_y, 60.0);

  // A step of its own: nothing on the way, nothing rounded.
  out.step = rapid(axis_xy, {1, 2, 3});
  write_link(link.pins, out);
  EXPECT_EQ(link.via, static_cast<int>(Via::none));
  EXPECT_EQ(link.blend, 0.0);
}

}  // namespace
}  // namespace fatc::linuxcnc
