// The state diagram, read from the transition tables (its own compiler run:
// walking every table is as heavy as dispatching them).

#include "change_flow.hpp"
#include "changer.hpp"
#include "chuck_flow.hpp"
#include "dot.hpp"
#include "load_flow.hpp"
#include "machine.hpp"
#include "measure_all_flow.hpp"
#include "unload_flow.hpp"
#include "verify_flow.hpp"

std::string fatc::Changer::dot() { return machine::dot_of<machine::Machine_>("fixed_atc_probe"); }
