"""The wall oracle's forces and rates compiled (numba): what :class:`.oracle_forces.Forces` and the oracle's
regimes (:mod:`.oracle`) compute at every stage of scipy's DOP853, where the same lines in numpy took about
20 us a call (a capped Hertz-Mindlin collision about 0.1 s, most of it here).

The state is :mod:`.oracle_forces`' (delta, v_n, v (2), w = r omega (2), A or s (2)), or a 3-D slide's
(the same up to w, then the angle of s, log |u'_perp| and its sign). A law's coefficients are one row ``P``
(:func:`coefficients`); ``turned``: F_n has passed through zero on the way out; ``tensile``: it may pull.
"""

from __future__ import annotations

import math

import numpy as np

from .vec3 import kernel

__all__ = ["coefficients", "radius_power", "normal", "tangential", "stick_rate", "across_stiffness", "cap",
           "rates", "push", "FREE", "COAST", "STICK", "SLIP"]

(M, R, ALPHA, K, POWER, KT, SPRING_POWER, FORCE_HISTORY, RESCALE, MU, C_N, C_T, DAMPING_POWER,
 SLIP_MASS) = range(14)
#: The regimes, as :func:`rates` takes them.
FREE, COAST, STICK, SLIP = range(4)
#: A 3-D slide's slots beyond :mod:`.oracle_forces`' (delta, v_n, v, w at 0 to 5, which the functions below
#: index directly): the angle of s, log |u'_perp| and its sign; the state's size (:mod:`.oracle` takes them).
THETA, LOG_ACROSS, SIDE, TURNING = 6, 7, 8, 9


def coefficients(law) -> np.ndarray:
    """The row ``P`` of a :class:`.wall_law.Law`."""
    return np.array([law.m, law.r, law.alpha, law.K, law.power, law.k, law.spring_power, float(law.force_history),
                     float(law.rescale), law.mu, law.c_n, law.c_t, law.damping_power,
                     (1.0 + 1.0 / law.alpha) / law.m])


@kernel
def radius_power(y, P, s):
    """(a^s, d(a^s)/dt) of the contact radius a = sqrt(r |delta|) (even past the exit); (1, 0) for s = 0."""
    if s == 0.0:
        return 1.0, 0.0
    a_s = (P[R] * abs(y[0])) ** (s / 2.0)
    return a_s, (s * a_s * -y[1] / (2.0 * y[0]) if y[0] != 0.0 else 0.0)


@kernel
def normal(y, P):
    """(F_n, dF_n/dt) before any cut at zero, odd in delta past the exit (:meth:`.Forces.normal`)."""
    delta, rate = y[0], -y[1]
    depth = abs(delta) ** (P[POWER] - 1.0) if P[POWER] != 1.0 else 1.0
    damp, damp_rate = radius_power(y, P, P[DAMPING_POWER])
    f = P[K] * depth * delta + P[C_N] * damp * rate
    accel = -f / P[M]
    return f, P[K] * P[POWER] * depth * rate + P[C_N] * (damp * accel + damp_rate * rate)


@kernel
def tangential(y, P):
    """(k_t, R, gamma_t, gamma_t') of the sticking trial force (:meth:`.Forces.tangential`)."""
    k = radius_power(y, P, P[SPRING_POWER])[0]
    gt, gt_rate = radius_power(y, P, P[DAMPING_POWER])
    scale = (0.0 if P[FORCE_HISTORY] else P[SPRING_POWER]) + (1.0 if P[RESCALE] and y[1] > 0.0 else 0.0)
    shrink = -y[1] / (2.0 * y[0]) if scale != 0.0 and y[0] != 0.0 else 0.0
    return P[KT] * k, scale * shrink, P[C_T] * gt, P[C_T] * gt_rate


@kernel
def stick_rate(y, P, f0, f1, u0, u1):
    """A' while sticking, the friction force being (f0, f1) and the slip rate (u0, u1)."""
    k, scale, gt, gt_rate = tangential(y, P)
    r0 = (k + gt_rate) * u0 + gt * P[SLIP_MASS] * f0
    r1 = (k + gt_rate) * u1 + gt * P[SLIP_MASS] * f1
    if scale != 0.0:
        return r0 + scale * (-f0 - gt * u0), r1 + scale * (-f1 - gt * u1)
    return r0, r1


@kernel
def across_stiffness(y, P):
    """The sticking A' per unit slip across s: k_t - R gamma_t + gamma_t'."""
    k, scale, gt, gt_rate = tangential(y, P)
    return k - scale * gt + gt_rate


@kernel
def cap(y, P, turned, tensile):
    """(mu |F_n|, its rate) after limit_damping's cut, continued smoothly past a turn (:meth:`.oracle._Contact.cap`)."""
    f, df = normal(y, P)
    if turned:
        if not tensile:
            return 0.0, 0.0
        return -P[MU] * f, -P[MU] * df
    return P[MU] * f, P[MU] * df


@kernel
def _direction(y):
    """A slide's unit s: as stored in the plane, from its angle in a 3-D slide's state."""
    if y.size == TURNING:
        return math.cos(y[THETA]), math.sin(y[THETA])
    return y[6], y[7]


@kernel
def push(y, P, s0, s1, c):
    """How fast sticking would carry A outwards along s, with A on a cap of radius c."""
    r0, r1 = stick_rate(y, P, -c * s0, -c * s1, y[2] + y[4], y[3] + y[5])
    return s0 * r0 + s1 * r1


@kernel
def rates(y, phase, P, turned, tensile, turn_floor, out):
    """d(state)/dt in regime ``phase`` into ``out`` (zeros where nothing moves)."""
    for i in range(y.size):
        out[i] = 0.0
    out[0] = -y[1]
    if phase == FREE:
        return
    out[1] = 0.0 if turned and not tensile else normal(y, P)[0] / P[M]
    if phase == COAST:
        return
    u0, u1 = y[2] + y[4], y[3] + y[5]
    if phase == STICK:
        f0, f1 = -y[6], -y[7]
        out[6], out[7] = stick_rate(y, P, f0, f1, u0, u1)
    else:  # a slide: A = c s rides the cap, s turning towards the slip (3-D)
        c = cap(y, P, turned, tensile)[0]
        s0, s1 = _direction(y)
        f0, f1 = -c * s0, -c * s1
        if y.size == TURNING and y[SIDE] != 0.0:
            rate = across_stiffness(y, P) / math.hypot(c, turn_floor)
            across = min(math.exp(min(y[LOG_ACROSS], 700.0)), math.hypot(u0, u1))  # |q| <= |u'|
            out[THETA] = rate * y[SIDE] * across
            out[LOG_ACROSS] = -rate * (s0 * u0 + s1 * u1)
    out[2], out[3] = f0 / P[M], f1 / P[M]
    out[4], out[5] = f0 / (P[ALPHA] * P[M]), f1 / (P[ALPHA] * P[M])
