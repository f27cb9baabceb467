// The event dispatch of the legs the flows share (favor_compile_time, see
// Machine_of in common.hpp), generated here once: a return serves four flows,
// a fetch three, the handovers and the probe two each, and a flow's own file
// calls a leg through this dispatch instead of compiling the leg again.
// All in one compiler run: 1.2 GB, where adding them to engine.cpp took 1.8.

#include "handover.hpp"
#include "probing_leg.hpp"
#include "retrieve_leg.hpp"
#include "return_leg.hpp"

namespace fatc::machine {
using ReturnBefore = ReturnLeg<Before>;
using ReturnPutAway = ReturnLeg<PutAway>;
}  // namespace fatc::machine

BOOST_MSM_BACK_GENERATE_PROCESS_EVENT(fatc::machine::ReturnBefore)
BOOST_MSM_BACK_GENERATE_PROCESS_EVENT(fatc::machine::ReturnPutAway)
BOOST_MSM_BACK_GENERATE_PROCESS_EVENT(fatc::machine::RetrieveLeg)
BOOST_MSM_BACK_GENERATE_PROCESS_EVENT(fatc::machine::FlushLeg)
BOOST_MSM_BACK_GENERATE_PROCESS_EVENT(fatc::machine::ProbingLeg)
BOOST_MSM_BACK_GENERATE_PROCESS_EVENT(fatc::machine::MeasureLeg)
BOOST_MSM_BACK_GENERATE_PROCESS_EVENT(fatc::machine::InsertLeg)
BOOST_MSM_BACK_GENERATE_PROCESS_EVENT(fatc::machine::RemoveLeg)
BOOST_MSM_BACK_GENERATE_PROCESS_EVENT(fatc::machine::HandOutLeg)
BOOST_MSM_BACK_GENERATE_PROCESS_EVENT(fatc::machine::HandInLeg)
