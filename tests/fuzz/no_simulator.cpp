// ini.cpp's check of STEP_TIMEOUT plans the changer's sequences (the
// Simulator: the whole state machine, minutes to compile with the
// sanitizers). fuzz_ini reads INIs and their soft limits only and never asks
// for it: linked in its place, it says so if it ever is.
#include "core/dry_run/simulator.hpp"
#include "invariants.hpp"

double fatc::longest_executor_wait(const Config&) {
  fatc::fuzz::broken("fuzz_ini plans no sequence", "longest_executor_wait called");
}
