"""The compiled references' first use on a machine: each family (a solver and the compiled functions it calls)
compiled once, by one process at a time, with a note on stderr.

numba compiles a function at its first call and keeps the result in the cache folder (:mod:`.vec3`). Compiled
one after another, the four families took 32 to 55 s of one core in CI and here (alone: 17 s the uncapped Hooke batch,
18 to 30 s the capped one, 3 to 6 s each the laws on the contact radius; twice that with both cores busy).
Two processes compiling at once would each pay it, and could corrupt the cache: numba numbers a function's
cached versions from an index that each process reads, extends and writes back, so two processes compiling
different versions of one function (``vec3.dot`` on tuples and on arrays, the DOP853 step of two batches) can
both write version 1, and the index can then name the other's code. So a family is compiled under a lock on the
cache folder, by solving its own small example (:func:`example`); a marker file then tells every later process
that the cache holds it. numba keys its cached code on more than the sources the folder is named by (the
folder it was loaded from, Python's version, the CPU), and so does the marker. The wall's oracle
(:mod:`.oracle_kernel`) shares no compiled function with another family and compiles on its first call (2 s).
"""

from __future__ import annotations

import fcntl
import functools
import hashlib
import os
import sys
import time
from collections.abc import Callable
from pathlib import Path

import numba

from .vec3 import cache_folder

__all__ = ["example", "once", "compile_all", "EXAMPLES", "WAIT_SECONDS"]

#: family: (its small example, the seconds of one idle core its compiling took alone when measured).
EXAMPLES: dict[str, tuple[Callable[[], object], float]] = {}
#: How long a process waits for another's compiling before it compiles without the lock (a holder stopped
#: with Ctrl-Z, say, would otherwise hold every later command).
WAIT_SECONDS = 600.0
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
    note to ``log``, stderr by default), or by another that held it. Nothing to do without a cache folder, or
    with numba's compiling switched off."""
    folder = cache_folder()
    if family in _READY or folder is None or _HOLDING[0] or numba.config.DISABLE_JIT:
        return
    _READY.add(family)  # once a process, whatever happens below
    marker = Path(folder) / f"compiled-{family.replace(' ', '-')}-{_machine()}"
    if not marker.exists():
        _compile(family, marker, log or _stderr)


def compile_all(log: Callable[[str], object] | None = None) -> dict[str, float]:
    """Every declared family compiled (:func:`once`): the seconds each took here (nearly 0 where cached)."""
    seconds = {}
    for family in EXAMPLES:
        started = time.perf_counter()
        once(family, log)
        seconds[family] = time.perf_counter() - started
    return seconds


@functools.cache
def _machine() -> str:
    """What numba's cached code holds for beyond the sources: the folder they were loaded from, Python's
    version and the CPU numba compiles for (its codegen's magic tuple, part of every cached entry's key)."""
    from numba.core.registry import cpu_target

    parts = (str(Path(__file__).parent.absolute()), sys.implementation.cache_tag,
             repr(cpu_target.target_context.codegen().magic_tuple()))
    return hashlib.sha256("\n".join(parts).encode()).hexdigest()[:12]


def _compile(family: str, marker: Path, log: Callable[[str], object]) -> None:
    lock = os.open(marker.parent / "compiling.lock", os.O_RDONLY | os.O_CREAT, 0o644)
    try:
        held = _acquire(lock, marker, log)
        if marker.exists():  # another process compiled it while this one waited
            return
        run, seconds = EXAMPLES[family]
        log(f"spinbounce: compiling the {family} reference for this machine, once (about {seconds:.0f} s of "
            f"one core; cached in {marker.parent})")
        _HOLDING[0] = held
        try:
            run()
        except Exception as exc:  # its solver compiles what it calls at its own first call instead
            log(f"spinbounce: compiling the {family} reference ahead failed ({exc}); it compiles as it is used")
            return
        finally:
            _HOLDING[0] = False
        if held:
            marker.touch()  # an empty file, made at once: there is nothing half-written to read
    finally:
        os.close(lock)  # and with it the lock


def _acquire(lock: int, marker: Path, log: Callable[[str], object]) -> bool:
    """Whether the lock was taken: at once, or within :data:`WAIT_SECONDS` of another process's compiling."""
    try:
        fcntl.flock(lock, fcntl.LOCK_EX | fcntl.LOCK_NB)
        return True
    except BlockingIOError:
        log(f"spinbounce: waiting for another process compiling the exact references (in {marker.parent})")
    deadline = time.monotonic() + WAIT_SECONDS
    while time.monotonic() < deadline:
        time.sleep(0.5)
        try:
            fcntl.flock(lock, fcntl.LOCK_EX | fcntl.LOCK_NB)
            return True
        except BlockingIOError:
            continue
    log(f"spinbounce: still locked after {WAIT_SECONDS:.0f} s; compiling without the lock")
    return False


def _stderr(line: str) -> None:
    print(line, file=sys.stderr, flush=True)
