"""The uncapped Hookean pair reference for many pairs at once: :func:`spinbounce.exact.pair_exact.solve`
vectorised over a batch.

The same equations (:func:`.pair_exact._rates`: Hooke's force, linear_history with its normal
component kept, both velocity dashpots, each sphere's lever arm r - delta/2), the same integrator
(scipy's DOP853 tableau, its error norm and its accept and reject rule, rtol 1e-12, each pair its own
step, absolute tolerance and longest step from :func:`.pair_exact.start`'s rules; the first step an
eighth of the longest, where scipy picks its own) and the same end (the centres' distance back to
r_a + r_b, as scipy's event finds it). Every pair advances in one numpy array with its own step;
the contact's end is located inside the step that crosses it by Newton's method on the step's
length, each trial a DOP853 step from the step's start, so the end state is as accurate as any
step. Measured against the scipy reference on random pairs (tests/test_pair_batch.py): within 1e-9 of
the speeds (about 1e-11 typically, 4e-10 for pairs closing at 1e-7 of their speed), at about 50
microseconds a pair. A pair the batch cannot carry to its end (:data:`CONTACT_TIMES`) is handed to
the scipy reference.

Laws on the contact radius (their rates are singular in time at touch and at the end), a Coulomb cap
and ``limit_damping`` with a normal dashpot (the normal force's turn) are not taken here:
:func:`solvable` says which laws are, and callers solve the rest one pair at a time.
"""

from __future__ import annotations

import numpy as np
from scipy.integrate import DOP853

from . import pair_exact
from .pair_exact import HOOKE, RTOL, PairOutcome, longest_step, pair_scales, tolerance_scale

__all__ = ["solve", "solvable", "CHUNK"]

#: Pairs integrated together: the stages of a chunk stay in the processor's cache.
CHUNK = 2048
#: scipy's DOP853: 12 stages, its 5th and 3rd order error estimates (13 entries: the last for the
#: step's end), and its step-size controller's constants.
_A, _B, _C, _E3, _E5 = DOP853.A, DOP853.B, DOP853.C, DOP853.E3, DOP853.E5
_STAGES = DOP853.n_stages
_EXPONENT = -1.0 / (DOP853.error_estimator_order + 1)
_SAFETY, _MIN_FACTOR, _MAX_FACTOR = 0.9, 0.2, 10.0
#: The tableau's nonzero entries, (stage, coefficient), of each stage's row, of B, E5 and E3: the
#: stages are combined by element-wise sums, not by BLAS, whose threads only contend on arrays this
#: small (measured 4x slower with another process busy on the second core).
_A_TERMS = [[(j, c) for j, c in enumerate(_A[s, :s]) if c != 0.0] for s in range(_STAGES)]
_B_TERMS, _E5_TERMS, _E3_TERMS = ([(j, c) for j, c in enumerate(row) if c != 0.0] for row in (_B, _E5, _E3))
#: A pair not separated within CONTACT_TIMES contact times (the scipy reference's bound), whose step
#: shrinks below MIN_STEP of its longest, or still in contact after MAX_STEPS steps of the batch is
#: solved by the scipy reference alone (a contact that ends within rounding of its start, a nearly
#: critical dashpot's slow exit): that answers it, or says why it cannot.
CONTACT_TIMES = 20.0
MIN_STEP = 1e-12
MAX_STEPS = 20_000
#: Newton iterations locating a contact's end inside its step; the end is found when the gap is
#: below END_GAP of r_a + r_b (rounding of the centres' distance) or the bracket below 1e-15 of the step.
MAX_ITERATIONS = 60
END_GAP = 4e-16


def solvable(law: dict, tensile: bool = True) -> bool:
    """Whether :func:`solve` takes ``law`` (the keyword arguments of :func:`.pair_exact.solve` beyond
    the pair): Hooke's shape (:data:`.pair_exact.HOOKE`), and no turn of the normal force to cut."""
    shape_is_hooke = all(law.get(key, value) == value for key, value in HOOKE.items())
    return shape_is_hooke and (tensile or law.get("gamma_n", 0.0) == 0.0)


def _cross(a, b):
    """a x b of (3, M) arrays."""
    return np.stack([a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]])


def _rates(y, p, planar: bool):
    """d(state)/dt of (18, M) states (d, v_a, v_b, w_a, w_b, xi): :func:`.pair_exact._rates` for Hooke's law."""
    d, v_a, v_b, w_a, w_b, xi = y[0:3], y[3:6], y[6:9], y[9:12], y[12:15], y[15:18]
    if planar:
        n = p["n0"]
        delta = p["radsum"] - np.einsum("im,im->m", d, n)
        lever_a, lever_b = p["r_a"], p["r_b"]
    else:
        dist = np.sqrt(np.einsum("im,im->m", d, d))
        n = d / dist
        delta = p["radsum"] - dist
        lever_a, lever_b = p["r_a"] - 0.5 * delta, p["r_b"] - 0.5 * delta
    v = v_a - v_b
    v_n = np.einsum("im,im->m", v, n)
    slip = v - v_n * n - _cross(p["r_a"] * w_a + p["r_b"] * w_b, n)
    f_t = -p["kt"] * xi - p["gamma_t"] * slip
    force = (p["kn"] * delta - p["gamma_n"] * v_n) * n + f_t
    arm = _cross(f_t, n)
    return np.concatenate([v, force / p["m_a"], -force / p["m_b"], lever_a * arm / p["i_a"],
                           lever_b * arm / p["i_b"], slip])


def _gap(y, p, planar: bool):
    d = y[0:3]
    dist = np.einsum("im,im->m", d, p["n0"]) if planar else np.sqrt(np.einsum("im,im->m", d, d))
    return dist - p["radsum"]


def _combine(terms, stages):
    """sum of coefficient * stages[j] over ``terms``, element-wise."""
    (j, c), *rest = terms
    out, scratch = c * stages[j], np.empty_like(stages[j])
    for j, c in rest:
        out += np.multiply(stages[j], c, out=scratch)
    return out


def _step(y, f, h, p, planar: bool):
    """One DOP853 step of each column: (state at t + h, its rates, the stages)."""
    stages = np.empty((_STAGES + 1,) + y.shape)
    stages[0] = f
    for s in range(1, _STAGES):
        stages[s] = _rates(y + h * _combine(_A_TERMS[s], stages), p, planar)
    y_new = y + h * _combine(_B_TERMS, stages)
    stages[_STAGES] = _rates(y_new, p, planar)
    return y_new, stages[_STAGES], stages


def _error_norm(stages, h, scale):
    """scipy DOP853's error norm, per column."""
    err5 = _combine(_E5_TERMS, stages) / scale
    err3 = _combine(_E3_TERMS, stages) / scale
    e5, e3 = np.sum(err5 * err5, axis=0), np.sum(err3 * err3, axis=0)
    denom = np.sqrt((e5 + 0.01 * e3) * scale.shape[0])
    return np.divide(np.abs(h) * e5, denom, out=np.zeros_like(e5), where=denom > 0.0)


def _subset(p: dict, idx) -> dict:
    return {k: (v[..., idx] if isinstance(v, np.ndarray) else v) for k, v in p.items()}


def _integrate(y, p, longest, atol, planar: bool, t_bound):
    """Each column from first touch to the step that carries it past the end: (start of that step, its
    length, the time there, and which columns it did not carry there: past ``t_bound``, a step shrunk
    below MIN_STEP of the longest, or MAX_STEPS taken; :func:`_solve_chunk` solves those one by one)."""
    m = y.shape[1]
    t, h = np.zeros(m), longest / 8.0
    f = _rates(y, p, planar)
    rejected, stuck = np.zeros(m, dtype=bool), np.zeros(m, dtype=bool)
    last = (np.empty_like(y), np.empty(m), np.empty(m))
    active = np.arange(m)
    for _ in range(MAX_STEPS):
        if active.size == 0:
            break
        q = _subset(p, active)
        ya, hs = y[:, active], np.fmin(h[active], longest[active])
        y_new, f_new, stages = _step(ya, f[:, active], hs, q, planar)
        scale = atol[active] + np.maximum(np.abs(ya), np.abs(y_new)) * RTOL
        err = _error_norm(stages, hs, scale)
        ok = err < 1.0  # NaN is not: its step shrinks until MIN_STEP gives the pair up
        grow = np.where(err == 0.0, _MAX_FACTOR, _SAFETY * np.power(np.where(err == 0.0, 1.0, err), _EXPONENT))
        factor = np.where(ok, np.fmin(_MAX_FACTOR, grow), np.fmax(_MIN_FACTOR, grow))
        factor = np.where(ok & rejected[active], np.fmin(1.0, factor), factor)
        h[active] = hs * factor
        rejected[active] = ~ok
        crossed = ok & (_gap(y_new, q, planar) >= 0.0)  # scipy's event: the gap back to zero or above
        ended = active[crossed]
        last[0][:, ended], last[1][ended], last[2][ended] = ya[:, crossed], hs[crossed], t[ended]
        stepped = ok & ~crossed
        moved = active[stepped]
        y[:, moved], f[:, moved], t[moved] = y_new[:, stepped], f_new[:, stepped], t[moved] + hs[stepped]
        lost = ~crossed & ((t[active] > t_bound[active]) | (h[active] < MIN_STEP * longest[active]))
        stuck[active[lost]] = True
        active = active[~crossed & ~lost]
    stuck[active] = True
    return last[0], last[1], last[2], stuck


def _locate_end(y0, h, p, planar: bool):
    """The state and the time into the step where each column's gap returns to zero: Newton's method on
    the step's length (the gap's rate is the relative velocity along d/|d|), kept inside the bracket
    the sign of the gap gives (bisection where Newton would leave it)."""
    f0 = _rates(y0, p, planar)
    lo, hi = np.zeros_like(h), h.copy()
    s = 0.5 * h
    end, at = y0.copy(), h.copy()
    todo = np.arange(h.size)
    for _ in range(MAX_ITERATIONS):
        if todo.size == 0:
            return end, at
        q = _subset(p, todo)
        y_s = _step(y0[:, todo], f0[:, todo], s[todo], q, planar)[0]
        g = _gap(y_s, q, planar)
        end[:, todo], at[todo] = y_s, s[todo]
        upper = g > 0.0
        lo[todo], hi[todo] = np.where(upper, lo[todo], s[todo]), np.where(upper, s[todo], hi[todo])
        newton = s[todo] - g / _gap_rate(y_s, q, planar)
        inside = (newton > lo[todo]) & (newton < hi[todo])
        s[todo] = np.where(inside, newton, 0.5 * (lo[todo] + hi[todo]))
        done = (np.abs(g) <= END_GAP * q["radsum"]) | (hi[todo] - lo[todo] <= 1e-15 * h[todo])
        todo = todo[~done]
    raise RuntimeError(f"the end of {todo.size} contact(s) was not located within {MAX_ITERATIONS} iterations")


def _outcomes(end, t, n0) -> list[PairOutcome]:
    """:func:`.pair_exact.outcome` of each column of ``end`` (states at separation, times ``t``): the
    turns computed together, each outcome's vectors read-only views of one array."""
    rows = np.ascontiguousarray(end[:15].T).reshape(-1, 5, 3)
    rows.setflags(write=False)
    d_end = rows[:, 0]
    cosine = np.einsum("mi,mi->m", d_end, n0) / np.sqrt(np.einsum("mi,mi->m", d_end, d_end))
    turns = np.arccos(np.clip(cosine, -1.0, 1.0)).tolist()
    return [PairOutcome(v_a=row[1], v_b=row[2], w_a=row[3], w_b=row[4], contact_time=time, turn=turn, d_end=row[0])
            for row, time, turn in zip(rows, t.tolist(), turns, strict=True)]


def _gap_rate(y, p, planar: bool):
    """d(gap)/dt: the relative velocity along n0 (planar) or along d/|d|."""
    d, v = y[0:3], y[3:6] - y[6:9]
    if planar:
        return np.einsum("im,im->m", v, p["n0"])
    return np.einsum("im,im->m", d, v) / np.sqrt(np.einsum("im,im->m", d, d))


def solve(n, v_a, v_b, w_a, w_b, m_a, r_a, alpha_a, m_b, r_b, alpha_b, kn, kt, gamma_n=0.0, gamma_t=0.0,
          planar: bool = False) -> list[PairOutcome]:
    """Each pair from first touch until it separates, as :func:`.pair_exact.solve` with Hooke's law.

    ``n``, ``v_a``, ``v_b``, ``w_a``, ``w_b``: (N, 3) arrays (n need not be unit); the spheres'
    properties and the law's coefficients: scalars or (N,) arrays."""
    n = np.atleast_2d(np.asarray(n, dtype=float))
    count = n.shape[0]
    columns = {k: np.broadcast_to(np.asarray(v, dtype=float), (count,) if np.ndim(v) < 2 else (count, 3))
               for k, v in dict(v_a=v_a, v_b=v_b, w_a=w_a, w_b=w_b, m_a=m_a, r_a=r_a, alpha_a=alpha_a, m_b=m_b,
                                r_b=r_b, alpha_b=alpha_b, kn=kn, kt=kt, gamma_n=gamma_n, gamma_t=gamma_t).items()}
    out: list[PairOutcome] = []
    for first in range(0, count, CHUNK):
        part = slice(first, min(count, first + CHUNK))
        out.extend(_solve_chunk(n[part], {k: v[part] for k, v in columns.items()}, planar))
    return out


def _solve_chunk(n, c: dict, planar: bool) -> list[PairOutcome]:
    n0 = n / np.linalg.norm(n, axis=1, keepdims=True)
    v_rel = c["v_a"] - c["v_b"]
    if np.any(np.einsum("mi,mi->m", v_rel, n0) >= 0.0):
        raise ValueError("the spheres must approach at first touch: (v_a - v_b).n < 0")
    radsum = c["r_a"] + c["r_b"]
    p = {"n0": n0.T, "radsum": radsum, "r_a": c["r_a"], "r_b": c["r_b"], "m_a": c["m_a"], "m_b": c["m_b"],
         "i_a": c["alpha_a"] * c["m_a"] * c["r_a"] ** 2, "i_b": c["alpha_b"] * c["m_b"] * c["r_b"] ** 2,
         "kn": c["kn"], "kt": c["kt"], "gamma_n": c["gamma_n"], "gamma_t": c["gamma_t"],
         "r_eff": c["r_a"] * c["r_b"] / radsum, "K": c["kn"], **HOOKE}
    m_star = c["m_a"] * c["m_b"] / (c["m_a"] + c["m_b"])
    tau, fast = pair_scales(p, v_rel, n0, m_star)
    longest = tau / 8.0 if planar else longest_step(tau, v_rel, n0, radsum)
    atol = tolerance_scale(RTOL, v_rel, c["w_a"], c["w_b"], radsum, fast)
    y = np.concatenate([(radsum[:, None] * n0), c["v_a"], c["v_b"], c["w_a"], c["w_b"], np.zeros_like(n0)],
                       axis=1).T.copy()
    start, h, t, stuck = _integrate(y, p, longest, atol, planar, CONTACT_TIMES * tau)
    done = np.flatnonzero(~stuck)
    end, into = _locate_end(start[:, done], h[done], _subset(p, done), planar)
    out: list = [None] * n0.shape[0]
    for k, found in zip(done, _outcomes(end, t[done] + into, n0[done]), strict=True):
        out[k] = found
    for k in np.flatnonzero(stuck):  # scipy's reference, one pair: its answer, or its own error
        out[k] = pair_exact.solve(n0[k], **{name: value[k] for name, value in c.items()}, planar=planar)
    return out
