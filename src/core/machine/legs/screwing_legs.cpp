// The event dispatch of the collet-nut legs (favor_compile_time, see
// Machine_of in common.hpp), in a compiler run of their own beside legs.cpp:
// the return and the fetch call them through it.

#include "screwing_off.hpp"
#include "screwing_on.hpp"

BOOST_MSM_BACK_GENERATE_PROCESS_EVENT(fatc::machine::ScrewingOff)
BOOST_MSM_BACK_GENERATE_PROCESS_EVENT(fatc::machine::ScrewingOn)
