component fatc_rack_guard "Keeps every motion out of fixed_atc_probe's tool rack: holds G-code motion and stops jogs before the spindle or its tool enters";
description """
Watches the commanded position every servo period. From its velocity and
the axes' accelerations it works out where the spindle nose would stand if
motion stopped now; when that point lies in the rack's volume (\\fBbox.N\\fR,
with no floor, its top raised by \\fBtool-length\\fR: the tool hangs below the
nose) and closer to it than where the nose is, the guard trips:
\\fBfeed-inhibit\\fR holds G-code motion (programs and MDI decelerate at the
axes' acceleration) and \\fBjog-stop\\fR stops a jog. Motion away from the
rack, or along it, is never held, so a spindle left inside can always be moved
out. Tripped holds until motion stands with nothing queued (the program or MDI
aborted, the jog stopped); fixed_atc_probe aborts it and says what was about to
enter where. While \\fBenable\\fR is false (the changer's own moves, teaching,
the keep-out switched off) nothing is held but \\fBhold-in\\fR.
""";
pin in bit enable "true: armed; fixed_atc_probe drives it";
pin in float pos-x "commanded X, machine units (axis.x.pos-cmd)";
pin in float pos-y "commanded Y (axis.y.pos-cmd)";
pin in float pos-z "commanded Z (axis.z.pos-cmd)";
pin in float accel-x "[AXIS_X]MAX_ACCELERATION";
pin in float accel-y "[AXIS_Y]MAX_ACCELERATION";
pin in float accel-z "[AXIS_Z]MAX_ACCELERATION";
pin in float accel-fraction = 0.5 "the part of that acceleration a stop is counted on: blended moves stop at half";
pin in float tool-length "of the tool in the spindle: the volume reaches this much higher";
pin in s32 boxes "how many boxes of the rack's volume are set";
pin in float box.#.x-min[4] "the rack's volume, box N (fixed_atc_probe sets them)";
pin in float box.#.x-max[4];
pin in float box.#.y-min[4];
pin in float box.#.y-max[4];
pin in float box.#.z-max[4] "the top of box N, for an empty spindle";
pin in bit in-position "motion.in-position";
pin in bit jog-active "motion.jog-is-active";
pin in bit hold-in "another reason to hold G-code motion, passed on to feed-inhibit";
pin out bit feed-inhibit "to motion.feed-inhibit";
pin out bit jog-stop "to motion.jog-stop";
pin out bit tripped "a motion was about to enter the rack; held until motion stands with nothing queued";
pin out s32 trips "counts the trips: a jog's may end before anyone reads tripped";
pin out s32 box "the box of the last trip";
pin out float at-x "where the nose was at the last trip";
pin out float at-y;
pin out float at-z;
variable double last_x;
variable double last_y;
variable double last_z;
variable int started = 0;
function _;
license "GPL";
;;
#include <rtapi_math.h>

/* Signed distance from (x, y, z) to box k raised by `lift`: negative inside. */
static double distance_to(struct __comp_state *__comp_inst, int k, double lift,
                          double x, double y, double z) {
    double top = box_z_max(k) + lift;
    double dx = fmax(fmax(box_x_min(k) - x, x - box_x_max(k)), 0.0);
    double dy = fmax(fmax(box_y_min(k) - y, y - box_y_max(k)), 0.0);
    double dz = fmax(z - top, 0.0);
    if (dx > 0.0 || dy > 0.0 || dz > 0.0) return sqrt(dx * dx + dy * dy + dz * dz);
    return -fmin(fmin(fmin(x - box_x_min(k), box_x_max(k) - x),
                      fmin(y - box_y_min(k), box_y_max(k) - y)), top - z);
}

/* How far an axis moving at v goes before it stands: along the path (the
   planner stops the path at the acceleration its slowest axis allows) or on
   its own (a jog stops each axis at its own), whichever is longer; plus
   three servo periods' travel: a trip may come a period late (the nose moves
   a period's travel between two looks), and two before the hold takes effect. */
static double run_out(double v, double speed, double path_accel, double axis_accel, double period) {
    double along = speed > 0.0 ? fabs(v) * speed / (2.0 * path_accel) : 0.0;
    double own = v * v / (2.0 * axis_accel);
    return copysign(fmax(along, own) + 3.0 * period * fabs(v), v);
}

FUNCTION(_) {
    double v[3] = {0.0, 0.0, 0.0};
    double a[3];
    double f = accel_fraction > 0.01 ? accel_fraction : 0.01;
    double speed, path_accel = 1e30, lift = tool_length > 0.0 ? tool_length : 0.0;
    double sx, sy, sz;
    int k, n = boxes < 0 ? 0 : boxes > 4 ? 4 : boxes;
    if (started) {
        v[0] = (pos_x - last_x) / fperiod;
        v[1] = (pos_y - last_y) / fperiod;
        v[2] = (pos_z - last_z) / fperiod;
    }
    last_x = pos_x;
    last_y = pos_y;
    last_z = pos_z;
    started = 1;
    if (!enable) {
        tripped = 0;
    } else if (tripped) {
        if (v[0] == 0.0 && v[1] == 0.0 && v[2] == 0.0 && in_position && !jog_active) {
            tripped = 0;
        }
    } else {
        /* An acceleration not set counts as a slow one: the guard trips early, never late. */
        a[0] = (accel_x > 1.0 ? accel_x : 1.0) * f;
        a[1] = (accel_y > 1.0 ? accel_y : 1.0) * f;
        a[2] = (accel_z > 1.0 ? accel_z : 1.0) * f;
        speed = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        for (k = 0; k < 3; k++) {
            if (v[k] != 0.0) path_accel = fmin(path_accel, a[k] * speed / fabs(v[k]));
        }
        sx = pos_x + run_out(v[0], speed, path_accel, a[0], fperiod);
        sy = pos_y + run_out(v[1], speed, path_accel, a[1], fperiod);
        sz = pos_z + run_out(v[2], speed, path_accel, a[2], fperiod);
        for (k = 0; k < n && !tripped; k++) {
            double stop = distance_to(__comp_inst, k, lift, sx, sy, sz);
            if (stop <= 0.0 && stop < distance_to(__comp_inst, k, lift, pos_x, pos_y, pos_z) - 1e-9) {
                tripped = 1;
                trips++;
                box = k;
                at_x = pos_x;
                at_y = pos_y;
                at_z = pos_z;
            }
        }
    }
    feed_inhibit = hold_in || tripped;
    jog_stop = tripped;
}
