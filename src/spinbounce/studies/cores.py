"""Processes confined to CPUs, and what the machine gives several at once: the ceiling a sweep's workers are
measured against (``spinbounce bench``), with no spinbounce code in its timing."""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

__all__ = ["ON_CPUS", "BARE_DECK", "first_cpus", "engine_ceiling", "ceiling_words"]

#: A process that confines itself to the CPUs of its first argument, then becomes the command after it (set in
#: the child itself: a parent's preexec_fn is unsafe beside the threads a bench has started by then).
ON_CPUS = ("import os, sys; os.sched_setaffinity(0, {int(c) for c in sys.argv[1].split(',')}); "
           "os.execv(sys.executable, [sys.executable, *sys.argv[2:]])")


def first_cpus(count: int) -> set[int] | None:
    """The first ``count`` CPUs this process may run on (logical CPUs: two may share a core); None where it may
    run on fewer, or where the system cannot confine a process to some."""
    allowed = sorted(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else []
    return set(allowed[:count]) if len(allowed) >= count else None


BARE_DECK = ("import sys, time; from spinbounce.lammps.runner import run_deck; "  # one deck, LAMMPS's seconds
             "started = time.perf_counter(); run_deck(sys.argv[1]); print(time.perf_counter() - started)")


def engine_ceiling(deck, spheres: int, workers: int = 2, repeats: int = 2) -> dict | None:
    """What the machine gives ``workers`` processes at once, no spinbounce code timed: a deck (of ``spheres``, a data
    file's route) run by the bare engine on each CPU alone, then in ``workers`` processes at once, each on
    a CPU of its own (each the fastest of ``repeats``, in turn: noise slows a run, never speeds it). Its
    ``efficiency`` (the mean over CPUs of a run's rate beside the others over its rate alone on the same CPU: two
    CPUs of a shared machine need not run alike) is the ceiling a sweep's workers reach here
    (CPUs can share a memory bus, a cache or a core). None for one worker or CPU; its error if a run failed."""
    from ..lammps.decks import prepare_run_dir

    cpus = first_cpus(workers)
    if cpus is None or workers < 2:
        return None
    cpus = sorted(cpus)
    lone, together = np.full(workers, np.inf), np.full(workers, np.inf)  # per CPU: they need not run alike
    with tempfile.TemporaryDirectory(prefix="spinbounce-bench-ceiling-") as folder:
        paths = [prepare_run_dir(Path(folder) / f"deck{k}", deck, durable=False) for k in range(workers)]
        try:
            for _ in range(repeats):
                for k, cpu in enumerate(cpus):
                    lone[k] = min(lone[k], _bare_runs(paths[:1], [cpu])[0])
                together = np.minimum(together, _bare_runs(paths, cpus))
        except (RuntimeError, subprocess.TimeoutExpired) as exc:  # the bench's other lines are kept
            return {"workers": workers, "error": str(exc)}
    return {"workers": workers, "spheres": spheres, "lone_seconds": lone.tolist(), "together_seconds":
            together.tolist(), "efficiency": float(np.mean(lone / together)), "repeats": repeats}


def _bare_runs(paths: list, cpus: list) -> list[float]:
    """LAMMPS's seconds of each deck of ``paths``, all started at once, each in a process on its CPU of ``cpus``."""
    runs = [subprocess.Popen([sys.executable, "-c", ON_CPUS, str(cpu), "-c", BARE_DECK, str(path)],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
            for path, cpu in zip(paths, cpus, strict=True)]
    try:
        done = [run.communicate(timeout=600) for run in runs]  # every one waited for, before any is judged
    finally:
        for run in runs:
            run.kill()  # none outlives its folder (a no-op on one that ended)
    for run, (_, stderr) in zip(runs, done, strict=True):
        if run.returncode:
            raise RuntimeError("the bare engine's run failed: " + (stderr.strip().splitlines() or ["no message"])[-1])
    return [float(stdout.split()[-1]) for stdout, _ in done]


def ceiling_words(machine: dict | None, times: str) -> str:
    """The machine's own ceiling (:func:`engine_ceiling`) as words for :func:`.speed.core_line`."""
    if not machine:
        return ""
    if "error" in machine:
        return f"; the machine's own ceiling could not be measured ({machine['error']})"
    return (f"; the machine's own ceiling, the bare engine in {machine['workers']} processes at once on "
            f"{machine['spheres']:,}-sphere decks: {machine['efficiency']:.0%} of {times} one")
