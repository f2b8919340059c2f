"""The study's cases: which scenes, which states, and what theory says their order is.

Each case names a contact model, the initial states it runs (one LAMMPS run holds them
all), the reference its error is measured against, and per form the order of convergence
that the mechanisms in :data:`MECHANISMS` predict.

Why a handful of states per case is enough: without a Coulomb cap the Hookean contact is
linear (springs, viscous dashpots) and the time the contact ends does not depend on the
state (the overlap is v_n times a function of time), so LAMMPS's discrete map is, like
the exact one, a linear map of the state. Its error is then linear in the state too, and
its largest value over a box of initial states sits at one of the box's corners.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...scenes.collision import STATE_3D
from ...model.contact import ContactModel

__all__ = ["Case", "cases", "corners", "box_sample", "MECHANISMS", "BOX",
           "MID", "EDGE", "ANY", "FROZEN", "FROZEN_T_END", "FROZEN_Z"]

#: Collision forms: the contact's end in the middle of a step (dt = tau/(M + 1/2)), on a
#: step boundary (dt = tau/M), or wherever one dt puts each sphere's own end (Hertz).
MID, EDGE, ANY = "mid-step end", "end on a step", "end anywhere"
#: The frozen contact's single form.
FROZEN = "frozen"
#: Duration and height of the frozen contacts (as in Figs. 2 and 7).
FROZEN_T_END = 10.0
FROZEN_Z = 0.1
#: The sweep's box of initial states: v_n in [-1.5, -0.1], v_t and r omega in [-2, 2].
BOX = ((-1.5, -0.1), (-2.0, 2.0), (-2.0, 2.0))
#: The 3-D box adds v_s, r omega_s and r omega_n in [-2, 2].
BOX_3D = BOX + ((-2.0, 2.0),) * 3
#: A Hertzian wall with the paper's kn tunnels above |v_n| = 1: its speeds stop at 0.8. Its
#: contact time depends on v_n, so it takes several speeds, each with the tangential corners.
HERTZ_SPEEDS = (-0.8, -0.6, -0.4, -0.2, -0.1)
#: ContactModel's constructor keywords: what a case's record says of its model.
MODEL_KEYWORDS = ("m", "r", "alpha", "kn", "kt", "gamma_n", "gamma_t", "mu", "limit_damping", "normal")


def corners(box=BOX) -> tuple[tuple[float, ...], ...]:
    """Every corner of ``box`` (one (low, high) pair per state column)."""
    grid = np.stack(np.meshgrid(*box, indexing="ij"), axis=-1).reshape(-1, len(box))
    return tuple(map(tuple, grid.tolist()))


def box_sample(n: int, seed: int, box=BOX) -> np.ndarray:
    """``n`` states drawn uniformly from ``box``."""
    lo, hi = np.array(box).T
    return np.random.default_rng(seed).uniform(lo, hi, size=(n, len(box)))


@dataclass(frozen=True)
class Case:
    """One row of the study: a scene kind, a model, its states and why it is here.

    ``states``: per sphere (v_n, v_t, r omega), or the six columns of STATE_3D for a 3-D
    case; a frozen contact has one (0, v_t, r omega), held at FROZEN_Z for FROZEN_T_END.
    ``expected``: form -> the order the reasoning in ``limit`` predicts; its keys are the
    forms the case runs in. ``theory``: what the error is measured against. ``rough``: the
    forms whose error is not a smooth series in dt (it jumps with where a switch or an end
    falls inside a step), so that its local orders swing and the fitted one is approximate.
    """

    name: str
    label: str
    kind: str
    model: ContactModel
    states: tuple
    why: str
    limit: str
    expected: dict
    theory: str = "Eq. 18"
    rough: tuple[str, ...] = ()

    @property
    def forms(self) -> tuple[str, ...]:
        return tuple(self.expected)

    @property
    def state_names(self) -> tuple[str, ...]:
        return STATE_3D[: len(self.states[0])]

    def record(self) -> dict:
        return {"name": self.name, "label": self.label, "kind": self.kind,
                "model": {k: getattr(self.model, k) for k in MODEL_KEYWORDS},
                "states": [list(s) for s in self.states], "why": self.why, "limit": self.limit,
                "expected_order": dict(self.expected), "theory": self.theory, "rough_forms": list(self.rough)}


#: What limits the order: the mechanisms, each named once. The contact starts on a step
#: (t = 0) with zero overlap and zero slip, so entry costs nothing in the undamped model;
#: what matters is the exit, the dashpots and the cap.
MECHANISMS = {
    "normal over-kick": (
        "with the end mid-step, the contact's last kick applies the normal spring at overlap "
        "|v_n| dt/2 for a whole half step, while the exact force fades to zero within it: the "
        "outgoing |v_n| comes out too large by |v_n| (w_n dt)^2/8, second order (w_n = sqrt(kn/m)). At "
        "the paper's defaults this is the largest error"),
    "tangential cut": (
        "the tangential spring force -kt u(tau) is still finite when the contact ends and drops to zero "
        "in one step. With the end mid-step the cut's first-order error cancels and second order is "
        "left; with the end on a step boundary the force is applied for a half step or not at all: "
        "first order, whatever the other terms do"),
    "normal end on a step": (
        "with the end on a step, the overlap there is only velocity Verlet's O(dt^2) phase slip, so "
        "the last half-kick is O(dt^3), and v_n sits at the flat bottom of its cosine: third order"),
    "phase error": (
        "velocity Verlet's phase error: second order, growing linearly with time; with no contact end "
        "it is the only error"),
    "dashpot lag": (
        "LAMMPS evaluates velocity-dependent forces with the half-step velocity, a first-order lag; a "
        "dashpot force -gamma v is also finite at entry and exit, so it is cut wherever the end falls: "
        "first order in the components it acts on, in both forms"),
    "Coulomb cap": (
        "|F_t| <= mu F_n and F_n -> 0 at the exit (and at entry), so every contact with u(tau) != 0 "
        "slides at its end: the cap brings F_t to zero continuously and so removes the tangential cut "
        "in both forms. The switches between sticking and sliding fall between steps, but they are "
        "kinks in the force (continuous, with a jump in slope), which velocity Verlet's trapezoidal "
        "kick integrates with a second-order error whose size depends on where in its step each "
        "switch falls: order 2, with local orders that wobble (the error is not a smooth series in dt)"),
    "Hertzian end": (
        "a Hertzian contact lasts tau(v_n), so one dt cannot put every sphere's end mid-step: each "
        "end falls at its own place inside a step, and the tangential cut is first order with a "
        "coefficient that jumps with dt. Running each speed at its own dt = tau(v_n)/(M + 1/2) puts "
        "every end mid-step again, and the cut's first-order error cancels as for the Hookean wall"),
}

_DEFAULT_LIMIT = ("mid-step: normal over-kick (v_n) and the cancelled tangential cut, both second order. "
                  "On a step: the tangential cut, first order; v_n is third order")
_RIGID = "; fix rigid's step is velocity Verlet too, so the integrator changes nothing"


def cases() -> list[Case]:
    """The study's cases, in the order of the table (the paper's defaults first)."""
    d = ContactModel()
    box_corners = corners()
    damped = "Eq. 18, exact damped Omega and restitution"
    coulomb_states = np.vstack([box_corners, box_sample(8, seed=1)])
    return [
        # the paper's Hookean wall without a cap: its parameters, ratios and inertias
        Case("defaults", "paper defaults", "collision", d, box_corners,
             "the paper's parameters (kt/kn = 1/10, alpha = 2/5) at the 8 corners of the sweep's box, "
             "which bound its error", _DEFAULT_LIMIT, {MID: 2.0, EDGE: 1.0}),
        Case("magic", "magic ratio kt/kn = 2/7", "collision", ContactModel(kt=20.0 / 7.0), box_corners,
             "tau sqrt(Q) = pi: the slip displacement u is back to 0 when the contact ends",
             "mid-step: normal over-kick, and the same over-kick in the slip (u(tau) = 0 like the overlap), "
             "second order. On a step: u(tau) = 0, so both forces vanish at the end, nothing is cut, and "
             "every component is third order", {MID: 2.0, EDGE: 3.0}),
        Case("soft", "soft, kt/kn = 0.01", "collision", ContactModel(kt=0.1), box_corners,
             "a slow slip mode (tau sqrt(Q) = 0.19 pi); the normal mode sets dt", _DEFAULT_LIMIT,
             {MID: 2.0, EDGE: 1.0}),
        Case("stiff", "stiff, kt/kn = 5", "collision", ContactModel(kt=50.0), box_corners,
             "a fast slip mode (4.2 slip half-periods per contact) that sets dt",
             _DEFAULT_LIMIT + "; the slip mode sets dt, so the normal over-kick is 17 times smaller and the "
             "tangential terms set the error", {MID: 2.0, EDGE: 1.0}),
        Case("alpha_small", "alpha = 0.1", "collision", ContactModel(alpha=0.1), box_corners,
             "mass near the centre: a fast slip mode, run through fix rigid instead of nve/sphere",
             _DEFAULT_LIMIT + _RIGID, {MID: 2.0, EDGE: 1.0}),
        Case("alpha_shell", "alpha = 2/3", "collision", ContactModel(alpha=2.0 / 3.0), box_corners,
             "a thin shell, the largest physical alpha, through fix rigid", _DEFAULT_LIMIT + _RIGID,
             {MID: 2.0, EDGE: 1.0}),
        # dashpots, measured against the exact damped Omega and restitution
        Case("damped_t", "damped, gamma_t = 1", "collision", ContactModel(gamma_t=1.0), box_corners,
             "a tangential dashpot (exact damped Omega)",
             "dashpot lag: v_t and r omega first order in both forms; v_n keeps its undamped order "
             "(on a step, down to the 1e-12 normal dashpot that carries gamma_t in LAMMPS)",
             {MID: 1.0, EDGE: 1.0}, damped),
        Case("damped_n", "damped, gamma_n = 1", "collision", ContactModel(gamma_n=1.0), box_corners,
             "a normal dashpot (restitution 0.37; the theory lets the normal force turn tensile and ends "
             "the contact at z = r, as LAMMPS does)",
             "dashpot lag: v_n first order in both forms; v_t and r omega keep their undamped orders "
             "(2 mid-step, 1 on a step)", {MID: 1.0, EDGE: 1.0}, damped),
        Case("damped", "damped, gamma_n = gamma_t = 1", "collision", ContactModel(gamma_n=1.0, gamma_t=1.0),
             box_corners, "both dashpots at once",
             "dashpot lag in every component, first order in both forms", {MID: 1.0, EDGE: 1.0}, damped),
        # single columns of the linear error: grazing, head-on and spin-dominated incidence
        Case("grazing", "grazing, |v_n| = 0.01", "collision", d,
             ((-0.01, 1.0, 0.0), (-0.01, 0.0, 1.0), (-0.01, -1.0, 2.0)),
             "nearly tangential incidence with slip 1: the overlap stays below 1e-3 r",
             "the contact's timing does not depend on v_n: the defaults' mechanisms, with the normal "
             "over-kick scaled down by |v_n|, so the tangential terms set the error", {MID: 2.0, EDGE: 1.0}),
        Case("head_on", "head-on, no spin", "collision", d, ((-1.5, 0.0, 0.0), (-0.1, 0.0, 0.0)),
             "v_t = omega = 0: no slip, only the normal spring acts",
             "no tangential force. Mid-step: the normal over-kick, second order. On a step: nothing is cut "
             "and v_n is third order: here ending on a step beats ending mid-step", {MID: 2.0, EDGE: 3.0}),
        Case("head_on_spin", "head-on with spin", "collision", d, ((-1.0, 0.0, 1.0), (-1.0, 0.0, -2.0)),
             "v_t = 0: all the slip comes from r omega", _DEFAULT_LIMIT, {MID: 2.0, EDGE: 1.0}),
        Case("high_spin", "high spin, |r omega| = 20 |v_n|", "collision", d,
             ((-0.1, 0.0, 2.0), (-0.1, 0.0, -2.0), (-0.1, 1.0, -2.0)),
             "spin dominates: slip 20 times the normal speed", _DEFAULT_LIMIT, {MID: 2.0, EDGE: 1.0}),
        # 3-D spin, the Hertzian wall and the Coulomb cap, each against its own theory
        Case("spin_3d", "3-D spin", "collision", d, corners(BOX_3D),
             "out of the plane: v_s, omega_s (which rolls along s) and omega_n at the 64 corners of the "
             "6-D box; the contact is still linear, so the corners still bound the error",
             "the defaults' mechanisms in each tangential direction (mid-step 2, on a step 1); the spin "
             "about the normal feels no torque and stays exact", {MID: 2.0, EDGE: 1.0}, "Eq. 18, 6x6 block form"),
        Case("hertz", "Hertzian wall", "collision", ContactModel(normal="hertz"),
             corners((HERTZ_SPEEDS, BOX[1], BOX[2])),
             f"F_n = kn sqrt(r) delta^(3/2): tau and Omega depend on v_n; {len(HERTZ_SPEEDS)} speeds from "
             f"{-HERTZ_SPEEDS[-1]:g} to {-HERTZ_SPEEDS[0]:g}, each with the 4 corners of (v_t, r omega): the map "
             "is not linear in v_n, so these states sample the box rather than bound it",
             "Hertzian end: one dt for every sphere, first order; each speed alone at its own mid-step dt, "
             "second order", {MID: 2.0, ANY: 1.0}, "Eq. 18 with Omega(v_n) (exact.hertz)", rough=(ANY,)),
        Case("coulomb", "Coulomb cap mu = 0.5", "collision", ContactModel(mu=0.5),
             tuple(map(tuple, coulomb_states.tolist())),
             "a finite Coulomb cap (sliding), against the Coulomb oracle (exact.oracle, adaptive DOP853 at "
             "rtol 1e-12 with stick-slip events); 8 corners and 8 states from the box (with sliding the map "
             "is no longer linear, so corners alone need not bound it)",
             "Coulomb cap: no cut at the end, kinks between steps; second order in both forms (v_n is the "
             "defaults': the cap acts on the tangential force only)", {MID: 2.0, EDGE: 2.0},
             "Coulomb oracle (exact.oracle.bounce_many)", rough=(MID, EDGE)),
        Case("frozen", "frozen, defaults", "frozen", d, ((0.0, 1.0, 0.0),),
             f"sphere held at z = {FROZEN_Z:g} for t = {FROZEN_T_END:g} (Fig. 2): no contact end",
             "phase error, second order", {FROZEN: 2.0}, "Eq. 10"),
        Case("frozen_damped", "frozen, gamma_t = 1", "frozen", ContactModel(gamma_t=1.0), ((0.0, 1.0, 0.0),),
             f"the damped frozen contact (Fig. 7), held for t = {FROZEN_T_END:g}",
             "dashpot lag, first order, with no contact end to blame", {FROZEN: 1.0}, "Eq. 10, exact damped form"),
    ]
