"""Exact theory of LAMMPS's Mindlin tangential sub-models against a wall, without a cap.

A Mindlin tangential force grows with the contact radius a = sqrt(R delta) (R = r against a
wall). LAMMPS (``GranSubModTangentialMindlin`` and its variants, read in the pinned build and
confirmed against converged runs) keeps a history h per contact and, with slip rate u' =
v_t + r omega and a tangential dashpot c,

* ``mindlin``: h is a displacement, h' = u', F_t = -k a h - c u';
* ``mindlin/force``: h is the elastic force, h' = -k a u', F_t = h - c u';
* ``mindlin_rescale``, ``mindlin_rescale/force``: the same, and while a shrinks (unloading)
  h is scaled by a_new/a_old each step: in continuous time h' gains h a'/a where a' < 0.

m v_t' = F_t and alpha m (r omega)' = F_t, so u'' = (1 + alpha)/(alpha m) F_t: with no cap
the slip is linear and homogeneous in its initial rate, so the outcome keeps the form of the
paper's Eq. 18 with Omega = u'(tau)/u'(0) - 1, whatever the normal force (restitution 1: the
normal force is undamped here).

Scaled. With the normal motion m delta'' = -K delta^p (Hooke: K = kn, p = 1; Hertz: K = kn sqrt(R),
p = 3/2) in units t_0 = (m/(K |v_n|^(p - 1)))^(1/(p + 1)) and delta_0 = |v_n| t_0, so that
x'' = -x^p, the slip obeys, with w = u'/u'(0) and sigma = sqrt(x),

    displacement:  h' = w,              w' = -lam sigma h - zeta w
    force:         h' = -lam sigma w,   w' = h - zeta w

with lam = (1 + alpha)/(alpha m) k sqrt(R delta_0) t_0^2 and zeta = (1 + alpha)/(alpha m) c t_0.
For the Hertzian force lam = (1 + alpha)/alpha k/kn: with no dashpot Omega does not depend on
v_n at all, and with LAMMPS's NULL stiffness (k = 8 G*, k/kn = 3 (1 - nu)/(2 - nu) against a
wall) it is a function of Poisson's ratio and alpha only.

Integration (scipy's DOP853 at rtol 1e-13): near the contact's ends a ~ sqrt(t) has an
infinite slope, so there the independent variable is sigma (ds = 2 sigma d sigma / x', smooth
while x' is away from 0) and a rescaled history h/sigma is carried while unloading (the
rescale makes d(h/sigma)/ds smooth); through the deepest point, where x' = 0, it is the time s.

Pure numpy and scipy; knows nothing of LAMMPS.
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

__all__ = ["Variant", "VARIANTS", "slip_ratio", "Omega", "time_unit", "lam", "speed_free_lam", "zeta",
           "wall_stiffness_ratio", "LAM_SEARCHED",
           "unit_ratio_lams", "poisson_ratio_of", "RTOL"]

RTOL = 1.0e-13
ATOL = 1.0e-15
#: Where the variable changes from sigma to s and back: x at this fraction of its largest value.
SWITCH = 0.5
#: The reach of the explicit integration: lam beyond it turns the slip some 160 times in a contact
#: (seconds a solve, growing as sqrt(lam)); zeta beyond it damps the slip out within 1e-3 of one.
LAM_MAX = 1.0e6
ZETA_MAX = 1.0e3


class Variant(tuple):
    """(force, rescale): the history is a force (not a displacement); it is rescaled on unloading."""

    def __new__(cls, force: bool, rescale: bool):
        return super().__new__(cls, (bool(force), bool(rescale)))

    force = property(lambda self: self[0])
    rescale = property(lambda self: self[1])


#: LAMMPS's keywords and their variants.
VARIANTS = {"mindlin": Variant(False, False), "mindlin/force": Variant(True, False),
            "mindlin_rescale": Variant(False, True), "mindlin_rescale/force": Variant(True, True)}

def _normal(power: float):
    """(f, P, x_max) of the scaled normal motion x'' = -x^power, x(0) = 0, x'(0) = 1, with
    x'^2 = 1 - 2 P(x): P = x^(power + 1)/(power + 1), deepest at x_max = ((power + 1)/2)^(1/(power + 1))."""
    return (lambda x: max(x, 0.0) ** power, lambda x: max(x, 0.0) ** (power + 1.0) / (power + 1.0),
            ((power + 1.0) / 2.0) ** (1.0 / (power + 1.0)))


def _rates(h, w, sigma, lam, zeta_, force):
    """(h', w') in the time s, with the history h as carried (times sigma where ``scaled``)."""
    if force:
        return -lam * sigma * w, h - zeta_ * w
    return w, -lam * sigma * h - zeta_ * w


def _sigma_leg(y0, sigma0, sigma1, lam, zeta_, variant, power, unloading):
    """Carry (h, w) from sigma0 to sigma1 with sigma as the variable: ds = 2 sigma dsigma/x'.

    Unloading with a rescale, the carried history is g = h/sigma, which stays smooth to the end."""
    _, potential, _ = _normal(power)
    sign = -1.0 if unloading else 1.0
    scaled = unloading and variant.rescale

    def rhs(sigma, y):
        x_dot = sign * math.sqrt(max(1.0 - 2.0 * potential(sigma * sigma), 0.0))
        h = y[0] * sigma if scaled else y[0]
        dh, dw = _rates(h, y[1], sigma, lam, zeta_, variant.force)
        ds = 2.0 * sigma / x_dot
        # carried g = h/sigma: the rescale's h sigma'/sigma cancels, d(g)/ds = h'/sigma with h' the
        # unrescaled rate, and ds/sigma = 2 dsigma/x' has no 1/sigma left
        return [dh * (2.0 / x_dot if scaled else ds), dw * ds]

    if scaled:  # start carrying g = h/sigma (sigma0 > 0 here)
        y0 = [y0[0] / sigma0, y0[1]]
    sol = solve_ivp(rhs, (sigma0, sigma1), y0, method="DOP853", rtol=RTOL, atol=ATOL)
    return sol.y[:, -1]


def _time_leg(y0, x0, lam, zeta_, variant, power):
    """Carry (x, x', h, w) from x = x0 going in, through the deepest point, to x = x0 going out."""
    force_of, potential, _ = _normal(power)

    def rhs(s, y):
        x, x_dot, h, w = y
        sigma = math.sqrt(max(x, 0.0))
        dh, dw = _rates(h, w, sigma, lam, zeta_, variant.force)
        if variant.rescale and x_dot < 0.0:  # a'/a = x'/(2 x) while a shrinks
            dh += h * x_dot / (2.0 * x)
        return [x_dot, -float(force_of(x)), dh, dw]

    def deepest(s, y):
        return y[1]

    def out(s, y):
        return y[0] - x0

    deepest.terminal, deepest.direction = True, -1
    out.terminal, out.direction = True, -1
    state = [x0, math.sqrt(1.0 - 2.0 * float(potential(x0))), *y0]
    for event in (deepest, out):  # the rescale's kink at x' = 0: no step straddles it
        sol = solve_ivp(rhs, (0.0, 100.0), state, method="DOP853", rtol=RTOL, atol=ATOL, events=event)
        state = sol.y_events[0][0] if sol.y_events[0].size else sol.y[:, -1]
    return state[2:]


@lru_cache(maxsize=65536)
def _ratio(lam: float, zeta_: float, variant: Variant, power: float) -> float:
    """u'(end)/u'(0) of one scaled contact."""
    x_max = _normal(power)[2]
    x0 = SWITCH * x_max
    sigma0 = math.sqrt(x0)
    y = _sigma_leg([0.0, 1.0], 0.0, sigma0, lam, zeta_, variant, power, unloading=False)
    y = _time_leg(y, x0, lam, zeta_, variant, power)
    y = _sigma_leg(y, sigma0, 0.0, lam, zeta_, variant, power, unloading=True)
    return float(y[1])


def slip_ratio(lam, zeta_, variant: Variant, power: float) -> np.ndarray:
    """u'(tau)/u'(0) for each (lam, zeta) pair (broadcast), one scaled contact each, under a
    normal force K delta^power (1: Hooke; 3/2: Hertz)."""
    lam, zeta_ = np.broadcast_arrays(np.asarray(lam, dtype=float), np.asarray(zeta_, dtype=float))
    out = [_ratio(float(a), float(b), Variant(*variant), float(power)) for a, b in zip(lam.ravel(), zeta_.ravel())]
    return np.asarray(out, dtype=float).reshape(lam.shape)


def Omega(lam, zeta_, variant: Variant, power: float) -> np.ndarray:
    """Eq. 18's Omega: slip_ratio - 1 (-2: the slip reverses; |Omega + 1| > 1: energy gained)."""
    return slip_ratio(lam, zeta_, variant, power) - 1.0


def time_unit(power: float, m: float, K: float, v_n) -> np.ndarray:
    """t_0 of the scaled normal motion of m delta'' = -K delta^power at each |v_n|:
    (m/(K |v_n|^(power - 1)))^(1/(power + 1))."""
    v = np.abs(np.asarray(v_n, dtype=float))
    return (m / (K * v ** (power - 1.0))) ** (1.0 / (power + 1.0))


def lam(k: float, alpha: float, m: float, r: float, v_n, t0) -> np.ndarray:
    """lam = (1 + alpha)/(alpha m) k sqrt(r |v_n| t_0) t_0^2; for the Hertzian force (K = kn sqrt(r),
    power 3/2) this is :func:`speed_free_lam`, at every speed."""
    t0 = np.asarray(t0, dtype=float)
    return (1.0 + alpha) / (alpha * m) * k * np.sqrt(r * np.abs(np.asarray(v_n, dtype=float)) * t0) * t0**2


def speed_free_lam(k: float, kn: float, alpha: float) -> float:
    """lam of the Hertzian force F = kn sqrt(r) delta^(3/2): (1 + alpha)/alpha k/kn."""
    return (1.0 + alpha) / alpha * k / kn


def zeta(c: float, m: float, alpha: float, t0) -> np.ndarray:
    """zeta of a tangential dashpot c: (1 + alpha)/(alpha m) c t_0."""
    return (1.0 + alpha) / (alpha * m) * c * np.asarray(t0, dtype=float)


def wall_stiffness_ratio(poisson_ratio) -> np.ndarray:
    """k/kn of LAMMPS's NULL Mindlin stiffness against a wall: 8 G*/(4/3 E*) = 3 (1 - nu)/(2 - nu)."""
    nu = np.asarray(poisson_ratio, dtype=float)
    return 3.0 * (1.0 - nu) / (2.0 - nu)


#: Where :func:`unit_ratio_lams` looks: lam on a grid of this step (offset so that no grid point
#: falls on a simple rational lam, where the ratio may touch -1 or +1), up to ``lam_max``.
LAM_GRID_STEP = 0.2
LAM_GRID_OFFSET = 0.1371


#: How far :func:`unit_ratio_lams` looks by default.
LAM_SEARCHED = 30.0


@lru_cache(maxsize=64)
def unit_ratio_lams(variant: Variant, power: float = 1.5,
                    lam_max: float = LAM_SEARCHED) -> dict[str, tuple[float, ...]]:
    """Every lam up to ``lam_max`` at which the slip ratio crosses -1 (Omega = -2: the slip
    reverses, the paper's energy-conserving bounce) or +1 (Omega = 0: the tangential state comes
    back unchanged), refined to 1e-12; undamped (zeta = 0). Between two crossings of the same
    value |ratio| > 1: the bounce gains energy. A crossing closer than a grid step to the next
    one of the same value may be missed; a touch without a crossing is not listed."""
    grid = np.arange(LAM_GRID_OFFSET, lam_max, LAM_GRID_STEP)
    values = slip_ratio(grid, 0.0, variant, power)
    found: dict[str, tuple[float, ...]] = {}
    for target, key in ((-1.0, "Omega = -2"), (1.0, "Omega = 0")):
        excess = values - target
        found[key] = tuple(float(brentq(lambda x: float(slip_ratio(x, 0.0, variant, power)) - target,
                                        grid[i], grid[i + 1], xtol=1e-13))
                           for i in np.flatnonzero(excess[:-1] * excess[1:] < 0.0))
    return found


def poisson_ratio_of(stiffness_ratio: float) -> float | None:
    """The Poisson's ratio whose NULL Mindlin stiffness has k/kn = ``stiffness_ratio`` against a
    wall (inverting 3 (1 - nu)/(2 - nu)), or None outside (-1, 1/2]."""
    q = stiffness_ratio
    nu = (3.0 - 2.0 * q) / (3.0 - q) if q != 3.0 else math.inf
    return float(nu) if -1.0 < nu <= 0.5 + 1e-12 else None
