#pragma once

#include <csignal>
#include <iosfwd>

#include "io/cli.hpp"

namespace fatc::linuxcnc {

/// --operator ACTION: asks the running fixed_atc_probe, as its panel does, by
/// the pins the panel pulses (HAL's own lookup, from a HAL component of its
/// own) and the words of the status file beside the state file; prints each
/// message meanwhile and the outcome; returns the exit status
/// (io::operator_exit_status). `stop` set (SIGINT, SIGTERM) ends the watching;
/// the request goes on in the component.
int run_operator(const io::Options& options, std::ostream& out, std::ostream& err,
                 const volatile std::sig_atomic_t& stop);

}  // namespace fatc::linuxcnc
