"""A gas run's series: LAMMPS's kinetic energies and open contacts, as temperatures and collisions per sphere."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ...errors import ResultError
from .deck import CONTACTS_FILE, SERIES_FILE

__all__ = ["read_series", "COLUMNS"]

#: The series' columns: time, the temperatures (2 KE / (3 N)), the kinetic energy per sphere, and the
#: collisions per sphere counted from the open contacts.
COLUMNS = ("step", "t", "t_tr", "t_rot", "ratio", "energy", "collisions")


def _rows(path: Path, width: int) -> np.ndarray:
    if not path.exists():
        raise ResultError(f"{path}: LAMMPS wrote no series")
    rows = np.loadtxt(path, comments="#", ndmin=2)
    if rows.shape[1] != width or not np.all(np.isfinite(rows)):
        raise ResultError(f"{path}: expected {width} finite numbers a row (a NaN or a cut line)")
    return rows


def read_series(gas, folder: Path, contact_time) -> dict[str, np.ndarray]:
    """The series at each reported step. ``contact_time(t_tr)``: the mean contact time of the gas's
    collisions at a temperature (the pair references'): each collision keeps a pair open that long, so
    the collisions per sphere are the open contacts' time integral over it."""
    energies = _rows(Path(folder) / SERIES_FILE, 3)
    contacts = _rows(Path(folder) / CONTACTS_FILE, 2)
    expected = np.arange(0, gas.nsteps + 1, gas.interval)
    if not np.array_equal(energies[:, 0], expected) or not np.array_equal(contacts[:, 0], expected[1:]):
        raise ResultError(f"{folder}: the series stop before step {gas.nsteps} (an unfinished run)")
    n = gas.spheres
    t_tr, t_rot = 2.0 * energies[:, 1] / (3.0 * n), 2.0 * energies[:, 2] / (3.0 * n)
    middle = (t_tr[1:] + t_tr[:-1]) / 2.0
    per_interval = contacts[:, 1] / n * gas.interval * gas.dt / np.array([contact_time(x) for x in middle])
    return {"step": energies[:, 0].astype(int), "t": energies[:, 0] * gas.dt, "t_tr": t_tr, "t_rot": t_rot,
            "ratio": t_rot / t_tr, "energy": (energies[:, 1] + energies[:, 2]) / n,
            "collisions": np.concatenate([[0.0], np.cumsum(per_interval)])}
