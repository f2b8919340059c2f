"""The compiled references' first use on a machine: each family (a solver and the compiled functions it calls)
compiled once, by one process at a time, with a note on stderr.

numba compiles a function at its first call and keeps the result in the cache folder (:mod:`.vec3`): 17 s of
one core for the uncapped Hooke batch, 30 s for the capped one, 3 to 6 s for the laws on the contact radius
(an idle core; twice that with both cores busy). Two processes compiling at once would each pay it, and could
corrupt the cache: numba numbers a function's cached versions from an index that each process reads, extends and
writes back, so two processes compiling different versions of one function (``vec3.dot`` on tuples and on arrays,
the DOP853 step of two batches) can both write version 1, and the index can then name the other's code. So a
family is compiled under a lock on the cache folder, by solving its own small example (:func:`example`); a marker
file then tells every later process that the cache holds it. The wall's oracle (:mod:`.oracle_kernel`) shares no
compiled function with another family and compiles on its first call (2 s).
"""

from __future__ import annotations

import fcntl
import sys
import time
from collections.abc import Callable
from pathlib import Path

from .vec3 import cache_folder

__all__ = ["example", "once", "compile_all", "EXAMPLES"]

#: family: (its small example, the seconds of one idle core its compiling took when measured).
EXAMPLES: dict[str, tuple[Callable[[], object], float]] = {}
_READY: set[str] = set()  # the families this process has compiled, or found in the cache
_HOLDING = [False]  # whether this process holds the lock (an example's own solver asks for its family again)


def example(family: str, seconds: float):
    """Declares the decorated function (no arguments) as ``family``'s example: it solves a case that calls
    every compiled function of the family with the argument types the family's solver passes."""
    def register(function):
        EXAMPLES[family] = (function, seconds)
        return function
    return register


def once(family: str, log: Callable[[str], object] | None = None) -> None:
    """``family`` compiled, or found in the cache, before its solver runs: by this process under the lock (with a
    note to ``log``, stderr by default), or by another that held it. Nothing to do without a cache folder."""
    folder = cache_folder()
    if family in _READY or folder is None or _HOLDING[0]:
        return
    marker = Path(folder) / f"compiled-{family.replace(' ', '-')}"
    if not marker.exists():
        _compile(family, marker, log or _stderr)
    _READY.add(family)


def compile_all(log: Callable[[str], object] | None = None) -> dict[str, float]:
    """Every declared family compiled (:func:`once`): the seconds each took here (nearly 0 where cached)."""
    seconds = {}
    for family in EXAMPLES:
        started = time.perf_counter()
        once(family, log)
        seconds[family] = time.perf_counter() - started
    return seconds


def _compile(family: str, marker: Path, log: Callable[[str], object]) -> None:
    run, seconds = EXAMPLES[family]
    with open(marker.parent / "compiling.lock", "a") as lock:
        try:
            fcntl.flock(lock, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            log(f"spinbounce: waiting for another process compiling the exact references (in {marker.parent})")
            fcntl.flock(lock, fcntl.LOCK_EX)
        try:
            if marker.exists():  # the other process compiled it
                return
            log(f"spinbounce: compiling the {family} reference for this machine, once (about {seconds:.0f} s of "
                f"one core; cached in {marker.parent})")
            _HOLDING[0] = True
            try:
                run()
            finally:
                _HOLDING[0] = False
            marker.touch()  # an empty file, made at once: there is nothing half-written to read
        finally:
            fcntl.flock(lock, fcntl.LOCK_UN)


def _stderr(line: str) -> None:
    print(line, file=sys.stderr, flush=True)
