// The change flow's start (run_flow); its dispatch is in change_flow.cpp.

#include "change_flow.hpp"
#include "flow_run_of.hpp"

FATC_FLOW_RUN(ChangeFlow_, ToolChange)
