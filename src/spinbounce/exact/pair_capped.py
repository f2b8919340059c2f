"""What LAMMPS integrates for two free spheres with a Coulomb cap, in 3-D: the capped reference.

``pair_style granular <normal> ... damping <model> tangential <law> KT X_T MU`` with a finite MU.
It differs from the uncapped model of :mod:`.pair_exact` in two ways, both read in LAMMPS's
tangential sub-models (``linear_history`` and the Mindlin variants):

* every step whose |h.n| k exceeds 1e-10 mu |F_n| (every step once the line of centres turns)
  projects the history h back into the tangent plane and restores its length: in continuous
  time h turns with n, h' gaining -(h.n') n, and keeps no normal component;
* |F_t| <= mu |F_n| with F_n the total normal force, damping included (LAMMPS's Fncrit): on the
  cap the history is reset so that the trial force has length mu |F_n|.

The state beyond the spheres' is the trial force A = E + gamma_t a^s u' (F_t = -A on a while
sticking), E the history's elastic force (k a^q h for a displacement history, the history itself
for a force history) and u' the slip rate. Sticking (|A| < mu |F_n|):

    A' = k a^q u' + R E - (E.n') n + (gamma_t a^s u')',

R = a'/a times q for a displacement history, once more while a shrinks with a rescale. Sliding,
A = c s rides the cap c = mu |F_n| and its direction s turns towards the sticking rate:
s' = -(s.n') n + ((n x s).A'_stick) (n x s)/c, with A'_stick the rate above at A = c s. A slide
lasts while sticking would carry A beyond the cap (s.A'_stick > c'); each switch, the normal
force's zero (the cap's kink, with gamma_n > 0), a rescale's deepest point and the end of contact
are events of scipy's DOP853 at rtol 1e-12, restarted at each: the outcome is accurate to ~1e-10
of the speeds. ``planar=True`` freezes n and the lever arms: the wall's capped problem of the
equivalent sphere (:mod:`.pair`), which the wall's references must then reproduce
(tests/test_pairs_capped.py, tests/test_pairs_nonlinear.py).

A law on the contact radius (a force K delta^p, a spring k a^q, dashpots a^s: the keys of
:data:`.pair_exact.HOOKE`) starts FIRST_TOUCH contact times after first touch and ends
LAST_OVERLAP of its depth before the overlap does, where a's rates are infinite (the wall's
oracle does the same).
"""

from __future__ import annotations

import numpy as np

from . import pair_exact
from .pair_exact import (
    RTOL,
    PairOutcome,
    contact_radius_power,
    cross,
    free_flight,
    geometry,
    normal_force,
    outcome,
    start,
)
from .pair_exact import undamped_depth as pair_depth
from .wall_law import on_contact_radius

__all__ = ["solve", "MAX_PHASES"]

#: More phases than this in one contact is chattering, not a contact (the measured cases take < 10).
MAX_PHASES = 200
#: Points inside each integrator step where a phase's switching function is also sampled.
INTERIOR_SAMPLES = 8
#: A switch must be passed by this fraction of the cap's scale (as in the wall's oracle).
MARGIN = 1e-12
#: Below this fraction of the cap's scale a slide turns s no faster than at it (the wall's oracle's
#: TURN_FLOOR): near the cap's zeros s' ~ 1/c would grow without bound; the slower turn only bends
#: a force that small.
TURN_FLOOR = 1e-8
#: A law on the contact radius starts this many contact times after first touch and ends where the
#: overlap is back to LAST_OVERLAP of its undamped depth (the wall's oracle does the same).
FIRST_TOUCH = 1e-12
LAST_OVERLAP = 1e-10


def _unit(x: np.ndarray) -> np.ndarray | None:
    size = np.linalg.norm(x)
    return x / size if size > 0.0 else None


class _Contact:
    """The pair's equations in one phase (``sliding`` or not); y[15:18] is A sticking, s sliding, and
    y[18] the overlap delta, a state of its own (delta' = -v.n): from the centres' distance, rounding
    would blur it by ~1e-16 (r_a + r_b), more than a law on the contact radius starts with."""

    def __init__(self, p: dict, n0: np.ndarray, planar: bool):
        self.p, self.n0, self.planar = p, n0, planar
        self.m_star = p["m_a"] * p["m_b"] / (p["m_a"] + p["m_b"])
        self.sliding, self.f_side = False, 1.0

    def kinematics(self, y) -> dict:
        p = self.p
        _, v_a, v_b, w_a, w_b = y[:15].reshape(5, 3)
        n, delta, levers, dist = geometry(y, self.n0, p, self.planar, overlap=y[18])
        v = v_a - v_b
        v_n = v @ n
        v_t = v - v_n * n
        turn = np.zeros(3) if self.planar else v_t / dist  # n'
        spin = p["r_a"] * w_a + p["r_b"] * w_b
        rate = -v_n  # the overlap's rate
        depth = abs(delta) ** (p["power"] - 1.0) if p["power"] != 1.0 else 1.0
        damp, shrink = contact_radius_power(p, delta, p["damping_power"]), (rate / (2.0 * delta) if delta else 0.0)
        f_n = normal_force(p, delta, v_n)
        accel = -(f_n / self.m_star + v_t @ turn)  # delta''
        df_n = p["K"] * p["power"] * depth * rate + p["gamma_n"] * damp * (accel + p["damping_power"] * shrink * rate)
        scale = (0.0 if p["force_history"] else p["spring_power"]) + (1.0 if p["rescale"] and rate < 0.0 else 0.0)
        return {"n": n, "turn": turn, "v": v, "v_n": v_n, "spin": spin, "slip": v_t - cross(spin, n),
                "f_n": f_n, "df_n": df_n, "levers": levers,
                "spring": p["kt"] * contact_radius_power(p, delta, p["spring_power"]), "growth": scale * shrink,
                "dashpot": p["gamma_t"] * damp, "dashpot_rate": p["gamma_t"] * p["damping_power"] * shrink * damp}

    def accelerations(self, k: dict, f_t: np.ndarray) -> tuple:
        """(v_a', v_b', w_a', w_b') under the normal force and the friction ``f_t`` on a."""
        p = self.p
        force = k["f_n"] * k["n"] + f_t
        arm = -cross(k["n"], f_t)
        return (force / p["m_a"], -force / p["m_b"], k["levers"][0] * arm / p["i_a"],
                k["levers"][1] * arm / p["i_b"])

    def stick_rate(self, k: dict, trial: np.ndarray) -> np.ndarray:
        """A' while sticking with the trial force ``trial`` (the friction -trial)."""
        p, n, turn = self.p, k["n"], k["turn"]
        dv_a, dv_b, dw_a, dw_b = self.accelerations(k, -trial)
        dv = dv_a - dv_b
        dspin = p["r_a"] * dw_a + p["r_b"] * dw_b
        slip_rate = (dv - (dv @ n) * n - (turn @ k["v"]) * n - k["v_n"] * turn  # u''
                     - cross(dspin, n) - cross(k["spin"], turn))
        elastic = trial - k["dashpot"] * k["slip"]
        return (k["spring"] * k["slip"] + k["growth"] * elastic - (elastic @ turn) * n
                + k["dashpot_rate"] * k["slip"] + k["dashpot"] * slip_rate)

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
        s = y[15:18] - (y[15:18] @ k["n"]) * k["n"]
        return s / np.linalg.norm(s)

    def rates(self, _t, y):
        k = self.kinematics(y)
        if self.sliding:
            s = self.direction(k, y)
            c = self.cap(k)
            across = cross(k["n"], s)
            tail = (-(s @ k["turn"]) * k["n"]
                    + (across @ self.stick_rate(k, c * s)) * across / np.hypot(c, self.turn_floor))
            trial = c * s
        else:
            trial = y[15:18]
            tail = self.stick_rate(k, trial)
        return np.concatenate([k["v"], *self.accelerations(k, -trial), tail, [-k["v_n"]]])

    def stick_ends(self, _t, y) -> float:
        k = self.kinematics(y)
        return np.linalg.norm(y[15:18]) - self.cap(k) - MARGIN * self.force_scale

    def push(self, k: dict, s: np.ndarray) -> float:
        """How fast sticking would carry A outwards along s with A = c s on the cap, less the cap's rate."""
        return s @ self.stick_rate(k, self.cap(k) * s) - self.cap_rate(k)

    def slide_ends(self, _t, y) -> float:
        k = self.kinematics(y)
        return self.push(k, self.direction(k, y)) + MARGIN * self.force_scale / self.tau

    def normal_force(self, _t, y) -> float:
        """F_n on the side it started the phase on: falls through 0 when F_n changes sign."""
        return self.f_side * self.kinematics(y)["f_n"]

    def deepest(self, _t, y) -> float:
        """The overlap's rate: a rescale starts where it falls through 0 (a kink in A')."""
        return -self.kinematics(y)["v_n"]

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
        elif which == "stick_ends":
            self.sliding, y[15:18] = True, y[15:18] / np.linalg.norm(y[15:18])
        elif which == "slide_ends":
            self.sliding, y[15:18] = False, self.cap(k) * self.direction(k, y)
        else:  # normal_force: A is on or inside a cap of zero, and leaves it the way sticking pushes it
            self.f_side = np.sign(k["df_n"]) or -self.f_side
            self.on_cap(y, self.rate_direction(k))

    def rate_direction(self, k: dict) -> np.ndarray | None:
        """Where sticking pushes a trial force of zero (the cap's zero, first touch): the unit A'
        at A = 0, else the slip's (None if neither has one). A slide's s would turn there at an
        infinite rate (s' ~ 1/c), whatever it was before."""
        rate = _unit(self.stick_rate(k, np.zeros(3)))
        return rate if rate is not None else _unit(k["slip"])

    def events(self) -> list:
        """End of contact, the phase's own end, and (with damping) the normal force's zero, (with a
        rescale) the deepest point; each stops the integration, which restarts there."""
        out = [_event(self.separated, 1.0), _event(self.slide_ends, -1.0) if self.sliding
               else _event(self.stick_ends, 1.0)]
        if self.p["gamma_n"] > 0.0:
            out.append(_event(self.normal_force, -1.0))
        if self.p["rescale"] and not self.unloading:
            out.append(_event(self.deepest, -1.0))
        return out


def _event(function, direction: float):
    def event(t, y):
        return function(t, y)

    event.terminal, event.direction, event.__name__ = True, direction, function.__name__
    return event


def _first_event(solution, events) -> tuple[float, int, np.ndarray]:
    """The first event of a segment: (time, which, state). The integrator sees a switch only
    as a sign change between its steps; the phase's own switching function (``events[1]``) is
    also sampled at :data:`INTERIOR_SAMPLES` points inside each step, so that a stick or a slide
    shorter than a step is not stepped over."""
    from scipy.optimize import (
        brentq,  # here, as solve_ivp in solve: what a compiled batch never needs
    )

    fired = [(ts[0], k) for k, ts in enumerate(solution.t_events) if len(ts)]
    if not fired:
        raise RuntimeError(f"the capped pair did not separate within its window: {solution.message}")
    t_end, which = min(fired)
    switch, dense = events[1], solution.sol
    g = lambda time: switch(time, dense(time))  # noqa: E731
    for t0, t1 in zip(dense.ts[:-1], dense.ts[1:]):
        if t0 >= t_end:
            break
        grid = np.linspace(t0, min(t1, t_end), INTERIOR_SAMPLES + 2)
        values = [g(time) for time in grid]
        for k in range(len(grid) - 1):
            if switch.direction * values[k] < 0.0 <= switch.direction * values[k + 1] and grid[k + 1] < t_end:
                root = brentq(g, grid[k], grid[k + 1], xtol=4.0 * np.finfo(float).eps * max(1.0, abs(grid[k])))
                return root, 1, dense(root)
    return t_end, which, solution.y_events[which][0].copy()


def _first_touch(contact: _Contact, y, t: float) -> np.ndarray:
    """The state t after first touch (a law on the contact radius): the centres moved by v t, the
    elastic force grown as k a^q u' t (over 1 + q/2 for a force history), the dashpot's part beside it."""
    p = contact.p
    y[:3] += (y[3:6] - y[6:9]) * t
    y[18] = -((y[3:6] - y[6:9]) @ contact.n0) * t
    k = contact.kinematics(y)
    elastic = k["spring"] * k["slip"] * t / (1.0 + p["spring_power"] / 2.0 if p["force_history"] else 1.0)
    y[15:18] = elastic + k["dashpot"] * k["slip"]
    return y


def solve(n, v_a, v_b, w_a, w_b, m_a, r_a, alpha_a, m_b, r_b, alpha_b, kn, kt, mu, gamma_n=0.0, gamma_t=0.0,
          planar=False, rtol=RTOL, tensile=True, **law) -> PairOutcome:
    """One capped pair from first touch until it separates (arguments as :func:`.pair_exact.solve`,
    ``law`` its keys of :data:`.pair_exact.HOOKE`; ``tensile`` False: LAMMPS's ``limit_damping``, the
    normal force and with it the cap cut at their turn, from which the spheres part force-free). A law
    on the contact radius is integrated at a tenth of ``rtol``, as the wall's oracle does: a stick whose
    first trial force starts just inside the cap (0.97 of it) kept 2e-7 at rtol itself, 1e-8 at a tenth."""
    from scipy.integrate import solve_ivp

    if not mu > 0.0:
        raise ValueError(f"mu = {mu!r}: the capped pair reference needs a cap > 0 (mu = 0 is the uncapped "
                         "reference without a tangential force)")
    if on_contact_radius(law.get("power", 1.0), law.get("spring_power", 0.0), law.get("damping_power", 0.0)):
        rtol = rtol / 10.0
    n0, p, y, v_rel, tau, longest, atol = start(n, v_a, v_b, w_a, w_b, m_a, r_a, alpha_a, m_b, r_b, alpha_b,
                                                kn, kt, planar, rtol, mu=mu, gamma_n=gamma_n, gamma_t=gamma_t, **law)
    contact = _Contact(p, n0, planar)
    contact.tau, contact.unloading = tau, False
    radial = on_contact_radius(p["power"], p["spring_power"], p["damping_power"])
    contact.runaway = not p["force_history"] and p["spring_power"] > p["damping_power"] and gamma_t > 0.0
    m_star, speed = contact.m_star, abs(v_rel @ n0)
    depth = pair_depth(p, v_rel, n0, m_star)
    stiffness = p["K"] * p["power"] * depth ** (p["power"] - 1.0)  # kn for the Hookean force
    contact.f_rounding = 16.0 * stiffness * np.spacing(r_a + r_b)
    contact.force_scale = mu * speed * np.sqrt(m_star * stiffness)
    contact.turn_floor = TURN_FLOOR * contact.force_scale
    # a law on the contact radius starts a hair after first touch and ends a hair before the overlap
    # does, where a's rates are infinite (what the ends would do, ~ (1e-10)^(1 + s/2) of the speed, is left)
    contact.last = LAST_OVERLAP * depth if radial else 0.0
    t = FIRST_TOUCH * tau if radial else 0.0
    y = _first_touch(contact, np.append(y, np.zeros(4)), t)
    # the overlap's tolerance: relative from its first touch on (a law on the contact radius starts at ~1e-12 of it)
    # and a stick's trial force's: of its size at first touch there (~ a, sqrt(FIRST_TOUCH) of the force's scale).
    # Held to the force's scale, a stick on the cap whose trial force and cap grow alike (dashpots of the spring's
    # power) gained 1e-6 of its size in the first steps, unseen by the error estimate, and slid the whole contact
    # (0.43 off the wall's oracle); held to 1e-12 of the scale, a stick near A = 0 took minutes
    stick_atol = rtol * contact.force_scale * (np.sqrt(FIRST_TOUCH) if radial else 1.0)
    atol = np.concatenate([np.full(15, atol), np.full(3, stick_atol), [rtol * 1e-12 * depth]])
    window = float(pair_exact.window(tau, m_a, m_b, kn, gamma_n, radial))
    contact.begin(y)
    for _ in range(MAX_PHASES):
        events = contact.events()
        if contact.sliding:  # s is a unit vector: its tolerance is rtol's
            atol[15:18] = rtol
        else:
            atol[15:18] = stick_atol
        solution = solve_ivp(contact.rates, (t, t + window), y, method="DOP853", rtol=rtol, atol=atol,
                             events=events, max_step=longest, dense_output=True)
        t, which, y = _first_event(solution, events)
        if which == 0:
            if contact.last:  # the spheres part freely from the cut to the end of the overlap
                k = contact.kinematics(y)
                t += contact.last / max(abs(k["v_n"]), 1e-300)
            return outcome(y, t, n0)
        if not tensile and events[which].__name__ == "normal_force":  # limit_damping: no force from here
            return outcome(*free_flight(y, t, n0, planar, y[18]), n0)
        contact.switch(y, events[which].__name__)
    raise RuntimeError(f"the capped pair switched phase more than {MAX_PHASES} times (chattering)")
