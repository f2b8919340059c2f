"""What LAMMPS integrates for two free spheres with a Coulomb cap, in planar motion: the capped reference.

``pair_style granular hooke KN ETA_N damping velocity tangential linear_history KT 0 MU`` with a
finite MU. It differs from the uncapped model of :mod:`.pair_exact` in two ways, both read
in LAMMPS's linear_history sub-model:

* every step whose |xi.n| kt exceeds 1e-10 mu |F_n| (every step once the line of centres
  turns) projects the history xi back into the tangent plane and restores its length: in
  continuous time xi turns with n and keeps no normal component;
* |F_t| <= mu |F_n| with F_n the total normal force, damping included (LAMMPS's Fncrit):
  on the cap the history is rescaled so that kt |xi| = mu |F_n|.

Solved here for motion in one plane (the line of centres, both velocities in the plane,
both spins along its normal e), where the slip and the history lie along the in-plane
tangent t = e x n and the history is a number: xi' = u'.t while sticking. The contact
sticks while kt |xi| < mu |F_n|, slides while the sticking rate would carry the force past
the cap (sigma kt u'.t > d(mu |F_n|)/dt, sigma the slide's sign), and each switch, the
normal force's zero (the cap's kink, with gamma_n > 0) and the end of contact are events
of scipy's DOP853 at rtol 1e-12, restarted at each: the outcome is accurate to ~1e-10 of
the speeds. Without tangential damping (gamma_t = 0) only. ``planar=True`` freezes n and
the lever arms: the wall's capped problem of the equivalent sphere (:mod:`.pair`), which
the wall's exact solver must then reproduce (tests/test_pairs_capped.py).

Any law of :data:`.pair_exact.HOOKE` (a force K delta^p, a spring k a^q on a displacement or a
force history, rescaled or not, dashpots a^s): the sticking state is the elastic force E (F_t = -E
along t), E' = k a^q u'.t + R E with R = a'/a (q for a displacement history, once more while a
shrinks with a rescale), pinned to the cap in a slide; such a law starts FIRST_TOUCH contact times
after first touch and ends LAST_OVERLAP of its depth before the overlap does (the wall's oracle
does the same; tests/test_pairs_nonlinear.py holds it to the wall's references).
"""

from __future__ import annotations

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from . import pair as pair_theory

from .pair_exact import RTOL, PairOutcome, outcome, start
from .pair_exact import undamped_depth as pair_depth
from .wall_law import on_contact_radius

__all__ = ["solve", "plane_normal", "MAX_PHASES"]

#: More phases than this in one contact is chattering, not a contact (the measured cases take < 10).
MAX_PHASES = 200
#: Points inside each integrator step where a phase's switching function is also sampled.
INTERIOR_SAMPLES = 8
#: A switch must be passed by this fraction of the cap's scale (as in the wall's oracle).
MARGIN = 1e-12
#: A law on the contact radius starts this many contact times after first touch and ends where the
#: overlap is back to LAST_OVERLAP of its undamped depth (the wall's oracle does the same).
FIRST_TOUCH = 1e-12
LAST_OVERLAP = 1e-10


def plane_normal(n, v_a, v_b, w_a, w_b) -> np.ndarray | None:
    """The unit normal e of the plane the motion keeps to, or None when it does not keep to one.

    The line of centres and both velocities must lie in one plane, and both spins along its
    normal, to 1e-12 of their sizes; a head-on pair without spin has any such plane."""
    n = np.asarray(n, dtype=float) / np.linalg.norm(n)
    candidates = [np.cross(n, v) for v in (v_a, v_b)] + [np.asarray(w, dtype=float) for w in (w_a, w_b)]
    e = max(candidates, key=np.linalg.norm)
    if np.linalg.norm(e) == 0.0:
        helper = np.eye(3)[int(np.argmin(np.abs(n)))]
        return np.cross(n, helper) / np.linalg.norm(np.cross(n, helper))
    e = e / np.linalg.norm(e)
    in_plane = [abs(np.dot(e, x)) <= 1e-12 * max(np.linalg.norm(x), 1e-300) for x in (n, v_a, v_b)]
    along = [np.linalg.norm(np.cross(e, w)) <= 1e-12 * max(np.linalg.norm(w), 1e-300) for w in (w_a, w_b)]
    return e if all(in_plane) and all(along) else None


class _Contact:
    """The pair's equations in one phase: 0 sticking, +1 or -1 sliding that way."""

    def __init__(self, p: dict, e: np.ndarray, n0: np.ndarray, planar: bool):
        self.p, self.e, self.n0, self.planar = p, e, n0, planar
        self.m_star = p["m_a"] * p["m_b"] / (p["m_a"] + p["m_b"])
        self.phase, self.f_side = 0, 1.0

    def kinematics(self, y) -> dict:
        p = self.p
        d, v_a, v_b, w_a, w_b = y[:15].reshape(5, 3)
        radsum = p["r_a"] + p["r_b"]
        if self.planar:
            n, dist = self.n0, d @ self.n0
            levers = (p["r_a"], p["r_b"])
        else:
            dist = np.sqrt(d @ d)
            n = d / dist
            levers = (p["r_a"] - 0.5 * (radsum - dist), p["r_b"] - 0.5 * (radsum - dist))
        v = v_a - v_b
        v_n = v @ n
        t = np.cross(self.e, n)
        slip = (v - v_n * n - np.cross(p["r_a"] * w_a + p["r_b"] * w_b, n)) @ t
        delta, rate = radsum - dist, -v_n  # the overlap and its rate
        depth = abs(delta) ** (p["power"] - 1.0) if p["power"] != 1.0 else 1.0
        damp, shrink = self.radius_power(delta, p["damping_power"]), (rate / (2.0 * delta) if delta else 0.0)
        f_n = p["K"] * depth * delta + p["gamma_n"] * damp * rate
        across = 0.0 if self.planar else float((v - v_n * n) @ (v - v_n * n)) / dist
        accel = -(f_n / self.m_star + across)  # delta''
        df_n = (p["K"] * p["power"] * depth * rate
                + p["gamma_n"] * damp * (accel + (p["damping_power"] * shrink * rate if p["damping_power"] else 0.0)))
        # the sticking elastic force E (F_t = -E): E' = k a^q u' + R E, R = a'/a (q for a displacement
        # history, and once more while a shrinks with a rescale)
        spring = p["kt"] * self.radius_power(delta, p["spring_power"])
        scale = (0.0 if p["force_history"] else p["spring_power"]) + (1.0 if p["rescale"] and rate < 0.0 else 0.0)
        return {"n": n, "t": t, "v": v, "slip": slip, "f_n": f_n, "df_n": df_n, "dist": dist, "levers": levers,
                "elastic": y[15], "spring": spring, "growth": scale * shrink}

    def radius_power(self, delta: float, s: float) -> float:
        """a^s of the contact radius a = sqrt(R_eff |delta|) (1 for s = 0)."""
        return 1.0 if s == 0.0 else (self.p["r_eff"] * abs(delta)) ** (s / 2.0)

    def stick_rate(self, k: dict, elastic: float) -> float:
        """E' while sticking with the elastic force ``elastic``."""
        return k["spring"] * k["slip"] + k["growth"] * elastic

    def cap(self, k: dict) -> float:
        """mu |F_n|, with |F_n| taken as F_n on the phase's side (``f_side``): a phase ends where F_n
        changes sign, and beyond the end of contact the cap keeps falling below zero instead of
        growing back, so that no switch is crossed twice within one step of the integrator."""
        return self.p["mu"] * self.f_side * k["f_n"]

    def cap_rate(self, k: dict) -> float:
        """d(mu |F_n|)/dt on the phase's side."""
        return self.p["mu"] * self.f_side * k["df_n"]

    def rates(self, _t, y):
        p, k = self.p, self.kinematics(y)
        f_t = -(k["elastic"] if self.phase == 0 else self.phase * self.cap(k))
        force = k["f_n"] * k["n"] + f_t * k["t"]
        arm = -np.cross(k["n"], f_t * k["t"])
        return np.concatenate([k["v"], force / p["m_a"], -force / p["m_b"], k["levers"][0] * arm / p["i_a"],
                               k["levers"][1] * arm / p["i_b"],
                               [self.stick_rate(k, k["elastic"]) if self.phase == 0 else 0.0]])

    def stick_ends(self, _t, y) -> float:
        k = self.kinematics(y)
        return abs(k["elastic"]) - self.cap(k) - MARGIN * self.force_scale

    def slide_ends(self, _t, y) -> float:
        k = self.kinematics(y)
        return (self.phase * self.stick_rate(k, self.phase * self.cap(k)) - self.cap_rate(k)
                + MARGIN * self.force_scale / self.tau)

    def normal_force(self, _t, y) -> float:
        """F_n on the side it started the phase on: falls through 0 when F_n changes sign."""
        return self.f_side * self.kinematics(y)["f_n"]

    def restart(self, y, switched: bool = False, normal_zero: bool = False) -> None:
        """Enter the next phase from state y: the other one after a switch (a stick that reached
        the cap slides the history's way, a slide whose cap outgrew it sticks; deciding again
        from y could undo the switch, as the event's root is found only to ~1e-15 s), or the
        one that holds at first touch or after F_n's zero (``normal_zero``: F_n is then on the
        side it moves to, whatever the sign of the residue the root leaves)."""
        k = self.kinematics(y)
        # the sign of F_n; at F_n = 0 (to rounding, or its zero's event), the sign it moves to
        at_zero = normal_zero or not abs(k["f_n"]) > self.f_rounding
        self.f_side = np.sign(k["df_n"]) if at_zero else np.sign(k["f_n"])
        if switched:
            self.phase = int(np.sign(k["elastic"]) or np.sign(k["slip"])) if self.phase == 0 else 0
        else:
            self.phase = self.phase_at(y)

    def separated(self, _t, y) -> float:
        return self.kinematics(y)["dist"] - (self.p["r_a"] + self.p["r_b"]) + self.last

    def phase_at(self, y) -> int:
        """The phase that holds from state y: a slide (the history's way, or the slip's where the
        history is 0) while the sticking rate outruns the cap, else sticking."""
        k = self.kinematics(y)
        if abs(k["elastic"]) < self.cap(k) - MARGIN * self.force_scale:
            return 0
        sign = np.sign(k["elastic"]) or self.phase or np.sign(k["slip"])
        return int(sign) if sign * self.stick_rate(k, sign * self.cap(k)) > self.cap_rate(k) else 0


def _event(function, direction: float):
    def event(t, y):
        return function(t, y)

    event.terminal, event.direction = True, direction
    return event


def _events(contact: _Contact) -> list:
    """End of contact, the phase's own end, and (with damping) the normal force's zero; all stop
    the integration, which restarts there."""
    events = [_event(contact.separated, 1.0),
              _event(contact.stick_ends, 1.0) if contact.phase == 0 else _event(contact.slide_ends, -1.0)]
    if contact.p["gamma_n"] > 0.0:
        events.append(_event(contact.normal_force, -1.0))
    return events


def _first_event(solution, events) -> tuple[float, int, np.ndarray]:
    """The first event of a segment: (time, which, state). The integrator sees a switch only
    as a sign change between its steps; the phase's own switching function (``events[1]``) is
    also sampled at :data:`INTERIOR_SAMPLES` points inside each step, so that a stick or a slide
    shorter than a step is not stepped over."""
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


def solve(n, v_a, v_b, w_a, w_b, m_a, r_a, alpha_a, m_b, r_b, alpha_b, kn, kt, mu, gamma_n=0.0, gamma_t=0.0,
          planar=False, rtol=RTOL, **law) -> PairOutcome:
    """One capped pair from first touch until it separates (arguments as :func:`.pair_exact.solve`,
    ``law`` its keys of :data:`.pair_exact.HOOKE`)."""
    if gamma_t != 0.0:
        raise ValueError("the capped pair reference has no tangential damping (gamma_t must be 0)")
    e = plane_normal(n, v_a, v_b, w_a, w_b)
    if e is None:
        raise ValueError("the capped pair reference needs planar motion: the line of centres and both "
                         "velocities in one plane, both spins along its normal")
    n0, p, y, v_rel, tau, longest, atol = start(n, v_a, v_b, w_a, w_b, m_a, r_a, alpha_a, m_b, r_b, alpha_b,
                                                kn, kt, planar, rtol, mu=mu, gamma_n=gamma_n, **law)
    contact = _Contact(p, e, n0, planar)
    contact.tau = tau
    radial = on_contact_radius(p["power"], p["spring_power"], p["damping_power"])
    m_star, speed = contact.m_star, abs(v_rel @ n0)
    depth = pair_depth(p, v_rel, n0, m_star)
    stiffness = p["K"] * p["power"] * depth ** (p["power"] - 1.0)  # kn for the Hookean force
    contact.f_rounding = 16.0 * stiffness * np.spacing(r_a + r_b)
    contact.force_scale = mu * speed * np.sqrt(m_star * stiffness)
    # a law on the contact radius starts a hair after first touch (the elastic force grown as u' t,
    # over 1 + q/2 for a force history) and ends a hair before the overlap does, where a's rates
    # are infinite (what the ends would do, ~ (1e-10)^(1 + s/2) of the speed, is left)
    contact.last = LAST_OVERLAP * depth if radial else 0.0
    t = FIRST_TOUCH * tau if radial else 0.0
    y = np.append(y, 0.0)
    if t:
        y[:3] += v_rel * t
        k0 = contact.kinematics(y)
        y[15] = k0["spring"] * k0["slip"] * t / (1.0 + p["spring_power"] / 2.0 if p["force_history"] else 1.0)
    atol = np.append(np.full(15, atol), rtol * contact.force_scale)
    damped_time = float(pair_theory.contact_time(m_a, m_b, kn, gamma_n)) if not radial else tau
    window = 20.0 * (max(contact.tau, damped_time) if np.isfinite(damped_time) else contact.tau)
    contact.restart(y)
    for _ in range(MAX_PHASES):
        events = _events(contact)
        solution = solve_ivp(contact.rates, (t, t + window), y, method="DOP853", rtol=rtol, atol=atol,
                             events=events, max_step=longest, dense_output=True)
        t, which, y = _first_event(solution, events)
        if which == 0:
            if contact.last:  # the spheres part freely from the cut to the end of the overlap
                k = contact.kinematics(y)
                t += contact.last / max(abs(k["v"] @ k["n"]), 1e-300)
            return outcome(y, n0, t)
        if contact.phase != 0:  # leaving a slide (or passing F_n = 0 in one): the elastic force on the cap
            y[15] = contact.phase * p["mu"] * abs(contact.kinematics(y)["f_n"])
        contact.restart(y, switched=which == 1, normal_zero=which == 2)
    raise RuntimeError(f"the capped pair switched phase more than {MAX_PHASES} times (chattering)")
