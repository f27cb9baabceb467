// The event dispatch of some submachines, generated here and nowhere else
// (favor_compile_time, see Machine_of in common.hpp): one compiler run per
// group keeps the memory and time of a build within a small machine.

#include "flows.hpp"

namespace fatc::machine {
using InsertHoldingTheProgram = InsertLeg<HoldingTheProgram>;
using InsertEndingTheRun = InsertLeg<EndingTheRun>;
using RemoveHoldingTheProgram = RemoveLeg<HoldingTheProgram>;
using RemoveEndingTheRun = RemoveLeg<EndingTheRun>;
}  // namespace fatc::machine

BOOST_MSM_BACK_GENERATE_PROCESS_EVENT(fatc::machine::HandOutLeg)
BOOST_MSM_BACK_GENERATE_PROCESS_EVENT(fatc::machine::HandInLeg)
BOOST_MSM_BACK_GENERATE_PROCESS_EVENT(fatc::machine::InsertHoldingTheProgram)
BOOST_MSM_BACK_GENERATE_PROCESS_EVENT(fatc::machine::InsertEndingTheRun)
BOOST_MSM_BACK_GENERATE_PROCESS_EVENT(fatc::machine::RemoveHoldingTheProgram)
BOOST_MSM_BACK_GENERATE_PROCESS_EVENT(fatc::machine::RemoveEndingTheRun)
