"""The frozen contact's time series beside Eq. 10: LAMMPS's dump in the paper's variables.

``scene`` is this folder's :class:`.scene.Frozen`, which calls this module
(never the other way round).
"""

from __future__ import annotations


import pandas as pd


__all__ = ["paper_variables", "frozen_table"]


def paper_variables(frames: pd.DataFrame, r: float) -> pd.DataFrame:
    """Add the paper's variables (v_n, v_t, omega, r_omega, and the slip) to dump rows."""
    out = frames.copy()
    out["v_n"] = frames["vz"]
    out["v_t"] = frames["vx"]
    out["omega"] = -frames["omegay"] + 0.0  # + 0.0: no "-0" in tables
    out["r_omega"] = r * out["omega"]
    out["slip"] = out["v_t"] + out["r_omega"]
    return out


def frozen_table(scene, frames: pd.DataFrame) -> pd.DataFrame:
    """The frozen time series: t, v_t, omega, r_omega (LAMMPS's) and the theory's v_t and r_omega."""
    paper = paper_variables(frames, scene.model.r)
    t = paper["step"].to_numpy() * scene.dt
    v_t_theory, r_omega_theory = scene.predicted(t)
    return pd.DataFrame(
        {
            "t": t,
            "v_t": paper["v_t"].to_numpy(),
            "omega": paper["omega"].to_numpy(),
            "r_omega": paper["r_omega"].to_numpy(),
            "v_t_theory": v_t_theory,
            "r_omega_theory": r_omega_theory,
            "z": paper["z"].to_numpy(),
            "v_n": paper["v_n"].to_numpy(),
        }
    )
