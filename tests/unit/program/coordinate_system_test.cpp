// The program's coordinate system, held against LinuxCNC's interpreter:
// rs274 (LinuxCNC 2.9) printed these calls for G53 moves under a G54 from
// the parameter file (X12.5 Y-7.25 Z-3), a G92, a G10 L2 R30 rotation and a
// G43.1; each must put the nose where the G53 said.
#include "core/program/coordinate_system.hpp"

#include <gtest/gtest.h>

namespace fatc::program {
namespace {

/// SET_G5X_OFFSET(1, 12.5, -7.25, -3), SET_G92_OFFSET(-17.5, 2.25, -2)
/// after `G92 X5 Y5 Z5`, SET_XY_ROTATION(30), all under G21 on a mm machine.
CoordinateSystem captured() {
  CoordinateSystem system;
  system.g5x = {12.5, -7.25, -3.0};
  system.g92 = {-17.5, 2.25, -2.0};
  system.xy_rotation_degrees = 30.0;
  return system;
}

void expect_near(const Point& a, const Point& b, double tolerance) {
  EXPECT_NEAR(a.x, b.x, tolerance);
  EXPECT_NEAR(a.y, b.y, tolerance);
  EXPECT_NEAR(a.z, b.z, tolerance);
}

TEST(CoordinateSystem, shouldPutTheNoseWhereAG53MoveSaidUnderEveryOffset) {
  CoordinateSystem system = captured();
  system.tool_offset = {0.0, 0.0, 30.0};  // G43.1 Z30
  // G53 G0 X150 Y20 Z-5: STRAIGHT_TRAVERSE(150.2035, -47.4008, -30.0000, ...)
  expect_near(system.machine({150.2035, -47.4008, -30.0}), {150.0, 20.0, -5.0}, 2e-4);
}

TEST(CoordinateSystem, shouldTakeAnInchProgramOnAMmMachine) {
  CoordinateSystem system = captured();
  system.config_units_per_program_unit = 25.4;  // G20 after G49
  // G53 G0 X4 Y1 Z-0.5: STRAIGHT_TRAVERSE(4.3696, -0.7293, -0.3031, ...)
  expect_near(system.machine({4.3696, -0.7293, -0.3031}), {101.6, 25.4, -12.7}, 2e-3);
}

TEST(CoordinateSystem, shouldTurnAMachinePositionBackIntoTheProgramsOwn) {
  CoordinateSystem system = captured();
  system.tool_offset = {0.0, 0.0, 30.0};
  system.config_units_per_program_unit = 1.0 / 25.4;  // an inch config, a G21 program
  const Point machine{5.9, 0.8, -0.2};
  expect_near(system.machine(system.program(machine)), machine, 1e-12);
}

}  // namespace
}  // namespace fatc::program
