"""Claims about the frozen contact (Sec. 3, Eqs. 10-13) and its damped decay (Sec. 5)."""

from __future__ import annotations

import math

import numpy as np

from ...exact import linear
from ...model.contact import ContactModel
from .ledger import FROZEN_TOL, Claim, Runs, verdict


def frozen_mean_rolling(runs: Runs) -> Claim:
    model = ContactModel()
    w = math.sqrt(model.Q)
    _, t = runs.frozen("frozen-mean", model, z=0.1, v_t=1.0, omega=0.0, t_end=10.0)
    time = t["t"].to_numpy()
    slip = (t["v_t"] + t["r_omega"]).to_numpy()
    # slip = mean + a cos(w t) + b sin(w t): the mean without cutting the series at a period
    basis = np.column_stack([np.ones_like(time), np.cos(w * time), np.sin(w * time)])
    mean = float(np.linalg.lstsq(basis, slip, rcond=None)[0][0])
    c = Claim("frozen-mean", "the frozen oscillation is centred on the rolling state: mean(v_t + r omega) = 0",
              "Eq. 11", 0.0, mean, 0.0, runs=["frozen-mean"])
    c.verdict = verdict(0.0, mean, 0.0, 0.0, FROZEN_TOL)
    c.evidence = (f"centre of the LAMMPS slip oscillation (least squares over 10 time units, frequency sqrt(Q)): "
                  f"{mean:.1e}, for a slip amplitude of 1")
    return c


def _far_end_miss(vt: np.ndarray, rw: np.ndarray, vt0: float, rw0: float, alpha: float) -> float:
    """How far the trajectory's extent is from the segment between the start and Eq. 12's far end."""
    far_vt, far_rw = linear.frozen_extremes(vt0, rw0, alpha)
    return max(abs(vt.min() - min(vt0, far_vt)), abs(vt.max() - max(vt0, far_vt)),
               abs(rw.min() - min(rw0, far_rw)), abs(rw.max() - max(rw0, far_rw)))


def frozen_slope(runs: Runs) -> Claim:
    model = ContactModel()
    slopes, misses = [], []
    starts = (-1.0, 0.0, 1.0, 1.5)  # not 0.5: with r omega(0) = -0.5 that one rolls and never moves
    for vt0 in starts:
        _, t = runs.frozen(f"frozen-slope-{vt0:g}", model, z=0.1, v_t=vt0, omega=-0.5 / model.r, t_end=8.0)
        vt, rw = t["v_t"].to_numpy(), t["r_omega"].to_numpy()
        slopes.append(np.polyfit(rw, vt, 1)[0])
        misses.append(_far_end_miss(vt, rw, vt0, -0.5, model.alpha))
    slopes = np.array(slopes)
    c = Claim("frozen-slope", "frozen trajectories are straight lines of slope dv_t/d(r omega) = alpha = 2/5",
              "Eq. 13, Fig. 3", 0.4, float(slopes.mean()), model.alpha,
              runs=[f"frozen-slope-{v:g}" for v in starts])
    c.verdict = verdict(0.4, float(slopes[np.argmax(np.abs(slopes - 0.4))]), 0.4, 0.0, FROZEN_TOL)
    c.evidence = (f"least-squares slope of 4 LAMMPS trajectories (r omega(0) = -0.5): "
                  f"{', '.join(f'{s:.7f}' for s in slopes)}; the trajectories reach the end points of Eq. 12 "
                  f"within {max(misses):.1e}")
    return c


def _peaks(t: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Local maxima of a sampled curve, each refined by a parabola through its 3 samples."""
    i = np.flatnonzero((y[1:-1] > y[:-2]) & (y[1:-1] >= y[2:])) + 1
    y0, y1, y2 = y[i - 1], y[i], y[i + 1]
    shift = 0.5 * (y0 - y2) / (y0 - 2 * y1 + y2)
    h = t[1] - t[0]
    return np.column_stack([t[i] + shift * h, y1 - 0.25 * (y0 - y2) * shift])


def decay_rate(runs: Runs) -> Claim:
    gamma_t = 0.2
    model = ContactModel(gamma_t=gamma_t)
    dt = 2e-4  # first order in dt with damping: the fitted rate is good to ~1e-5 here
    _, t = runs.frozen("decay-rate", model, z=0.1, v_t=1.0, omega=1.0 / model.r, t_end=12.0, dt=dt, every=5)
    means = linear.frozen_means(1.0, 1.0, model.alpha)
    excursion = (t["v_t"] - means[0]).to_numpy()
    peaks = _peaks(t["t"].to_numpy(), np.abs(excursion))
    rate = -np.polyfit(peaks[:, 0], np.log(peaks[:, 1]), 1)[0]
    exact = linear.damping_rate(gamma_t, model.m, model.alpha)
    c = Claim("decay-rate", "with gamma_t > 0 the frozen oscillation decays as exp(-gamma_t t/m)",
              "Sec. 5, before Eq. 22", gamma_t / model.m, float(rate), exact, runs=["decay-rate"])
    c.verdict = verdict(gamma_t / model.m, float(rate), exact, 1e-6, 1e-3, approx_tol=0.02)
    c.evidence = (f"decay rate of the LAMMPS v_t excursion peaks (gamma_t = {gamma_t:g}): {rate:.5f}; "
                  f"exact zeta = gamma_t (1+alpha)/(2 alpha m) = {exact:.5f}; the paper's gamma_t/m = "
                  f"{gamma_t / model.m:.5f} is {exact / (gamma_t / model.m):.2f}x too slow for a solid sphere")
    return c
