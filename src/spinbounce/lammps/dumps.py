"""Read LAMMPS ``dump custom`` text files into tidy pandas tables.

One row per (timestep, atom), with the dump's own column names plus ``step``. Frames are
kept in file order and atoms sorted by id, so initial and final states pair by id.
"""

from __future__ import annotations

import io
from pathlib import Path

import numpy as np
import pandas as pd
from ..errors import DumpError, ResultError

__all__ = ["DumpError", "read_dump", "finite_frames"]


def read_dump(path: Path) -> pd.DataFrame:
    """Parse every frame of a ``dump custom`` file.

    Raises :class:`DumpError` on a malformed or empty file, or when frames disagree on
    their columns.
    """
    path = Path(path)
    lines = path.read_text().splitlines()
    while lines and not lines[-1].strip():
        lines.pop()
    body: list[str] = []
    steps: list[int] = []
    counts: list[int] = []
    columns: list[str] | None = None
    i = 0
    while i < len(lines):
        if lines[i] != "ITEM: TIMESTEP":
            raise DumpError(f"{path}:{i + 1}: expected 'ITEM: TIMESTEP', found {lines[i]!r}")
        try:
            step = int(lines[i + 1])
            if lines[i + 2] != "ITEM: NUMBER OF ATOMS":
                raise DumpError(f"{path}:{i + 3}: expected 'ITEM: NUMBER OF ATOMS'")
            natoms = int(lines[i + 3])
            if not lines[i + 4].startswith("ITEM: BOX BOUNDS"):
                raise DumpError(f"{path}:{i + 5}: expected 'ITEM: BOX BOUNDS'")
            header = lines[i + 8]
        except (IndexError, ValueError) as exc:
            raise DumpError(f"{path}:{i + 1}: truncated or malformed frame header") from exc
        if not header.startswith("ITEM: ATOMS "):
            raise DumpError(f"{path}:{i + 9}: expected 'ITEM: ATOMS ...', found {header!r}")
        cols = header.split()[2:]
        if columns is None:
            columns = cols
        elif cols != columns:
            raise DumpError(f"{path}:{i + 9}: columns {cols} differ from the first frame's {columns}")
        frame = lines[i + 9 : i + 9 + natoms]
        if len(frame) != natoms or "\nITEM:" in "\n" + "\n".join(frame):  # a row of the next frame's header
            raise DumpError(f"{path}: frame at step {step} is missing atoms (truncated file?)")
        body.extend(frame)
        steps.append(step)
        counts.append(natoms)
        i += 9 + natoms
    if columns is None:
        raise DumpError(f"{path}: no frames")
    if body:
        out = pd.read_csv(io.StringIO("\n".join(body)), sep=r"\s+", header=None, names=columns)
    else:
        out = pd.DataFrame({c: pd.Series(dtype=float) for c in columns})
    # NaN where LAMMPS itself wrote nan/inf (a blown-up run) is data; from a short row it is not
    def written_nan() -> bool:  # looked at only where a value is missing
        return any(("nan" in row.lower()) or ("inf" in row.lower()) for row in body)

    if out.shape[1] != len(columns) or (out.isna().to_numpy().any() and not written_nan()):
        raise DumpError(f"{path}: rows do not have the {len(columns)} columns {columns}")
    out.insert(0, "step", np.repeat(np.asarray(steps, dtype=np.int64), counts))
    if "id" in out:
        out["id"] = out["id"].astype(np.int64)
        out = out.sort_values(["step", "id"], kind="stable", ignore_index=True)
    return out


def finite_frames(frames: pd.DataFrame, where) -> pd.DataFrame:
    """A dump's ``frames``, or a :class:`ResultError` at the first row LAMMPS wrote a non-finite value in."""
    bad = ~np.isfinite(frames.drop(columns=["step", "id"]).to_numpy(dtype=float)).all(axis=1)
    if bad.any():
        first = frames[bad].iloc[0]
        raise ResultError(f"{where}: non-finite positions or velocities (first at step {int(first['step'])}, "
                          f"atom {int(first['id'])}): the integration blew up")
    return frames
