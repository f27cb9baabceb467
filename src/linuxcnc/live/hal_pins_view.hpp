#pragma once

// What goes between the pins and the changer: the inputs read into the
// core's types, the changer's status and the executor link written out.

#include <optional>

#include "core/machine/changer.hpp"
#include "core/protocol/executor_link.hpp"

namespace fatc::linuxcnc {

struct HalPins;

/// What the optional sensors read now: only those `config` says are wired,
/// so an unconnected pin never wakes the changer.
SensorReadings read_sensors(const HalPins& pins, const Config& config);
/// The executor's and iocontrol's side of the handshake.
LinkInputs read_link(const HalPins& pins, std::optional<bool> interpreter_idle);
/// The step on offer and the handshake bits.
void write_link(HalPins& pins, const LinkOutputs& out);
/// The changer's status and what a panel needs beside it; toggles the
/// heartbeat. `executor_attached`: an executor run is under way;
/// `linuxcnc_task`: NML reaches task (Cancel can stop a probe over MDI).
void write_status(HalPins& pins, const Status& status, const Changer& changer,
                  bool executor_attached, bool linuxcnc_task);

}  // namespace fatc::linuxcnc
