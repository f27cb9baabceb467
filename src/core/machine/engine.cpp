#include "engine.hpp"

namespace fatc::machine {

Engine::Engine(const Config& config, Ports& ports, ToolState tools)
    : context(config, ports, std::move(tools)), fsm(&context) {
  context.refuse_step = [this](const std::string& why) { fsm.process_event(UnsafeStep{why}); };
  context.raise_check_failed = [this](const CheckFailed& e) { fsm.process_event(e); };
  context.recheck_sensors = [this] { fsm.process_event(SensorReport{}); };
  fsm.start();
}

Engine::~Engine() = default;

}  // namespace fatc::machine
