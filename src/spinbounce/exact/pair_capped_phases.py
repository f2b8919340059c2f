"""The equations of two free spheres in contact under a Coulomb cap, phase by phase: what
:mod:`.pair_capped` integrates (the module's docstring says what LAMMPS does and how it is followed).

:class:`Contact` holds a pair's rates and switching functions while it sticks (the trial force A a
state) or slides (A's unit s on the cap), and what each switch leaves; :class:`ClassicContact` is
``linear_history_classic``'s cap, whose reset by k alone makes it saw-tooth (:mod:`.oracle_classic`).
The equations themselves, which the integrator calls at every stage, are compiled (:mod:`.pair_kernel`);
the phases' decisions, taken a few times a contact, are here.
"""

from __future__ import annotations

import numpy as np

from . import pair_kernel as kernel
from .oracle_classic import NEAR_ONE, note_cap, reset, slides

__all__ = ["Contact", "ClassicContact", "MARGIN", "TURN_FLOOR", "MAX_EVALUATIONS", "EXPLICIT_EVALUATIONS",
           "TooManyEvaluations"]

#: A switch must be passed by this fraction of the cap's scale (as in the wall's oracle).
MARGIN = 1e-12
#: Below this fraction of the cap's scale a slide turns s no faster than at it (the wall's oracle's
#: TURN_FLOOR): near the cap's zeros s' ~ 1/c would grow without bound; the slower turn only bends
#: a force that small.
TURN_FLOOR = 1e-8
#: A phase whose rates are asked for more often than this is refused (about 20 s of one core).
MAX_EVALUATIONS = 1_000_000
#: A phase DOP853 has not ended after this many evaluations (2 to 4 s) is stiff, and is integrated again from its
#: start by Radau (:func:`.pair_capped._phase`): the stiffest pairs measured take ~1e5 in all (3-D Hertz-Mindlin
#: with dashpots: 8e4 to 1.1e5). The stiff one measured: a 3-D slide from first touch on a spring on the contact
#: radius with a tangential dashpot (the runaway start), where the history's growth a'/a ~ 1/(2t) pulls s back
#: onto the slip at ~4e19 per second (the dashpot's part of A, ~gamma_t |u'|, 1e17 times the cap), and DOP853's
#: steps fell to 1e-19 of the contact time.
EXPLICIT_EVALUATIONS = 200_000


class TooManyEvaluations(RuntimeError):
    """A phase's rates were asked for more often than its integrator's budget allows."""


#: The names of :func:`.pair_kernel.kinematics`' fields.
_KINEMATICS = ("n", "turn", "v", "v_n", "spin", "slip", "f_n", "df_n", "lever_a", "lever_b", "spring", "growth",
               "dashpot", "dashpot_rate")


def _unit(x: np.ndarray) -> np.ndarray | None:
    size = np.linalg.norm(x)
    return x / size if size > 0.0 else None


class Contact:
    """The pair's equations in one phase (``sliding``, ``coasting`` or sticking); y[15:18] is A sticking, s sliding
    (nothing coasting), and y[18] the overlap delta, a state of its own (delta' = -v.n): from the centres' distance,
    rounding would blur it by ~1e-16 (r_a + r_b), more than a law on the contact radius starts with. A slide whose
    cap falls below a switch's margin coasts, as the wall's oracle does: no tangential force until the cap is back
    (near the contact's end the growth a'/a of a law on the contact radius turns s ever faster, a cap ~1e-12 of its
    scale)."""

    #: Whether a slide whose cap vanishes coasts (the classic cap's slides run on to the end of contact).
    COASTS = True

    def __init__(self, p: dict, n0: np.ndarray, planar: bool):
        self.p, self.n0, self.planar = p, np.ascontiguousarray(n0, dtype=float), planar
        self.P = kernel.coefficients(p)
        self.m_star = self.P[kernel.M_STAR]
        self.sliding, self.coasting, self.f_side = False, False, 1.0
        self.evaluations, self.budget = 0, MAX_EVALUATIONS

    def kinematics(self, y) -> dict:
        """The state's kinematics (:func:`.pair_kernel.kinematics`) by name, the compiled tuple as ``raw``."""
        raw = kernel.kinematics(y, self.P, self.n0, self.planar)
        k = dict(zip(_KINEMATICS, (np.array(x) if isinstance(x, tuple) else x for x in raw), strict=True))
        return k | {"levers": (raw[kernel.LEVER_A], raw[kernel.LEVER_B]), "raw": raw}

    def stick_rate(self, k: dict, trial: np.ndarray) -> np.ndarray:
        """A' while sticking with the trial force ``trial`` (the friction -trial)."""
        return np.array(kernel.stick_rate(k["raw"], self.P, tuple(float(x) for x in trial)))

    def cap(self, k: dict) -> float:
        """mu |F_n|, with |F_n| taken as F_n on the phase's side (``f_side``): a phase ends where F_n
        changes sign, and beyond the end of contact the cap keeps falling below zero instead of
        growing back, so that no switch is crossed twice within one step of the integrator."""
        return self.p["mu"] * self.f_side * k["f_n"]

    def cap_rate(self, k: dict) -> float:
        """d(mu |F_n|)/dt on the phase's side."""
        return self.p["mu"] * self.f_side * k["df_n"]

    def direction(self, k: dict, y) -> np.ndarray:
        """A slide's unit s, held in the tangent plane (its drift off it is the integrator's)."""
        return np.array(kernel.direction(k["raw"], y))

    def rates(self, _t, y):
        self._counted()
        out = np.empty(19)
        if self.sliding:
            kernel.slide_rates(y, self.P, self.n0, self.planar, self.f_side, self.turn_floor, out)
        elif self.coasting:
            kernel.coast_rates(y, self.P, self.n0, self.planar, out)
        else:
            kernel.stick_rates(y, self.P, self.n0, self.planar, out)
        return out

    def _counted(self) -> None:
        self.evaluations += 1
        if self.evaluations > self.budget:
            phase = "sliding" if self.sliding else "coasting" if self.coasting else "sticking"
            raise TooManyEvaluations(f"the capped pair's rates were asked for {self.budget:,} times in one phase, its "
                                     f"steps {phase} too short to end it")

    def stick_ends(self, _t, y) -> float:
        return kernel.stick_end(y, self.P, self.n0, self.planar, self.f_side, MARGIN * self.force_scale)

    def push(self, k: dict, s: np.ndarray) -> float:
        """How fast sticking would carry A outwards along s with A = c s on the cap, less the cap's rate."""
        return s @ self.stick_rate(k, self.cap(k) * s) - self.cap_rate(k)

    def slide_ends(self, _t, y) -> float:
        return kernel.slide_end(y, self.P, self.n0, self.planar, self.f_side, MARGIN * self.force_scale / self.tau)

    def cap_gone(self, _t, y) -> float:
        """The cap less a switch's margin: falls through zero where a slide's cap vanishes (at the contact's end,
        or at F_n's zero)."""
        return self.p["mu"] * self.normal_force(_t, y) - MARGIN * self.force_scale

    def cap_back(self, _t, y) -> float:
        """The same, rising through zero where a coast's cap is back without F_n changing sign."""
        return self.cap_gone(_t, y)

    def normal_force(self, _t, y) -> float:
        """F_n on the side it started the phase on: falls through 0 when F_n changes sign."""
        return self.f_side * kernel.normal_force(y, self.P, self.n0, self.planar)

    def deepest(self, _t, y) -> float:
        """The overlap's rate: a rescale starts where it falls through 0 (a kink in A')."""
        return -kernel.closing(y, self.P, self.n0, self.planar)

    def separated(self, _t, y) -> float:
        return self.last - y[18]

    def on_cap(self, y, s: np.ndarray | None) -> None:
        """With A on the cap along s (or just past it): slide if sticking would push A outwards faster
        than the cap grows, else stick with A = c s (no s, no slip: stick with A = 0)."""
        k = self.kinematics(y)
        if s is None:
            self.sliding, y[15:18] = False, 0.0
        elif self.push(k, s) > 0.0:
            self.sliding, y[15:18] = True, s
        else:
            self.sliding, y[15:18] = False, self.cap(k) * s

    def begin(self, y) -> None:
        """The phase at first touch: sticking if A is inside the cap, else as :meth:`on_cap` along A
        (or the slip). A displacement history on a^q with a dashpot a^s, s < q, whose first trial
        force is beyond the cap slides along the slip from the start (the wall oracle's
        ``first_phase``, :attr:`.wall_law.Law.first_touch_runaway`)."""
        k = self.kinematics(y)  # F_n's side: at first touch (to rounding) the side it moves to
        self.f_side = np.sign(k["f_n"] if abs(k["f_n"]) > self.f_rounding else k["df_n"]) or 1.0
        trial = y[15:18]
        if np.linalg.norm(trial) < self.cap(k) - MARGIN * self.force_scale:
            self.sliding = False
            return
        s = _unit(trial)
        self.on_cap(y, s if s is not None else self.rate_direction(k))
        if self.runaway and not self.sliding and s is not None:
            self.sliding, y[15:18] = True, -s

    def switch(self, y, which: str) -> None:
        """The phase after the event ``which``: a stick that reached the cap slides along A, a slide
        whose cap outgrew it sticks on the cap (deciding again from y could undo the switch, the
        event's root found only to ~1e-15 s); at F_n's zero the cap restarts from zero on the side F_n
        moves to, whatever the sign of the residue the root leaves."""
        k = self.kinematics(y)
        if which == "deepest":
            self.unloading = True
        elif which == "stick_ends" and self._vanishing(k):
            self.coasting, y[15:18] = True, 0.0  # a stick meeting a cap already vanishing: nothing left to slide
        elif which == "stick_ends":
            self.sliding, y[15:18] = True, y[15:18] / np.linalg.norm(y[15:18])
        elif which == "slide_ends":
            self.sliding, y[15:18] = False, self.cap(k) * self.direction(k, y)
        elif which == "cap_gone":  # no tangential force to speak of until the cap is back (the wall's coast)
            self.sliding, self.coasting, y[15:18] = False, True, 0.0
        elif which == "cap_back":
            self.coasting = False
            self.on_cap(y, self.rate_direction(k))
        else:  # normal_force: A is on or inside a cap of zero, and leaves it the way sticking pushes it
            self.f_side, self.coasting = np.sign(k["df_n"]) or -self.f_side, False
            self.on_cap(y, self.rate_direction(k))

    def _vanishing(self, k: dict) -> bool:
        """Whether the cap is below a switch's margin and falling, where a slide would coast at once."""
        return self.COASTS and self.cap(k) < MARGIN * self.force_scale and self.cap_rate(k) <= 0.0

    def rate_direction(self, k: dict) -> np.ndarray | None:
        """Where sticking pushes a trial force of zero (the cap's zero, first touch): the unit A'
        at A = 0, else the slip's (None if neither has one). A slide's s would turn there at an
        infinite rate (s' ~ 1/c), whatever it was before."""
        rate = _unit(self.stick_rate(k, np.zeros(3)))
        return rate if rate is not None else _unit(k["slip"])

    def events(self) -> list:
        """End of contact, the phase's own end (second: :func:`.pair_capped._first_event` samples it inside each
        step), a slide's vanishing cap, (with damping) the normal force's zero and (with a rescale) the deepest
        point; each stops the integration, which restarts there."""
        if self.coasting:
            out = [_event(self.separated, 1.0), _event(self.cap_back, 1.0)]
        else:
            out = [_event(self.separated, 1.0), _event(self.slide_ends, -1.0) if self.sliding
                   else _event(self.stick_ends, 1.0)]
        if self.sliding and self.COASTS:
            out.append(_event(self.cap_gone, -1.0))
        if self.p["gamma_n"] > 0.0:
            out.append(_event(self.normal_force, -1.0))
        if self.p["rescale"] and not self.unloading:
            out.append(_event(self.deepest, -1.0))
        return out


class ClassicContact(Contact):
    """``linear_history_classic``'s cap, its history reset by k alone (:mod:`.oracle_classic`, the wall's): the
    next trial force A+ = f c s + (1 - f) gamma_t a^s u', f = a^q; a slide is along the slip while
    gamma_t a^s |u'| >= c. ``zeno``: a tooth shorter than ZENO tau (teeth from zero size, :func:`.solve`);
    ``cut`` scales the slide's hold and the cap's margin."""

    COASTS = False

    def __init__(self, p: dict, n0: np.ndarray, planar: bool, cut: float):
        super().__init__(p, n0, planar)
        self.cut, self.zeno, self.now, self.last_cap = cut, False, 0.0, -np.inf

    def direction(self, k: dict, y) -> np.ndarray:
        return np.array(kernel.classic_direction(k["raw"], y))

    def rates(self, t, y):
        if not self.sliding:
            return super().rates(t, y)
        self._counted()
        out = np.empty(19)
        kernel.classic_slide_rates(y, self.P, self.n0, self.planar, self.f_side, out)
        return out

    def stick_ends(self, _t, y) -> float:
        return kernel.stick_end(y, self.P, self.n0, self.planar, self.f_side, self.cut * MARGIN * self.force_scale)

    def slide_ends(self, _t, y) -> float:
        """> 0 while the dashpot's force alone exceeds the cap, held on a little (the wall's slide_margin)."""
        return kernel.classic_slide_end(y, self.P, self.n0, self.planar, self.f_side, MARGIN * self.force_scale,
                                        NEAR_ONE, self.cut)

    def _reset(self, k: dict, s: np.ndarray | None) -> np.ndarray:
        f = k["spring"] / self.p["kt"] if self.p["kt"] else 0.0
        return reset(f, self.cap(k), np.zeros(3) if s is None else s, k["dashpot"] * k["slip"])

    def on_cap(self, y, s: np.ndarray | None) -> None:
        """The capped step's reset along s (the trial force's unit): stick from A+, or slide along the slip."""
        k = self.kinematics(y)
        after = self._reset(k, s)
        self.sliding = slides(after, self.cap(k), k["dashpot"] * k["slip"])
        y[15:18] = k["slip"] / np.linalg.norm(k["slip"]) if self.sliding else after

    def switch(self, y, which: str) -> None:
        if which in ("stick_ends", "slide_ends"):
            note_cap(self, which == "stick_ends")
        if which == "stick_ends":
            self.on_cap(y, _unit(y[15:18]))
        elif which == "slide_ends":  # the reset along the slip, then a stick from inside the cap
            k = self.kinematics(y)
            self.sliding, y[15:18] = False, self._reset(k, self.direction(k, y))
        else:
            super().switch(y, which)


def _event(function, direction: float):
    def event(t, y):
        return function(t, y)

    event.terminal, event.direction, event.__name__ = True, direction, function.__name__
    return event
