"""figures/two_walls: a sphere's state over many bounces between two parallel walls, LAMMPS
beside the product of scattering matrices (:mod:`spinbounce.scenes.two_walls`)."""

from __future__ import annotations

import time
from pathlib import Path

import matplotlib.style
import numpy as np

from ..exact import choose
from ..model.contact import ContactModel
from ..records import software
from ..scenes.two_walls import TwoWalls, run_two_walls, theory_path
from ..outputs import check_outputs
from .core import STYLE, figure_files, new_figure, save

__all__ = ["make_figure", "figure_tables", "FIGURE_CASES"]

#: The figure's cases: (label, model, steps per half-period). Damped and Coulomb contacts
#: converge at first order (their contacts do not stay aligned with the step): finer steps.
FIGURE_CASES = (
    ("paper's model (kt/kn = 1/10)", ContactModel(), 1000),
    ("magic kt/kn = 2/7 (rough sphere)", ContactModel(kt=20.0 / 7.0), 1000),
    ("damped: gamma_n = 0.5, gamma_t = 0.3", ContactModel(gamma_n=0.5, gamma_t=0.3), 4000),
    ("Coulomb: mu = 0.3", ContactModel(mu=0.3), 4000),
)
FIGURE_STATE = (-1.0, 1.0, 0.0)
FIGURE_BOUNCES = 40


def figure_tables(runs: Path, bounces: int = FIGURE_BOUNCES) -> list[dict]:
    """One LAMMPS run per case of :data:`FIGURE_CASES`: LAMMPS's path and the theory's."""
    out = []
    for k, (label, model, steps) in enumerate(FIGURE_CASES):
        scene = TwoWalls((model,), np.array([FIGURE_STATE]), bounces=bounces, steps_per_half_period=steps)
        result = run_two_walls(scene, Path(runs) / f"case{k + 1}")
        theory = theory_path(model, scene.initial, bounces)[:, 0]
        out.append({"label": label, "model": model, "dt": scene.dt, "gap": scene.gap, "deck": result.deck,
                    "theory_kind": choose.which(model).kind, "lammps": result.states[:, 0], "theory": theory})
    return out


def make_figure(out: Path, runs: Path) -> dict:
    """figures/two_walls.png, .pdf, .json: the state's path over many bounces between two walls."""
    check_outputs(out, figure_files("two_walls"))  # before its runs (spinbounce.outputs)
    started = time.perf_counter()
    cases = figure_tables(runs)
    with matplotlib.style.context(STYLE):
        fig, axes = new_figure(1, 3, figsize=(13.0, 4.2))
        path_ax, energy_ax, error_ax = axes[0]
        bounce = np.arange(FIGURE_BOUNCES + 1)
        for k, case in enumerate(cases):
            colour, marker = f"C{k}", "osD^"[k]
            lam, th = case["lammps"], case["theory"]
            alpha = case["model"].alpha
            path_ax.plot(th[:, 2], th[:, 1], "-", color=colour, lw=0.8)
            path_ax.plot(lam[:, 2], lam[:, 1], marker, color=colour, ms=3, mfc="none", label=case["label"])
            energy = 0.5 * (lam[:, 1] ** 2 + alpha * lam[:, 2] ** 2)
            energy_ax.semilogy(bounce, np.maximum(energy, 1e-30), marker + "-", color=colour, ms=3, lw=0.8, mfc="none")
            # the two undamped cases share their error (v_n's, the same in both): open markers show both
            error_ax.semilogy(bounce[1:], np.abs(lam - th).max(axis=1)[1:], marker + "-", color=colour, ms=3, lw=0.8,
                              mfc="none")
        path_ax.set(xlabel=r"$r\omega$ (bottom wall's frame)", ylabel=r"$v_t$",
                    title="(a) tangential state after each bounce")
        path_ax.axhline(0.0, color="0.7", lw=0.5)
        path_ax.axvline(0.0, color="0.7", lw=0.5)
        path_ax.legend(fontsize=7, loc="lower left")
        energy_ax.set(xlabel="bounce", ylabel=r"$(v_t^2 + \alpha (r\omega)^2)/2$",
                      title="(b) tangential kinetic energy (m = 1)")
        error_ax.set(xlabel="bounce", ylabel="max |LAMMPS - theory|",
                     title="(c) LAMMPS against matrices / oracle")
        fig.suptitle(f"A sphere between two parallel walls, (v_n, v_t, r omega) = {FIGURE_STATE}: "
                     "lines theory, circles LAMMPS", fontsize=9)
        metadata = {"figure": "two_walls", "bounces": FIGURE_BOUNCES, "initial_state": FIGURE_STATE, **software(),
                    "cases": [{"label": c["label"], "model": {f: getattr(c["model"], f) for f in
                                                               ("kn", "kt", "gamma_n", "gamma_t", "mu")},
                               "theory": c["theory_kind"], "dt": c["dt"], "gap": c["gap"], "deck": str(c["deck"]),
                               "max_abs_deviation": float(np.abs(c["lammps"] - c["theory"]).max()),
                               "lammps_path": c["lammps"], "theory_path": c["theory"]} for c in cases]}
        return save(fig, out, "two_walls", metadata, started).metadata
