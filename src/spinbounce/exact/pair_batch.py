"""The uncapped Hookean pair reference for many pairs at once: :func:`spinbounce.exact.pair_exact.solve`
compiled (numba) and run over a batch.

The same equations (:func:`.pair_exact._rates`: Hooke's force, linear_history with its normal
component kept, both velocity dashpots, each sphere's lever arm r - delta/2), the same integrator
(scipy's DOP853 tableau, error norm, accept and reject rule and dense output, :mod:`.dop853`; rtol
1e-12, each pair its own step, absolute tolerance and longest step from :func:`.pair_exact.start`'s
rules; the first step an eighth of the longest, where scipy picks its own) and the same end (the
centres' distance back to r_a + r_b, located on the step's dense output as scipy's event is). Each
pair is integrated on its own in compiled code: no numpy call per step, and no reference count in the
step and the rates (:func:`.vec3.kernel`: they took half the time). Measured against the scipy
reference on random pairs (tests/test_pair_batch.py): within 1e-11 of the speeds typically, always
within 1e-9; a sweep's pair takes 13.7 steps, a random 3-D pair 18.6 (``spinbounce bench``: pairs/s). A
pair the batch cannot carry to its end (its window, :func:`.pair_exact.window`) is handed to the scipy
reference.

Laws on the contact radius (their rates are singular in time at touch and at the end), a Coulomb cap
and ``limit_damping`` with a normal dashpot (the normal force's turn) are not taken here:
:func:`solvable` says which laws are, and callers solve the rest one pair at a time.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from . import first_use, pair_exact
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
from .pair_exact import HOOKE, PairOutcome, longest_step, pair_scales, tolerance_scale
from .vec3 import compiled, kernel

__all__ = ["solve", "solvable", "Batch", "prepare", "finish", "example_batch"]

#: A pair not separated within the scipy reference's window (:func:`.pair_exact.window`), whose step
#: shrinks below MIN_STEP of its longest, or still in contact after MAX_STEPS steps is solved by the
#: scipy reference alone (a contact that ends within rounding of its start, a nearly critical
#: dashpot's slow exit): that answers it, or says why it cannot.
MIN_STEP = 1e-12
MAX_STEPS = 20_000
#: Newton iterations locating a contact's end inside its step; the end is found when the gap is
#: below END_GAP of r_a + r_b (rounding of the centres' distance) or the bracket below 1e-15 of the step.
MAX_ITERATIONS = 60
END_GAP = 4e-16
#: The columns of a pair's coefficients (``p``) in the compiled functions: the radii, the inverse masses and
#: moments of inertia, the law's coefficients, r_a + r_b.
R_A, R_B, M_A, M_B, I_A, I_B, KN, KT, GAMMA_N, GAMMA_T, RADSUM = range(11)
#: What :func:`_solve_all` says of a pair: carried to its end, or left to the scipy reference.
ENDED, STUCK = 0, 1


def solvable(law: dict, tensile: bool = True) -> bool:
    """Whether :func:`solve` takes ``law`` (the keyword arguments of :func:`.pair_exact.solve` beyond
    the pair): Hooke's shape (:data:`.pair_exact.HOOKE`), and no turn of the normal force to cut."""
    shape_is_hooke = all(law.get(key, value) == value for key, value in HOOKE.items())
    return shape_is_hooke and (tensile or law.get("gamma_n", 0.0) == 0.0)


@kernel
def _rates(y, p, n0, planar, mode, out):
    """d(state)/dt of a state (d, v_a, v_b, w_a, w_b, xi) into ``out``: :func:`.pair_exact._rates` for
    Hooke's law (``mode``: unused, no cap), written out in components (no array is made per call)."""
    if planar:
        nx, ny, nz = n0[0], n0[1], n0[2]
        delta = p[RADSUM] - (y[0] * nx + y[1] * ny + y[2] * nz)
        lever_a, lever_b = p[R_A], p[R_B]
    else:
        dist = np.sqrt(y[0] * y[0] + y[1] * y[1] + y[2] * y[2])
        inverse = 1.0 / dist
        nx, ny, nz = y[0] * inverse, y[1] * inverse, y[2] * inverse
        delta = p[RADSUM] - dist
        lever_a, lever_b = p[R_A] - 0.5 * delta, p[R_B] - 0.5 * delta
    vx, vy, vz = y[3] - y[6], y[4] - y[7], y[5] - y[8]
    v_n = vx * nx + vy * ny + vz * nz
    sx = p[R_A] * y[9] + p[R_B] * y[12]
    sy = p[R_A] * y[10] + p[R_B] * y[13]
    sz = p[R_A] * y[11] + p[R_B] * y[14]
    ux = vx - v_n * nx - (sy * nz - sz * ny)  # the slip rate v - (v.n) n - spin x n
    uy = vy - v_n * ny - (sz * nx - sx * nz)
    uz = vz - v_n * nz - (sx * ny - sy * nx)
    tx = -p[KT] * y[15] - p[GAMMA_T] * ux
    ty = -p[KT] * y[16] - p[GAMMA_T] * uy
    tz = -p[KT] * y[17] - p[GAMMA_T] * uz
    f_n = p[KN] * delta - p[GAMMA_N] * v_n
    fx, fy, fz = f_n * nx + tx, f_n * ny + ty, f_n * nz + tz
    ax, ay, az = ty * nz - tz * ny, tz * nx - tx * nz, tx * ny - ty * nx  # f_t x n
    out[0], out[1], out[2] = vx, vy, vz
    a, b = p[M_A], -p[M_B]  # their inverses
    out[3], out[4], out[5] = fx * a, fy * a, fz * a
    out[6], out[7], out[8] = fx * b, fy * b, fz * b
    a, b = lever_a * p[I_A], lever_b * p[I_B]
    out[9], out[10], out[11] = a * ax, a * ay, a * az
    out[12], out[13], out[14] = b * ax, b * ay, b * az
    out[15], out[16], out[17] = ux, uy, uz


_step, _dense = make_step(_rates), make_dense(_rates)


@kernel
def _gap(y, p, n0, planar):
    if planar:
        return y[0] * n0[0] + y[1] * n0[1] + y[2] * n0[2] - p[RADSUM]
    return np.sqrt(y[0] * y[0] + y[1] * y[1] + y[2] * y[2]) - p[RADSUM]


@kernel
def _gap_rate(y, n0, planar):
    """d(gap)/dt: the relative velocity along n0 (planar) or along d/|d|."""
    vx, vy, vz = y[3] - y[6], y[4] - y[7], y[5] - y[8]
    if planar:
        return vx * n0[0] + vy * n0[1] + vz * n0[2]
    return (y[0] * vx + y[1] * vy + y[2] * vz) / np.sqrt(y[0] * y[0] + y[1] * y[1] + y[2] * y[2])


@kernel
def _locate_end(y0, g0, g1, h, F, p, n0, planar, end):
    """The fraction of the step from ``y0`` (gap ``g0`` < 0 there, ``g1`` >= 0 at its end, dense output
    ``F``) where the gap returns to zero, its state in ``end``: Newton's method on the interpolant (the
    gap's rate is the relative velocity along d/|d|) from the gap's linear interpolation, kept inside the
    bracket the sign of the gap gives (bisection where Newton would leave it); NaN if not located within
    MAX_ITERATIONS."""
    lo, hi = 0.0, 1.0
    x = g0 / (g0 - g1) if g1 > g0 else 0.5
    for _ in range(MAX_ITERATIONS):
        interpolate(F, y0, x, end)
        g = _gap(end, p, n0, planar)
        at = x
        if g > 0.0:
            hi = x
        else:
            lo = x
        newton = x - g / (h * _gap_rate(end, n0, planar))
        x = newton if lo < newton < hi else 0.5 * (lo + hi)
        if abs(g) <= END_GAP * p[RADSUM] or hi - lo <= 1e-15:
            return at
    return np.nan


@compiled
def _solve_one(y, p, n0, planar, longest, atol, t_bound, max_steps, end):
    """One pair from first touch (state ``y``, changed) to its end (state into ``end``) within ``max_steps``
    steps: (time, status)."""
    stages, scratch = new_scratch(y.size)
    y_new, f, F = np.empty(y.size), np.empty(y.size), np.empty((INTERPOLATOR_POWER, y.size))
    _rates(y, p, n0, planar, 0, f)
    t, h, rejected = 0.0, longest / 8.0, False
    for _ in range(max_steps):
        hs = min(h, longest)
        _step(y, f, hs, p, n0, planar, 0, stages, scratch, y_new)
        err = error_norm(stages, hs, y, y_new, atol, RTOL)
        ok = err < 1.0
        h = hs * step_factor(err, rejected)
        rejected = not ok
        if ok:
            g = _gap(y_new, p, n0, planar)
            if g >= 0.0:  # scipy's event: the gap back to zero or above, located on the step's dense output
                _dense(y, y_new, hs, p, n0, planar, 0, stages, scratch, F)
                into = _locate_end(y, _gap(y, p, n0, planar), g, hs, F, p, n0, planar, end)
                return t + into * hs, (ENDED if into == into else STUCK)
            accept(y, f, y_new, stages)
            t += hs
        if t > t_bound or h < MIN_STEP * longest:
            return t, STUCK
    return t, STUCK


@compiled
def _solve_all(y, p, n0, planar, longest, atol, t_bound, max_steps):
    """Each row of ``y`` (states at first touch) to its end: (end states, times, statuses)."""
    count = y.shape[0]
    ends, times, status = np.empty_like(y), np.empty(count), np.empty(count, dtype=np.int64)
    tolerance = np.empty(y.shape[1])
    for k in range(count):
        tolerance[:] = atol[k]
        times[k], status[k] = _solve_one(y[k].copy(), p[k], n0[k], planar, longest[k], tolerance, t_bound[k],
                                         max_steps, ends[k])
    return ends, times, status


def _outcomes(end, t, n0) -> list[PairOutcome]:
    """:func:`.pair_exact.outcome` of each row of ``end`` (states at separation, times ``t``): the
    turns computed together, each outcome's vectors read-only views of one array."""
    rows = np.ascontiguousarray(end[:, :15]).reshape(-1, 5, 3)
    rows.setflags(write=False)
    d_end = rows[:, 0]
    cosine = np.einsum("mi,mi->m", d_end, n0) / np.sqrt(np.einsum("mi,mi->m", d_end, d_end))
    turns = np.arccos(np.clip(cosine, -1.0, 1.0)).tolist()
    return [PairOutcome(row[1], row[2], row[3], row[4], time, turn, row[0])
            for row, time, turn in zip(rows, t.tolist(), turns, strict=True)]


class Batch(NamedTuple):
    """What both compiled pair references start from: the columns (``c``, each (N,) or (N, 3)), unit n0,
    v_a - v_b and its closing speed along n0, r_a + r_b, the reduced mass, the coefficients ``p`` (the
    columns R_A to RADSUM), contact times, longest steps, absolute tolerances of the spheres' state,
    windows and the states (d, v_a, v_b, w_a, w_b, 0) at first touch."""

    c: dict
    n0: np.ndarray
    v_rel: np.ndarray
    closing: np.ndarray
    radsum: np.ndarray
    m_star: np.ndarray
    p: np.ndarray
    tau: np.ndarray
    longest: np.ndarray
    atol: np.ndarray
    window: np.ndarray
    y: np.ndarray


def prepare(n, planar: bool, **columns) -> Batch:
    """A :class:`Batch` of the pairs ``n`` (N, 3, need not be unit) with ``columns`` (the keyword arguments
    of :func:`solve` beyond n: scalars, (N,) or (N, 3) arrays), their rules :func:`.pair_exact.start`'s."""
    n = np.atleast_2d(np.asarray(n, dtype=float))
    count = n.shape[0]
    c = {k: np.broadcast_to(np.asarray(v, dtype=float), (count,) if np.ndim(v) < 2 else (count, 3))
         for k, v in columns.items()}
    n0 = n / np.linalg.norm(n, axis=1, keepdims=True)
    v_rel = c["v_a"] - c["v_b"]
    closing = np.einsum("mi,mi->m", v_rel, n0)
    if np.any(closing >= 0.0):
        raise ValueError("the spheres must approach at first touch: (v_a - v_b).n < 0")
    radsum = c["r_a"] + c["r_b"]
    i_a, i_b = c["alpha_a"] * c["m_a"] * c["r_a"] ** 2, c["alpha_b"] * c["m_b"] * c["r_b"] ** 2
    m_star = c["m_a"] * c["m_b"] / (c["m_a"] + c["m_b"])
    p = np.stack([c["r_a"], c["r_b"], 1.0 / c["m_a"], 1.0 / c["m_b"], 1.0 / i_a, 1.0 / i_b, c["kn"], c["kt"],
                  c["gamma_n"], c["gamma_t"], radsum], axis=1)
    law = {"K": c["kn"], "kt": c["kt"], "r_eff": c["r_a"] * c["r_b"] / radsum, "r_a": c["r_a"], "r_b": c["r_b"],
           "m_a": c["m_a"], "m_b": c["m_b"], "i_a": i_a, "i_b": i_b, **HOOKE}
    tau, fast = pair_scales(law, v_rel, n0, m_star)
    tau = np.broadcast_to(tau, (count,))

    def column(x):
        return np.ascontiguousarray(np.broadcast_to(x, (count,)), dtype=float)

    longest = column(tau / 8.0 if planar else longest_step(tau, v_rel, n0, radsum))
    atol = column(tolerance_scale(RTOL, v_rel, c["w_a"], c["w_b"], radsum, fast))
    window = column(pair_exact.window(tau, c["m_a"], c["m_b"], c["kn"], c["gamma_n"]))
    y = np.concatenate([radsum[:, None] * n0, c["v_a"], c["v_b"], c["w_a"], c["w_b"], np.zeros_like(n0)], axis=1)
    return Batch(c, n0, v_rel, closing, radsum, m_star, p, tau, longest, atol, window, y)


def finish(batch: Batch, ends, times, status, one_pair, planar: bool) -> list[PairOutcome]:
    """The outcomes of the pairs the compiled reference ended, and ``one_pair`` (a scipy reference) of
    the others: its answer, or its own error."""
    out: list = [None] * batch.n0.shape[0]
    done = np.flatnonzero(status == ENDED)
    for k, found in zip(done, _outcomes(ends[done], times[done], batch.n0[done]), strict=True):
        out[k] = found
    for k in np.flatnonzero(status != ENDED):
        out[k] = one_pair(batch.n0[k], **{name: value[k] for name, value in batch.c.items()}, planar=planar)
    return out


def solve(n, v_a, v_b, w_a, w_b, m_a, r_a, alpha_a, m_b, r_b, alpha_b, kn, kt, gamma_n=0.0, gamma_t=0.0,
          planar: bool = False) -> list[PairOutcome]:
    """Each pair from first touch until it separates, as :func:`.pair_exact.solve` with Hooke's law.

    ``n``, ``v_a``, ``v_b``, ``w_a``, ``w_b``: (N, 3) arrays (n need not be unit); the spheres'
    properties and the law's coefficients: scalars or (N,) arrays."""
    first_use.once("pair batch")
    b = prepare(n, planar, v_a=v_a, v_b=v_b, w_a=w_a, w_b=w_b, m_a=m_a, r_a=r_a, alpha_a=alpha_a, m_b=m_b, r_b=r_b,
                alpha_b=alpha_b, kn=kn, kt=kt, gamma_n=gamma_n, gamma_t=gamma_t)
    ends, times, status = _solve_all(b.y, b.p, b.n0, planar, b.longest, b.atol, b.window, MAX_STEPS)
    return finish(b, ends, times, status, pair_exact.solve, planar)


def example_batch() -> dict:
    """:data:`.pair_exact.EXAMPLE` as a batch of one pair (the compiled batches' examples)."""
    return {k: [v] if isinstance(v, tuple) else v for k, v in pair_exact.EXAMPLE.items()}


@first_use.example("pair batch", seconds=17)
def _example() -> None:
    """pair_exact's example pair, free and held."""
    solve(**example_batch())
    solve(**example_batch(), planar=True)
