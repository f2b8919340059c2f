"""The fit of a sweep of any size in bounded memory: the dataset read in batches, twice.

Pass one accumulates, per model group, the normal equations of the least-squares matrix
(X^T X and X^T Y), Eq. 19's sums for Omega, the largest deviation of the theory from the
frictionless matrix (does the group stick throughout?), and each row's deviation (kept for
the median: 8 bytes a row). Pass two, with the matrix known, sums the residuals. The
result is :func:`spinbounce.fitting.fit_groups`'s, to rounding, whatever the row count:
memory grows with the number of groups and the batch, not with the rows.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pandas as pd

from .scenes.collision import STATE, STATE_3D
from .fitting import (GROUP_KEYS, PAIR_GEOMETRY, deviation_summary, group_report, model_of_group,
                      off_uncapped, omega_gains, regime, slip_changes)

__all__ = ["fit_dataset", "BATCH_ROWS"]

#: Rows read at once.
BATCH_ROWS = 200_000


@dataclass
class _Group:
    params: dict
    names: tuple
    n: int = 0
    xtx: np.ndarray | None = None
    xty: np.ndarray | None = None
    omega_xx: float = 0.0
    omega_xy: float = 0.0
    scale: float = 0.0
    off_uncapped: float = 0.0
    speeds: set = field(default_factory=set)
    errors: list = field(default_factory=list)
    relative: list = field(default_factory=list)
    status: dict = field(default_factory=dict)
    residual_ss: np.ndarray | None = None
    residual_max: np.ndarray | None = None
    omega_ss: float = 0.0
    #: A pair group's largest planar_error, eps and centrifugal ratio (fitting.regime).
    geometry: dict = field(default_factory=dict)
    found: tuple = (None, "")  # fitting.regime's (the theory's matrix or None, the regime's name)
    coef: np.ndarray | None = None
    omega: float = math.nan


def _batches(files, columns):
    """The files' rows, BATCH_ROWS at a time, one file after another (no read-ahead)."""
    import pyarrow.parquet as pq

    from .sweeps import SweepError

    for path in files:
        try:
            reader = pq.ParquetFile(str(path))
            present = [c for c in columns if c in reader.schema_arrow.names]
            for batch in reader.iter_batches(batch_size=BATCH_ROWS, columns=present):
                yield batch.to_pandas()
        except (OSError, ValueError) as exc:  # a file whose footer reads and whose rows do not
            raise SweepError(f"{path}: not a readable sweep chunk ({exc})") from None


def _arrays(frame: pd.DataFrame, names) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    return tuple(frame[[f"{s}_{suffix}" for s in names]].to_numpy() for suffix in ("initial", "lammps", "theory"))


def _first_pass(g: _Group, frame: pd.DataFrame, model) -> None:
    initial, final, theory = _arrays(frame, g.names)
    g.n += len(frame)
    g.xtx = initial.T @ initial + (0.0 if g.xtx is None else g.xtx)
    g.xty = initial.T @ final + (0.0 if g.xty is None else g.xty)
    x, y = slip_changes(initial[:, :3], final[:, :3], omega_gains(g.params))
    g.omega_xx += float(x @ x)
    g.omega_xy += float(x @ y)
    g.scale = max(g.scale, float(np.abs(initial).max()))
    g.off_uncapped = max(g.off_uncapped, off_uncapped(model, initial, theory))
    for key in PAIR_GEOMETRY:
        if key in frame:
            g.geometry[key] = max(g.geometry.get(key, 0.0), float(frame[key].max()))
    if len(g.speeds) < 2:
        g.speeds.update(np.unique(initial[:, 0])[:2].tolist())
    g.errors.append(np.abs(frame[[f"{s}_error" for s in g.names]].to_numpy()).max(axis=1))
    # a copy: a column's array is a view of the whole batch's block, which would stay alive
    g.relative.append(frame["error"].to_numpy().copy() if "error" in frame else
                      g.errors[-1] / np.linalg.norm(initial, axis=1))
    if "status" in frame:
        for name, count in frame["status"].value_counts().items():
            g.status[name] = g.status.get(name, 0) + int(count)


def _second_pass(g: _Group, frame: pd.DataFrame) -> None:
    initial, final, _ = _arrays(frame, g.names)
    residuals = final - initial @ g.coef
    g.residual_ss = (residuals**2).sum(axis=0) + (0.0 if g.residual_ss is None else g.residual_ss)
    worst = np.abs(residuals).max(axis=0)
    g.residual_max = worst if g.residual_max is None else np.maximum(g.residual_max, worst)
    x, y = slip_changes(initial[:, :3], final[:, :3], omega_gains(g.params))
    g.omega_ss += float(((y - g.omega * x) ** 2).sum())


def _parts(frame: pd.DataFrame, keys):
    """(label, rows) of each model group in a batch; the label is the same in every batch."""
    for values, part in frame.groupby(keys, dropna=False, sort=False, observed=True):
        yield repr(tuple(values) if isinstance(values, tuple) else (values,)), part


def fit_dataset(files, names=None) -> list[dict]:
    """:func:`spinbounce.fitting.fit_groups` of the rows in ``files`` (Parquet), streamed."""
    from .sweeps.run import chunk_files

    files = chunk_files(Path(files)) if not isinstance(files, list) else files
    import pyarrow.parquet as pq

    schema = pq.read_schema(str(files[0])).names
    names = names or (STATE_3D if f"{STATE_3D[-1]}_initial" in schema else STATE)
    keys = [k for k in GROUP_KEYS if k in schema]
    columns = (keys + [f"{s}_{x}" for s in names for x in ("initial", "lammps", "theory", "error")]
               + ["error", "status", *PAIR_GEOMETRY])
    groups: dict[str, _Group] = {}
    for frame in _batches(files, columns):
        for label, part in _parts(frame, keys):
            if label not in groups:
                first = (v.item() if isinstance(v, np.generic) else v for v in part[keys].iloc[0])
                groups[label] = _Group(dict(zip(keys, first, strict=True)), names)
            group = groups[label]
            _first_pass(group, part, model_of_group(group.params))
    for g in groups.values():
        g.found = regime(g.params, len(g.names) == 6, g.off_uncapped, g.scale, g.speeds, g.geometry)
        if g.found[0] is not None:
            g.coef = np.linalg.solve(g.xtx, g.xty)
            g.omega = g.omega_xy / g.omega_xx if g.omega_xx else math.nan
    for frame in _batches(files, columns):  # pass two: the residuals of the groups that have a matrix
        for label, part in _parts(frame, keys):
            if groups[label].coef is not None:
                _second_pass(groups[label], part)
    order = sorted(groups, key=lambda label: tuple(str(groups[label].params[k]) for k in keys))
    return [_report(groups[label]) for label in order]


def _report(g: _Group) -> dict:
    fit = None
    if g.coef is not None:
        dof = max(g.n - len(g.names), 1)
        stderr = np.sqrt(np.outer(g.residual_ss / dof, np.diag(np.linalg.inv(g.xtx))))
        fit = (g.coef.T, stderr, g.omega, math.sqrt(g.omega_ss / max(2 * g.n - 1, 1) / g.omega_xx),
               np.sqrt(g.residual_ss / g.n), g.residual_max)
    deviations = deviation_summary(g.errors, g.relative, g.status or None)
    return group_report(g.params, g.n, g.found, deviations, fit)
