"""Files a command writes into a folder the user names (figures, records, reports): one writer.

A command replaces such a file only if spinbounce wrote it and nobody changed it since: each
folder keeps the names and SHA-256 digests of what spinbounce wrote there in
:data:`MANIFEST`. Any other file of the same name (a user's, or one edited since) is refused
with a one-line error naming it, and kept, unless the command runs under :func:`replacing`
(``--force``). A rerun of the same command into its own folder refreshes its files.
"""

from __future__ import annotations

import contextlib
import contextvars
import hashlib
import json
from collections.abc import Callable
from pathlib import Path

from .records import locked, write_atomic, write_atomic_with

__all__ = ["MANIFEST", "replacing", "forced", "check_outputs", "check_replaceable", "write_output", "write_output_with"]

#: The record, in each folder written into, of the files spinbounce wrote there.
MANIFEST = ".spinbounce-outputs.json"
_FORCE = contextvars.ContextVar("spinbounce_replace_any", default=False)


@contextlib.contextmanager
def replacing(force: bool = True):
    """Within this block, files of any origin may be replaced (a command's ``--force``)."""
    token = _FORCE.set(bool(force))
    try:
        yield
    finally:
        _FORCE.reset(token)


def forced() -> bool:
    """Whether this block replaces files of any origin (:func:`replacing`): what a worker is told."""
    return _FORCE.get()


def _digest(path: Path) -> str:
    with open(path, "rb") as handle:
        return hashlib.file_digest(handle, "sha256").hexdigest()


def _written(folder: Path) -> dict[str, str]:
    """name -> digest of what spinbounce wrote in ``folder``; an unreadable record counts as empty
    (then nothing in the folder is taken for spinbounce's, so nothing is replaced unasked)."""
    try:
        value = json.loads((folder / MANIFEST).read_text())
    except (OSError, ValueError):
        return {}
    return value.get("files", {}) if isinstance(value, dict) and isinstance(value.get("files"), dict) else {}


def check_outputs(folder: Path, names, option: str = "--out") -> None:
    """:func:`check_replaceable` for each file ``names`` in ``folder``: what a command calls before it
    runs anything, so that a refusal leaves the folder as it was."""
    for name in names:
        check_replaceable(Path(folder) / name, option)


def check_replaceable(path: Path, option: str = "--out") -> None:
    """Refuse to replace ``path`` if it exists and is not an unchanged file spinbounce wrote,
    unless under :func:`replacing`."""
    from .errors import SceneError

    path = Path(path)
    if _FORCE.get() or not path.exists():
        return
    if path.is_dir():
        raise SceneError(option, str(path), "is a folder where a file is to be written: give another folder")
    if _written(path.parent).get(path.name) != _digest(path):
        raise SceneError(option, str(path), "exists and was not written by spinbounce (or was changed since): "
                                            "give another folder, or --force to replace it")


def _record(path: Path) -> None:
    """Add ``path``'s digest to its folder's manifest (under a lock: commands may share a folder)."""
    folder = path.parent
    with locked(folder):  # the folder itself: no lock file left beside the outputs
        files = {**_written(folder), path.name: _digest(path)}
        write_atomic(folder / MANIFEST, json.dumps({"files": dict(sorted(files.items()))}, indent=1) + "\n")


def write_output_with(path: Path, write: Callable[[Path], None], option: str = "--out") -> Path:
    """Check ``path`` may be replaced, let ``write`` fill it atomically, and record it."""
    path = Path(path)
    check_replaceable(path, option)
    write_atomic_with(path, write)
    _record(path)
    return path


def write_output(path: Path, data: str | bytes, option: str = "--out") -> Path:
    """Text or bytes to ``path`` (:func:`write_output_with`)."""
    write = Path.write_text if isinstance(data, str) else Path.write_bytes
    return write_output_with(path, lambda tmp: write(tmp, data), option)
