"""Every row's own accuracy and status, measured against the exact reference, for any scene.

Each reference spinbounce checks against is exact to far better than the default accuracy
(closed forms to 1e-15, the oracle, the classic-wall solver and the pair references to
about 1e-9), so a row's deviation from it *is* its error. A scene states its rows as
:class:`RowStates` (velocities and r times spins, whichever spheres it reports); the
columns added to its table are the same for every scene:

* ``energy_gain``: (E(final) - E(0)) / E(0), as LAMMPS ran it;
* ``error``: the largest |LAMMPS - reference| over the state's components, divided by the
  row's ``scale`` (the wall: the size of the initial state |(v_n, v_t, r omega, ...)|; a
  pair: the larger of the impact speed and the initial slip speed);
* ``energy_excess``: kinetic energy LAMMPS ended with beyond the reference's, over E(0);
* ``status``, the first that applies: ``grazing`` (the largest overlap is too small for
  double precision to resolve against the radius), ``energy_gained`` (more energy than the
  reference allows, beyond what the row's error can explain), ``inaccurate`` (error above
  the target), ``ok``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .model.timestep import ACCURACY

__all__ = ["STATUSES", "RESOLVABLE_OVERLAP_ULPS", "RowStates", "add_row_checks", "summary", "tally", "notes"]

#: Row statuses, worst first.
STATUSES = ("grazing", "no_limit", "energy_gained", "inaccurate", "ok")
#: The largest overlap must span this many units in the last place of the length it is
#: measured against (the radius; a pair's sum of radii): positions are doubles near it, so an
#: overlap of N ulps is resolved to 1/N (measured: v_n = -1e-11 at the paper's defaults, an
#: overlap of 3e4 ulps, errs by 2e-3; 1e-6, 3e9 ulps, by 2e-5).
RESOLVABLE_OVERLAP_ULPS = 1e7


@dataclass(frozen=True)
class RowStates:
    """A scene's rows as the checks read them: (n, k) states of velocities and r times spins.

    ``weights``: each component's share of the kinetic energy, E = sum(weights x^2)/2 (a mass,
    or alpha times a mass for r omega), one row or one per row; ``scale``: what each row's
    error is measured in; ``overlap``: each row's largest overlap; ``length``: the length an
    overlap is resolved against.
    """

    initial: np.ndarray
    final: np.ndarray
    reference: np.ndarray
    weights: np.ndarray
    scale: np.ndarray
    overlap: np.ndarray
    length: float | np.ndarray


def _energy(weights: np.ndarray, states: np.ndarray) -> np.ndarray:
    return 0.5 * (weights * states**2).sum(axis=1)


def add_row_checks(columns: dict, rows: RowStates, target: float = ACCURACY) -> float:
    """Add ``error``, ``energy_gain``, ``energy_excess`` and ``status`` to a table's columns;
    return the largest absolute deviation of any component (the run's, in the state's units)."""
    deviation = np.abs(rows.final - rows.reference)
    error = deviation.max(axis=1) / rows.scale
    e0, e1 = _energy(rows.weights, rows.initial), _energy(rows.weights, rows.final)
    excess = (e1 - _energy(rows.weights, rows.reference)) / e0
    status = np.full(len(error), "ok", dtype=object)
    status[~(error <= target)] = "inaccurate"  # NaN too: a state no run reached is never ok
    status[np.isnan(rows.reference).any(axis=1)] = "no_limit"  # LAMMPS has no dt -> 0 limit here: no reference
    # the most E(final) can move, over E(0), when each component errs by delta: by Cauchy-Schwarz,
    # sum w (x d + d^2/2) <= delta sqrt(W sum w x^2) + W delta^2/2, W = sum w
    delta = np.maximum(error, target) * rows.scale
    total = np.broadcast_to(rows.weights, rows.initial.shape).sum(axis=1)
    allowance = (2.0 * np.sqrt(2.0 * e0 * total) * delta + total * delta**2) / (2.0 * e0)
    status[excess > allowance] = "energy_gained"
    status[rows.overlap < RESOLVABLE_OVERLAP_ULPS * np.spacing(rows.length)] = "grazing"
    columns["energy_gain"] = (e1 - e0) / e0
    columns["error"] = error
    columns["energy_excess"] = excess
    columns["status"] = status
    measured = deviation[~np.isnan(rows.reference).any(axis=1)]  # rows without a reference have no deviation
    return float(measured.max()) if measured.size else float("nan")


def summary(status) -> dict[str, int]:
    """How many rows have each status (every status listed, zeros included)."""
    values = np.asarray(status, dtype=object)
    return {name: int(np.count_nonzero(values == name)) for name in STATUSES}


def tally(counted: dict[str, int]) -> dict[str, int]:
    """Counts by status, every status listed in :data:`STATUSES`' order (zeros included); a name
    that is not a status is an error, not a row lost."""
    unknown = set(counted) - set(STATUSES)
    if unknown:
        raise ValueError(f"status {sorted(unknown)[0]!r}: not one of {', '.join(STATUSES)}")
    return {name: int(counted.get(name, 0)) for name in STATUSES}


def notes(status, target: float = ACCURACY) -> list[str]:
    """One line for each status other than ok that some rows have."""
    counts = summary(status)
    total = sum(counts.values())
    why = {"grazing": "the impact is too slow for the overlap to be resolved in double precision",
           "no_limit": "LAMMPS's outcome has no dt -> 0 limit for these states, so there is no reference "
                       "(its warning names the first)",
           "energy_gained": "LAMMPS ended with more kinetic energy than the theory allows",
           "inaccurate": f"the deviation from the theory exceeds the target {target:g}"}
    return [f"{counts[name]} of {total} row(s) {name}: {why[name]}" for name in STATUSES[:-1] if counts[name]]
