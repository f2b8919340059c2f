"""Worker processes: how they start, and how they end with their parent.

A sweep runs its chunks, and ``reproduce`` its products, in worker processes on the cores this
process may use (:func:`cores`); both start them with :func:`context` and :func:`die_with_parent`.
"""

from __future__ import annotations

import contextlib
import operator
import os
import sys

__all__ = ["context", "die_with_parent", "cores", "main_unseen", "checked_count"]


def context():
    """Workers forked while this process has not loaded LAMMPS (a script without a ``__main__``
    guard works then); spawned once it has, since a forked MPI library is not safe."""
    import multiprocessing

    return multiprocessing.get_context("spawn" if "lammps" in sys.modules else "fork")


def die_with_parent(parent: int) -> None:
    """A worker ends when its parent (process ``parent``) does, even after SIGKILL (Linux's parent-death
    signal). A pool's ``initializer``, with ``initargs=(os.getpid(),)``."""
    import ctypes
    import signal

    try:
        ctypes.CDLL("libc.so.6", use_errno=True).prctl(1, signal.SIGTERM)  # PR_SET_PDEATHSIG = 1
    except OSError:  # not Linux: workers then end when they find their task queue gone
        pass
    # Ctrl-C reaches the whole process group: the parent alone answers it (a worker stopped inside
    # LAMMPS's clean-up would print)
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    if os.getppid() != parent:  # the parent died before the call above (its children go to another)
        os._exit(1)


def cores() -> int:
    """The CPUs this process may run on (its affinity; all of the machine's where that is not known)."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:
        return os.cpu_count() or 1


@contextlib.contextmanager
def main_unseen():
    """While a pool of :func:`context`'s workers starts (its creation and its submissions), the caller's script
    (``__main__``'s file and module name) hidden from spawned workers: spawn imports it again in each worker,
    which runs a script without an ``if __name__ == "__main__":`` guard again there. The workers run
    spinbounce's own functions, which need nothing of it. Forked workers copy the script's state instead:
    nothing is hidden then."""
    main = sys.modules.get("__main__")
    if main is None or context().get_start_method() != "spawn":
        yield
        return
    saved = {k: main.__dict__[k] for k in ("__file__", "__spec__") if k in main.__dict__}
    main.__dict__.pop("__file__", None)
    main.__dict__["__spec__"] = None
    try:
        yield
    finally:
        main.__dict__.pop("__spec__", None)
        main.__dict__.update(saved)


def checked_count(workers) -> int:
    """``workers`` as a count of worker processes: a whole number >= 1 and at most the cores this process may use
    (more only slow each other); a ValueError naming the value and the limit otherwise."""
    try:
        count = operator.index(workers)  # an int of any kind (numpy's too), not a float
    except TypeError:
        count = None
    if isinstance(workers, bool) or count is None or not 1 <= count <= cores():
        raise ValueError(f"workers = {workers!r}: must be a whole number from 1 to the {cores()} core(s) available")
    return count
