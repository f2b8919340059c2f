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
"""

from __future__ import annotations

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from . import pair as pair_theory

from .pair_exact import RTOL, PairOutcome, outcome, start

__all__ = ["solve", "plane_normal", "MAX_PHASES"]

#: More phases than this in one contact is chattering, not a contact (the measured cases take < 10).
MAX_PHASES = 200
#: Points inside each integrator step where a phase's switching function is also sampled.
INTERIOR_SAMPLES = 8
#: A switch must be passed by this fraction of the cap's scale (as in the wall's oracle).
MARGIN = 1e-12


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
        f_n = p["kn"] * (radsum - dist) - p["gamma_n"] * v_n
        across = 0.0 if self.planar else float((v - v_n * n) @ (v - v_n * n)) / dist
        df_n = -p["kn"] * v_n - p["gamma_n"] * (f_n / self.m_star + across)
        return {"n": n, "t": t, "v": v, "slip": slip, "f_n": f_n, "df_n": df_n, "dist": dist, "levers": levers,
                "xi": y[15]}

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
        f_t = -(p["kt"] * k["xi"] if self.phase == 0 else self.phase * self.cap(k))
        force = k["f_n"] * k["n"] + f_t * k["t"]
        arm = -np.cross(k["n"], f_t * k["t"])
        return np.concatenate([k["v"], force / p["m_a"], -force / p["m_b"], k["levers"][0] * arm / p["i_a"],
                               k["levers"][1] * arm / p["i_b"], [k["slip"] if self.phase == 0 else 0.0]])

    def stick_ends(self, _t, y) -> float:
        k = self.kinematics(y)
        return self.p["kt"] * abs(k["xi"]) - self.cap(k) - MARGIN * self.force_scale

    def slide_ends(self, _t, y) -> float:
        k = self.kinematics(y)
        return self.phase * self.p["kt"] * k["slip"] - self.cap_rate(k) + MARGIN * self.force_scale / self.tau

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
            self.phase = int(np.sign(k["xi"]) or np.sign(k["slip"])) if self.phase == 0 else 0
        else:
            self.phase = self.phase_at(y)

    def separated(self, _t, y) -> float:
        return self.kinematics(y)["dist"] - (self.p["r_a"] + self.p["r_b"])

    def phase_at(self, y) -> int:
        """The phase that holds from state y: a slide (the history's way, or the slip's where the
        history is 0) while the sticking rate outruns the cap, else sticking."""
        k = self.kinematics(y)
        if self.p["kt"] * abs(k["xi"]) < self.cap(k) - MARGIN * self.force_scale:
            return 0
        sign = np.sign(k["xi"]) or self.phase or np.sign(k["slip"])
        return int(sign) if sign * self.p["kt"] * k["slip"] > self.cap_rate(k) else 0


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
          planar=False, rtol=RTOL) -> PairOutcome:
    """One capped pair from first touch until it separates (arguments as :func:`.pair_exact.solve`)."""
    if gamma_t != 0.0:
        raise ValueError("the capped pair reference has no tangential damping (gamma_t must be 0)")
    e = plane_normal(n, v_a, v_b, w_a, w_b)
    if e is None:
        raise ValueError("the capped pair reference needs planar motion: the line of centres and both "
                         "velocities in one plane, both spins along its normal")
    n0, p, y, v_rel, tau, longest, atol = start(n, v_a, v_b, w_a, w_b, m_a, r_a, alpha_a, m_b, r_b, alpha_b,
                                                kn, kt, planar, rtol, mu=mu, gamma_n=gamma_n)
    contact = _Contact(p, e, n0, planar)
    contact.tau = tau
    contact.f_rounding = 16.0 * kn * np.spacing(r_a + r_b)
    contact.force_scale = mu * abs(v_rel @ n0) * np.sqrt(contact.m_star * kn)
    y = np.append(y, 0.0)
    atol = np.append(np.full(15, atol), rtol * contact.force_scale / kt)
    damped_time = float(pair_theory.contact_time(m_a, m_b, kn, gamma_n))  # the window: 20 contact times
    window = 20.0 * (max(contact.tau, damped_time) if np.isfinite(damped_time) else contact.tau)
    contact.restart(y)
    t = 0.0
    for _ in range(MAX_PHASES):
        events = _events(contact)
        solution = solve_ivp(contact.rates, (t, t + window), y, method="DOP853", rtol=rtol, atol=atol,
                             events=events, max_step=longest, dense_output=True)
        t, which, y = _first_event(solution, events)
        if which == 0:
            return outcome(y, n0, t)
        if contact.phase != 0:  # leaving a slide (or passing F_n = 0 in one): the history sits on the cap
            y[15] = contact.phase * p["mu"] * abs(contact.kinematics(y)["f_n"]) / kt
        contact.restart(y, switched=which == 1, normal_zero=which == 2)
    raise RuntimeError(f"the capped pair switched phase more than {MAX_PHASES} times (chattering)")
