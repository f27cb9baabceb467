// The event dispatch of this submachine, generated here and nowhere else
// (favor_compile_time, see Machine_of in common.hpp): a compiler run reads
// only the tables it dispatches.

#include "handover.hpp"

BOOST_MSM_BACK_GENERATE_PROCESS_EVENT(fatc::machine::InsertLeg)
BOOST_MSM_BACK_GENERATE_PROCESS_EVENT(fatc::machine::RemoveLeg)
BOOST_MSM_BACK_GENERATE_PROCESS_EVENT(fatc::machine::HandOutLeg)
BOOST_MSM_BACK_GENERATE_PROCESS_EVENT(fatc::machine::HandInLeg)
