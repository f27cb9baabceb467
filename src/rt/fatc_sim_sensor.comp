component fatc_sim_sensor "A simulated tool touch-off sensor for fixed_atc_probe's simulated machines: trips while the spindle nose is inside its box";
description """
For a simulated machine only. \\fBout\\fR is true while \\fBx\\fR, \\fBy\\fR
lie inside \\fBx-min\\fR..\\fBx-max\\fR, \\fBy-min\\fR..\\fBy-max\\fR and
\\fBz\\fR is below \\fBz-trip\\fR: a tool coming down onto the sensor's
button. One module of its own, so that it loads beside LinuxCNC's simulated
configurations, which load \\fBcomp\\fR, \\fBwcomp\\fR and \\fBor2\\fR
themselves (a module loads once).
""";
pin in float x "the spindle nose, machine units (joint.0.pos-fb on a mill)";
pin in float y;
pin in float z;
pin in float x-min "the sensor's button, machine units";
pin in float x-max;
pin in float y-min;
pin in float y-max;
pin in float z-trip "the nose's height at which the button trips";
pin out bit out "true while tripped: to motion.probe-input and fixed_atc_probe.probe";
function _;
license "GPL";
;;
FUNCTION(_) {
    out = x > x_min && x < x_max && y > y_min && y < y_max && z < z_trip;
}
