// The state diagram, read from the transition tables (its own compiler run:
// walking every table is as heavy as dispatching them).

#include "changer.hpp"
#include "dot.hpp"
#include "machine.hpp"

std::string fatc::Changer::dot() { return machine::dot_of<machine::Machine_>("fixed_atc_probe"); }
