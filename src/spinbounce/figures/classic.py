"""figures/classic: this build's classic wall, Omega_eff against v_n, beside the paper's Omega.

The curves are theory.classic's exact sticking Omega (contact radius a = sqrt(r delta),
mu -> infinity); the points are LAMMPS's classic wall (``fix wall/gran hooke/history``,
mu = 1e4, gamma_n = 1e-100) at a few speeds; the dashed lines are the paper's Eq. 18,
which does not depend on v_n.
"""

from __future__ import annotations

import tempfile
import time
from pathlib import Path

import numpy as np

from ..model.timestep import mid_step_dt
from ..records import software
from ..studies.doctor import run_wall
from ..theory import classic, linear
from .core import STYLE, FigureRecord, new_figure, save

__all__ = ["KT_OVER_KN", "compute", "draw", "make_classic"]

KN, M, R, ALPHA = 10.0, 1.0, 0.5, 0.4
KT_OVER_KN = (0.1, 2.0 / 7.0, 0.5)
#: Below the tunnelling speed r sqrt(kn/m) = 1.58 (LAMMPS_FACTS section 6).
SPEEDS = np.linspace(0.05, 1.5, 59)
LAMMPS_SPEEDS = (0.25, 0.75, 1.5)
STEPS = 4000


def _lammps_omegas(kt: float, folder: Path) -> list[float]:
    wall = classic.ClassicWall(KN, kt, 0.0, 0.0, None, ALPHA, R, M)
    states = [(-v, 1.0, 0.0) for v in LAMMPS_SPEEDS]
    final = run_wall(f"hooke/history {KN!r} {kt!r} 1e-100 0.0 10000.0 1", states, folder,
                     mid_step_dt(wall.tau, STEPS), STEPS + 50, r=R, m=M)
    return (final[:, 1] + final[:, 2] - 1.0).tolist()


def compute(folder: Path) -> dict:
    """The figure's numbers: theory curves, the paper's Omega and LAMMPS's points, per kt/kn."""
    series = []
    for ratio in KT_OVER_KN:
        kt = ratio * KN
        series.append({
            "kt_over_kn": ratio,
            "v_n": SPEEDS.tolist(),
            "omega_eff": [classic.Omega_eff(-v, KN, kt, ALPHA, R, M) for v in SPEEDS],
            "omega_paper": linear.Omega(KN, kt, ALPHA),
            "lammps_v_n": list(LAMMPS_SPEEDS),
            "lammps_omega": _lammps_omegas(kt, Path(folder) / f"kt{kt:g}"),
        })
    return {"kn": KN, "m": M, "r": R, "alpha": ALPHA, "steps_per_contact": STEPS, "series": series}


def draw(data: dict):
    import matplotlib.style

    with matplotlib.style.context(STYLE):
        fig, axes = new_figure(figsize=(5.0, 3.6))
        ax = axes[0, 0]
        for s in data["series"]:
            line, = ax.plot(s["v_n"], s["omega_eff"], label=f"kt/kn = {s['kt_over_kn']:.3g}")
            ax.axhline(s["omega_paper"], color=line.get_color(), linestyle="--", linewidth=0.8)
            ax.plot(s["lammps_v_n"], s["lammps_omega"], "o", color=line.get_color(), markersize=4)
        ax.set_xlabel("|v_n|")
        ax.set_ylabel("Omega")
        ax.set_title("classic wall in this build (lines: theory, dots: LAMMPS; dashed: Eq. 18)", fontsize=8)
        ax.legend(fontsize=7)
    return fig


def make_classic(out: Path) -> FigureRecord:
    """Compute, draw and save figures/classic.{png,pdf,json} with provenance."""
    started = time.perf_counter()
    with tempfile.TemporaryDirectory(prefix="spinbounce-classic-") as folder:
        data = compute(Path(folder))
    metadata = {"figure": "classic", "title": "Omega_eff of the classic wall's contact-radius spring against v_n",
                "theory": "spinbounce.theory.classic.Omega_eff (exact, sticking); paper's Eq. 18",
                "upstream": "LAMMPS PR #5007 removes the contact radius from linear_history_classic",
                "software": software(), **data}
    return save(draw(data), out, "classic", metadata, started)
