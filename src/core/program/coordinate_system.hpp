#pragma once

#include "../motion/point.hpp"

namespace fatc::program {

/// The program's coordinate system as LinuxCNC's interpreter sets it through
/// its canonical calls (USE_LENGTH_UNITS, SET_G92_OFFSET, SET_XY_ROTATION,
/// SET_G5X_OFFSET, USE_TOOL_LENGTH_OFFSET), each offset taken in the
/// config's units at the moment it is set, as LinuxCNC does.
struct CoordinateSystem {
  double config_units_per_program_unit = 1.0;  ///< 25.4 for G20 on a mm config
  Point g92;
  double xy_rotation_degrees = 0.0;  ///< G10 L2 R
  Point g5x;                         ///< G54-G59.3
  Point tool_offset;                 ///< G43, G43.1, G43.2; 0 under G49

  /// Where the spindle nose is (machine coordinates, G53) when the program
  /// is at `program` (the tool tip, in the program's units). LinuxCNC's own
  /// order, emccanon.cc's from_prog then rotate_and_offset_pos: to its
  /// units, plus G92, rotated about the program's origin, plus G5x, plus the
  /// tool length offset.
  Point machine(const Point& program) const;
  /// The inverse: the program position whose nose is at `machine`.
  Point program(const Point& machine) const;
};

}  // namespace fatc::program
