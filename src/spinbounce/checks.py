"""Every collision row's own accuracy and status, measured against the exact theory.

Each theory spinbounce checks against is exact to far better than the default accuracy
(closed forms to 1e-15, the oracle and the classic-wall solver to about 1e-9), so a row's
deviation from it *is* its error. Columns added to a collision table:

* ``energy_gain``: (E(final) - E(0)) / E(0), as LAMMPS ran it;
* ``error``: the largest |LAMMPS - theory| over the state columns, divided by the size of
  the initial state |(v_n, v_t, r omega, ...)|;
* ``energy_excess``: kinetic energy LAMMPS ended with beyond the theory's, over E(0);
* ``status``, the first that applies: ``grazing`` (the largest overlap is too small for
  double precision to resolve against the radius), ``energy_gained`` (more energy than the
  theory allows, beyond what the row's error can explain), ``inaccurate`` (error above the
  target), ``ok``.
"""

from __future__ import annotations

import numpy as np

from . import exact
from .model.timestep import ACCURACY

__all__ = ["STATUSES", "RESOLVABLE_OVERLAP_ULPS", "add_row_checks", "summary", "notes"]

#: Row statuses, worst first.
STATUSES = ("grazing", "energy_gained", "inaccurate", "ok")
#: The largest overlap must span this many units in the last place of r: positions are
#: doubles near r, so an overlap of N ulps is resolved to 1/N (measured: v_n = -1e-11 at the
#: paper's defaults, an overlap of 3e4 ulps, errs by 2e-3; 1e-6, 3e9 ulps, by 2e-5).
RESOLVABLE_OVERLAP_ULPS = 1e7


def _largest_overlap(model, v_n: np.ndarray) -> np.ndarray:
    return model.max_overlap(np.abs(v_n))


def _energy_allowance(initial: np.ndarray, error: np.ndarray, alpha: float) -> np.ndarray:
    """The most E(final) can move, over E(0), when each state column errs by error * |initial|."""
    # E = m/2 sum w_i s_i^2 over (v_n, v_t, r omega, v_s, r omega_s, r omega_n): spins weigh alpha
    weights = np.array([1.0, 1.0, alpha, 1.0, alpha, alpha])[: initial.shape[1]]
    twice_energy = (weights * initial**2).sum(axis=1)
    delta = error * np.linalg.norm(initial, axis=1)
    total = weights.sum()
    return (2.0 * np.sqrt(twice_energy * total) * delta + total * delta**2) / twice_energy


def add_row_checks(columns: dict, names, model, target: float = ACCURACY) -> None:
    """Add ``error``, ``energy_excess`` and ``status`` to a collision table's columns."""
    initial = np.column_stack([columns[f"{s}_0"] for s in names])
    final = np.column_stack([columns[f"{s}_final"] for s in names])
    predicted = np.column_stack([columns[f"{s}_theory"] for s in names])
    size = np.linalg.norm(initial, axis=1)
    error = np.abs(final - predicted).max(axis=1) / size
    e0, e1 = exact.energy(initial, model.m, model.alpha), exact.energy(final, model.m, model.alpha)
    columns["energy_gain"] = (e1 - e0) / e0
    excess = (e1 - exact.energy(predicted, model.m, model.alpha)) / e0
    status = np.full(len(size), "ok", dtype=object)
    status[error > target] = "inaccurate"
    status[excess > _energy_allowance(initial, np.maximum(error, target), model.alpha)] = "energy_gained"
    resolvable = RESOLVABLE_OVERLAP_ULPS * np.spacing(model.r)
    status[_largest_overlap(model, initial[:, 0]) < resolvable] = "grazing"
    columns["error"] = error
    columns["energy_excess"] = excess
    columns["status"] = status


def summary(status) -> dict[str, int]:
    """How many rows have each status (every status listed, zeros included)."""
    values = np.asarray(status, dtype=object)
    return {name: int(np.count_nonzero(values == name)) for name in STATUSES}


def notes(status, target: float = ACCURACY) -> list[str]:
    """One line for each status other than ok that some rows have."""
    counts = summary(status)
    total = sum(counts.values())
    why = {"grazing": "the impact is too slow for the overlap to be resolved in double precision",
           "energy_gained": "LAMMPS ended with more kinetic energy than the theory allows",
           "inaccurate": f"the deviation from the theory exceeds the target {target:g}"}
    return [f"{counts[name]} of {total} row(s) {name}: {why[name]}" for name in STATUSES[:-1] if counts[name]]
