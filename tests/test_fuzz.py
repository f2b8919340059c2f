"""The fuzz set: unusual and wrong invocations of ``spinbounce``, each run as a user runs it.

Every case (tests/fuzz_cases.py) runs ``python -m spinbounce.cli ...`` (or ``python -m spinbounce``) in a
process of its own, in a folder of its own holding the files it needs; two at a time, since the machine may
have no more cores. The process is forked from a server that has imported the command line and its libraries
once (tests/fuzz_server.py: Python's start and those imports were most of each case's half second); the
``pipe`` cases, whose reader goes away mid-output, run as subprocesses of their own. A case that does not end
within :data:`TIMEOUT` fails: the set is made of refusals that come before LAMMPS starts and runs of one tiny
collision.
"""

from __future__ import annotations

import json
import os
import queue
import select
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from pathlib import Path

import pytest

import spinbounce
from fuzz_cases import CASES, Case
from fuzz_support import make, snapshot

#: Seconds one invocation may take; the slowest case (a frozen contact in LAMMPS) takes about 2.
TIMEOUT = 60.0
#: At most this many invocations at once.
PARALLEL = 2


@dataclass
class Outcome:
    code: int | None
    stdout: str
    stderr: str
    seconds: float
    before: dict
    after: dict


def _environment() -> dict:
    env = dict(os.environ)
    source = str(Path(spinbounce.__file__).resolve().parents[1])
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [source, env.get("PYTHONPATH")]))
    env.pop("COLUMNS", None)
    return env


def _kill(pid: int) -> None:
    """The whole process group of a case's process ``pid``: a sweep's workers go with their parent."""
    try:
        os.killpg(pid, signal.SIGKILL)
    except ProcessLookupError:
        pass


class _Server:
    """A fork server (tests/fuzz_server.py): runs one case at a time, each in a fresh process."""

    def __init__(self):
        self.process = subprocess.Popen([sys.executable, "-m", "fuzz_server"], cwd=Path(__file__).parent,
                                        env=_environment(), stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
        self.scratch = Path(tempfile.mkdtemp(prefix="fuzz-stdio-"))
        self.pending = b""
        said = self._reply(TIMEOUT)
        if said is None or said["import_output"]:
            self.close()
            raise RuntimeError(f"the fuzz server's imports printed (or never ended): {said}")

    def _reply(self, seconds: float | None = None) -> dict | None:
        """The server's next line, read unbuffered (a buffered reader could hold it where select does not
        look); None if none comes within ``seconds``."""
        deadline = None if seconds is None else time.monotonic() + seconds
        while b"\n" not in self.pending:
            left = None if deadline is None else max(deadline - time.monotonic(), 0.0)
            if not select.select([self.process.stdout], [], [], left)[0]:
                return None
            data = os.read(self.process.stdout.fileno(), 4096)
            if not data:
                raise RuntimeError(f"the fuzz server ended (exit {self.process.wait()})")
            self.pending += data
        line, self.pending = self.pending.split(b"\n", 1)
        return json.loads(line)

    def invoke(self, case: Case, folder: Path) -> tuple[int | None, str, str]:
        out, err = self.scratch / f"{case.id}.out", self.scratch / f"{case.id}.err"
        request = {"module": case.module, "argv": list(case.argv), "cwd": str(folder), "stdout": str(out),
                   "stderr": str(err)}
        self.process.stdin.write(json.dumps(request) + "\n")
        self.process.stdin.flush()
        pid = self._reply()["pid"]
        ended = self._reply(TIMEOUT)
        if ended is None:
            _kill(pid)
            self._reply()
            return None, "", f"timed out after {TIMEOUT:.0f} s"
        if ended["left_running"]:
            return None, out.read_text(), err.read_text() + "\nleft processes running after it ended (killed)"
        return ended["code"], out.read_text(), err.read_text()

    def close(self) -> None:
        self.process.stdin.close()
        self.process.stdout.close()
        self.process.wait()
        shutil.rmtree(self.scratch, ignore_errors=True)


def _invoke(case: Case, folder: Path) -> tuple[int | None, str, str]:
    """A ``pipe`` case, as a subprocess of its own (its reader goes away after one line)."""
    command = [sys.executable, "-m", case.module, *case.argv]
    process = subprocess.Popen(command, cwd=folder, env=_environment(), stdin=subprocess.DEVNULL,
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True)
    try:  # the reader takes one line and goes away, as `| head -1` does
        first = process.stdout.readline()
        process.stdout.close()
        return process.wait(timeout=TIMEOUT), first, process.stderr.read()
    except subprocess.TimeoutExpired:
        _kill(process.pid)
        process.wait()
        return None, "", f"timed out after {TIMEOUT:.0f} s"


def run_case(case: Case, folder: Path, servers: queue.Queue) -> Outcome:
    make(folder, case.files)
    before = snapshot(folder)
    started = time.perf_counter()
    if case.expect == "pipe":
        code, stdout, stderr = _invoke(case, folder)
    else:
        server = servers.get()
        try:
            code, stdout, stderr = server.invoke(case, folder)
        finally:
            servers.put(server)
    return Outcome(code, stdout, stderr, time.perf_counter() - started, before, snapshot(folder))


@pytest.fixture(scope="module")
def outcomes(request, tmp_path_factory) -> dict[str, tuple[Outcome, Path]]:
    """Every selected case, run PARALLEL at a time, once: {case id: (outcome, its folder)}."""
    selected = [item.callspec.params["case"] for item in request.session.items
                if item.module.__name__ == __name__ and hasattr(item, "callspec")]
    folders = [tmp_path_factory.mktemp(f"fuzz-{case.id}") for case in selected]
    servers: queue.Queue = queue.Queue()
    for _ in range(PARALLEL):
        servers.put(_Server())
    try:
        with ThreadPoolExecutor(max_workers=PARALLEL) as pool:
            results = list(pool.map(lambda case, folder: run_case(case, folder, servers), selected, folders))
    finally:
        while not servers.empty():
            servers.get().close()
    return {case.id: (result, folder) for case, result, folder in zip(selected, results, folders)}


def _marks(case: Case):
    return [pytest.mark.lammps] if case.expect == "ok" and case.argv[0] in ("collide", "frozen") else []


@pytest.mark.slow
@pytest.mark.xdist_group("fuzz")  # one worker: `outcomes` runs every case at once, once
@pytest.mark.parametrize("case", [pytest.param(c, id=c.id, marks=_marks(c)) for c in CASES])
def test_invocation(case: Case, outcomes):
    got, folder = outcomes[case.id]
    shown = f"spinbounce {' '.join(case.argv)} -> exit {got.code}\nstdout: {got.stdout[-2000:]}\nstderr: {got.stderr}"
    assert got.code is not None, shown
    assert "Traceback" not in got.stderr, shown
    if case.expect == "refused":
        lines = got.stderr.strip().splitlines()
        assert got.code == 2 and len(lines) == 1 and lines[0].startswith("spinbounce"), shown
        missing = [needle for needle in case.needles if needle not in lines[0]]
        assert not missing, f"the refusal does not name {missing}\n{shown}"
        assert got.after == got.before, f"a refusal changed the files\n{shown}"
    elif case.expect == "ok":
        assert got.code == 0, shown
        if "--force" not in case.argv:
            changed = [name for name, content in got.before.items() if got.after.get(name) != content]
            assert not changed, f"a user's file was changed: {changed}\n{shown}"
        case.check(got.stdout, folder)
    else:
        assert got.code == 0 and got.stdout and not got.stderr.strip(), shown


def test_the_set_is_large_and_readable():
    """At least 150 invocations, each with a unique readable id and an expected class."""
    ids = [case.id for case in CASES]
    assert len(CASES) >= 150 and len(set(ids)) == len(ids)
    assert all(case.expect in ("refused", "ok", "pipe") for case in CASES)
    assert all(case.needles for case in CASES if case.expect == "refused")
    assert all(case.check is not None for case in CASES if case.expect == "ok")
