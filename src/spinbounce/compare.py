"""Dump tables in the paper's variables, set beside the theory.

LAMMPS frame -> paper: v_n = v_z, v_t = v_x, omega = -omega_y (anticlockwise positive),
r_omega = r * omega.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from .model.scenes import STATE, STATE_3D, Collision, Frozen

__all__ = ["STATE", "STATE_3D", "paper_variables", "collision_table", "frozen_table"]

#: Each state column from LAMMPS's columns: (column, sign), then times r for the spins.
#: The paper's omega is -omega_y; the second pair's spin is +omega_x (slip v_y + r omega_x).
_FROM_LAMMPS = {"vn": ("vz", 1.0), "vt": ("vx", 1.0), "r_omega": ("omegay", -1.0),
                "vs": ("vy", 1.0), "r_omega_s": ("omegax", 1.0), "r_omega_n": ("omegaz", 1.0)}
#: The spin columns and the angular velocity each one carries.
_SPINS = {"r_omega": "omega", "r_omega_s": "omega_s", "r_omega_n": "omega_n"}


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
    A 3-D scene adds the columns of :data:`STATE_3D` beyond the paper's three.
    ``as_frame=False`` returns the columns as a dict of arrays.
    """
    r = scene.model.r
    names = scene.state_names
    spins = [_SPINS[s] for s in names if s in _SPINS]
    requested = scene.initial
    theory = scene.predicted()
    columns = {"id": np.arange(1, scene.n + 1)}
    for k, name in enumerate(names):
        columns[f"{name}_0"] = requested[:, k]
    for spin in spins:
        columns[f"{spin}_0"] = np.asarray(getattr(scene, spin))
    for when, frame in (("lammps_0", initial), ("final", final)):
        values = {"z": np.asarray(frame["z"])}
        for name in names:
            column, sign = _FROM_LAMMPS[name]
            value = sign * np.asarray(frame[column]) + 0.0  # + 0.0: no "-0" in tables
            if name in _SPINS:
                values[_SPINS[name]] = value
                value = r * value
            values[name] = value
        for name in names + tuple(spins) + ("z",):
            columns[f"{name}_{when}"] = values[name]
    for k, name in enumerate(names):
        columns[f"{name}_theory"] = theory[:, k]
    for name, spin in _SPINS.items():
        if name in names:
            columns[f"{spin}_theory"] = columns[f"{name}_theory"] / r
    for name in names + tuple(spins):
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
