"""The fit of a sweep of any size in bounded memory: the dataset read in batches, twice.

Pass one accumulates, per model group, the normal equations of the least-squares matrix
(X^T X and X^T Y), Eq. 19's sums for Omega, the largest deviation of the theory from the
frictionless matrix (does the group stick throughout?), and each row's deviation (kept for
the median: 8 bytes a row). Pass two, with the matrix known, sums the residuals. The
result is :func:`spinbounce.fitting.fit_groups`'s, to rounding, whatever the row count:
memory grows with the number of groups and the batch, not with the rows.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .scenes.collision import STATE, STATE_3D
from .fitting import GROUP_KEYS, PAIR_GEOMETRY, GroupFit, accumulate, add_residuals, report, solve

__all__ = ["fit_dataset", "BATCH_ROWS"]

#: Rows read at once.
BATCH_ROWS = 200_000


def _batches(files, columns, keys):
    """(label, rows) of each model group in each batch of BATCH_ROWS rows, one file after another
    (no read-ahead); a group's label is the same in every batch."""
    import pyarrow.parquet as pq

    from .sweeps import SweepError

    for path in files:
        try:
            reader = pq.ParquetFile(str(path))
            present = [c for c in columns if c in reader.schema_arrow.names]
            for batch in reader.iter_batches(batch_size=BATCH_ROWS, columns=present):
                for values, part in batch.to_pandas().groupby(keys, dropna=False, sort=False, observed=True):
                    yield repr(tuple(values) if isinstance(values, tuple) else (values,)), part
        except (OSError, ValueError) as exc:  # a file whose footer reads and whose rows do not
            raise SweepError(f"{path}: not a readable sweep chunk ({exc})") from None


def fit_dataset(files, names=None) -> list[dict]:
    """:func:`spinbounce.fitting.fit_groups` of the rows in ``files`` (Parquet), streamed."""
    from .sweeps.dataset import chunk_files

    files = chunk_files(Path(files)) if not isinstance(files, list) else files
    import pyarrow.parquet as pq

    # the columns every chunk has: a sweep resumed under a later spinbounce has chunks with the
    # columns of parameters added since (at their defaults in the later chunks)
    schema = set.intersection(*(set(pq.read_schema(str(f)).names) for f in files))
    names = names or (STATE_3D if f"{STATE_3D[-1]}_initial" in schema else STATE)
    keys = [k for k in GROUP_KEYS if k in schema]
    columns = (keys + [f"{s}_{x}" for s in names for x in ("initial", "lammps", "theory", "error")]
               + ["error", "status", *PAIR_GEOMETRY])
    groups: dict[str, GroupFit] = {}
    for label, part in _batches(files, columns, keys):
        if label not in groups:
            first = (v.item() if isinstance(v, np.generic) else v for v in part[keys].iloc[0])
            groups[label] = GroupFit(dict(zip(keys, first, strict=True)), names)
        accumulate(groups[label], part)
    for g in groups.values():
        solve(g)
    # pass two: the residuals of the groups that have a matrix
    for label, part in _batches(files, columns, keys):
        if groups[label].coef is not None:
            add_residuals(groups[label], part)
    order = sorted(groups, key=lambda label: tuple(str(groups[label].params[k]) for k in keys))
    return [report(groups[label]) for label in order]
