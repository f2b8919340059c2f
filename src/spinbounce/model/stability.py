"""Stability of LAMMPS's velocity-Verlet step for one damped contact mode.

Each contact mode here is linear: x'' + c x' + w^2 x = 0 (normal: w^2 = kn/m, c = gamma_n/m;
slip: w^2 = Q, c = 2 zeta). LAMMPS advances it as

    v_half = v + dt/2 a;  x_new = x + dt v_half;
    a_new = -w^2 x_new - c v_half;        (the force sees the half-step velocity)
    v_new = v_half + dt/2 a_new

(the tangential history is incremented by dt times the half-step slip rate, the same
map for u). That is a linear map of (x, v, a); the step is stable while its spectral
radius stays at or below 1. Without damping the limit is the textbook dt < 2/w; with
damping it is smaller, and it is found here numerically from the same map rather than
from a rule of thumb.
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

__all__ = ["stability_limit", "overlap_stretch"]


def stability_limit(w: float, c: float = 0.0, rtol: float = 1e-10) -> float:
    """Largest dt for which the step of x'' + c x' + w^2 x = 0 does not grow.

    Returns math.inf for a mode with neither stiffness nor damping. The limit times the mode's
    rate depends only on the damping ratio: it is found for a mode of unit rate, and scaled, so
    that no rate (sqrt(kn/m) = 3e150 at m = 1e-300) meets the overflow of its square.
    """
    if w <= 0.0 and c <= 0.0:
        return math.inf
    rate = max(w, c)
    return _unit_limit(w / rate, c / rate, rtol) / rate


@lru_cache(maxsize=1024)
def _unit_limit(w: float, c: float, rtol: float) -> float:
    """:func:`stability_limit` of a mode whose larger rate is 1. Cached: a bisection costs ~100
    eigenvalue problems, and sweeps ask for the same modes again and again."""

    def stable(dt: float) -> bool:
        """Whether the spectral radius of one step's map of (x, v, a) is at most 1 (it is 1 for any
        dt below the limit when undamped: allow for rounding)."""
        half = np.array([0.0, 1.0, 0.5 * dt])  # v_half = v + dt/2 a, as a row acting on (x, v, a)
        x_new = np.array([1.0, 0.0, 0.0]) + dt * half
        a_new = -w * w * x_new - c * half
        step = np.vstack([x_new, half + 0.5 * dt * a_new, a_new])
        return float(np.max(np.abs(np.linalg.eigvals(step)))) <= 1.0 + 1e-12

    hi = 4.0 / max(w, c)
    while stable(hi):
        hi *= 2.0
    lo = 0.0
    while hi - lo > rtol * hi:
        mid = 0.5 * (lo + hi)
        if stable(mid):
            lo = mid
        else:
            hi = mid
    return lo


def overlap_stretch(w: float, dt: float) -> float:
    """How far the step stretches the largest overlap of a spring of frequency w (inf past 2/w).

    LAMMPS's velocity Verlet keeps v^2 + w^2 x^2 (1 - (w dt/2)^2) constant in the undamped
    linear spring, so its largest overlap exceeds the exact one by the factor
    1/sqrt(1 - (w dt/2)^2): a coarse step can tunnel where the exact motion would not. With w at a
    nonlinear spring's stiffest point this bounds its stretch too (Hertz: to leading order
    1 + (w dt)^2/36 against 1 + (w dt)^2/8; tests/test_hertz.py replays the step).
    """
    half_step = 0.5 * w * dt
    return 1.0 / math.sqrt(1.0 - half_step**2) if half_step < 1.0 else math.inf
