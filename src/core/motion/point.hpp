#pragma once

namespace fatc {

/// A position in machine coordinates (G53), in the config's units.
struct Point {
  double x = 0.0;
  double y = 0.0;
  double z = 0.0;
};

/// An offset in the XY plane, in the config's units.
struct PlanarOffset {
  double x = 0.0;
  double y = 0.0;
};

}  // namespace fatc
