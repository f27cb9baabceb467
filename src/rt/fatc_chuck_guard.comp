component fatc_chuck_guard "Closes fixed_atc_probe's chuck by itself when the component stops answering";
description """
The drawbar valve follows the chuck request of the fixed_atc_probe userspace
component only while the component's heartbeat toggles: when no edge came for
\\fBtimeout\\fR seconds (the component died, hangs or was unloaded), \\fBchuck\\fR
falls to false, the safe state, and \\fBalive\\fR tells the NGC step executor to
stop the program.
""";
pin in bit request "the component's chuck request: true opens";
pin in bit heartbeat "toggles on every poll of the component";
pin in float timeout = 0.5 "seconds without a heartbeat edge before the chuck closes";
pin out bit chuck "to the drawbar valve: the request, while the component is alive";
pin out bit alive "a heartbeat edge came within timeout";
variable int last_beat = 0;
variable double quiet = 1e9;
function _;
license "GPL";
;;
if (heartbeat != last_beat) {
    last_beat = heartbeat;
    quiet = 0;
} else if (quiet < 1e9) {
    quiet += fperiod;
}
alive = quiet < timeout;
chuck = request && alive;
