"""The equations of two spheres in contact compiled (numba), for every law of :data:`.pair_exact.HOOKE`'s
shape: a normal force K delta^p, a spring k a^q or a force history, dashpots gamma a^s, a rescale, a history
projected as n turns, and the classic spring's cap. scipy's DOP853 calls them at every stage of every step
of the one-pair references, where the same equations in numpy took 0.05 to 0.2 ms a call (a capped Hertzian
pair took 1 to 10 s): :func:`free_rates` is :mod:`.pair_exact`'s uncapped contact; the rest are the phases
of :mod:`.pair_capped`, whose :class:`.pair_capped_phases.Contact` says what they mean and when each holds.

A capped state is (d, v_a, v_b, w_a, w_b, A or s, overlap); ``side`` is F_n's side (+-1), ``margin`` a
switch's margin in force (or in force a time, for a slide's push). The coefficients are one row ``P``
(:func:`coefficients`: the inverse masses and moments of inertia, K = kn R_eff^(p - 1)).
"""

from __future__ import annotations

import numpy as np

from .vec3 import axpy, cross, dot, kernel, unit

__all__ = ["coefficients", "normal_law", "geometry", "free_rates", "kinematics", "stick_rate", "stick_rates",
           "slide_rates", "coast_rates", "classic_slide_rates", "direction", "classic_direction", "stick_end",
           "slide_end",
           "classic_slide_end", "normal_force", "closing"]

(R_A, R_B, M_A, M_B, I_A, I_B, K, KT, GAMMA_N, GAMMA_T, RADSUM, MU, M_STAR, R_EFF, POWER, SPRING_POWER,
 DAMPING_POWER, FORCE_HISTORY, RESCALE, PROJECTED) = range(20)
#: The fields of :func:`kinematics`' tuple.
(N, TURN, V, V_N, SPIN, SLIP, F_N, DF_N, LEVER_A, LEVER_B, SPRING, GROWTH, DASHPOT, DASHPOT_RATE) = range(14)


def coefficients(p: dict) -> np.ndarray:
    """The row ``P`` of a pair's coefficients (:func:`.pair_exact.start`'s dict; no cap: mu 0)."""
    m_star = p["m_a"] * p["m_b"] / (p["m_a"] + p["m_b"])
    return np.array([p["r_a"], p["r_b"], 1.0 / p["m_a"], 1.0 / p["m_b"], 1.0 / p["i_a"], 1.0 / p["i_b"], p["K"],
                     p["kt"], p["gamma_n"], p["gamma_t"], p["r_a"] + p["r_b"], p.get("mu", 0.0), m_star, p["r_eff"],
                     p["power"], p["spring_power"], p["damping_power"], float(p["force_history"]),
                     float(p["rescale"]), float(p["projected"])])


@kernel
def _scaled(c, a):
    return (c * a[0], c * a[1], c * a[2])


@kernel
def _radius_power(P, delta, s):
    """a^s of the contact radius a = sqrt(R_eff |delta|) (1 for s = 0)."""
    return 1.0 if s == 0.0 else (P[R_EFF] * abs(delta)) ** (s / 2.0)


@kernel
def normal_law(P, delta, v_n):
    """(F_n on a along n, delta^(p - 1), a^s) at the overlap ``delta`` and v.n: K delta^p - gamma_n a^s v.n."""
    depth = abs(delta) ** (P[POWER] - 1.0) if P[POWER] != 1.0 else 1.0
    damp = _radius_power(P, delta, P[DAMPING_POWER])
    return P[K] * depth * delta - P[GAMMA_N] * damp * v_n, depth, damp


@kernel
def geometry(y, P, n0, planar):
    """(n, the centres' distance along it, the lever arm of a, of b) of a state: n held at n0 and the levers the
    radii (``planar``), else n = d/|d| and each lever the distance to the middle of the overlap (the columns
    R_A, R_B and RADSUM are the batches' too)."""
    d = (y[0], y[1], y[2])
    if planar:
        return (n0[0], n0[1], n0[2]), dot(d, n0), P[R_A], P[R_B]
    dist = np.sqrt(dot(d, d))
    return _scaled(1.0 / dist, d), dist, P[R_A] - 0.5 * (P[RADSUM] - dist), P[R_B] - 0.5 * (P[RADSUM] - dist)


@kernel
def free_rates(y, P, n0, planar, overlap, out):
    """d(state)/dt of an uncapped contact's (d, v_a, v_b, w_a, w_b, history) into ``out``: the history xi
    (a displacement, F_t = -k a^q xi - gamma_t a^s u', or with FORCE_HISTORY the force itself), kept in the
    tangent plane as n turns where PROJECTED; ``overlap``: where it is known better than from the centres
    (:func:`.pair_exact._tail`), else NaN."""
    n, dist, lever_a, lever_b = geometry(y, P, n0, planar)
    delta = P[RADSUM] - dist if overlap != overlap else overlap
    v = (y[3] - y[6], y[4] - y[7], y[5] - y[8])
    xi = (y[15], y[16], y[17])
    v_n = dot(v, n)
    spin = (P[R_A] * y[9] + P[R_B] * y[12], P[R_A] * y[10] + P[R_B] * y[13], P[R_A] * y[11] + P[R_B] * y[14])
    v_t = axpy(-v_n, n, v)
    slip = axpy(-1.0, cross(spin, n), v_t)
    f_n, _, damp = normal_law(P, delta, v_n)
    spring = P[KT] * _radius_power(P, delta, P[SPRING_POWER])
    elastic = xi if P[FORCE_HISTORY] else _scaled(-spring, xi)
    f_t = axpy(-P[GAMMA_T] * damp, slip, elastic)
    force = axpy(f_n, n, f_t)
    arm = cross(f_t, n)
    history = _scaled(-spring, slip) if P[FORCE_HISTORY] else slip
    if P[RESCALE] and v_n > 0.0 and delta > 0.0:  # a shrinks: the history by a_new/a_old (a'/a = delta'/2 delta)
        history = axpy(-v_n / (2.0 * delta), xi, history)
    if P[PROJECTED] and not planar:  # kept in the tangent plane as n turns (n' = (v - v_n n)/|d|)
        history = axpy(-dot(xi, v_t) / dist, n, history)
    for i in range(3):
        out[i] = v[i]
        out[3 + i] = force[i] * P[M_A]
        out[6 + i] = -force[i] * P[M_B]
        out[9 + i] = lever_a * arm[i] * P[I_A]
        out[12 + i] = lever_b * arm[i] * P[I_B]
        out[15 + i] = history[i]


@kernel
def kinematics(y, P, n0, planar):
    """(n, n', v, v.n, spin r_a w_a + r_b w_b, slip rate, F_n, F_n', lever of a, of b, k a^q, the history's
    growth rate, gamma_t a^s, its rate) of a state."""
    n, dist, lever_a, lever_b = geometry(y, P, n0, planar)
    delta = y[18]
    v = (y[3] - y[6], y[4] - y[7], y[5] - y[8])
    v_n = dot(v, n)
    v_t = axpy(-v_n, n, v)
    turn = (0.0, 0.0, 0.0) if planar else _scaled(1.0 / dist, v_t)
    spin = (P[R_A] * y[9] + P[R_B] * y[12], P[R_A] * y[10] + P[R_B] * y[13], P[R_A] * y[11] + P[R_B] * y[14])
    rate = -v_n  # the overlap's
    f_n, depth, damp = normal_law(P, delta, v_n)
    shrink = rate / (2.0 * delta) if delta != 0.0 else 0.0
    accel = -(f_n / P[M_STAR] + dot(v_t, turn))  # delta''
    df_n = P[K] * P[POWER] * depth * rate + P[GAMMA_N] * damp * (accel + P[DAMPING_POWER] * shrink * rate)
    scale = (0.0 if P[FORCE_HISTORY] else P[SPRING_POWER]) + (1.0 if P[RESCALE] and rate < 0.0 else 0.0)
    slip = axpy(-1.0, cross(spin, n), v_t)
    spring = P[KT] * _radius_power(P, delta, P[SPRING_POWER])
    return (n, turn, v, v_n, spin, slip, f_n, df_n, lever_a, lever_b, spring, scale * shrink, P[GAMMA_T] * damp,
            P[GAMMA_T] * P[DAMPING_POWER] * shrink * damp)


@kernel
def accelerations(k, P, f_t):
    """(v_a', v_b', w_a', w_b') under the normal force and the friction ``f_t`` on a."""
    force = axpy(k[F_N], k[N], f_t)
    arm = cross(f_t, k[N])
    return (_scaled(P[M_A], force), _scaled(-P[M_B], force), _scaled(k[LEVER_A] * P[I_A], arm),
            _scaled(k[LEVER_B] * P[I_B], arm))


@kernel
def stick_rate(k, P, trial):
    """A' while sticking with the trial force ``trial`` (the friction -trial on a)."""
    n, turn, v, v_n, spin, slip = k[N], k[TURN], k[V], k[V_N], k[SPIN], k[SLIP]
    dv_a, dv_b, dw_a, dw_b = accelerations(k, P, _scaled(-1.0, trial))
    dv = axpy(-1.0, dv_b, dv_a)
    dspin = axpy(P[R_A], dw_a, _scaled(P[R_B], dw_b))
    along = dot(dv, n) + dot(turn, v)
    a, b = cross(dspin, n), cross(spin, turn)
    elastic = axpy(-k[DASHPOT], slip, trial)
    tilt = dot(elastic, turn)
    return (k[SPRING] * slip[0] + k[GROWTH] * elastic[0] - tilt * n[0] + k[DASHPOT_RATE] * slip[0]
            + k[DASHPOT] * (dv[0] - along * n[0] - v_n * turn[0] - a[0] - b[0]),
            k[SPRING] * slip[1] + k[GROWTH] * elastic[1] - tilt * n[1] + k[DASHPOT_RATE] * slip[1]
            + k[DASHPOT] * (dv[1] - along * n[1] - v_n * turn[1] - a[1] - b[1]),
            k[SPRING] * slip[2] + k[GROWTH] * elastic[2] - tilt * n[2] + k[DASHPOT_RATE] * slip[2]
            + k[DASHPOT] * (dv[2] - along * n[2] - v_n * turn[2] - a[2] - b[2]))


@kernel
def direction(k, y):
    """A slide's unit s, held in the tangent plane (its drift off it is the integrator's)."""
    a = (y[15], y[16], y[17])
    return unit(axpy(-dot(a, k[N]), k[N], a))[0]


@kernel
def classic_direction(k, y):
    """The classic cap's slide: along the slip, else as :func:`direction`."""
    s, size = unit(k[SLIP])
    return s if size > 0.0 else direction(k, y)


@kernel
def _write(out, k, P, f_t, tail):
    dv_a, dv_b, dw_a, dw_b = accelerations(k, P, f_t)
    for i in range(3):
        out[i] = k[V][i]
        out[3 + i] = dv_a[i]
        out[6 + i] = dv_b[i]
        out[9 + i] = dw_a[i]
        out[12 + i] = dw_b[i]
        out[15 + i] = tail[i]
    out[18] = -k[V_N]


@kernel
def stick_rates(y, P, n0, planar, out):
    """d(state)/dt while sticking, into ``out``."""
    k = kinematics(y, P, n0, planar)
    trial = (y[15], y[16], y[17])
    _write(out, k, P, _scaled(-1.0, trial), stick_rate(k, P, trial))


@kernel
def slide_rates(y, P, n0, planar, side, floor, out):
    """d(state)/dt while sliding (s turning towards the sticking rate; ``floor``: the turn's floor in force)."""
    k = kinematics(y, P, n0, planar)
    n = k[N]
    s = direction(k, y)
    c = P[MU] * side * k[F_N]
    across = cross(n, s)
    bend = dot(across, stick_rate(k, P, _scaled(c, s))) / np.hypot(c, floor)
    _write(out, k, P, _scaled(-c, s), axpy(bend, across, _scaled(-dot(s, k[TURN]), n)))


@kernel
def coast_rates(y, P, n0, planar, out):
    """d(state)/dt with the cap below a switch's margin at the contact's end: no tangential force, s held."""
    _write(out, kinematics(y, P, n0, planar), P, (0.0, 0.0, 0.0), (0.0, 0.0, 0.0))


@kernel
def classic_slide_rates(y, P, n0, planar, side, out):
    """d(state)/dt while the classic cap slides along the slip (s held)."""
    k = kinematics(y, P, n0, planar)
    _write(out, k, P, _scaled(-P[MU] * side * k[F_N], classic_direction(k, y)), (0.0, 0.0, 0.0))


@kernel
def stick_end(y, P, n0, planar, side, margin):
    """|A| less the cap and ``margin``: rises through zero where a stick reaches the cap."""
    k = kinematics(y, P, n0, planar)
    return np.sqrt(y[15] ** 2 + y[16] ** 2 + y[17] ** 2) - P[MU] * side * k[F_N] - margin


@kernel
def slide_end(y, P, n0, planar, side, margin):
    """How fast sticking would carry A = c s outwards along s, less the cap's rate, plus ``margin``."""
    k = kinematics(y, P, n0, planar)
    s = direction(k, y)
    c = P[MU] * side * k[F_N]
    return dot(s, stick_rate(k, P, _scaled(c, s))) - P[MU] * side * k[DF_N] + margin


@kernel
def classic_slide_end(y, P, n0, planar, side, margin, near_one, cut):
    """The dashpot's force less the cap, held on by ``cut`` (near_one of their scale plus ``margin``)."""
    k = kinematics(y, P, n0, planar)
    drag, c = k[DASHPOT] * np.sqrt(dot(k[SLIP], k[SLIP])), P[MU] * side * k[F_N]
    return drag - c + cut * (near_one * (c + abs(drag)) + margin)


@kernel
def normal_force(y, P, n0, planar):
    """F_n on a along n."""
    return kinematics(y, P, n0, planar)[F_N]


@kernel
def closing(y, P, n0, planar):
    """(v_a - v_b).n: the overlap shrinks while it is > 0."""
    return kinematics(y, P, n0, planar)[V_N]
