"""Reference tables: a case's run reduced to its stored columns, their exact CSV form, and
a fresh table compared with a stored one: per column, the largest deviation against its
tolerance; every failing column (and every structural difference) is a violation."""

from __future__ import annotations

import csv
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pandas as pd

from ...errors import FileFault
from ...pipeline import run_scene, run_series
from ...records import write_atomic
from .cases import ReferenceCase, Tolerance, tolerances_for


def run_case(case: ReferenceCase, out_dir: Path, atoms: str | None = None) -> pd.DataFrame:
    """Run one case in ``out_dir`` (a fresh folder) and return its reference table: the stored
    columns of the run's result table, in the stored order.

    ``atoms``: a collision's atom route (:data:`decks.ATOM_ROUTES`); the stored tables
    come from the default (inline) route, and every route must reproduce them.
    """
    scene = case.scene()
    if case.kind == "collision":
        result = run_scene(scene, out_dir, atoms=atoms, record=False)
    elif atoms is not None:
        raise ValueError(f"case {case.name!r}: a frozen contact has no atom routes")
    else:
        result = run_series(scene, out_dir)
    return result.table[list(tolerances_for(case))].reset_index(drop=True)


def write_table(table: pd.DataFrame, path: Path) -> None:
    """Plain CSV, one header line, every value as ``repr`` of its float (exact on reading)."""
    cells = []
    for name in table.columns:
        values = table[name].to_numpy(dtype=float)
        if name == "id" and not np.array_equal(values, np.round(values)):
            raise ValueError(f"ids {values.tolist()} are not all whole numbers")
        cells.append([str(int(v)) if name == "id" else repr(v) for v in values.tolist()])
    lines = [",".join(table.columns), *(",".join(row) for row in zip(*cells, strict=True))]
    write_atomic(path, "\n".join(lines) + "\n")


def read_table(path: Path) -> pd.DataFrame:
    """A stored table, every value parsed with ``float`` (exactly what was written); a
    :class:`~spinbounce.errors.FileFault` naming the file if it is unreadable, empty or corrupt."""
    try:
        with open(path, newline="") as handle:
            rows = list(csv.reader(handle))
    except UnicodeDecodeError:
        raise FileFault(f"{path}: reference table is not text (a CSV file is expected)") from None
    except (OSError, csv.Error) as exc:
        raise FileFault(f"{path}: reference table cannot be read ({getattr(exc, 'strerror', None) or exc})") from None
    if not rows:
        raise FileFault(f"{path}: empty reference table")
    header, body = rows[0], rows[1:]
    bad = [i + 2 for i, row in enumerate(body) if len(row) != len(header)]
    if bad:
        raise FileFault(f"{path}: line {bad[0]} has a different number of fields than the header")
    try:
        data = np.array([[float(x) for x in row] for row in body], dtype=float).reshape(len(body), len(header))
    except ValueError as exc:
        raise FileFault(f"{path}: a value of the reference table is not a number ({exc})") from None
    return pd.DataFrame(data, columns=header)


@dataclass(frozen=True)
class Violation:
    """A stored column that a fresh table does not reproduce within its tolerance.

    ``row`` is the worst row (None for a structural problem: a missing column, a
    different number of rows); ``rows`` counts the rows beyond tolerance.
    """

    case: str
    column: str
    message: str
    row: int | None = None
    fresh: float = math.nan
    stored: float = math.nan
    deviation: float = math.nan
    tolerance: float = math.nan
    rows: int = 0

    def __str__(self) -> str:
        return f"{self.case}: {self.column}: {self.message}"


@dataclass(frozen=True)
class Deviation:
    """The largest |fresh - stored| of one column and where it is."""

    column: str
    deviation: float
    row: int | None
    tolerance: float
    beyond: int  # rows beyond tolerance

    @property
    def ok(self) -> bool:
        return self.beyond == 0


def deviations(fresh: pd.DataFrame, stored: pd.DataFrame, tolerances: dict) -> list[Deviation]:
    """Per stored column: the largest deviation, its row, and the rows beyond tolerance.

    A NaN on either side that is not NaN on the other counts as an infinite deviation.
    Columns missing on either side and a different number of rows are left to
    :func:`compare_tables`.
    """
    out = []
    for column, tol in tolerances.items():
        if column not in fresh.columns or column not in stored.columns or len(fresh) != len(stored):
            continue
        a, b = fresh[column].to_numpy(dtype=float), stored[column].to_numpy(dtype=float)
        dev = np.where(np.isnan(a) & np.isnan(b), 0.0, np.abs(a - b))
        dev[np.isnan(dev)] = np.inf
        atol = tol.atol if isinstance(tol, Tolerance) else float(tol)
        worst = int(np.argmax(dev)) if dev.size else None
        out.append(Deviation(column, float(dev[worst]) if dev.size else 0.0, worst, atol, int(np.sum(dev > atol))))
    return out


def compare_tables(fresh: pd.DataFrame, stored: pd.DataFrame, tolerances: dict, case: str = "") -> list[Violation]:
    """Every way ``fresh`` fails to reproduce ``stored``: one :class:`Violation` per failing column.

    ``tolerances`` maps each stored column to a :class:`Tolerance` (or a plain absolute
    tolerance); a column fails when any row differs by more than it. A stored column with
    no tolerance, a column missing from either table and a different number of rows are
    violations too: nothing is compared loosely by default.
    """
    found = [Violation(case, column, f"missing from the {which} table") for column in tolerances
             for table, which in ((stored, "stored"), (fresh, "fresh")) if column not in table.columns]
    found += [Violation(case, column, "stored column has no tolerance") for column in stored.columns
              if column not in tolerances]
    if len(fresh) != len(stored):
        found.append(Violation(case, "*", f"{len(fresh)} fresh rows, {len(stored)} stored"))
        return found
    for d in deviations(fresh, stored, tolerances):
        if d.ok:
            continue
        a, b = float(fresh[d.column].iloc[d.row]), float(stored[d.column].iloc[d.row])
        found.append(Violation(
            case, d.column,
            f"{d.beyond} row(s) beyond tolerance {d.tolerance:.1e}; worst row {d.row}: "
            f"fresh {a!r}, stored {b!r}, |difference| {d.deviation:.3e}",
            row=d.row, fresh=a, stored=b, deviation=d.deviation, tolerance=d.tolerance, rows=d.beyond))
    return found
