"""Reference tables: a case's run reduced to its stored columns, and their exact CSV form."""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np
import pandas as pd

from ...pipeline import run_scene, run_series
from ...records import write_atomic
from .cases import ReferenceCase, tolerances_for

__all__ = ["read_table", "reference_table", "run_case", "write_table"]


def reference_table(case: ReferenceCase, result) -> pd.DataFrame:
    """The stored columns of a run's result table, in the stored order."""
    return result.table[list(tolerances_for(case))].reset_index(drop=True)


def run_case(case: ReferenceCase, out_dir: Path, atoms: str | None = None) -> pd.DataFrame:
    """Run one case in ``out_dir`` (a fresh folder) and return its reference table.

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
    return reference_table(case, result)


def write_table(table: pd.DataFrame, path: Path) -> None:
    """Plain CSV, one header line, every value as ``repr`` of its float (exact on reading)."""
    cells = []
    for name in table.columns:
        values = table[name].to_numpy(dtype=float)
        if name == "id":
            if not np.array_equal(values, np.round(values)):
                raise ValueError(f"ids {values.tolist()} are not all whole numbers")
            cells.append([str(int(v)) for v in values])
        else:
            cells.append([repr(v) for v in values.tolist()])
    lines = [",".join(table.columns), *(",".join(row) for row in zip(*cells, strict=True))]
    write_atomic(path, "\n".join(lines) + "\n")


def read_table(path: Path) -> pd.DataFrame:
    """A stored table, every value parsed with ``float`` (exactly what was written)."""
    with open(path, newline="") as handle:
        rows = list(csv.reader(handle))
    if not rows:
        raise ValueError(f"{path}: empty reference table")
    header, body = rows[0], rows[1:]
    bad = [i + 2 for i, row in enumerate(body) if len(row) != len(header)]
    if bad:
        raise ValueError(f"{path}: line {bad[0]} has a different number of fields than the header")
    data = np.array([[float(x) for x in row] for row in body], dtype=float).reshape(len(body), len(header))
    return pd.DataFrame(data, columns=header)

