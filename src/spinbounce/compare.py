"""Dump tables in the paper's variables, set beside the theory.

LAMMPS frame -> paper: v_n = v_z, v_t = v_x, omega = -omega_y (anticlockwise positive),
r_omega = r * omega.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from .scenes import Collision, Frozen

__all__ = ["STATE", "paper_variables", "collision_table", "frozen_table"]

#: State order everywhere: (v_n, v_t, r*omega).
STATE = ("vn", "vt", "r_omega")


def paper_variables(frames: pd.DataFrame, r: float) -> pd.DataFrame:
    """Add the paper's variables (vn, vt, omega, r_omega, and the slip) to dump rows."""
    out = frames.copy()
    out["vn"] = frames["vz"]
    out["vt"] = frames["vx"]
    out["omega"] = -frames["omegay"] + 0.0  # + 0.0: no "-0" in tables
    out["r_omega"] = r * out["omega"]
    out["slip"] = out["vt"] + out["r_omega"]
    return out


def collision_table(scene: Collision, initial, final, as_frame: bool = True):
    """One row per sphere: requested, initial (as LAMMPS saw it), final, theory and error.

    ``initial`` and ``final`` map LAMMPS's column names (z, vx, vz, omegay, ...) to one
    value per sphere in id order (ids 1..n): a dump frame or a dict of arrays. The theory
    acts on the *requested* initial state, so a mangled input would show as an error.
    ``as_frame=False`` returns the columns as a dict of arrays.
    """
    r = scene.model.r
    requested = scene.initial
    theory = scene.predicted()
    columns = {"id": np.arange(1, scene.n + 1)}
    for k, name in enumerate(STATE):
        columns[f"{name}_0"] = requested[:, k]
    columns["omega_0"] = np.asarray(scene.omega)
    for when, frame in (("lammps_0", initial), ("final", final)):
        omega = -np.asarray(frame["omegay"]) + 0.0  # + 0.0: no "-0" in tables
        values = {"vn": np.asarray(frame["vz"]), "vt": np.asarray(frame["vx"]), "r_omega": r * omega,
                  "omega": omega, "z": np.asarray(frame["z"])}
        for name in STATE + ("omega", "z"):
            columns[f"{name}_{when}"] = values[name]
    for k, name in enumerate(STATE):
        columns[f"{name}_theory"] = theory[:, k]
    columns["omega_theory"] = theory[:, 2] / r
    for name in STATE + ("omega",):
        columns[f"{name}_error"] = columns[f"{name}_final"] - columns[f"{name}_theory"]
    return pd.DataFrame(columns) if as_frame else columns


def frozen_table(scene: Frozen, frames: pd.DataFrame) -> pd.DataFrame:
    """The frozen time series: t, vt, omega, r_omega and the theory's vt and r_omega."""
    paper = paper_variables(frames, scene.model.r)
    t = paper["step"].to_numpy() * scene.dt
    vt_theory, r_omega_theory = scene.predicted(t)
    return pd.DataFrame(
        {
            "t": t,
            "vt": paper["vt"].to_numpy(),
            "omega": paper["omega"].to_numpy(),
            "r_omega": paper["r_omega"].to_numpy(),
            "vt_theory": vt_theory,
            "r_omega_theory": r_omega_theory,
            "z": paper["z"].to_numpy(),
            "vn": paper["vn"].to_numpy(),
        }
    )
