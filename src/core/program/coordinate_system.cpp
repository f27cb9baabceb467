#include "coordinate_system.hpp"

#include <cmath>

namespace fatc::program {
namespace {

Point rotated(const Point& p, double degrees) {
  if (degrees == 0.0) return p;
  const double t = degrees * M_PI / 180.0;
  return {p.x * std::cos(t) - p.y * std::sin(t), p.x * std::sin(t) + p.y * std::cos(t), p.z};
}

Point plus(const Point& a, const Point& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Point minus(const Point& a, const Point& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }

}  // namespace

Point CoordinateSystem::machine(const Point& program) const {
  const double k = config_units_per_program_unit;
  const Point in_units{program.x * k, program.y * k, program.z * k};
  return plus(plus(rotated(plus(in_units, g92), xy_rotation_degrees), g5x), tool_offset);
}

Point CoordinateSystem::program(const Point& machine) const {
  const double k = config_units_per_program_unit;
  const Point p = minus(rotated(minus(minus(machine, tool_offset), g5x), -xy_rotation_degrees), g92);
  return {p.x / k, p.y / k, p.z / k};
}

}  // namespace fatc::program
