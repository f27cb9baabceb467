#pragma once

#include <iosfwd>

#include "options.hpp"

namespace fatc::linuxcnc {

/// --operator ACTION: asks the running fixed_atc_probe, as its panel does, by
/// the pins the panel pulses (HAL's own lookup, from a HAL component of its
/// own) and the words of the status file beside the state file; prints each
/// message meanwhile and the outcome; returns the exit status
/// (io::operator_exit_status). A signal io::Interruptible notes (the caller
/// keeps one alive around it) ends the watching: it leaves HAL, says so and
/// returns 128 + the signal; the request goes on in the component.
int run_operator(const io::Options& options, std::ostream& out, std::ostream& err);

}  // namespace fatc::linuxcnc
