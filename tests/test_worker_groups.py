"""The test run's own set-up: tests of one xdist group (a session's product, the SLURM) run on one worker."""

import os
import subprocess
import sys
import textwrap

MEMBERS = 8


def test_a_groups_tests_run_on_one_worker(tmp_path):
    """pytest-xdist's loadgroup, as pyproject.toml sets it, on the installed pytest: one worker runs every member of
    a group (pytest 9.2's test ids drop the group xdist 3.8 appends, which spread a group over workers and made the
    session's reproduction twice)."""
    (tmp_path / "test_grouped.py").write_text(textwrap.dedent(f"""
        import os
        from pathlib import Path

        import pytest

        @pytest.mark.xdist_group("one")
        @pytest.mark.parametrize("k", range({MEMBERS}))
        def test_member(k):
            (Path(os.environ["WORKERS_SEEN"]) / str(k)).write_text(os.environ["PYTEST_XDIST_WORKER"])

        @pytest.mark.parametrize("k", range({MEMBERS}))
        def test_free(k):
            pass
    """))
    seen = tmp_path / "seen"
    seen.mkdir()
    done = subprocess.run([sys.executable, "-m", "pytest", "-q", "-c", os.devnull, "--rootdir", str(tmp_path),
                           "-p", "no:cacheprovider", "-n", "2", "--dist", "loadgroup", str(tmp_path / "test_grouped.py")],
                          capture_output=True, text=True, env={**os.environ, "WORKERS_SEEN": str(seen)}, cwd=tmp_path)
    assert done.returncode == 0, done.stdout + done.stderr
    workers = {p.read_text() for p in seen.iterdir()}
    assert len(list(seen.iterdir())) == MEMBERS and len(workers) == 1, workers
