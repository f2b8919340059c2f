"""The fuzz set's fork server: each invocation in a fresh process forked from one that imported the libraries.

One interpreter imports the command line and the libraries its commands load, then forks a process for each
invocation, which runs ``python -m MODULE ARGV`` as a new interpreter would: in its own folder (first on
sys.path, as ``-m`` puts it), its own session (a timeout kills the whole group, workers included), stdin from
/dev/null, stdout and stderr to files, and the exit status Python gives (SystemExit's code; 1 and the traceback
for an uncaught exception; atexit handlers run).
Starting Python and importing numpy, pandas and scipy took most of each of the 273 invocations' half second.

It first writes {"import_output": ...}: whatever those imports printed, which a fresh interpreter would print into
every case's stderr (the test fails on any). Requests are then JSON lines on stdin ({"module", "argv", "cwd",
"stdout", "stderr"}); for each the server writes {"pid": ...} when the process starts and {"code": ...,
"left_running": ...} when it ends (code negative: killed by that signal; left_running: processes of its group
still ran after it, killed then, which a case must not leave).
"""

from __future__ import annotations

import atexit
import importlib
import json
import os
import runpy
import signal
import sys
import tempfile
import threading
import traceback

#: What the commands load, imported once here (never LAMMPS: each run loads its own library).
PRELOADED = ("spinbounce.cli", "numpy", "pandas", "pyarrow.parquet", "scipy.optimize", "scipy.integrate")


def _redirect(request: dict) -> None:
    for fd, path, flags in ((0, os.devnull, os.O_RDONLY),
                            (1, request["stdout"], os.O_WRONLY | os.O_CREAT | os.O_TRUNC),
                            (2, request["stderr"], os.O_WRONLY | os.O_CREAT | os.O_TRUNC)):
        handle = os.open(path, flags, 0o644)
        os.dup2(handle, fd)
        os.close(handle)


def _run(module: str) -> int:
    """``python -m module`` in this process: its exit status as the interpreter would give it (non-daemon threads
    joined and atexit handlers run before it ends; an uncaught KeyboardInterrupt ends it by SIGINT)."""
    interrupted = False
    try:
        runpy.run_module(module, run_name="__main__", alter_sys=True)
        code = 0
    except SystemExit as exc:
        code = exc.code if isinstance(exc.code, int) else (0 if exc.code is None else 1)
        if not isinstance(exc.code, int) and exc.code is not None:
            print(exc.code, file=sys.stderr)
    except KeyboardInterrupt:
        traceback.print_exc()
        code, interrupted = 1, True
    except BaseException:
        traceback.print_exc()
        code = 1
    try:
        threading._shutdown()
        atexit._run_exitfuncs()
        sys.stdout.flush()
        sys.stderr.flush()
    except BaseException:
        traceback.print_exc()
        code = 120  # what Python gives when stdout cannot be flushed at exit
    if interrupted:
        signal.signal(signal.SIGINT, signal.SIG_DFL)
        os.kill(os.getpid(), signal.SIGINT)
    return code


def _child(request: dict, channel: int) -> None:
    """The case's process: never returns (an error before the case runs ends it with status 70)."""
    code = 70
    try:
        os.close(channel)
        os.setsid()
        os.chdir(request["cwd"])
        _redirect(request)
        sys.path[0] = os.getcwd()
        sys.argv = [request["module"], *request["argv"]]
        code = _run(request["module"])
    finally:
        os._exit(code)


def _group_left(pid: int) -> bool:
    """Whether processes of the case's group still run after it ended; if so, they are killed."""
    try:
        os.killpg(pid, 0)
    except ProcessLookupError:
        return False
    os.killpg(pid, signal.SIGKILL)
    return True


def _preload() -> str:
    """Import PRELOADED; what they printed (a fresh ``python -m`` would print it into each case's output)."""
    with tempfile.TemporaryFile() as said:
        saved = os.dup(1), os.dup(2)
        os.dup2(said.fileno(), 1)
        os.dup2(said.fileno(), 2)
        try:
            for name in PRELOADED:
                importlib.import_module(name)
        finally:
            sys.stdout.flush()
            sys.stderr.flush()
            for fd, copy in zip((1, 2), saved):
                os.dup2(copy, fd)
                os.close(copy)  # no case inherits a copy of the server's own channel
        said.seek(0)
        return said.read().decode(errors="replace")


def _send(channel: int, reply: dict) -> None:
    os.write(channel, (json.dumps(reply) + "\n").encode())


def main() -> None:
    channel = os.dup(1)
    _send(channel, {"import_output": _preload()})
    for line in sys.stdin:
        request = json.loads(line)
        sys.stdout.flush()
        sys.stderr.flush()
        pid = os.fork()
        if pid == 0:
            _child(request, channel)
        _send(channel, {"pid": pid})
        _, status = os.waitpid(pid, 0)
        _send(channel, {"code": os.waitstatus_to_exitcode(status), "left_running": _group_left(pid)})


if __name__ == "__main__":
    main()
