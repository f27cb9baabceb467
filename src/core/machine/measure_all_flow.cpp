// This flow's event dispatch and its start, generated here and nowhere else
// (flow_run.hpp): a compiler run reads only the tables this flow dispatches.

#include "measure_all_flow.hpp"
#include "flow_run_of.hpp"

FATC_FLOW_DISPATCH(MeasureAllFlow_)
FATC_FLOW_RUN(MeasureAllFlow_, MeasureRequest)
