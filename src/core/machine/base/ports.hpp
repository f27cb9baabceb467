#pragma once

#include <string>

#include "../../motion/step.hpp"
#include "../../rack/tool_state.hpp"
#include "../../rack/touch.hpp"
#include "prompt.hpp"

namespace fatc {

enum class MessageKind {
  info,    ///< something happened ("tool 3 returned to its pocket")
  prompt,  ///< the operator must act, then press Continue or Cancel (the words of a Prompt)
  error,   ///< something failed; says what and where the tools are
};

/// Everything the state machine does to the world goes through here; the
/// LinuxCNC adapter implements it with pins, NML and a clock, tests with fakes.
class Ports {
 public:
  virtual ~Ports() = default;
  /// Offers the step executor its next step.
  virtual void publish(const Step& step) = 0;
  /// true opens the chuck (drops or takes a tool), false closes it.
  virtual void set_chuck_open(bool open) = 0;
  /// true opens the rack cover, false closes it (only with `rack_cover`).
  virtual void set_rack_cover_open(bool open) = 0;
  /// The air blast that cleans the spindle taper (only with `air_blast`).
  virtual void set_air_blast(bool on) = 0;
  /// Arms the one timer; TimerElapsed arrives after `seconds`. Re-arming replaces it.
  virtual void start_timer(double seconds) = 0;
  virtual void cancel_timer() = 0;
  virtual void tell(MessageKind kind, const std::string& text) = 0;
  /// The operator must act, then press Continue or Cancel; words(prompt) is what they read.
  virtual void ask(const Prompt& prompt) = 0;
  /// Called after every change of the tool state, to persist it.
  virtual void save(const ToolState& state) = 0;
  /// The operator accepted what touching found: config.json takes it through
  /// the teach path (validated, backed up) once the changer is idle; `datum`:
  /// the rack datum's taught position, else the pockets'.
  virtual void write_found(const std::vector<Found>& found, bool datum) = 0;
  /// An event arrived that no state expects: a bug. The machine faults after this.
  virtual void unexpected(const std::string& state, const std::string& event) = 0;
};

}  // namespace fatc
