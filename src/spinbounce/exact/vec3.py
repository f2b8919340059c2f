"""3-vectors as tuples in compiled code (numba keeps them in registers: no array is made per call)."""

from __future__ import annotations

import hashlib
import os
import tempfile
from pathlib import Path

import numba
import numpy as np
from numba import njit

__all__ = ["FLAGS", "cache_folder", "compiled", "kernel", "dot", "cross", "axpy", "unit", "COMPILED"]

#: The compiled references' numba options: cached on disk, and IEEE arithmetic (a division by zero is
#: inf or NaN, as numpy's, not an exception).
FLAGS = dict(cache=True, error_model="numpy")
#: The modules whose code and constants the compiled references are built from. numba keys a cached
#: function on its own file only, so an edit to one of the others (the DOP853 step, a constant of the
#: capped reference) would leave the cache serving the old code: the cache lives in a folder named by
#: the digest of all of them.
COMPILED = ("vec3.py", "dop853.py", "dop853_tableau.json", "pair_exact.py", "pair_batch.py", "pair_capped.py",
            "pair_capped_phases.py", "pair_capped_batch.py", "pair_kernel.py", "oracle_kernel.py")


def _writable(folder: Path) -> bool:
    try:
        folder.mkdir(parents=True, exist_ok=True)
        with tempfile.TemporaryFile(dir=folder):
            return True
    except OSError:
        return False


def _cache_dir() -> str | None:
    """The digest's folder under the user's cache (numba's own setting, XDG_CACHE_HOME or ~/.cache), else
    under the system's temporary folder; None if neither can be written (then nothing is cached: numba's
    fallback, a cache beside each file, would be keyed on that file alone)."""
    here = Path(__file__).parent
    sources = b"".join((here / name).read_bytes() for name in COMPILED)  # and numba's version: first_use's markers
    digest = hashlib.sha256(sources + numba.__version__.encode()).hexdigest()[:16]  # hold for this numba only
    bases = [numba.config.CACHE_DIR, os.environ.get("XDG_CACHE_HOME"), os.environ.get("HOME") and
             str(Path(os.environ["HOME"]) / ".cache"), str(Path(tempfile.gettempdir()) / f"spinbounce-{os.getuid()}")]
    for base in filter(None, bases):
        folder = Path(base) / "spinbounce-numba" / digest
        if _writable(folder):
            return str(folder)
    return None


_CACHE_DIR = _cache_dir()
if _CACHE_DIR is None:
    FLAGS["cache"] = False


def cache_folder() -> str | None:
    """The folder the compiled references are cached in (named by the digest of their sources), or None."""
    return _CACHE_DIR


def compiled(function, **options):
    """``function`` compiled with :data:`FLAGS` (and numba's ``options``), its cache in the digest's folder (numba
    reads the folder when a cached function is declared: set for that moment only, the process's own setting kept)."""
    previous = numba.config.CACHE_DIR
    numba.config.CACHE_DIR = _CACHE_DIR or previous
    try:
        return njit(**FLAGS, **options)(function)
    finally:
        numba.config.CACHE_DIR = previous


def kernel(function):
    """:func:`compiled` for a function that makes no array (it reads and writes those it is given, by element):
    without numba's reference counts, an atomic increment and decrement of every array argument at every call,
    which took half of the pair batches' time (perf: NRT_incref and NRT_decref, called from the DOP853 step and
    the rates; numba's option ``_nrt``). Such a function may not allocate, copy a slice or return an array."""
    return compiled(function, _nrt=False)


@compiled
def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


@compiled
def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


@compiled
def axpy(c, a, b):
    """c a + b of 3-tuples."""
    return (c * a[0] + b[0], c * a[1] + b[1], c * a[2] + b[2])


@compiled
def unit(a):
    size = np.sqrt(dot(a, a))
    return (a[0] / size, a[1] / size, a[2] / size), size
