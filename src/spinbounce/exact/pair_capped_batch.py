"""The capped Hookean pair reference for many pairs at once: :func:`spinbounce.exact.pair_capped.solve`
compiled (numba) for Hooke's force and linear_history, each pair on its own.

The same equations (:class:`.pair_capped_phases.Contact`: the history turned with n, the trial force
A = E + gamma_t u' as a state while sticking and its unit direction s on the cap while sliding, the
overlap a state of its own), the same phases and switches (:meth:`~.pair_capped_phases.Contact.begin`,
``on_cap``, ``switch``), the same integrator (scipy's DOP853 at rtol 1e-12, :mod:`.dop853`) and
the same events: the end of contact, the phase's own end (also sampled at INTERIOR_SAMPLES points
inside each step, so that a stick or a slide shorter than a step is not stepped over) and, with a
normal dashpot, the normal force's zero; each located on the step's dense output and the integration
restarted there. Measured against the scipy reference on random pairs (tests/test_pair_capped_batch.py).

Laws on the contact radius, ``limit_damping`` with a normal dashpot (the normal force's turn cuts the
contact) and pairs this batch cannot carry to their end (more than MAX_PHASES switches, a step shrunk to
nothing) are solved one at a time by :func:`.pair_capped.solve`: :func:`solvable` says which laws are taken.
"""

from __future__ import annotations

import numpy as np

from . import first_use, pair_capped
from .dop853 import (
    INTERPOLATOR_POWER,
    accept,
    RTOL,
    error_norm,
    interpolate,
    make_dense,
    make_step,
    new_scratch,
    step_factor,
)
from .pair_batch import ENDED, STUCK, example_batch, finish, prepare
from .pair_batch import solvable as uncapped_solvable
from .pair_capped import INTERIOR_SAMPLES, MAX_PHASES
from .pair_capped_phases import MARGIN, TURN_FLOOR
from .pair_kernel import geometry
from .vec3 import axpy, compiled, cross, dot, kernel, unit

__all__ = ["solve", "solvable"]

#: The columns of a pair's coefficients: radii, inverse masses and moments of inertia, the law, r_a + r_b,
#: the reduced mass, and the scales of :func:`.pair_capped.solve` (force, rounding of F_n, turn floor, tau).
(R_A, R_B, M_A, M_B, I_A, I_B, KN, KT, GAMMA_N, GAMMA_T, RADSUM, MU, M_STAR, FORCE, ROUNDING, FLOOR,
 TAU) = range(17)
#: The phases (``mode``): sticking or sliding, its sign F_n's side.
STICK, SLIDE = 1, 2
#: The events of a phase: the end of contact, the phase's own end, the normal force's zero.
SEPARATED, OWN_END, NORMAL_ZERO = 0, 1, 2
#: A pair whose step shrinks below MIN_STEP of its longest, or still in one phase after MAX_STEPS steps,
#: is left to the scipy reference (300 times slower). A slide can take tens of thousands of steps as
#: its cap closes (31,640 seen on a grazing pair, at 1e-11 of the longest step), so MAX_STEPS is large:
#: it stops a runaway phase (MAX_PHASES of them at most) after seconds, not minutes.
MIN_STEP = 1e-12
MAX_STEPS = 1_000_000


def solvable(law: dict, tensile: bool = True) -> bool:
    """Whether :func:`solve` takes ``law``: Hooke's shape, and no turn of the normal force to cut (limit_damping
    cuts it only where a normal dashpot turns it)."""
    return uncapped_solvable(law, tensile)


@kernel
def _kinematics(y, p, n0, planar):
    """(n, n', v, v.n, spin, slip rate, F_n, F_n', lever of a, of b): :meth:`.pair_capped_phases.Contact.kinematics`
    for Hooke's law."""
    n, dist, lever_a, lever_b = geometry(y, p, n0, planar)
    v = (y[3] - y[6], y[4] - y[7], y[5] - y[8])
    v_n = dot(v, n)
    v_t = axpy(-v_n, n, v)
    turn = (0.0, 0.0, 0.0) if planar else (v_t[0] / dist, v_t[1] / dist, v_t[2] / dist)
    spin = (p[R_A] * y[9] + p[R_B] * y[12], p[R_A] * y[10] + p[R_B] * y[13], p[R_A] * y[11] + p[R_B] * y[14])
    f_n = p[KN] * y[18] - p[GAMMA_N] * v_n
    df_n = -p[KN] * v_n - p[GAMMA_N] * (f_n / p[M_STAR] + dot(v_t, turn))
    slip = axpy(-1.0, cross(spin, n), v_t)
    return n, turn, v, v_n, spin, slip, f_n, df_n, lever_a, lever_b


@kernel
def _stick_rate(k, p, trial):
    """A' while sticking with the trial force ``trial`` (the friction -trial on a)."""
    n, turn, v, v_n, spin, slip, f_n, _, lever_a, lever_b = k
    force = axpy(f_n, n, (-trial[0], -trial[1], -trial[2]))
    arm = cross(force, n)  # (-trial) x n: the normal part has none
    dv = (force[0] * (p[M_A] + p[M_B]), force[1] * (p[M_A] + p[M_B]), force[2] * (p[M_A] + p[M_B]))
    spun = p[R_A] * lever_a * p[I_A] + p[R_B] * lever_b * p[I_B]
    dspin = (spun * arm[0], spun * arm[1], spun * arm[2])
    along = dot(dv, n) + dot(turn, v)
    a, b = cross(dspin, n), cross(spin, turn)
    slip_rate = (dv[0] - along * n[0] - v_n * turn[0] - a[0] - b[0], dv[1] - along * n[1] - v_n * turn[1] - a[1] - b[1],
                 dv[2] - along * n[2] - v_n * turn[2] - a[2] - b[2])
    elastic = axpy(-p[GAMMA_T], slip, trial)
    tilt = dot(elastic, turn)
    return (p[KT] * slip[0] - tilt * n[0] + p[GAMMA_T] * slip_rate[0],
            p[KT] * slip[1] - tilt * n[1] + p[GAMMA_T] * slip_rate[1],
            p[KT] * slip[2] - tilt * n[2] + p[GAMMA_T] * slip_rate[2])


@kernel
def _direction(k, y):
    """A slide's unit s, held in the tangent plane."""
    n = k[0]
    a = (y[15], y[16], y[17])
    return unit(axpy(-dot(a, n), n, a))[0]


@kernel
def _cap(k, p, side):
    return p[MU] * side * k[6]


@kernel
def _push(k, p, side, s):
    """How fast sticking would carry A outwards along s with A = c s on the cap, less the cap's rate."""
    c = _cap(k, p, side)
    return dot(s, _stick_rate(k, p, (c * s[0], c * s[1], c * s[2]))) - p[MU] * side * k[7]


@kernel
def _rates(y, p, n0, planar, mode, out):
    """d(state)/dt of (d, v_a, v_b, w_a, w_b, A or s, overlap) in phase ``mode`` (its sign F_n's side)."""
    k = _kinematics(y, p, n0, planar)
    n, turn, v, v_n = k[0], k[1], k[2], k[3]
    side = 1.0 if mode > 0 else -1.0
    if abs(mode) == SLIDE:
        s = _direction(k, y)
        c = _cap(k, p, side)
        across = cross(n, s)
        rate = _stick_rate(k, p, (c * s[0], c * s[1], c * s[2]))
        bend = dot(across, rate) / np.hypot(c, p[FLOOR])
        tail = axpy(bend, across, (-dot(s, turn) * n[0], -dot(s, turn) * n[1], -dot(s, turn) * n[2]))
        trial = (c * s[0], c * s[1], c * s[2])
    else:
        trial = (y[15], y[16], y[17])
        tail = _stick_rate(k, p, trial)
    force = axpy(k[6], n, (-trial[0], -trial[1], -trial[2]))
    arm = cross(force, n)
    for i in range(3):
        out[i] = v[i]
        out[3 + i] = force[i] * p[M_A]
        out[6 + i] = -force[i] * p[M_B]
        out[9 + i] = k[8] * arm[i] * p[I_A]
        out[12 + i] = k[9] * arm[i] * p[I_B]
        out[15 + i] = tail[i]
    out[18] = -v_n


_step, _dense = make_step(_rates), make_dense(_rates)


@kernel
def _event(which, y, p, n0, planar, mode):
    """The value of event ``which`` at ``y``, signed so that it fires rising through zero."""
    if which == SEPARATED:
        return -y[18]
    k = _kinematics(y, p, n0, planar)
    side = 1.0 if mode > 0 else -1.0
    if which == NORMAL_ZERO:  # F_n falls through zero on its side
        return -side * k[6]
    if abs(mode) == SLIDE:  # the slide ends where its push falls through the margin
        return -(_push(k, p, side, _direction(k, y)) + MARGIN * p[FORCE] / p[TAU])
    return np.sqrt(y[15] ** 2 + y[16] ** 2 + y[17] ** 2) - _cap(k, p, side) - MARGIN * p[FORCE]


@kernel
def _root(which, y0, F, x0, x1, g0, g1, h, t, p, n0, planar, mode, out):
    """The fraction of the step in (x0, x1] where event ``which`` rises through zero (``g0`` < 0 <= ``g1``),
    on the dense output, to scipy's event tolerance (4 eps in time): Illinois false position."""
    side = 0
    tolerance = 4.0 * np.finfo(np.float64).eps * max(1.0, abs(t)) / h
    for _ in range(200):
        if x1 - x0 <= tolerance:
            break
        x = (x0 * g1 - x1 * g0) / (g1 - g0)
        if not x0 < x < x1:
            x = 0.5 * (x0 + x1)
        interpolate(F, y0, x, out)
        g = _event(which, out, p, n0, planar, mode)
        if g < 0.0:
            x0, g0 = x, g
            if side == -1:
                g1 *= 0.5
            side = -1
        else:
            x1, g1 = x, g
            if side == 1:
                g0 *= 0.5
            side = 1
    interpolate(F, y0, x1, out)
    return x1


@kernel
def _rate_direction(k, p):
    """Where sticking pushes a trial force of zero: the unit A' at A = 0, else the slip's; (direction, found)."""
    rate, size = unit(_stick_rate(k, p, (0.0, 0.0, 0.0)))
    if size > 0.0:
        return rate, True
    slip, size = unit(k[5])
    return slip, size > 0.0


@kernel
def _on_cap(y, p, n0, planar, side, s, found):
    """The phase with A on the cap along ``s`` (``found`` False: no direction, stick with A = 0)."""
    k = _kinematics(y, p, n0, planar)
    if not found:
        y[15], y[16], y[17] = 0.0, 0.0, 0.0
        return STICK * side
    if _push(k, p, side, s) > 0.0:
        y[15], y[16], y[17] = s
        return SLIDE * side
    c = _cap(k, p, side)
    y[15], y[16], y[17] = c * s[0], c * s[1], c * s[2]
    return STICK * side


@kernel
def _begin(y, p, n0, planar):
    """The trial force at first touch (the dashpot's gamma_t u') and the phase it starts in."""
    k = _kinematics(y, p, n0, planar)
    f_n, df_n = k[6], k[7]
    side = np.sign(f_n if abs(f_n) > p[ROUNDING] else df_n)
    side = 1 if side == 0.0 else int(side)
    y[15], y[16], y[17] = p[GAMMA_T] * k[5][0], p[GAMMA_T] * k[5][1], p[GAMMA_T] * k[5][2]
    trial = (y[15], y[16], y[17])
    if np.sqrt(dot(trial, trial)) < _cap(k, p, side) - MARGIN * p[FORCE]:
        return STICK * side
    s, size = unit(trial)
    if size > 0.0:
        return _on_cap(y, p, n0, planar, side, s, True)
    s, found = _rate_direction(k, p)
    return _on_cap(y, p, n0, planar, side, s, found)


@kernel
def _switch(which, y, p, n0, planar, mode):
    """The phase after event ``which`` (:meth:`.pair_capped_phases.Contact.switch`)."""
    k = _kinematics(y, p, n0, planar)
    side = 1 if mode > 0 else -1
    if which == OWN_END and abs(mode) == STICK:  # the stick reached the cap: slide along A
        size = np.sqrt(y[15] ** 2 + y[16] ** 2 + y[17] ** 2)
        y[15], y[16], y[17] = y[15] / size, y[16] / size, y[17] / size
        return SLIDE * side
    if which == OWN_END:  # the cap outgrew the slide: stick on it
        s = _direction(k, y)
        c = _cap(k, p, side)
        y[15], y[16], y[17] = c * s[0], c * s[1], c * s[2]
        return STICK * side
    turned = np.sign(k[7])  # F_n's zero: the cap restarts on the side F_n moves to
    side = -side if turned == 0.0 else int(turned)
    s, found = _rate_direction(k, p)
    return _on_cap(y, p, n0, planar, side, s, found)


@kernel
def _first_event(y, y_new, F, h, t, g_start, g_end, events, p, n0, planar, mode, probe):
    """(fraction of the step, event) of the first event inside the step from ``y`` (-1 if none): each event
    where it rises through zero between the step's ends, and the phase's own end also between
    INTERIOR_SAMPLES points inside the step."""
    first, which = 2.0, -1
    for w in range(events):
        x0, g0 = 0.0, g_start[w]
        samples = INTERIOR_SAMPLES + 1 if w == OWN_END else 1
        for j in range(1, samples + 1):
            x1 = j / samples
            if j == samples:
                g1 = g_end[w]
            else:
                interpolate(F, y, x1, probe)
                g1 = _event(w, probe, p, n0, planar, mode)
            if x0 >= first:
                break
            if g0 <= 0.0 <= g1 and g1 > g0:
                x = _root(w, y, F, x0, x1, g0, g1, h, t, p, n0, planar, mode, probe)
                if x < first:
                    first, which = x, w
                break
            x0, g0 = x1, g1
    return first, which


@kernel
def _advance(y, f, t, target, h, p, n0, planar, mode, longest, atol, stages, scratch, y_new):
    """``y`` (rates ``f``) at ``t`` integrated to exactly ``target`` under the same error control, the last
    step ending there: the state at an event. Returns the next step's length (NaN if it shrank to nothing)."""
    rejected = False
    while t < target:
        hs = min(h, longest, target - t)
        _step(y, f, hs, p, n0, planar, mode, stages, scratch, y_new)
        err = error_norm(stages, hs, y, y_new, atol, RTOL)
        h = hs * step_factor(err, rejected)
        rejected = not err < 1.0
        if not rejected:
            accept(y, f, y_new, stages)
            t = target if hs == target - t else t + hs
        elif h < MIN_STEP * longest:
            return np.nan
    return h


@compiled
def _solve_one(y, p, n0, planar, longest, atol, window, max_steps, end):
    """One capped pair from first touch (state ``y``, changed) to its end (state into ``end``): (time, status)."""
    size = y.size
    stages, scratch = new_scratch(size)
    y_new, f, F = np.empty(size), np.empty(size), np.empty((INTERPOLATOR_POWER, size))
    probe = np.empty(size)
    g_start, g_end = np.empty(3), np.empty(3)
    events = 3 if p[GAMMA_N] > 0.0 else 2
    mode = _begin(y, p, n0, planar)
    t, h = 0.0, longest / 8.0
    for _ in range(MAX_PHASES):
        atol[15:18] = RTOL if abs(mode) == SLIDE else RTOL * p[FORCE]  # s is a unit vector
        _rates(y, p, n0, planar, mode, f)
        for w in range(events):
            g_start[w] = _event(w, y, p, n0, planar, mode)
        rejected, bound, which = False, t + window, -1  # a phase starts at the step the last one was taking
        for _ in range(max_steps):
            hs = min(h, longest)
            _step(y, f, hs, p, n0, planar, mode, stages, scratch, y_new)
            err = error_norm(stages, hs, y, y_new, atol, RTOL)
            ok = err < 1.0
            h = hs * step_factor(err, rejected)
            rejected = not ok
            if ok:
                for w in range(events):
                    g_end[w] = _event(w, y_new, p, n0, planar, mode)
                _dense(y, y_new, hs, p, n0, planar, mode, stages, scratch, F)
                x, which = _first_event(y, y_new, F, hs, t, g_start, g_end, events, p, n0, planar, mode, probe)
                if which >= 0:  # integrated to the event's time, not interpolated: a slide's s turns
                    h = _advance(y, f, t, t + x * hs, hs, p, n0, planar, mode, longest, atol, stages, scratch, y_new)
                    t += x * hs  # sharply as the cap closes, which a step's interpolant misses (1e-8 seen)
                    if h != h:
                        return t, STUCK
                    h = max(h, hs)  # the next phase starts at the step that found the event, not a sliver
                    break
                accept(y, f, y_new, stages)
                for w in range(events):
                    g_start[w] = g_end[w]
                t += hs
            if t > bound or h < MIN_STEP * longest:
                return t, STUCK
        if which < 0:
            return t, STUCK
        if which == SEPARATED:
            for i in range(size):  # element by element: a slice's copy compiles a shape check's message
                end[i] = y[i]
            return t, ENDED
        mode = _switch(which, y, p, n0, planar, mode)
    return t, STUCK


@compiled
def _solve_all(y, p, n0, planar, longest, atol, window, max_steps):
    """Each row of ``y`` (states at first touch) to its end: (end states, times, statuses)."""
    count = y.shape[0]
    ends, times, status = np.empty_like(y), np.empty(count), np.empty(count, dtype=np.int64)
    tolerance = np.empty(y.shape[1])
    for k in range(count):
        tolerance[:15] = atol[k, 0]
        tolerance[18] = atol[k, 1]
        times[k], status[k] = _solve_one(y[k].copy(), p[k], n0[k], planar, longest[k], tolerance, window[k],
                                         max_steps, ends[k])
    return ends, times, status


def solve(n, v_a, v_b, w_a, w_b, m_a, r_a, alpha_a, m_b, r_b, alpha_b, kn, kt, mu, gamma_n=0.0, gamma_t=0.0,
          planar: bool = False) -> list:
    """Each capped pair from first touch until it separates, as :func:`.pair_capped.solve` with Hooke's law.
    ``n``, ``v_a``, ``v_b``, ``w_a``, ``w_b``: (N, 3) arrays (n need not be unit); the spheres' properties
    and the law's coefficients (mu > 0): scalars or (N,) arrays."""
    if not np.all(np.asarray(mu) > 0.0):
        raise ValueError("the capped pair reference needs a cap > 0 (mu = 0 is the uncapped reference without a "
                         "tangential force)")
    first_use.once("capped pair batch")
    b = prepare(n, planar, v_a=v_a, v_b=v_b, w_a=w_a, w_b=w_b, m_a=m_a, r_a=r_a, alpha_a=alpha_a, m_b=m_b, r_b=r_b,
                alpha_b=alpha_b, kn=kn, kt=kt, mu=mu, gamma_n=gamma_n, gamma_t=gamma_t)
    kn, speed = b.c["kn"], np.abs(b.closing)
    force = b.c["mu"] * speed * np.sqrt(b.m_star * kn)  # pair_capped.solve's scales
    p = np.column_stack([b.p, b.c["mu"], b.m_star, force, 16.0 * kn * np.spacing(b.radsum), TURN_FLOOR * force, b.tau])
    atol = np.stack([b.atol, RTOL * 1e-12 * speed * np.sqrt(b.m_star / kn)], axis=1)  # the overlap's: of its depth
    y = np.concatenate([b.y, np.zeros((b.y.shape[0], 1))], axis=1)
    ends, times, status = _solve_all(y, p, b.n0, planar, b.longest, atol, b.window, MAX_STEPS)
    return finish(b, ends, times, status, pair_capped.solve, planar)


@first_use.example("capped pair batch", seconds=30)
def _example() -> None:
    """pair_exact's example pair under a cap, free and held."""
    solve(**example_batch(), mu=0.3)
    solve(**example_batch(), mu=0.3, planar=True)
