// The event dispatch of some submachines, generated here and nowhere else
// (favor_compile_time, see Machine_of in common.hpp): one compiler run per
// group keeps the memory and time of a build within a small machine.

#include "flows.hpp"

BOOST_MSM_BACK_GENERATE_PROCESS_EVENT(fatc::machine::ChangeFlow)
BOOST_MSM_BACK_GENERATE_PROCESS_EVENT(fatc::machine::LoadFlow)
BOOST_MSM_BACK_GENERATE_PROCESS_EVENT(fatc::machine::UnloadFlow)
BOOST_MSM_BACK_GENERATE_PROCESS_EVENT(fatc::machine::MeasureAllFlow)
BOOST_MSM_BACK_GENERATE_PROCESS_EVENT(fatc::machine::VerifyFlow)
BOOST_MSM_BACK_GENERATE_PROCESS_EVENT(fatc::machine::ChuckFlow)
