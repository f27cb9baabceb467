// The event dispatch of this submachine, generated here and nowhere else
// (favor_compile_time, see Machine_of in common.hpp): a compiler run reads
// only the tables it dispatches.

#include "spindle_run_down.hpp"

BOOST_MSM_BACK_GENERATE_PROCESS_EVENT(fatc::machine::SpindleRunDown)
