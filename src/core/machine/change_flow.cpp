// This flow's event dispatch, generated here and nowhere else (flow_run.hpp):
// a compiler run reads only the tables this flow dispatches. Its start is in
// change_flow_run.cpp: both in one run took 1.8 GB of compiler memory.

#include "change_flow.hpp"
#include "flow_run_of.hpp"

FATC_FLOW_DISPATCH(ChangeFlow_)
