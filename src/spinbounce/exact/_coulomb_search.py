"""Vectorised event location for :mod:`.coulomb`: the first downward zero of a switching
function, one per sphere, and safeguarded Newton to machine precision.

A switching function f (per sphere) is known on a shared time grid and, exactly, at any
time. Its first downward zero after a sphere's start lies in the first grid interval
whose right end is below zero, or in an earlier interval where f dips below zero between
two non-negative ends. Such a dip needs a local minimum (f' from - to +) whose value a
parabola through the ends' slopes puts near zero; only those intervals are resolved
exactly (the minimum by Newton on f'), the rest cannot dip: on a grid of 0.2 over the
fastest rate the parabola misses the minimum by far less than the margin used.
"""

from __future__ import annotations

import numpy as np

__all__ = ["first_crossing", "root"]

#: Grid columns evaluated at a time for the spheres still searching.
CHUNK = 8
#: A local minimum is resolved exactly when the parabola puts it below this share of
#: Delta t (|f'_left| + |f'_right|): the parabola's error is about (rate Delta t)/6 = 3% of that.
DIP_MARGIN = 0.25
#: Newton or bisection steps; bisection alone reaches machine precision in ~ 55.
ITERATIONS = 100


def root(fun, lo, hi, value_lo, value_hi, scale: float):
    """Root of fun in [lo, hi], per element, with value(lo) >= 0 > value(hi).

    ``fun(which, x)`` gives (value, slope) of the elements ``which`` at x. Newton from the
    secant through the ends, bisecting whenever a step would leave the bracket; an element
    stops once its step is below 64 ulp of the time scale (Newton's next step would be
    below rounding), so each iteration works only on the elements still moving.
    """
    lo, hi = np.array(lo, dtype=float), np.array(hi, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        share = value_lo / (value_lo - value_hi)
    x = lo + np.where((share > 0.0) & (share < 1.0), share, 0.5) * (hi - lo)
    tol = 64.0 * np.finfo(float).eps * scale
    moving = np.arange(x.size)
    for _ in range(ITERATIONS):
        if not moving.size:
            break
        xm, lm, hm = x[moving], lo[moving], hi[moving]
        value, slope = fun(moving, xm)
        above = value >= 0.0
        lm, hm = np.where(above, xm, lm), np.where(above, hm, xm)
        with np.errstate(divide="ignore", invalid="ignore"):
            newton = xm - value / slope
        following = np.where((newton > lm) & (newton < hm), newton, 0.5 * (lm + hm))
        settled = (np.abs(following - xm) <= tol) | (value == 0.0) | (hm - lm <= tol)
        x[moving], lo[moving], hi[moving] = np.where(value == 0.0, xm, following), lm, hm
        moving = moving[~settled]
    return x


def first_crossing(times, last, k0, t_s, f_s, d_s, noise, on_grid, exact, scale):
    """(lo, hi, f_lo, f_hi): brackets of each sphere's first downward zero of f + noise after
    t_s, and f + noise at their ends.

    ``times(rows, k)``: the grid's times (indices 0 to ``last``, t_s before the last);
    k0: each sphere's first grid index after t_s;
    f_s, d_s: f + noise and f' at t_s; ``on_grid(rows, offsets, k)`` gives (f, f') at grid
    indices k = k0[rows] + offsets; ``exact(rows, t)`` gives (f + noise, f', f'') at
    times t; ``scale``: the time scale, for the roots' tolerance. hi is NaN where f stays
    above -noise to the grid's end.
    """
    lo, hi, f_lo, f_hi = (np.full(k0.shape, np.nan) for _ in range(4))
    pending = np.arange(k0.size)
    t_l, f_l, d_l = t_s, f_s, d_s
    base = 0
    while pending.size:
        offsets = np.minimum(base + np.arange(CHUNK), last)
        k = k0[pending, None] + base + np.arange(CHUNK)
        valid = k <= last
        k = np.minimum(k, last)
        f, d = on_grid(pending, offsets, k)
        f = f + noise[pending, None]
        f_left = np.column_stack([f_l, f[:, :-1]])
        d_left = np.column_stack([d_l, d[:, :-1]])
        t_right = times(pending, k)
        t_left = np.column_stack([t_l, t_right[:, :-1]])
        crossing = f < 0.0
        dip, dip_value = _dips(exact, pending, valid & ~crossing, t_left, t_right, f_left, f,
                               d_left, d, scale)
        is_dip = np.isfinite(dip)
        event = valid & (crossing | is_dip)
        found = event.any(axis=1)
        first = np.argmax(event, axis=1)
        rows = np.flatnonzero(found)
        col = first[rows]
        at = pending[rows]
        lo[at], f_lo[at] = t_left[rows, col], f_left[rows, col]
        hi[at] = np.where(is_dip[rows, col], dip[rows, col], t_right[rows, col])
        f_hi[at] = np.where(is_dip[rows, col], dip_value[rows, col], f[rows, col])
        going = ~found & valid[:, -1]
        t_l, f_l, d_l = t_right[going, -1], f[going, -1], d[going, -1]
        pending = pending[going]
        base += CHUNK
    return lo, hi, f_lo, f_hi


def _dips(exact, pending, allowed, t_left, t_right, f_left, f, d_left, d, scale):
    """Where f dips below zero inside a grid interval: the time it is lowest (else NaN) and
    f + noise there."""
    candidate = allowed & (f_left >= 0.0) & (d_left < 0.0) & (d > 0.0)
    out, out_value = np.full(f.shape, np.nan), np.full(f.shape, np.nan)
    if not candidate.any():
        return out, out_value
    step = t_right - t_left
    with np.errstate(divide="ignore", invalid="ignore"):
        curvature = (d - d_left) / step
        lowest = np.minimum(f_left - d_left**2 / (2.0 * curvature), f - d**2 / (2.0 * curvature))
    candidate &= lowest < DIP_MARGIN * step * (np.abs(d_left) + np.abs(d))
    r, c = np.nonzero(candidate)
    if r.size:
        rows = pending[r]

        def slope(which, x):  # the minimum is the root of -f' (f' < 0 at its left, > 0 at its right)
            _, d1, d2 = exact(rows[which], x)
            return -d1, -d2

        t_min = root(slope, t_left[r, c], t_right[r, c], -d_left[r, c], -d[r, c], scale)
        value = exact(rows, t_min)[0]
        below = value < 0.0
        out[r[below], c[below]] = t_min[below]
        out_value[r[below], c[below]] = value[below]
    return out, out_value
