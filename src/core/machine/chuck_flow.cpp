// This flow's event dispatch and its start, generated here and nowhere else
// (flow_run.hpp): a compiler run reads only the tables this flow dispatches.

#include "chuck_flow.hpp"
#include "flow_run_of.hpp"

FATC_FLOW_DISPATCH(ChuckFlow_)
FATC_FLOW_RUN(ChuckFlow_, ChuckRequest)
