component fatc_spindle_guard "Holds the spindle still while fixed_atc_probe has a touch probe in it or changes tools without asking for it, and gives motion the probe's input then";
description """
While \\fBprobe-in-spindle\\fR is true (config.json's \\fBtools\\fR says the tool
in the spindle is a probe) the spindle is \\fBheld\\fR: \\fBspindle-on\\fR, the
drive's run, stays false whatever \\fBspindle-on-in\\fR (spindle.0.on) asks,
\\fBspeed-out\\fR, the drive's speed, stays 0 whatever \\fBspeed-in\\fR says,
and \\fBinhibit\\fR holds motion's spindle speed at 0 (spindle.0.inhibit, which
M49 and M51 P0 switch off), so an
M3 or M4 from a program, MDI, a GUI or halui turns nothing. \\fBrefused\\fR
(the spindle asked for: \\fBspindle-on-in\\fR or a \\fBspeed-command\\fR
speed) tells the component, which aborts what asked and says why. Once held, only a
live component releases it: when its heartbeat stops for \\fBtimeout\\fR
seconds (it died, hangs or was unloaded) the spindle stays held.
While the changer is busy (\\fBchanger-busy\\fR) the spindle is also
\\fBheld-for-change\\fR (\\fBspindle-on\\fR false, \\fBspeed-out\\fR 0): it
turns only in a step where the changer asks for it
(\\fBchanger-spindle\\fR: a collet nut screwed off or on) and only while the
component answers (\\fBalive\\fR); one that stops answering holds it even
though it asked. This hold raises neither \\fBrefused\\fR nor \\fBinhibit\\fR.
\\fBprobe-input\\fR, for motion.probe-input, is the probe's own input
(\\fBspindle-probe\\fR) while it is in the spindle and the changer is not
measuring (\\fBchanger-busy\\fR false) or is touching the rack with it
(\\fBtouching\\fR), else the touch-off \\fBsensor\\fR.
""";
pin in bit probe-in-spindle "fixed_atc_probe.probe-in-spindle: the spindle holds a probe";
pin in bit heartbeat "fixed_atc_probe.heartbeat: toggles on every poll of the component";
pin in float timeout = 0.5 "seconds without a heartbeat edge before the component is taken for gone";
pin in bit changer-busy "fixed_atc_probe.busy: the changer's own moves measure on the touch-off sensor";
pin in bit changer-spindle "fixed_atc_probe.changer-spindle: the changer turns the spindle in this step (a collet nut screwed off or on)";
pin in bit touching "fixed_atc_probe.touching: the changer's own moves touch the rack with the probe";
pin in bit chuck-held "fixed_atc_probe.chuck-held: a chuck atom holds the spindle as well";
pin in bit spindle-on-in "spindle.0.on: LinuxCNC asks for the spindle";
pin in float speed-command "spindle.0.speed-cmd-rps: the speed asked for, before spindle.0.inhibit (2.9.0 drops spindle.0.on with the inhibited speed)";
pin out bit spindle-on "to the spindle drive's run: spindle-on-in, unless held";
pin in float speed-in "the speed motion gives the drive (spindle.0.speed-out, or what your chain makes of it)";
pin out float speed-out "to the spindle drive's speed: speed-in, 0 while held (M49 and M51 P0 switch spindle.0.inhibit off; this holds still)";
pin out bit inhibit "to spindle.0.inhibit: held or chuck-held";
pin out bit held "a probe is in the spindle, or was when the component stopped answering";
pin out bit held-for-change "the changer is busy (or asks for the spindle) and does not ask for it, or asked and stopped answering";
pin out bit refused "held while LinuxCNC asks for the spindle (spindle-on-in, or a speed-command)";
pin in bit sensor "the touch-off sensor";
pin in bit spindle-probe "the touch probe's own input";
pin out bit probe-input "to motion.probe-input: the probe's input while it is in the spindle and the changer is not measuring or touches the rack with it, else the sensor's";
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
held = probe_in_spindle || (held && !alive);
held_for_change = (changer_busy || changer_spindle) && !(changer_spindle && alive);
spindle_on = spindle_on_in && !held && !held_for_change;
speed_out = (held || held_for_change) ? 0 : speed_in;
inhibit = held || chuck_held;
refused = held && (spindle_on_in || speed_command != 0);
probe_input = (probe_in_spindle && (!changer_busy || touching)) ? spindle_probe : sensor;
