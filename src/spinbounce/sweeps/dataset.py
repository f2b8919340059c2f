"""A sweep's dataset as it is read: its chunk files, checked to be a sweep's, their rows, their statuses.

Every reader of a sweep's output (``fit`` and its figure, the status counts, :func:`read_results`)
meets its files through :func:`chunk_files`: a corrupt, foreign or missing chunk is a
:class:`SweepError` naming the file, never a traceback.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from .. import checks
from .spec import SweepError

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["chunk_files", "read_results", "status_counts", "check_complete"]


def status_counts(path: Path) -> dict[str, int]:
    """How many rows of a sweep have each status (reads that one column only, file by file, as its
    dictionary: a dataset reader would cost more to load than to count a million rows)."""
    import numpy as np
    import pyarrow.parquet as pq

    counted: dict[str, int] = {}
    for f in chunk_files(Path(path)):
        for column in pq.ParquetFile(f, read_dictionary=["status"]).read(columns=["status"]).column("status").chunks:
            if column.null_count:
                raise SweepError(f"{f}: {column.null_count} row(s) without a status: not a chunk a sweep wrote")
            indices = column.indices  # its buffer read directly: to_numpy would load pandas (0.2 s)
            codes = np.frombuffer(indices.buffers()[1], dtype=str(indices.type))[indices.offset:][:len(indices)]
            tally = np.bincount(codes, minlength=len(column.dictionary))
            for name, n in zip(column.dictionary.to_pylist(), tally.tolist(), strict=True):
                counted[name] = counted.get(name, 0) + n
    return checks.tally(counted)


def chunk_files(path: Path) -> list[Path]:
    """A sweep's chunk files, each checked to be a readable Parquet file of a sweep (from its
    footer: the rows are not read), or a :class:`SweepError` naming the file. The one check of
    what ``fit``, its figure and the status counts read."""
    import pyarrow.parquet as pq

    if (path / "chunks").is_dir():
        path = path / "chunks"
    files = sorted(path.glob("chunk-*.parquet")) if path.is_dir() else [path]
    if not files or not files[0].exists():
        raise SweepError(f"{path}: no chunk files (a sweep's output folder, or its chunks/ folder, is expected)")
    for f in files:
        try:
            names = pq.read_schema(str(f)).names
        except (OSError, ValueError) as exc:  # pyarrow's errors for a corrupt or foreign file
            raise SweepError(f"{f}: not a readable sweep chunk ({exc})") from None
        if "v_n_initial" not in names:
            raise SweepError(f"{f}: a Parquet file, but not a spinbounce sweep's (no v_n_initial column)")
    return files


def read_results(path: Path) -> pd.DataFrame:
    """A sweep's rows, from its output folder or its ``chunks`` dataset folder."""
    import pandas as pd

    frames = []
    for f in chunk_files(Path(path)):
        try:
            frames.append(pd.read_parquet(f))
        except (OSError, ValueError) as exc:  # a file whose footer reads and whose rows do not
            raise SweepError(f"{f}: not a readable sweep chunk ({exc})") from None
    return pd.concat(frames, ignore_index=True)


def check_complete(path: Path) -> None:
    """Refuse a sweep's output folder whose record (sweep.json) names chunks it does not hold: a sweep stopped or
    failed before its end, whose rows a fit would take for the whole sweep (a missing model group among them).
    A chunks/ folder or file given directly, without its record, is read as it is."""
    from ..records import read_json
    from .run import missing_chunks
    from .spec import spec_from_dict

    path = Path(path)
    record = path / "sweep.json"
    if not record.is_file():
        return
    try:
        spec = spec_from_dict(read_json(record, "sweep record")["spec"])
    except SweepError:  # a sweep an earlier spinbounce took and this one would refuse: its chunks read as they are
        return
    chunks, missing = spec.chunks(), missing_chunks(spec, path)
    if missing:
        rows = sum(stop - start for _, _, start, stop in missing)
        total = spec.n * len(spec.groups)
        raise SweepError(f"{path}: an unfinished sweep: {len(missing)} of its {len(chunks)} chunks ({rows} of {total} "
                         "collisions) have no file; run the same sweep command again to finish it (it resumes), or "
                         "read its chunks/ folder as it stands")
