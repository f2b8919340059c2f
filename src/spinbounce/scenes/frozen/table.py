"""The frozen contact's time series beside Eq. 10: LAMMPS's dump in the paper's variables."""

from __future__ import annotations

import pandas as pd

__all__ = ["paper_variables", "frozen_table"]


def paper_variables(frames: pd.DataFrame, r: float) -> pd.DataFrame:
    """Add the paper's variables (v_n, v_t, omega, r_omega, and the slip) to dump rows."""
    return frames.assign(v_n=frames["vz"], v_t=frames["vx"], omega=-frames["omegay"] + 0.0,  # + 0.0: no "-0"
                         r_omega=lambda d: r * d["omega"], slip=lambda d: d["v_t"] + d["r_omega"])


def frozen_table(scene, frames: pd.DataFrame) -> pd.DataFrame:
    """The frozen time series: t, v_t, omega, r_omega (LAMMPS's) and the theory's v_t and r_omega."""
    paper = paper_variables(frames, scene.model.r)
    t = paper["step"].to_numpy() * scene.dt
    table = pd.DataFrame({"t": t, **{c: paper[c].to_numpy() for c in ("v_t", "omega", "r_omega")}})
    table["v_t_theory"], table["r_omega_theory"] = scene.predicted(t)
    return table.assign(z=paper["z"].to_numpy(), v_n=paper["v_n"].to_numpy())
