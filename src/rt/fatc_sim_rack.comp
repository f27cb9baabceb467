component fatc_sim_rack "A simulated tool rack for fixed_atc_probe's simulated machines: a plate with round bores that a touch probe in the spindle touches";
description """
For a simulated machine only. The rack is a plate: inside the outline
\\fBx-min\\fR..\\fBx-max\\fR, \\fBy-min\\fR..\\fBy-max\\fR, between
\\fBbottom-z\\fR and \\fBtop-z\\fR, with a round bore of \\fBbore-diameter\\fR
right through it at each of the first \\fBcount\\fR centres
\\fBpocket-x-N\\fR, \\fBpocket-y-N\\fR (N from 0: the first pocket's bore is
0). \\fBshift-x\\fR, \\fBshift-y\\fR, \\fBshift-z\\fR move the whole rack
(a test bumps it). The probe is a ball of \\fBstylus-radius\\fR whose lowest
point is \\fBprobe-length\\fR below the spindle nose (\\fBx\\fR, \\fBy\\fR,
\\fBz\\fR): the tool table's length of a probe measured on the touch-off
sensor, so a touch on the top face latches the nose at top-z plus
probe-length. \\fBtouching\\fR is true while the ball meets the plate's
material; \\fBout\\fR is touching or \\fBalso\\fR (another simulated probe's
input, passed on). The test is exact: the ball meets the plate when its
largest cross-section within the plate's thickness meets the outline less the
bores, so a touch on a bore's wall from inside (any direction), on the top
face from above or on an outside face trips at the true contact. A touch
latches within one servo period's travel of it when the rack reads the
position motion commands this period and motion reads its input the next
(config/sim/sim_rack.hal). Bores must not overlap one another. One module of
its own, so that it loads beside LinuxCNC's simulated configurations, which
load \\fBor2\\fR themselves (a module loads once).
""";
pin in float x "the spindle nose, machine units: the X joint's pos-cmd (joint.0.pos-cmd on a mill)";
pin in float y;
pin in float z;
pin in s32 count "how many bores are set, 0 to 16";
pin in float pocket-x-#[16] "bore N's centre, machine units, before the shift";
pin in float pocket-y-#[16];
pin in float bore-diameter;
pin in float top-z "the plate's top face";
pin in float bottom-z "the plate's bottom face";
pin in float x-min "the plate's outline";
pin in float x-max;
pin in float y-min;
pin in float y-max;
pin in float shift-x "the whole rack moved by this much";
pin in float shift-y;
pin in float shift-z;
pin in float probe-length "the probe's length: its ball's lowest point lies this far below the nose";
pin in float stylus-radius "the probe's ball";
pin in bit also "another simulated probe input (fatc-sim-probe.out), passed on to out";
pin out bit touching "the ball meets the rack's material";
pin out bit out "touching or also: to fatc-spindle-guard.spindle-probe";
function _;
license "GPL";
;;
#include <rtapi_math.h>

/* Rounding on a boundary: a point found on an edge or a bore's wall counts as material. */
#define ON_EDGE 1e-9

static int bores(struct __comp_state *__comp_inst) {
    return count < 0 ? 0 : count > 16 ? 16 : count;
}

/* (qx, qy), in the rack's own coordinates, is in the outline and in no bore. */
static int material(struct __comp_state *__comp_inst, double qx, double qy) {
    double r = bore_diameter / 2.0;
    int k;
    if (qx < x_min - ON_EDGE || qx > x_max + ON_EDGE || qy < y_min - ON_EDGE || qy > y_max + ON_EDGE) {
        return 0;
    }
    for (k = 0; k < bores(__comp_inst); k++) {
        double dx = qx - pocket_x(k), dy = qy - pocket_y(k);
        if (dx * dx + dy * dy < r * r - ON_EDGE) return 0;
    }
    return 1;
}

/* A point of the material within `reach` of (cx, cy). */
static int near(struct __comp_state *__comp_inst, double cx, double cy, double reach,
                double qx, double qy) {
    double dx = qx - cx, dy = qy - cy;
    return dx * dx + dy * dy <= reach * reach && material(__comp_inst, qx, qy);
}

/* Where bore k's wall crosses the outline's edge at x = at (vertical) or y = at. */
static int crossings(struct __comp_state *__comp_inst, int k, int vertical, double at,
                     double cx, double cy, double reach) {
    double r = bore_diameter / 2.0;
    double across = vertical ? at - pocket_x(k) : at - pocket_y(k);
    double along, centre;
    if (fabs(across) > r) return 0;
    along = sqrt(r * r - across * across);
    centre = vertical ? pocket_y(k) : pocket_x(k);
    if (vertical) {
        return near(__comp_inst, cx, cy, reach, at, centre - along) ||
               near(__comp_inst, cx, cy, reach, at, centre + along);
    }
    return near(__comp_inst, cx, cy, reach, centre - along, at) ||
           near(__comp_inst, cx, cy, reach, centre + along, at);
}

/* The disc of `reach` around (cx, cy) meets the material (the outline less the
   bores). The material's nearest point is the centre itself, the foot of the
   centre on an edge or a bore's wall, or a corner where two of those meet:
   every one that lies in the material is tried. */
static int reaches(struct __comp_state *__comp_inst, double cx, double cy, double reach) {
    double r = bore_diameter / 2.0;
    double edges[4] = {x_min, x_max, y_min, y_max};
    int k, e;
    if (material(__comp_inst, cx, cy)) return 1;
    for (e = 0; e < 4; e++) {
        int vertical = e < 2; /* x-min, x-max, then y-min, y-max */
        double foot_x = vertical ? edges[e] : fmin(fmax(cx, x_min), x_max);
        double foot_y = vertical ? fmin(fmax(cy, y_min), y_max) : edges[e];
        if (near(__comp_inst, cx, cy, reach, foot_x, foot_y) ||
            near(__comp_inst, cx, cy, reach, edges[e & 1], edges[2 + (e >> 1)])) {
            return 1;
        }
    }
    for (k = 0; k < bores(__comp_inst); k++) {
        double dx = cx - pocket_x(k), dy = cy - pocket_y(k);
        double d = sqrt(dx * dx + dy * dy);
        if (fabs(d - r) > reach) continue; /* this wall is out of reach */
        if (d > 0.0 ? near(__comp_inst, cx, cy, reach, pocket_x(k) + dx * r / d, pocket_y(k) + dy * r / d)
                    : near(__comp_inst, cx, cy, reach, pocket_x(k) + r, pocket_y(k))) {
            return 1;
        }
        for (e = 0; e < 4; e++) {
            if (crossings(__comp_inst, k, e < 2, edges[e], cx, cy, reach)) return 1;
        }
    }
    return 0;
}

FUNCTION(_) {
    double radius = stylus_radius > 0.0 ? stylus_radius : 0.0;
    /* The ball's centre, in the rack's own coordinates (before the shift). */
    double cx = x - shift_x, cy = y - shift_y, cz = z - probe_length + radius - shift_z;
    /* The ball's widest cross-section within the plate's thickness: the outline
       and the bores are the same at every height, so the ball meets the plate
       exactly when that disc meets them. */
    double dz = cz - fmin(fmax(cz, bottom_z), top_z);
    touching = 0;
    if (x_max > x_min && y_max > y_min && top_z > bottom_z && fabs(dz) <= radius) {
        touching = reaches(__comp_inst, cx, cy, sqrt(radius * radius - dz * dz));
    }
    out = touching || also;
}
