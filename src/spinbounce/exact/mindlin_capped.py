"""Exact reference of a Coulomb-capped Mindlin contact against a wall, in the paper's plane.

LAMMPS's Mindlin variants (:mod:`.mindlin`) cap the tangential force at mu F_n: when the
trial force -k a h (or the force history h) exceeds the cap it is scaled back onto it and the
history set to what gives that force (``GranSubModTangentialMindlin::calculate_forces``). In
continuous time the contact sticks (the history evolves by its law, rescaled with a while a
shrinks for the ``_rescale`` variants) and slides (F_t = -sigma mu F_n, the history pinned to
the cap) in turn:

* stick -> slip when |F_t| reaches mu F_n;
* slip -> stick when sticking would move |F_t| inward faster than the cap moves:
  d|F_t|/dt (sticking) < mu dF_n/dt;
* at first touch F_n and a vanish together: against the Hertzian force the trial force and the
  cap both grow as t^(3/2), so the contact starts sliding when k_t |u'(0)| (times 2/3 for a force
  history) exceeds mu kn |v_n| (Mindlin's and Cattaneo's criterion), and sticking otherwise;
  against the Hookean force the cap grows as t and the contact starts sticking.

Near its end the cap falls as delta^p while a sticking force falls as delta at most, so every
contact ends sliding (or with no slip). The normal force is undamped here (a damped Mindlin
contact is refused before any run), and there is no tangential dashpot.

Each collision is integrated with scipy's DOP853 (rtol 1e-12), restarting at every switch
(events) and at the deepest point (where the rescale starts); near the exit in the variable
sqrt(delta) (:func:`bounce`). Planar only: a 3-D slide turns its direction, which this module
does not follow.

Pure numpy and scipy; knows nothing of LAMMPS.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.integrate import solve_ivp

__all__ = ["bounce", "bounce_many", "RTOL"]

RTOL = 1.0e-12
ATOL = 1.0e-15
#: More switches than this in one contact mean the phases chatter: refuse.
MAX_PHASES = 200
# state: overlap, its rate, v_t, r omega, history
_D, _DR, _V, _W, _H = range(5)


class _Contact:
    """One collision's law: the normal force K delta^p and a Mindlin spring capped at mu F_n."""

    def __init__(self, variant, m, r, alpha, K, power, k, mu):
        self.force_history, self.rescale = bool(variant[0]), bool(variant[1])
        self.m, self.r, self.alpha, self.K, self.p, self.k, self.mu = m, r, alpha, K, power, k, mu

    def normal(self, y) -> tuple[float, float]:
        """(F_n, dF_n/dt)."""
        delta = max(y[_D], 0.0)
        return self.K * delta**self.p, self.K * self.p * delta ** (self.p - 1.0) * y[_DR] if delta > 0 else 0.0

    def radius(self, y) -> tuple[float, float]:
        """(a, a'/a) of the contact radius a = sqrt(r delta) (a'/a = delta'/(2 delta))."""
        delta = max(y[_D], 0.0)
        return math.sqrt(self.r * delta), (y[_DR] / (2.0 * delta) if delta > 0 else 0.0)

    def stick_force(self, y) -> float:
        a, _ = self.radius(y)
        return y[_H] if self.force_history else -self.k * a * y[_H]

    def stick_history_rate(self, y) -> float:
        """h' while sticking: u' (or -k a u'), plus h a'/a while a shrinks (``_rescale``)."""
        a, shrink = self.radius(y)
        slip = y[_V] + y[_W]
        rate = -self.k * a * slip if self.force_history else slip
        if self.rescale and y[_DR] < 0.0:
            rate += y[_H] * shrink
        return rate

    def pinned_history(self, y, sigma: float) -> float:
        """The history whose force is -sigma mu F_n (the cap)."""
        if self.force_history:
            return -sigma * self.mu * self.normal(y)[0]
        # mu K delta^p/(k sqrt(r delta)), written so that it vanishes with delta
        return sigma * self.mu * self.K * max(y[_D], 0.0) ** (self.p - 0.5) / (self.k * math.sqrt(self.r))

    def stick_magnitude_rate(self, y, sigma: float) -> float:
        """d|F_t|/dt if the contact stuck now, with F_t = -sigma |F_t|."""
        a, shrink = self.radius(y)
        rate_h = self.stick_history_rate(y)
        if self.force_history:
            return -sigma * rate_h
        return sigma * self.k * (a * shrink * y[_H] + a * rate_h)

    def rhs(self, phase: str, sigma: float, tail: bool):
        """dy/dt; in the tail, dy/d(sqrt(delta)) = dy/dt 2 sqrt(delta)/delta' (see :func:`bounce`)."""
        def f(x, y):
            force_n = self.normal(y)[0]
            force_t = -sigma * self.mu * force_n if phase == "slip" else self.stick_force(y)
            h_rate = self.stick_history_rate(y) if phase == "stick" else 0.0
            rates = np.array([y[_DR], -force_n / self.m, force_t / self.m, force_t / (self.alpha * self.m), h_rate])
            return rates * (2.0 * x / y[_DR]) if tail else rates
        return f

    def events(self, phase: str, sigma: float, leg: str):
        """The switches of ``phase``, and the end of ``leg``: the deepest point (load), x = x1 (unload)."""
        found = []
        if leg == "load":
            def deepest(t, y):
                return y[_DR]

            found.append(deepest)
        elif leg == "unload":
            def tail(t, y):
                return y[_D] - self.tail_overlap

            found.append(tail)
        if phase == "stick":
            def to_slip(t, y):
                return self.mu * self.normal(y)[0] - abs(self.stick_force(y))

            found.append(to_slip)
        else:
            def to_stick(t, y):
                y = np.array(y)
                y[_H] = self.pinned_history(y, sigma)
                return self.stick_magnitude_rate(y, sigma) - self.mu * self.normal(y)[1]

            found.append(to_stick)
        for event in found:
            event.terminal, event.direction = True, -1
        return found

    def first_phase(self, v: float, slip: float) -> str:
        """Stick or slip from first touch, from the t -> 0 limits of the trial force and the cap."""
        if slip == 0.0 or self.p < 1.5:
            return "stick"
        trial = self.k * math.sqrt(self.r * v) * abs(slip) * (2.0 / 3.0 if self.force_history else 1.0)
        return "slip" if trial > self.mu * self.K * v**1.5 else "stick"


#: The tail starts where the overlap is back to this fraction of its largest, and ends where
#: sqrt(delta) is this fraction of its value there: the force left beyond, ~ delta^p, moves the
#: velocities by ~ (1e-6)^(2 p + 2) of the speed (1e-24 at most): below it, rounding can make
#: the cap and a vanishing force chatter.
TAIL_START = 0.5
TAIL_END = 1.0e-6


def bounce(variant, *, m: float, r: float, alpha: float, K: float, power: float, k: float, mu: float,
           v_n: float, v_t: float, r_omega: float) -> tuple[float, float, float]:
    """Final (v_n, v_t, r omega) of one collision starting to touch at (v_n < 0, v_t, r omega).

    Three legs, each restarted at every stick/slip switch: in time from first touch to the
    deepest point and back out to half the deepest overlap; then the tail in the variable
    x = sqrt(delta), down to TAIL_END of its start: near the exit a = sqrt(r delta) has an
    infinite slope in time (and a rescaled history a term h a'/a), which in x are smooth.
    """
    contact = _Contact(variant, m, r, alpha, K, power, k, mu)
    speed = -v_n
    deepest = ((power + 1.0) * m * speed**2 / (2.0 * K)) ** (1.0 / (power + 1.0))
    contact.tail_overlap = TAIL_START * deepest
    y = np.array([0.0, speed, v_t, r_omega, 0.0])
    slip = v_t + r_omega
    phase = contact.first_phase(speed, slip)
    sigma = math.copysign(1.0, slip) if slip else 1.0
    leg, x = "load", 0.0
    span = 10.0 * deepest / speed  # several contact times
    x_tail = math.sqrt(contact.tail_overlap)
    for _ in range(MAX_PHASES):
        tail = leg == "tail"
        end = x_tail * TAIL_END if tail else x + span
        if tail and x == 0.0:
            x = x_tail
        events = contact.events(phase, sigma, leg)
        sol = solve_ivp(contact.rhs(phase, sigma, tail), (x, end), y, method="DOP853", rtol=RTOL, atol=ATOL,
                        events=events, first_step=span * 1e-9 if x == 0.0 else None)
        hit = [j for j, times in enumerate(sol.t_events) if times.size]
        if not hit:
            if not tail or sol.status != 0:
                raise RuntimeError(f"a capped Mindlin contact's {leg} did not end: {sol.message}")
            return -sol.y[_DR, -1], sol.y[_V, -1], sol.y[_W, -1]
        which = min(hit, key=lambda j: abs(sol.t_events[j][0] - x))
        x, y = float(sol.t_events[which][0]), np.array(sol.y_events[which][0])
        if tail and x <= end * (1.0 + 1e-9):  # a switch at the tail's end, where the forces have gone
            return -y[_DR], y[_V], y[_W]
        name = events[which].__name__
        if name == "deepest":
            leg = "unload"
        elif name == "tail":
            leg, x = "tail", 0.0
        elif name == "to_slip":
            phase, sigma = "slip", math.copysign(1.0, -contact.stick_force(y))
        else:  # to_stick: the history starts from the cap's
            y[_H] = contact.pinned_history(y, sigma)
            phase = "stick"
    raise RuntimeError(f"more than {MAX_PHASES} stick and slip phases in one contact")


def bounce_many(variant, states, **law) -> np.ndarray:
    """(n, 3) final states of (n, 3) initial states (v_n, v_t, r omega), one collision each."""
    return np.array([bounce(variant, v_n=s[0], v_t=s[1], r_omega=s[2], **law) for s in np.atleast_2d(states)])
