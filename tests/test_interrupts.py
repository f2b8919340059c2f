"""A sweep stopped by a signal leaves nothing behind, and the rerun finishes exactly.

A sweep stopped by a signal leaves nothing behind: no worker outlives a killed parent,
Ctrl-C leaves no temporary file, and the same command then finishes with exactly its rows.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pandas as pd
import pytest

pytestmark = pytest.mark.lammps

#: 30 chunks of about half a second each: the sweep is still running when the first chunk appears,
#: even on a loaded machine where this test's own polling may wait seconds for the CPU.
N, CHUNK = 300_000, 10_000


def _processes_mentioning(text: str) -> list[int]:
    found = []
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                if text in (entry / "cmdline").read_bytes().replace(b"\0", b" ").decode(errors="replace"):
                    found.append(int(entry.name))
            except OSError:  # the process ended while we looked
                pass
    return found


def _as_from_a_terminal() -> None:
    """Ctrl-C's default action, as a terminal's shell gives its commands: a test run started in
    the background of a non-interactive shell hands its children SIGINT ignored, and the sweep
    rightly keeps what it inherits."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def _start(out: Path) -> subprocess.Popen:
    argv = [sys.executable, "-m", "spinbounce.cli", "sweep", "--n", str(N), "--chunk-size", str(CHUNK),
            "--workers", "2", "--out", str(out)]
    return subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE, start_new_session=True,
                            preexec_fn=_as_from_a_terminal)


def _wait_for(predicate, seconds: float) -> bool:
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        if predicate():
            return True
        time.sleep(0.05)
    return False


def test_no_worker_outlives_a_killed_sweep(tmp_path):
    out = tmp_path / "killed"
    parent = _start(out)
    assert _wait_for(lambda: len(_processes_mentioning(str(out))) >= 3, 60), "the workers never started"
    parent.send_signal(signal.SIGKILL)
    parent.wait()
    assert _wait_for(lambda: not _processes_mentioning(str(out)), 5.0), _processes_mentioning(str(out))


@pytest.mark.slow
def test_ctrl_c_leaves_no_temporary_file_and_a_rerun_completes(tmp_path):
    out = tmp_path / "interrupted"
    sweep = _start(out)
    chunks = out / "chunks"
    assert _wait_for(lambda: chunks.is_dir() and any(chunks.glob("chunk-*.parquet")), 120)
    assert sweep.poll() is None, "the sweep ended before it could be interrupted"
    os.killpg(sweep.pid, signal.SIGINT)  # what a terminal's Ctrl-C sends: the whole group
    _, err = sweep.communicate(timeout=60)
    assert sweep.returncode != 0 and b"Traceback" not in err
    assert b"rerun the same command" in err or b"interrupted" in err
    assert _wait_for(lambda: not _processes_mentioning(str(out)), 5.0)
    assert not [p for p in out.rglob("*") if p.name.endswith(".tmp")]
    rerun = _start(out)
    assert rerun.wait(timeout=600) == 0, rerun.stderr.read().decode()[-2000:]
    rows = pd.read_parquet(chunks, columns=["group", "index"])
    assert len(rows) == N and not rows.duplicated().any()
