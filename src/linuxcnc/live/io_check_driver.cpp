#include "io_check_driver.hpp"

#include "hal_pins_detail.hpp"

namespace fatc::linuxcnc {
namespace {

/// Each action's button, in the order of kIoActions.
constexpr hal_bit_t* HalPins::*kButtons[] = {
    &HalPins::io_check_chuck_release, &HalPins::io_check_chuck_clamp, &HalPins::io_check_cover_open,
    &HalPins::io_check_cover_close, &HalPins::io_check_air_blast};
static_assert(std::size(kButtons) == kIoActionCount, "a button for each I/O check action");

constexpr IoOutput kOutputs[] = {IoOutput::chuck, IoOutput::cover, IoOutput::air_blast};

const char* output_words(IoOutput output) {
  switch (output) {
    case IoOutput::chuck:
      return "the chuck";
    case IoOutput::cover:
      return "the rack cover";
    case IoOutput::air_blast:
      return "the air blast";
  }
  return "";
}

}  // namespace

void IoCheckDriver::changer_sets(IoOutput which, bool value) {
  Output& o = output(which);
  o.changer = value;
  o.held.reset();
  if (timing_ && declared(timing_->action).output == which) timing_.reset();
  if (which == IoOutput::air_blast) air_off_at_.reset();
  write_pins();
}

SensorReadings IoCheckDriver::seen_by_changer(const SensorReadings& read) {
  seen_ = read;
  for (const IoOutput which : kOutputs) {
    if (!output(which).held) continue;
    for (const Sensor sensor : io_sensors_watching(which)) seen_.set(sensor, frozen_.reads(sensor));
  }
  return seen_;
}

bool IoCheckDriver::holds_any() const {
  for (const Output& o : outputs_) {
    if (o.held) return true;
  }
  return false;
}

void IoCheckDriver::write_pins() {
  *pins_->chuck = on(IoOutput::chuck);
  *pins_->rack_cover_open = on(IoOutput::cover);
  *pins_->air_blast = on(IoOutput::air_blast);
  *pins_->io_check_held = holds_any();
}

void IoCheckDriver::give_back(const std::string& why, Ports& ports) {
  std::string given;
  for (const IoOutput which : kOutputs) {
    Output& o = output(which);
    if (!o.held) continue;
    if (*o.held != o.changer)
      given += (given.empty() ? "" : ", ") + std::string(output_words(which));
    o.held.reset();
  }
  timing_.reset();
  air_off_at_.reset();
  write_pins();
  if (!given.empty()) {
    ports.tell(MessageKind::info, "I/O check: " + given + " back as the changer commands: " + why);
  }
}

void IoCheckDriver::drive(IoAction action, Clock::time_point now, const Config& config,
                          const SensorReadings& read, Ports& ports) {
  const IoActionDeclaration& a = declared(action);
  Output& o = output(a.output);
  if (!o.held) {
    // The changer keeps seeing this output's sensors as they were.
    for (const Sensor sensor : io_sensors_watching(a.output))
      frozen_.set(sensor, seen_.reads(sensor));
  }
  o.held = a.on;
  write_pins();
  timing_ = Timing{action, now, std::nullopt};
  if (const auto timeout = io_timeout(action, config)) {
    timing_->deadline = now + std::chrono::duration_cast<Clock::duration>(
                                  std::chrono::duration<double>(timeout->seconds));
  } else {
    timing_.reset();
    words_.last = io_timing_words(action, config, std::nullopt, read);
    ports.tell(MessageKind::info, "I/O check: " + words_.last);
  }
  if (action == IoAction::air_blast) {
    air_off_at_ = now + std::chrono::duration_cast<Clock::duration>(
                            std::chrono::duration<double>(kIoAirBlastSeconds));
  }
}

void IoCheckDriver::poll(Clock::time_point now, const Config& config, const SensorReadings& read,
                         IoFacts facts, Ports& ports) {
  // Before anything is judged: what the pins show is what was last commanded.
  if (holds_any() && (facts.busy || !facts.machine_on)) {
    give_back(facts.busy ? *facts.busy : "the machine is off", ports);
  }
  if (!facts.busy && output(IoOutput::chuck).changer && !output(IoOutput::chuck).held) {
    facts.busy = "a G-code release holds the chuck open: clamp it from G-code first";
  }
  facts.chuck_open = on(IoOutput::chuck);
  facts.cover_open = on(IoOutput::cover);
  facts.air_blast = on(IoOutput::air_blast);
  facts.holding_tool = *pins_->io_check_holding_tool;
  for (const IoActionDeclaration& a : kIoActions) {
    const std::size_t i = static_cast<std::size_t>(a.action);
    const bool down = *(pins_->*kButtons[i]);
    const bool rose = down && !pressed_[i];
    pressed_[i] = down;
    if (!rose) continue;
    if (const auto why = io_refusal(a.action, config, read, facts)) {
      words_.last = std::string(a.name) + " refused: " + *why;
      ports.tell(MessageKind::error, "I/O check: " + words_.last);
    } else {
      drive(a.action, now, config, read, ports);
      facts.chuck_open = on(IoOutput::chuck);
      facts.cover_open = on(IoOutput::cover);
    }
  }
  if (air_off_at_ && now >= *air_off_at_) {
    air_off_at_.reset();
    output(IoOutput::air_blast).held.reset();
    write_pins();
  }
  if (timing_) {
    const bool answered = io_answered(timing_->action, config, read);
    if (answered || now >= *timing_->deadline) {
      const std::optional<double> seconds =
          answered
              ? std::optional<double>(std::chrono::duration<double>(now - timing_->began).count())
              : std::nullopt;
      words_.last = io_timing_words(timing_->action, config, seconds, read);
      ports.tell(answered ? MessageKind::info : MessageKind::error, "I/O check: " + words_.last);
      timing_.reset();
    }
  }
  // An output back where the changer has it is the changer's again.
  for (const IoOutput which : kOutputs) {
    Output& o = output(which);
    if (o.held && *o.held == o.changer && !(timing_ && declared(timing_->action).output == which)) {
      o.held.reset();
      write_pins();
    }
  }
  words_.held = holds_any();
  words_.sensors.clear();
  for (const IoSensorLine& line : io_sensor_lines(config, read, facts)) {
    words_.sensors.push_back(line.words());
  }
  words_.refusals.clear();
  for (const IoActionDeclaration& a : kIoActions) {
    words_.refusals.emplace_back(a.name, io_refusal(a.action, config, read, facts).value_or(""));
  }
}

}  // namespace fatc::linuxcnc
