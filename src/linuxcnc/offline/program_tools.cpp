#include "program_tools.hpp"

#include <strings.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/program/interpreter_inputs.hpp"
#include "ini.hpp"
#include "io/files.hpp"
#include "machine_ini.hpp"

namespace fatc::io {

std::optional<MachineMotion> machine_motion(const std::optional<std::string>& ini_path,
                                            const Config& config, std::string& error) {
  const bool inch = config.units == Units::inch;
  MachineMotion machine;
  MotionLimits& limits = machine.timing.limits;
  const double velocity = inch ? kAssumedVelocityInch : kAssumedVelocityMm;
  const double acceleration = inch ? kAssumedAccelerationInch : kAssumedAccelerationMm;
  limits.velocity = {velocity, velocity, velocity};
  limits.acceleration = {acceleration, acceleration, acceleration};
  limits.linear_velocity = velocity;
  limits.linear_acceleration = acceleration;
  char buffer[120];
  std::snprintf(buffer, sizeof buffer, "the moves at %.0f %s and %.0f %s, assumed (",
                velocity * 60.0, inch ? "inch/min" : "mm/min", acceleration,
                inch ? "inch/s²" : "mm/s²");
  if (!ini_path) {
    machine.source = buffer + std::string("--ini gives the machine's [AXIS_*] and [TRAJ] limits)");
    return machine;
  }
  const auto ini = IniFile::read(*ini_path, error);
  if (!ini) return std::nullopt;
  // iocontrol's cycle as LinuxCNC reads it; its default where it is none.
  const auto cycle = ini->number("EMCIO", "CYCLE_TIME");
  if (cycle && std::isfinite(*cycle) && *cycle > 0.0 && *cycle <= 10.0) {
    machine.timing.iocontrol_cycle_seconds = *cycle;
  }
  std::string why;
  if (const auto found = motion_limits(*ini, config.units, why)) {
    limits = *found;
    machine.source = "the moves at the velocities and accelerations of " + shown_path(*ini_path);
    return machine;
  }
  machine.source = buffer + shown_path(*ini_path) +
                   " has no usable MAX_VELOCITY and MAX_ACCELERATION of [AXIS_X], [AXIS_Y] "
                   "and [AXIS_Z]: --plan --ini says why)";
  return machine;
}

std::optional<MachineIni> read_machine_ini(const std::optional<std::string>& ini_path,
                                           const Config& config, std::string& error) {
  MachineIni machine;
  const auto motion = machine_motion(ini_path, config, error);
  if (!motion) return std::nullopt;
  machine.motion = *motion;
  if (!ini_path) return machine;
  const auto ini = IniFile::read(*ini_path, error);
  if (!ini) return std::nullopt;
  const auto remaps = ini->get_all("RS274NGC", "REMAP");
  machine.remaps_m6 = std::any_of(remaps.begin(), remaps.end(),
                                  [](const std::string& remap) { return program::is_own_m6_remap(remap); });
  if (const auto table = ini->get("EMCIO", "TOOL_TABLE")) {
    machine.tool_table = (*table)[0] == '/' ? *table : folder_of(*ini_path) + "/" + *table;
  }
  if (const auto units = ini->linear_units(); units && *units > 0.0) machine.units_per_mm = units;
  machine.limits = soft_limits(*ini, config.units, machine.limits_error);
  machine.builtin_m6_moves = builtin_m6_moves(*ini);
  machine.include_problems = ini->include_problems();
  if (const auto back = ini->get("FIXED_ATC_PROBE", "RETURN_TO_XY")) {
    machine.return_to_xy = *back == "1" || strcasecmp(back->c_str(), "true") == 0;
  }
  return machine;
}

std::optional<program::InterpreterRun> interpret(InterpreterInput input, const Config& config,
                                                 std::string& error) {
  const auto rs274 = find_rs274(error);
  if (!rs274) return std::nullopt;
  input.rs274 = *rs274;
  input.inch_machine = config.units == Units::inch;
  return run_interpreter(input, error);
}

std::optional<std::vector<int>> program_tools(const std::string& program_path,
                                              const std::string& ini_path, const Config& config,
                                              std::string& error) {
  const std::optional<std::string> ini =
      ini_path.empty() ? std::nullopt : std::optional<std::string>(ini_path);
  const auto machine = read_machine_ini(ini, config, error);
  if (!machine) return std::nullopt;
  InterpreterInput input;
  input.program_path = program_path;
  input.ini_path = ini;
  input.tool_table_path = machine->tool_table;
  const auto run = interpret(input, config, error);
  if (!run) return std::nullopt;
  std::vector<int> tools;
  for (const auto& use : run->uses) {
    if (!use.tool || *use.tool == 0) continue;
    if (std::find(tools.begin(), tools.end(), *use.tool) == tools.end()) tools.push_back(*use.tool);
  }
  return tools;
}

}  // namespace fatc::io
