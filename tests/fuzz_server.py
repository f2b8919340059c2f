"""The fuzz set's fork server: each invocation in a fresh process forked from one that imported the libraries.

One interpreter imports the command line and the libraries its commands load, then forks a process for each
invocation, which runs ``python -m MODULE ARGV`` as a new interpreter would: in its own folder (first on
sys.path, as ``-m`` puts it), its own session (a timeout kills the whole group, workers included), stdin from
/dev/null, stdout and stderr to files, and the exit status Python gives (SystemExit's code; 1 and the traceback
for an uncaught exception; atexit handlers run).
Starting Python and importing numpy, pandas and scipy took most of each of the 273 invocations' half second.

Requests are JSON lines on stdin ({"module", "argv", "cwd", "stdout", "stderr"}); for each the server writes
{"pid": ...} when the process starts and {"code": ...} when it ends (negative: killed by that signal).
"""

from __future__ import annotations

import atexit
import importlib
import json
import os
import runpy
import sys
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
    """``python -m module`` in this process: its exit status as the interpreter would give it."""
    try:
        runpy.run_module(module, run_name="__main__", alter_sys=True)
        code = 0
    except SystemExit as exc:
        code = exc.code if isinstance(exc.code, int) else (0 if exc.code is None else 1)
        if not isinstance(exc.code, int) and exc.code is not None:
            print(exc.code, file=sys.stderr)
    except BaseException:
        traceback.print_exc()
        code = 1
    try:
        atexit._run_exitfuncs()
        sys.stdout.flush()
        sys.stderr.flush()
    except BaseException:
        traceback.print_exc()
        code = code or 120  # what Python gives when stdout cannot be flushed at exit
    return code


def _child(request: dict, channel: int) -> None:
    os.close(channel)
    os.setsid()
    os.chdir(request["cwd"])
    _redirect(request)
    sys.path[0] = os.getcwd()
    sys.argv = [request["module"], *request["argv"]]
    os._exit(_run(request["module"]))


def main() -> None:
    for name in PRELOADED:
        importlib.import_module(name)
    channel = os.dup(1)
    for line in sys.stdin:
        request = json.loads(line)
        sys.stdout.flush()
        sys.stderr.flush()
        pid = os.fork()
        if pid == 0:
            _child(request, channel)
        os.write(channel, (json.dumps({"pid": pid}) + "\n").encode())
        _, status = os.waitpid(pid, 0)
        os.write(channel, (json.dumps({"code": os.waitstatus_to_exitcode(status)}) + "\n").encode())


if __name__ == "__main__":
    main()
