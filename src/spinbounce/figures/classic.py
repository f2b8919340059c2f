"""figures/classic: this build's classic wall against the paper's model, for one contact model.

Left: Omega against |v_n| for the model's kt/kn and three others. The curves are
exact.classic's exact sticking Omega (contact radius a = sqrt(r delta), no cap); the points
are LAMMPS's classic wall (``fix wall/gran hooke/history``, MU = 1e4, the form's largest) at
the default step; the dashed lines are the paper's Omega (Eq. 18 or its damped form), which
does not depend on v_n. Right: for the model's own state, cap and damping, how far the
classic wall's rebound (v_t, r omega) lies from the paper's, and the kinetic energy each
form gains (> 0: the wall gave the sphere energy).
"""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np

from ..model.contact import ContactModel
from ..records import software
from ..studies import classic_effect as effect
from ..outputs import check_outputs
from .core import STYLE, FigureRecord, figure_files, new_figure, save

__all__ = ["compute", "draw", "make_classic"]


def compute(model: ContactModel, v_t: float, omega: float, runs: Path) -> dict:
    """The figure's numbers: Omega curves with LAMMPS's points per kt/kn, and the user's state's
    rebound through both forms along the curves' speeds."""
    curves = effect.omega_curves(model)
    for curve in curves:
        curve["lammps"] = effect.lammps_omegas(model, curve["kt_over_kn"], Path(runs) / f"kt_over_kn_{curve['kt_over_kn']:.6g}")
    speeds = effect.CURVE_FRACTIONS * effect.tunnelling_speed(model)
    rebound = effect.compare(model, speeds, v_t, omega)
    return {"model": model.as_record(), "state": {"v_t": v_t, "omega": omega}, "curves": curves,
            "rebound": rebound, "fix_lines": effect.fix_lines(model)}


def draw(data: dict):
    import matplotlib.style

    with matplotlib.style.context(STYLE):
        fig, axes = new_figure(1, 2, figsize=(10.0, 3.9))
        omega_ax, rebound_ax = axes[0]
        for curve in data["curves"]:
            line, = omega_ax.plot(curve["v_n"], curve["omega_classic"], label=f"kt/kn = {curve['kt_over_kn']:.3g}")
            omega_ax.axhline(curve["omega_meant"], color=line.get_color(), linestyle="--", linewidth=0.8)
            omega_ax.plot(curve["lammps"]["v_n"], curve["lammps"]["omega"], "o", color=line.get_color(), ms=4)
        omega_ax.set(xlabel="|v_n| (impact speed)", ylabel="Omega = u'(out)/u'(in) - 1 (sticking)",
                     title="lines: classic theory, dots: LAMMPS classic wall, dashed: paper")
        omega_ax.legend(fontsize=7)
        rows = data["rebound"]
        speeds = [row["v_n"] for row in rows]
        rebound_ax.plot(speeds, [row["d_vt"] for row in rows], label="v_t: classic - paper")
        rebound_ax.plot(speeds, [row["d_r_omega"] for row in rows], label="r omega: classic - paper")
        rebound_ax.plot(speeds, [row["energy_gain_classic"] for row in rows], ":", color="k",
                        label="energy gained, classic (E_out/E_in - 1)")
        rebound_ax.plot(speeds, [row["energy_gain_meant"] for row in rows], ":", color="0.6",
                        label="energy gained, paper")
        rebound_ax.axhline(0.0, color="0.8", linewidth=0.6, zorder=0)
        state = data["state"]
        rebound_ax.set(xlabel="|v_n| (impact speed)", ylabel="difference in the rebound",
                       title=f"the model's state: v_t = {state['v_t']:g}, omega = {state['omega']:g}")
        rebound_ax.legend(fontsize=7)
    return fig


def make_classic(out: Path, runs: Path, model: ContactModel | None = None, v_t: float = 1.0,
                 omega: float = 0.0) -> FigureRecord:
    """Compute, draw and save classic.{png,pdf,json} into ``out`` with provenance (LAMMPS runs in ``runs``)."""
    check_outputs(out, figure_files("classic"))  # before its runs (spinbounce.outputs)
    started = time.perf_counter()
    data = compute((model or ContactModel()).replace(wall="classic"), v_t, omega, runs)
    metadata = {"figure": "classic", "title": "this build's classic wall against the paper's model",
                "theory": "spinbounce.exact.classic (exact, contact radius); the paper's Eq. 18 / exact damped",
                "upstream": "LAMMPS PR #5007 removes the contact radius from linear_history_classic",
                "software": software(), **data}
    return save(draw(data), out, "classic", metadata, started)


def largest_lammps_error(record: dict) -> float:
    """The largest per-row error of LAMMPS's classic wall against the classic theory, in a record."""
    return float(np.max([np.max(c["lammps"]["error"]) for c in record["curves"]]))
