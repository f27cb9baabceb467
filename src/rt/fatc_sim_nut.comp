component fatc_sim_nut "A simulated collet-nut magazine for fixed_atc_probe's simulated machines: an ER nut per pocket that the spindle screws off and on";
description """
For a simulated machine only (config/sim/sim_nut.hal, collet-nut runs). Each
of the first \\fBcount\\fR pockets (at most 8; \\fBpocket-x-N\\fR,
\\fBpocket-y-N\\fR, N from 0: pocket 1 is 0) holds a nut or is empty, and
one nut may be on the spindle. The nose (\\fBx\\fR, \\fBy\\fR, \\fBz\\fR) is
over pocket N within \\fBcapture-radius\\fR of its centre, and in its engage
window from \\fBengage-z\\fR (the nose with the nut fully engaged) up to
\\fBengage-z\\fR + \\fBwindow\\fR. The nut reads the spindle's real signed
speed (\\fBspeed-in\\fR, rpm, forward positive) and turns with it only within
the band \\fBrpm-min\\fR..\\fBrpm-max\\fR. Screwing off: a nut on the
spindle, in the window over an empty pocket, the spindle reversing in the
band: after \\fBturns-off\\fR turns the nut is in that pocket. Screwing on:
the spindle empty, in the window over a pocket with a nut, forward in the
band: after \\fBturns-on\\fR turns the nut is on the spindle, hanging
\\fBunseated-drop\\fR low, and after \\fBturns-seat\\fR more turns forward in
a window (counted across plunges) it is \\fBseated\\fR. Leaving the window or
the band, or turning the wrong way, starts the screwing off or on again from
nothing. \\fBbeam-cut\\fR, the recognition sensor: the nose over a pocket and
a nut on the spindle spanning \\fBbeam-z\\fR (from the nose down
\\fBnut-length\\fR, plus \\fBunseated-drop\\fR while not seated). Faults:
\\fBreverse\\fR (the drive is miswired: the nut sees the speed negated; the
drive's own at-speed does not know), \\fBmissing-N\\fR (pocket N reads empty
and has nothing to screw on while true; false gives back what it holds),
\\fBcross-thread\\fR (a nut screwed on never seats), \\fBstall\\fR (the
spindle stops under load: \\fBspeed-out\\fR, the real speed the simulated
spindle's mass, encoder, at-speed and zero-speed see, reads 0 while the nose
is in a window with a nut there to turn). \\fBnut-in-pocket-init-N\\fR and
\\fBnut-on-spindle-init\\fR set the magazine when they change (a test's
starting nuts). One module of its own, so that it loads beside LinuxCNC's
simulated configurations.
""";
pin in float x "the spindle nose, machine units: joint.0.pos-cmd on a mill";
pin in float y;
pin in float z;
pin in float speed-in "the spindle's real signed speed, rpm (the simulated spindle's ramp, limit_speed.out)";
pin out float speed-out "speed-in, or 0 while stalled: to the simulated spindle's mass, encoder and zero-speed";
pin in s32 count "how many pockets are set, 0 to 8";
pin in float pocket-x-#[8] "the pocket's centre, machine units (M from 0: pocket 1 is 0)";
pin in float pocket-y-#[8];
pin in float engage-z "the nose with a nut fully engaged: every pocket's z";
pin in float window "the engage window's height: the nut turns with the nose from engage-z to engage-z + window";
pin in float capture-radius "the nose is over a pocket within this distance of its centre";
pin in float rpm-min "the band the nut turns in: rpm-min to rpm-max, either way";
pin in float rpm-max;
pin in float turns-off "turns reversing in the window that screw a nut off into its pocket";
pin in float turns-on "turns forward in the window that screw a nut on, not yet seated";
pin in float turns-seat "further turns forward in a window that seat it";
pin in float unseated-drop "how much lower than seated a nut not yet seated hangs";
pin in float nut-length "a seated nut's length below the nose";
pin in float beam-z "the recognition beam's height, machine Z";
pin in bit reverse "fault: the drive turns the other way (miswired)";
pin in bit missing-#[8] "fault: the pocket's nut is gone while true";
pin in bit cross-thread "fault: a nut screwed on never seats";
pin in bit stall "fault: the spindle stops under load in a window";
pin in bit nut-in-pocket-init-#[8] "on a change: puts a nut in the pocket (true) or takes it out (false)";
pin in s32 nut-on-spindle-init "on a change: a seated nut from this pocket number on the spindle, 0 none";
pin out bit nut-in-pocket-#[8] "the pocket holds a nut";
pin out bit nut-on-spindle;
pin out s32 nut-on-spindle-from "the pocket number the nut on the spindle came from, 0 none";
pin out bit seated "the nut on the spindle is screwed fully home";
pin out bit beam-cut "the recognition beam is cut by the nut on the spindle: to fixed_atc_probe.nut-seen";
pin out bit stalled "stall holds speed-out at 0 now";
pin out float turns "turns counted toward screwing a nut off or on";
pin out float seat-turns "turns counted toward seating the nut on the spindle";
variable int holds[8];
variable int last_init[8];
variable int last_spindle_init = 0;
variable int from = 0;
variable int home = 0;
function _;
license "GPL";
;;
#include <rtapi_math.h>

/* A nose exactly at a window's edge is in it. */
#define ON_EDGE 1e-9

static int pockets(struct __comp_state *__comp_inst) {
    return count < 0 ? 0 : count > 8 ? 8 : count;
}

/* The pocket the nose is over, or -1. */
static int over(struct __comp_state *__comp_inst) {
    int k;
    for (k = 0; k < pockets(__comp_inst); k++) {
        double dx = x - pocket_x(k), dy = y - pocket_y(k);
        if (dx * dx + dy * dy <= capture_radius * capture_radius + ON_EDGE) return k;
    }
    return -1;
}

/* holds[N]: pocket N has a nut (missing-N hides it). from: the pocket number
   the nut on the spindle came from, 0 none. home: that nut is seated. */

static int occupied(struct __comp_state *__comp_inst, int k) {
    return holds[k] && !missing(k);
}

FUNCTION(_) {
    int k, at, in_window, engaged, in_band;
    double seen, turned;
    for (k = 0; k < 8; k++) {
        if (nut_in_pocket_init(k) != last_init[k]) {
            last_init[k] = nut_in_pocket_init(k);
            holds[k] = last_init[k];
        }
    }
    if (nut_on_spindle_init != last_spindle_init) {
        last_spindle_init = nut_on_spindle_init;
        from = nut_on_spindle_init > 0 ? nut_on_spindle_init : 0;
        home = from > 0;
        seat_turns = 0;
    }
    at = over(__comp_inst);
    in_window = at >= 0 && z >= engage_z - ON_EDGE && z <= engage_z + window + ON_EDGE;
    engaged = in_window && (from > 0 || occupied(__comp_inst, at));
    stalled = stall && engaged;
    speed_out = stalled ? 0.0 : speed_in;
    seen = reverse ? -speed_out : speed_out;
    in_band = fabs(seen) >= rpm_min && fabs(seen) <= rpm_max;
    turned = fabs(seen) / 60.0 * fperiod;

    if (in_window && in_band && seen < 0 && from > 0 && !occupied(__comp_inst, at)) {
        turns += turned;
        if (turns >= turns_off) {
            holds[at] = 1;
            from = 0;
            home = 0;
            turns = 0;
            seat_turns = 0;
        }
    } else if (in_window && in_band && seen > 0 && from == 0 && occupied(__comp_inst, at)) {
        turns += turned;
        if (turns >= turns_on) {
            holds[at] = 0;
            from = at + 1;
            home = 0;
            turns = 0;
            seat_turns = 0;
        }
    } else {
        turns = 0;
        if (in_window && in_band && seen > 0 && from > 0 && !home && !cross_thread) {
            seat_turns += turned;
            if (seat_turns >= turns_seat) home = 1;
        }
    }

    for (k = 0; k < 8; k++) nut_in_pocket(k) = k < pockets(__comp_inst) && occupied(__comp_inst, k);
    nut_on_spindle = from > 0;
    nut_on_spindle_from = from;
    seated = from > 0 && home;
    beam_cut = 0;
    if (from > 0 && at >= 0) {
        double bottom = z - nut_length - (home ? 0.0 : unseated_drop);
        beam_cut = bottom <= beam_z && beam_z <= z;
    }
}
