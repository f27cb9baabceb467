// The state diagram, read from the transition tables (its own compiler run:
// walking every table is as heavy as dispatching them).

#include "../changer.hpp"
#include "../flows/air_run_flow.hpp"
#include "../flows/change_flow.hpp"
#include "../flows/chuck_flow.hpp"
#include "../flows/load_flow.hpp"
#include "../flows/measure_all_flow.hpp"
#include "../flows/touch_flow.hpp"
#include "../flows/unload_flow.hpp"
#include "../flows/verify_flow.hpp"
#include "../machine.hpp"
#include "dot.hpp"

std::string fatc::Changer::dot() { return machine::dot_of<machine::Machine_>("fixed_atc_probe"); }
