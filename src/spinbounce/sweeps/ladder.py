"""Wall collisions extrapolated to an accuracy: a damped wall's default (:func:`extrapolate_default`,
which gives way to one probed run where a rung fails), which groups of a sweep are extrapolated
(:func:`tolerance_of`: the sweep's ``tolerance``, or the damped default), and their rows as a default
run's table has them (:func:`ladder_columns`), so that every chunk of a sweep has the same columns
(:func:`estimate_columns` for the others)."""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np

from ..errors import LammpsError, ResultError, SceneError
from ..extrapolation import collision_frame, default_tolerance, extrapolate_collision
from ..scenes.collision import Collision

__all__ = ["tolerance_of", "extrapolates", "ladder_columns", "estimate_columns", "extrapolate_default",
           "LADDER_FAILURES"]

#: What makes a damped default's ladder give way to one probed run: a rung too coarse for LAMMPS (lost
#: atoms at a tunnelling speed, a contact not ended) or for the scene's own checks.
LADDER_FAILURES = (LammpsError, ResultError, SceneError)


def extrapolate_default(scene: Collision, out_dir: Path, log=lambda *_: None):
    """``scene``'s damped default (:func:`~spinbounce.extrapolation.default_tolerance`): its ladder
    extrapolated to ACCURACY of each row's size, as (result, finest scene); or None where a rung fails
    (:data:`LADDER_FAILURES`), its level folders removed, so that one probed run serves instead."""
    try:
        return extrapolate_collision(scene, default_tolerance(scene.model), out_dir, log, relative=True)
    except LADDER_FAILURES:
        for level in Path(out_dir).glob("level-*"):
            shutil.rmtree(level, ignore_errors=True)
        return None


def tolerance_of(spec, group: int) -> float | None:
    """The accuracy group ``group``'s chunks are extrapolated to, or None (one run at the step the rule
    or a probe chooses, or the group's given dt)."""
    if spec.scene == "pair":
        return None
    if spec.tolerance is not None:
        return spec.tolerance
    model, dt = spec.model(group)
    return default_tolerance(model) if dt is None else None


def extrapolates(spec) -> bool:
    """Whether any group of the sweep is extrapolated (then every chunk carries the estimate columns)."""
    return any(tolerance_of(spec, g) is not None for g in range(len(spec.groups)))


def ladder_columns(scene: Collision, tolerance: float, run_dir: Path,
                   default: bool = False) -> tuple[dict, float, int, float] | None:
    """(columns, the finest run's dt, the steps of all runs, their LAMMPS loop seconds) of ``scene``'s
    rows extrapolated to ``tolerance``: the finest run's table (its raw LAMMPS columns), each state's
    ``_lammps`` and ``_error`` the extrapolated values', ``_estimate`` their error estimates, and the
    rows checked as a run's are (error, energy, status: :func:`~spinbounce.extrapolation.collision_frame`).
    ``default``: the damped default (:func:`extrapolate_default`): None where one probed run must serve."""
    ladder = extrapolate_default(scene, run_dir) if default else extrapolate_collision(scene, tolerance, run_dir)
    if ladder is None:
        return None
    result, finest = ladder
    columns = {name: values.to_numpy() for name, values in result.finest.table.drop(columns=["id"]).items()}
    columns.update({name: values.to_numpy() for name, values in collision_frame(result, finest).items()})
    for s in finest.state_names:  # a spin's own column (omega) follows its r omega
        if s.startswith("r_") and f"{s[2:]}_lammps" in columns:
            columns[f"{s[2:]}_lammps"] = columns[f"{s}_lammps"] / scene.model.r
            columns[f"{s[2:]}_error"] = columns[f"{s[2:]}_lammps"] - columns[f"{s[2:]}_theory"]
    columns["tolerance"] = np.full(scene.n, tolerance)
    return columns, finest.dt, result.steps, sum(level["loop_seconds"] for level in result.levels)


def estimate_columns(names, n: int) -> dict:
    """The columns an extrapolated chunk adds, for a chunk run once: no estimate, no tolerance (NaN)."""
    return {**{f"{s}_estimate": np.full(n, np.nan) for s in names}, "tolerance": np.full(n, np.nan)}
