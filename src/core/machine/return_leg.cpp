// The event dispatch of this submachine, generated here and nowhere else
// (favor_compile_time, see Machine_of in common.hpp): a compiler run reads
// only the tables it dispatches.

#include "return_leg.hpp"

namespace fatc::machine {
using ReturnBefore = ReturnLeg<Before>;
using ReturnPutAway = ReturnLeg<PutAway>;
}  // namespace fatc::machine

BOOST_MSM_BACK_GENERATE_PROCESS_EVENT(fatc::machine::ReturnBefore)
BOOST_MSM_BACK_GENERATE_PROCESS_EVENT(fatc::machine::ReturnPutAway)
