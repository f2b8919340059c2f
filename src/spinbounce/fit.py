"""Least-squares scattering matrices from sweep results, beside the theory's.

For each model group: the 3x3 matrix M (6x6 for a 3-D sweep) with final = M @ initial over all its collisions
(states (v_n, v_t, r omega)), each element's standard error, and Omega fitted from Eq. 19
(Delta v_t = alpha Omega/(1+alpha) u_dot(0), r Delta omega = Omega/(1+alpha) u_dot(0)).
"""

from __future__ import annotations

import math

from pathlib import Path

import numpy as np
import pandas as pd

from . import theory
from .compare import STATE, STATE_3D
from .records import write_atomic_with

__all__ = ["GROUP_KEYS", "fit_matrix", "fit_omega", "fit_groups", "plot_groups"]

GROUP_KEYS = ["m", "r", "alpha", "kn", "kt", "gamma_n", "gamma_t", "mu", "dt"]


def fit_matrix(initial: np.ndarray, final: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Least squares final ~ initial @ M.T; returns (M, standard errors of M, residuals)."""
    coef, *_ = np.linalg.lstsq(initial, final, rcond=None)
    residuals = final - initial @ coef
    dof = max(len(initial) - initial.shape[1], 1)
    sigma2 = (residuals**2).sum(axis=0) / dof  # one variance per output row of M
    cov = np.linalg.inv(initial.T @ initial)
    stderr = np.sqrt(np.outer(sigma2, np.diag(cov)))
    return coef.T, stderr, residuals


def fit_omega(initial: np.ndarray, final: np.ndarray, alpha: float) -> tuple[float, float]:
    """Omega from Eq. 19 by least squares over both tangential rows; (Omega, its standard error)."""
    slip = initial[:, 1] + initial[:, 2]
    x = np.concatenate([alpha / (1 + alpha) * slip, slip / (1 + alpha)])
    y = np.concatenate([final[:, 1] - initial[:, 1], final[:, 2] - initial[:, 2]])
    xx = float(x @ x)
    if xx == 0.0:
        return math.nan, math.nan
    omega = float(x @ y) / xx
    dof = max(len(x) - 1, 1)
    return omega, math.sqrt(float(((y - omega * x) ** 2).sum()) / dof / xx)


def fit_groups(rows: pd.DataFrame) -> list[dict]:
    """One fit per distinct model group in a sweep's rows."""
    out = []
    keys = [k for k in GROUP_KEYS if k in rows]
    for values, group in rows.groupby(keys, dropna=False, sort=True):
        params = dict(zip(keys, values, strict=True))
        names = STATE_3D if f"{STATE_3D[-1]}_0" in group else STATE  # a 3-D sweep fits the 6x6 map
        initial = group[[f"{s}_0" for s in names]].to_numpy()
        final = group[[f"{s}_final" for s in names]].to_numpy()
        matrix, stderr, residuals = fit_matrix(initial, final)
        alpha = params["alpha"]
        omega, omega_err = fit_omega(initial[:, :3], final[:, :3], alpha)
        omega_theory = float(group["Omega_theory"].iloc[0])
        e = theory.restitution(params["m"], params["kn"], params["gamma_n"])
        matrix_theory = (theory.block_matrix if len(names) == 6 else theory.scattering_matrix)(alpha, omega_theory, e)
        out.append({
            "parameters": {k: (None if isinstance(v, float) and math.isnan(v) else v) for k, v in params.items()},
            "n": len(group),
            "matrix": matrix.tolist(),
            "matrix_stderr": stderr.tolist(),
            "matrix_theory": matrix_theory.tolist(),
            "max_element_diff": float(np.abs(matrix - matrix_theory).max()),
            "omega": omega,
            "omega_stderr": omega_err,
            "omega_theory": omega_theory,
            "omega_diff": omega - omega_theory,
            "residual_rms": np.sqrt((residuals**2).mean(axis=0)).tolist(),
            "residual_max": np.abs(residuals).max(axis=0).tolist(),
            "max_abs_error_vs_theory": float(np.abs(group[[f"{s}_error" for s in names]].to_numpy()).max()),
        })
    return out


def plot_groups(rows: pd.DataFrame, path: Path) -> Path:
    """Draw Eq. 19 per model group: LAMMPS's changes (points) and the theory's lines.

    One row of two panels per group: Delta v_t and r Delta omega against the initial slip
    u_dot(0) = v_t(0) + r omega(0). The format follows the suffix (.png or .pdf).
    """
    # Imported here so that fits, and everything else, work without drawing anything;
    # a bare Figure on the Agg canvas leaves pyplot's global backend alone.
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    path = Path(path)
    keys = [k for k in GROUP_KEYS if k in rows]
    groups = list(rows.groupby(keys, dropna=False, sort=True))
    fig = Figure(figsize=(8.0, 3.2 * len(groups)), layout="constrained")
    FigureCanvasAgg(fig)
    axes = fig.subplots(len(groups), 2, squeeze=False)
    for (values, group), (ax_vt, ax_rw) in zip(groups, axes, strict=True):
        params = dict(zip(keys, values, strict=True))
        alpha, big_omega = params["alpha"], float(group["Omega_theory"].iloc[0])
        slip = (group["vt_0"] + group["r_omega_0"]).to_numpy()
        line = np.array([slip.min(), slip.max()])
        label = (f"$\\alpha$ = {alpha:g}, $k_t/k_n$ = {params['kt'] / params['kn']:g}, "
                 f"$\\Omega$ = {big_omega:.5f}")
        d_vt = group["vt_final"] - group["vt_0"]
        d_rw = group["r_omega_final"] - group["r_omega_0"]
        for ax, change, slope, name in (
            (ax_vt, d_vt, alpha * big_omega / (1 + alpha), r"$\Delta v_t$"),
            (ax_rw, d_rw, big_omega / (1 + alpha), r"$r\,\Delta\omega$"),
        ):
            ax.plot(slip, change, ".", ms=2, color="tab:blue", rasterized=True, label="LAMMPS")
            ax.plot(line, slope * line, "-", lw=1, color="tab:red", label="Eq. 19")
            ax.set(xlabel=r"$\dot u(0)$", ylabel=name, title=label)
            ax.title.set_fontsize("small")
        ax_vt.legend(loc="best", fontsize="small")
    path.parent.mkdir(parents=True, exist_ok=True)
    write_atomic_with(path, lambda tmp: fig.savefig(tmp, format=path.suffix.lstrip(".").lower(), dpi=150))
    return path
