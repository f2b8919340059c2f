"""figures/pair_validity.*: where the planar pair theory can be trusted.

The map is the planar theory's error against the exact reference (what LAMMPS integrates;
tests/test_pairs.py checks LAMMPS against it to 1e-4 on 24 cases, whose LAMMPS errors
are drawn on top and recorded) over eps = v_t tau/(r_a + r_b) and the centrifugal ratio
v_t^2 tau/(pi (r_a + r_b) |v_n|).
"""

from __future__ import annotations

import tempfile
import time
from pathlib import Path

import numpy as np

from .core import STYLE, new_figure, save
from ..records import software
from ..pipeline import run_scene
from ..scenes.pair.scene import PairBatch
from ..studies.pairs import cases, validity_map

__all__ = ["make_pair_validity", "EPS", "CENTRIFUGAL"]

EPS = np.geomspace(1e-3, 4.0, 14)
CENTRIFUGAL = np.geomspace(1e-4, 10.0, 14)


def _draw(grid: dict, checked) -> object:
    import matplotlib.colors as colors
    import matplotlib.style

    eps, cen = np.array(grid["eps"]), np.array(grid["centrifugal"])
    error = np.ma.masked_invalid(np.array(grid["planar_error"], dtype=float))
    with matplotlib.style.context(STYLE):
        fig, axes = new_figure(figsize=(6.0, 4.6))
        ax = axes[0, 0]
        mesh = ax.pcolormesh(eps, cen, error, shading="nearest", norm=colors.LogNorm(1e-5, 1.0), cmap="viridis")
        fig.colorbar(mesh, ax=ax, label="planar theory's error / speed")
        levels = ax.contour(eps, cen, error, levels=[1e-4, 1e-3, 1e-2, 1e-1], colors="white", linewidths=0.8)
        ax.clabel(levels, fmt="%.0e", fontsize=7)
        for ratio in (0.1, 1.0, 10.0):  # constant v_t/|v_n|: c = eps (v_t/|v_n|)/pi
            ax.plot(eps, eps * ratio / np.pi, "--", color="0.8", linewidth=0.7)
            ax.annotate(f"v_t/|v_n| = {ratio:g}", (eps[-1], eps[-1] * ratio / np.pi), fontsize=6, color="0.8",
                        ha="right", va="bottom")
        ax.scatter(checked["eps"], checked["centrifugal"], s=14, marker="o", facecolors="none", edgecolors="red",
                   label="LAMMPS cases (error < 1e-4 vs exact)")
        ax.set(xscale="log", yscale="log", xlim=(eps[0], eps[-1]), ylim=(cen[0], cen[-1]),
               xlabel=r"$\epsilon = v_t\tau/(r_a + r_b)$",
               ylabel=r"$v_t^2\tau/(\pi (r_a + r_b)|v_n|)$",
               title="Sphere pairs: error of the planar theory")
        ax.legend(loc="upper left", fontsize=7)
    return fig


def make_pair_validity(out: Path, runs: Path | None = None):
    """Compute the map and the 24 LAMMPS cases, then write pair_validity.png/.pdf/.json in ``out``."""
    started = time.perf_counter()
    grid = validity_map(EPS, CENTRIFUGAL)
    with tempfile.TemporaryDirectory() as scratch:
        result = run_scene(PairBatch(cases()), Path(runs or scratch))
    table = result.table
    checked = {k: table[k].tolist() for k in ("eps", "centrifugal", "turn", "planar_error")}
    checked["lammps_error"] = table["error"].tolist()  # the record names whose error it is
    meta = {"figure": "pair_validity", "title": "Where the planar pair theory can be trusted",
            **software(), "map": grid, "lammps_cases": checked, "dt": result.scene.dt,
            "max_lammps_error": result.max_error, "max_planar_error_of_cases": float(result.table["planar_error"].max())}
    return save(_draw(grid, checked), Path(out), "pair_validity", meta, started)
