"""The soak on a collet-nut magazine (issue 46): soak.py's programs and
recoveries on config/sim/collet_nut.json with the simulated magazine
(config/sim/sim_nut.hal) as the truth. The magazine knows nuts, not tools:
which pocket holds a nut and which pocket the spindle's nut came from; this
follows each tool's nut as the spindle screws it on and off. A manual tool,
handed in at `loading`, is no nut of the magazine's. Faults: a pocket's nut
gone (missing-N: the fetch screws nothing on and zone 1 sees no nut), a nut
that never seats (cross-thread: zone 2 sees it hang), an estop, LinuxCNC's
Stop and the component killed, at a random moment or while the spindle turns
for the changer. The operator puts the missing nut back and screws a
cross-threaded one home by hand before confirming what they find."""
import contextlib
import time

import hal
import sim_nut
import soak
from soak import PLAN, POCKETS, HOME_POCKET, P, d

NUT = "fatc-sim-nut."
CUTS = ("estop", "abort", "kill")
# A change on the soak's fast axes, two spindle starts and stops and three
# plunges at the engage feed: some five seconds (the drawbar's 2.5).
CHANGE_SECONDS = 5.0


class ColletSoak(soak.Soak):
    FAULTS = ["missing", "cross_thread", "abort", "estop"]

    def __init__(self):
        super().__init__()
        self.where = {"spindle": 0, "pockets": {p: PLAN["rack"][str(p)] for p in POCKETS}}
        self.nut_from = 0  # the magazine's nut-on-spindle-from at the last look
        self.by_hand = False  # the operator's hands move nuts: not the spindle's screwing
        self.program_tools = []

    def run(self):
        if PLAN["start"] > 1:
            raise RuntimeError("the collet-nut soak keeps its magazine in one LinuxCNC start only")
        for pocket, tool in self.where["pockets"].items():
            sim_nut.put_in_pocket(pocket, bool(tool))
        super().run()

    def event(self, kind, **details):
        if kind == "program":
            self.program_tools = details["tools"]
        super().event(kind, **details)

    # ------------------------------------------------------------ the magazine's truth
    def poll(self):
        self.follow_nuts()
        return super().poll()

    def follow_nuts(self):
        """A nut the spindle screwed on or off since the last look. The
        component writes the pockets before nut-on-spindle-from in a servo
        period: read after it, they are at least as new."""
        if self.by_hand:
            return
        came_from = d.pin_value(NUT + "nut-on-spindle-from")
        if came_from == self.nut_from:
            return
        if came_from and not self.nut_from:
            self.where["spindle"] = self.where["pockets"][came_from]
            self.where["pockets"][came_from] = 0
        elif not came_from:
            into = [p for p in POCKETS if not self.where["pockets"][p] and
                    d.pin_value(NUT + "nut-in-pocket-%d" % (p - 1))]
            if into:
                self.where["pockets"][into[0]] = self.where["spindle"]
            self.where["spindle"] = 0
        self.nut_from = came_from

    @contextlib.contextmanager
    def hands(self):
        self.by_hand = True
        try:
            yield
        finally:
            self.nut_from = d.pin_value(NUT + "nut-on-spindle-from")
            self.by_hand = False

    def truth(self):
        return {"spindle": self.where["spindle"], "pockets": dict(self.where["pockets"])}

    def worst_moment(self):
        """Half the cuts strike while the spindle turns for the changer."""
        return d.pin_value(P + "changer-spindle")

    # ------------------------------------------------------------ faults
    def plan_fault(self, program_seconds):
        if PLAN["fault_cycle"]:
            kind = self.FAULTS[(PLAN["faults_before"] + self.faults) % len(self.FAULTS)]
        elif self.rng.random() >= PLAN["fault_rate"]:
            return
        else:
            kind = self.rng.choice(self.FAULTS)
        program_seconds *= CHANGE_SECONDS / PLAN["seconds_per_change"]
        at = time.monotonic() + self.rng.uniform(0.1, 0.5) * program_seconds
        self.pending_fault = {"kind": kind, "at": at,
                              "at_chuck": kind in CUTS and self.rng.random() < 0.5}
        if kind == "missing":
            # The nut of the last tool the program fetches from the magazine:
            # the changes before it are made.
            held = self.where["spindle"]
            fetched = [t for t in self.program_tools if t and t != held and
                       t in self.where["pockets"].values()]
            self.pending_fault["at"] = float("inf")
            if fetched:
                pocket = next(p for p, t in self.where["pockets"].items() if t == fetched[-1])
                hal.set_p(NUT + "missing-%d" % (pocket - 1), "1")
                self.injected(kind, pocket=pocket, tool=fetched[-1])

    def inject(self):
        """A cross-thread from its moment on: the next nut screwed on never seats."""
        if self.pending_fault["kind"] == "cross_thread":
            hal.set_p(NUT + "cross-thread", "1")
            self.injected("cross_thread", changer_state=d.pin_value(P + "state"))
        else:
            super().inject()

    def end_faults(self):
        """The missing nut back in its pocket, the thread good again."""
        for pocket in POCKETS:
            hal.set_p(NUT + "missing-%d" % (pocket - 1), "0")
        hal.set_p(NUT + "cross-thread", "0")
        self.pending_fault = None
        self.fault_active = False

    # ------------------------------------------------------------ the operator
    def recover(self, where, provoked=False):
        """A nut left hanging low is screwed home by hand first."""
        self.poll()
        nut = sim_nut.truth(POCKETS)
        if nut["spindle"] and not nut["seated"]:
            with self.hands():
                sim_nut.screw_on_by_hand(nut["spindle"])
            self.event("screwed home by hand", pocket=nut["spindle"], tool=self.where["spindle"])
        super().recover(where, provoked)

    def hand(self, words):
        """A manual tool handed in or out at loading; a tool of the magazine
        handed in gets its nut screwed on by hand."""
        spindle = self.where["spindle"]
        if "insert tool " in words and spindle == 0:
            tool = int(words.split("insert tool ")[1].split()[0])
            if tool in HOME_POCKET:
                with self.hands():
                    sim_nut.screw_on_by_hand(HOME_POCKET[tool])
            self.where["spindle"] = tool
        elif "remove tool " in words and spindle:
            with self.hands():
                sim_nut.screw_on_by_hand(0)
            self.where["spindle"] = 0
