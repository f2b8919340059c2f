"""Sweeps: scene-file validation (before any run), resumption after SIGKILL, fits."""

import json
import os
import signal
import subprocess
import sys
import time

import numpy as np
import pandas as pd
import pytest

from spinbounce.fitting import fit_groups
from spinbounce import checks
from spinbounce.sweeps import SweepError, load_spec, read_results, run_sweep
from spinbounce.sweeps import status_counts

GOOD = """
seed = 4
chunk_size = 300
[model]
kt = [1.0, 2.857142857142857]
[states]
n = 900
v_n = [-1.5, -0.1]
v_t = [-2.0, 2.0]
r_omega = [-2.0, 2.0]
"""


def write(tmp_path, text):
    path = tmp_path / "scene.toml"
    path.write_text(text)
    return path


def test_good_scene_file(tmp_path):
    spec = load_spec(write(tmp_path, GOOD))
    assert len(spec.groups) == 2 and spec.n == 900 and len(spec.chunks()) == 6
    a, b = spec.initial_states(0), spec.initial_states(0)
    np.testing.assert_array_equal(a, b)  # the seed fixes the sample
    # a chunk's rows, drawn alone by jumping the generator ahead, are the same rows
    np.testing.assert_array_equal(spec.initial_states(0, 300, 600), a[300:600])
    # and the sample is numpy's plain seeded uniform columns
    rng = np.random.default_rng(4)
    np.testing.assert_array_equal(a[:, 0], rng.uniform(-1.5, -0.1, 900))
    assert a[:, 0].min() >= -1.5 and a[:, 0].max() <= -0.1


@pytest.mark.parametrize(
    "edit, key",
    [
        (lambda t: t.replace("seed = 4", "seed = 4\ncolour = 1"), "colour"),
        (lambda t: t.replace("kt = [", "kq = ["), "model.kq"),
        (lambda t: t.replace("n = 900", 'n = "many"'), "states.n"),
        (lambda t: t.replace("kt = [1.0", 'kt = ["soft"'), "model.kt"),
        (lambda t: t.replace("v_t = [-2.0, 2.0]", "v_t = [2.0, -2.0]"), "states.v_t"),
        (lambda t: t.replace("v_n = [-1.5, -0.1]", "v_n = [-1.7, -0.1]"), "states.v_n"),
        (lambda t: t.replace("[model]", "[model]\ndt = 0.7"), "model.dt"),
        (lambda t: t.replace("[model]", "[model]\nalpha = 0"), "model.alpha"),
        (lambda t: t.replace("kt = [1.0, 2.857142857142857]", "kt = []"), "model.kt"),
    ],
    ids=["unknown-top", "unknown-model", "wrong-type", "wrong-type-list", "empty-range", "tunnels",
         "unstable-dt", "bad-alpha", "empty-grid"],
)
def test_bad_scene_files_name_the_key(tmp_path, edit, key):
    with pytest.raises(SweepError) as info:
        load_spec(write(tmp_path, edit(GOOD)))
    assert str(info.value).startswith(key), str(info.value)


@pytest.mark.lammps
def test_sweep_rows_fit_and_determinism(tmp_path):
    spec = load_spec(write(tmp_path, GOOD))
    run_sweep(spec, tmp_path / "a", workers=2, log=lambda *_: None)
    rows = read_results(tmp_path / "a")
    assert len(rows) == 1800 and not rows.duplicated(["group", "index"]).any()
    for col in ("scene_hash", "lammps_version", "spinbounce_version", "chunk", "dt", "v_t_theory", "v_t_error"):
        assert col in rows
    fits = fit_groups(rows)
    assert len(fits) == 2
    for f in fits:
        # per-collision error <= 5e-5 at the default step, so the fit is far inside 2e-4
        assert abs(f["Omega_diff"]) < 1e-4 and f["max_element_diff"] < 2e-4
    # same file, same seed: the same rows (LAMMPS is deterministic on one core)
    run_sweep(load_spec(write(tmp_path, GOOD)), tmp_path / "b", workers=1, log=lambda *_: None)
    again = read_results(tmp_path / "b")
    cols = ["v_n_initial", "v_t_initial", "r_omega_initial", "v_n_lammps", "v_t_lammps", "r_omega_lammps"]
    pd.testing.assert_frame_equal(rows.sort_values(["group", "index"])[cols].reset_index(drop=True),
                                  again.sort_values(["group", "index"])[cols].reset_index(drop=True))


def test_status_counts_read_from_the_files_match_the_rows(tmp_path):
    # a coarse given step (about 60 steps a contact at the paper's defaults) leaves many rows above 1e-4
    # and some below: both statuses must be counted, by Arrow from the files, as the rows hold them
    spec = load_spec(write(tmp_path, GOOD.replace("[model]", "[model]\ndt = 0.0025")))
    run_sweep(spec, tmp_path / "s", workers=1, log=lambda *_: None)
    counts = status_counts(tmp_path / "s")
    expected = read_results(tmp_path / "s")["status"].value_counts().to_dict()
    assert counts == {name: expected.get(name, 0) for name in checks.STATUSES}
    assert counts["ok"] and counts["inaccurate"] and sum(counts.values()) == 1800
    with pytest.raises(ValueError, match="'lost': not one of"):
        checks.tally({"ok": 3, "lost": 1})
    # a chunk with rows but no status is refused by name, not counted as another status
    from spinbounce.records import arrow_table, write_parquet_atomic

    chunk = sorted((tmp_path / "s" / "chunks").glob("chunk-*.parquet"))[0]
    write_parquet_atomic(chunk, arrow_table({"v_n_initial": np.zeros(2), "status": np.array(["ok", None])}))
    with pytest.raises(SweepError, match=f"{chunk.name}: 1 row"):
        status_counts(tmp_path / "s")


def test_chunk_tables_are_what_pyarrow_makes_and_a_writer_loads_no_pandas(tmp_path):
    """A chunk's Arrow table is built from its buffers (pyarrow.array loads pandas, 0.17 s of every
    worker): the same table as pyarrow's own, numbers, booleans, a strided column, text rows and labels;
    a process that writes one and counts its statuses never imports pandas."""
    import pyarrow as pa

    from spinbounce.records import arrow_table

    columns = {"x": np.array([0.5, np.nan, -1e300]), "k": np.arange(3)[::-1], "flag": np.array([True, False, True]),
               "strided": np.arange(6.0).reshape(3, 2)[:, 1], "status": np.array(["ok", "grazing", "ok"], dtype=object),
               "word": np.array(["a", "bé", ""])}
    expected = pa.table({**{k: pa.array(v) for k, v in columns.items()},
                         "theory": pa.array(["paper"] * 3).dictionary_encode()})
    table = arrow_table(columns, {"theory": "paper"})
    assert table.drop_columns("x").equals(expected.drop_columns("x")) and table.schema == expected.schema
    assert np.array_equal(table["x"].to_numpy(), columns["x"], equal_nan=True)  # NaN is no equal of itself
    # what has no buffer of its own to share is pyarrow's to read, as before: a masked column's nulls, 2-D refused
    assert arrow_table({"m": np.ma.masked_array([1.0, 2.0], mask=[False, True])})["m"].null_count == 1
    with pytest.raises(pa.ArrowInvalid):
        arrow_table({"two_d": np.zeros((3, 2))})
    script = ("import sys; import numpy as np; from pathlib import Path\n"
              "from spinbounce.records import arrow_table, write_parquet_atomic\n"
              "from spinbounce.sweeps import status_counts\n"
              f"out = Path({str(tmp_path)!r}) / 'chunks'; out.mkdir()\n"
              "table = arrow_table({'v_n_initial': np.zeros(4), 'status': np.array(['ok'] * 3 + ['inaccurate'])})\n"
              "write_parquet_atomic(out / 'chunk-0000-000000.parquet', table)\n"
              "print(status_counts(out.parent)['inaccurate'], 'pandas' in sys.modules)")
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, check=True)
    assert done.stdout.split() == ["1", "False"]


def test_a_chunk_keeps_what_was_there_before_out_of_cycle_collections_and_gives_it_back(tmp_path, monkeypatch):
    """A chunk runs with the heap it found frozen (out of Python's cycle collections: its many small objects
    would have the whole heap rescanned), the collector on for its own objects, and unfreezes it after, even
    when the chunk fails."""
    import gc

    from spinbounce.sweeps import run as sweep_run

    seen = []
    monkeypatch.setattr(sweep_run, "_run_chunk",
                        lambda *args: seen.append((gc.isenabled(), gc.get_freeze_count())) or (1, 0.0, 0.0))
    assert sweep_run.run_chunk({}, str(tmp_path), 0, 0, 0, 1) == (1, 0.0, 0.0)
    assert seen[0][0] and seen[0][1] > 1000 and gc.get_freeze_count() == 0
    monkeypatch.setattr(sweep_run, "_run_chunk", lambda *args: 1 / 0)
    with pytest.raises(ZeroDivisionError):
        sweep_run.run_chunk({}, str(tmp_path), 0, 0, 0, 1)
    assert gc.get_freeze_count() == 0

POLAR = """
seed = 2
[states]
n = 500
speed = [0.2, 1.5]
angle_deg = [-70.0, 70.0]
omega = [-3.0, 3.0]
"""


def test_speed_and_incidence_angle_sampling(tmp_path):
    spec = load_spec(write(tmp_path, POLAR))
    states = spec.initial_states(0)
    speed = np.hypot(states[:, 0], states[:, 1])
    angle = np.degrees(np.arctan2(states[:, 1], -states[:, 0]))
    assert speed.min() >= 0.2 and speed.max() <= 1.5
    assert angle.min() >= -70.0 and angle.max() <= 70.0 and (states[:, 0] < 0).all()
    # the same seed draws the same uniform numbers: only the coordinates differ
    rng = np.random.default_rng(2)
    np.testing.assert_allclose(speed, rng.uniform(0.2, 1.5, 500), rtol=1e-14)
    assert np.abs(states[:, 2]).max() <= 3.0  # omega given, not r*omega


@pytest.mark.parametrize(
    "edit, key",
    [
        (lambda t: t.replace("speed = [0.2, 1.5]", "speed = [0.2, 1.7]"), "states.speed"),
        (lambda t: t.replace("angle_deg = [-70.0, 70.0]", "angle_deg = [-70.0, 90.0]"), "states.angle_deg"),
        (lambda t: t.replace("speed = [0.2, 1.5]", "speed = [0.0, 1.5]"), "states.speed"),
        (lambda t: t.replace("[states]", "[states]\nv_t = [0.0, 1.0]"), "states.speed"),
    ],
    ids=["tunnels", "grazing-90", "zero-speed", "mixed-coordinates"],
)
def test_bad_polar_states_name_the_key(tmp_path, edit, key):
    with pytest.raises(SweepError) as info:
        load_spec(write(tmp_path, edit(POLAR)))
    assert str(info.value).startswith(key), str(info.value)


def test_output_folder_of_another_sweep_is_refused(tmp_path):
    out = tmp_path / "out"
    out.mkdir()
    (out / "sweep.json").write_text(json.dumps({"scene_hash": "somethingelse"}))
    with pytest.raises(SweepError, match="holds sweep"):
        run_sweep(load_spec(write(tmp_path, GOOD)), out, workers=1)


def test_two_sweeps_cannot_share_an_output(tmp_path):
    import fcntl

    out = tmp_path / "out"
    (out / "chunks").mkdir(parents=True)
    with open(out / ".lock", "w") as held:
        fcntl.flock(held, fcntl.LOCK_EX | fcntl.LOCK_NB)
        with pytest.raises(SweepError, match="another sweep"):
            run_sweep(load_spec(write(tmp_path, GOOD)), out, workers=1)


@pytest.mark.lammps
def test_sigkill_mid_sweep_then_rerun_completes_exactly(tmp_path):
    n, chunk = 60_000, 1500  # 40 chunks of ~0.05 s each: the kill lands well inside the run
    scene = write(tmp_path, f"seed = 9\nchunk_size = {chunk}\n[states]\nn = {n}\n"
                            "v_n = [-1.5, -0.1]\nv_t = [-2.0, 2.0]\nomega = [-4.0, 4.0]\n")
    out = tmp_path / "out"
    cmd = [sys.executable, "-m", "spinbounce.cli", "sweep", str(scene), "--out", str(out), "--workers", "1"]
    proc = subprocess.Popen(cmd, start_new_session=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    chunks = out / "chunks"
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline and len(list(chunks.glob("chunk-*.parquet"))) < 3:
        time.sleep(0.005)
    os.killpg(proc.pid, signal.SIGKILL)  # the sweep and its worker, mid-run
    proc.wait()
    finished_before = len(list(chunks.glob("chunk-*.parquet")))
    assert 3 <= finished_before < n // chunk, "the kill must land mid-sweep"
    done = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    assert "resuming" in done.stdout
    rows = read_results(out)
    assert len(rows) == n
    assert sorted(rows["index"]) == list(range(n))  # none lost, none duplicated
    assert not list(chunks.glob(".*.tmp"))


@pytest.mark.lammps
def test_a_failed_chunk_write_stops_the_sweep_and_a_rerun_completes_it(tmp_path, monkeypatch):
    """Chunks are written by a thread while the next one runs: a write that fails stops the sweep with
    its error, the chunks written before it stay, no temporary file is left, and a rerun resumes."""
    from spinbounce import records

    real, calls = records.write_parquet_atomic, []

    def failing_second(path, table):
        calls.append(path)
        if len(calls) == 2:
            raise OSError("disk full")
        return real(path, table)

    monkeypatch.setattr(records, "write_parquet_atomic", failing_second)
    spec = load_spec(write(tmp_path, GOOD))  # six chunks of 300
    out = tmp_path / "out"
    with pytest.raises(OSError, match="disk full"):
        run_sweep(spec, out, workers=1, log=lambda *_: None)
    written = list((out / "chunks").glob("chunk-*.parquet"))
    assert 1 <= len(written) < 6 and not list((out / "chunks").glob(".*.tmp"))
    monkeypatch.setattr(records, "write_parquet_atomic", real)
    run_sweep(spec, out, workers=1, log=lambda *_: None)
    rows = read_results(out)
    assert sorted(zip(rows["group"], rows["index"])) == [(g, k) for g in range(2) for k in range(900)]


@pytest.mark.lammps
def test_a_sweep_into_a_relative_folder_writes_every_chunk_there(tmp_path, monkeypatch):
    """Each chunk's file is written by a thread while LAMMPS runs the next chunk in its own folder (the
    working folder changes): a relative output folder must still receive every chunk."""
    spec = load_spec(write(tmp_path, GOOD))
    monkeypatch.chdir(tmp_path)
    run_sweep(spec, "relative-out", workers=1, log=lambda *_: None)
    assert len(list((tmp_path / "relative-out" / "chunks").glob("chunk-*.parquet"))) == 6
    assert len(read_results(tmp_path / "relative-out")) == 1800


@pytest.mark.lammps
def test_chunk_jobs_fill_the_same_dataset_as_a_whole_sweep(tmp_path):
    """A workflow engine runs chunks one by one (--chunk K); together they are the sweep."""
    from spinbounce.sweeps import chunk_table, run_one_chunk

    spec = load_spec(write(tmp_path, GOOD))
    out = tmp_path / "jobs"
    table = chunk_table(spec, out)
    assert [row["k"] for row in table] == list(range(6)) and not any(row["done"] for row in table)
    for row in reversed(table):  # any order
        run_one_chunk(spec, out, row["k"], log=lambda *_: None)
    assert all(row["done"] for row in chunk_table(spec, out))
    run_sweep(spec, tmp_path / "whole", workers=1, log=lambda *_: None)
    cols = ["group", "index", "v_n_lammps", "v_t_lammps", "r_omega_lammps"]
    a = read_results(out).sort_values(["group", "index"])[cols].reset_index(drop=True)
    b = read_results(tmp_path / "whole").sort_values(["group", "index"])[cols].reset_index(drop=True)
    pd.testing.assert_frame_equal(a, b)
    with pytest.raises(SweepError, match="must lie in"):
        run_one_chunk(spec, out, 6)


def test_chunk_jobs_and_a_whole_sweep_exclude_each_other(tmp_path):
    import fcntl

    from spinbounce.sweeps import run_one_chunk

    spec = load_spec(write(tmp_path, GOOD))
    out = tmp_path / "out"
    (out / "chunks").mkdir(parents=True)
    with open(out / ".lock", "w") as held:  # a chunk job is running: it holds the shared lock
        fcntl.flock(held, fcntl.LOCK_SH | fcntl.LOCK_NB)
        with pytest.raises(SweepError, match="another sweep"):
            run_sweep(spec, out, workers=1)
    with open(out / ".lock", "w") as held:  # a whole sweep is running
        fcntl.flock(held, fcntl.LOCK_EX | fcntl.LOCK_NB)
        with pytest.raises(SweepError, match="whole sweep"):
            run_one_chunk(spec, out, 0)
    with open(out / "chunks" / ".chunk-0000-000000.lock", "w") as held:  # the same chunk, twice
        fcntl.flock(held, fcntl.LOCK_EX | fcntl.LOCK_NB)
        with pytest.raises(SweepError, match="already being run"):
            run_one_chunk(spec, out, 0)


def test_workers_get_a_chunk_each_and_a_resume_keeps_the_chunks_begun(tmp_path):
    # 2,000 collisions fit one default chunk: with two workers the sweep is cut in two, so neither idles;
    # rerun with one worker, the folder's sweep is the same one (its chunks as begun), and nothing reruns
    from spinbounce import api

    raw = {"states": {"n": 2000, "v_n": [-1.5, -0.1], "v_t": [-2.0, 2.0], "r_omega": [-2.0, 2.0]}}
    logged = []
    api.run_sweep(raw, tmp_path / "s", workers=2, log=logged.append)
    assert len(list((tmp_path / "s" / "chunks").glob("chunk-*.parquet"))) == 2 and "in 2 chunks" in logged[0]
    again = []
    api.run_sweep(raw, tmp_path / "s", workers=1, log=again.append)
    assert again[0].split(":")[0] == logged[0].split(":")[0] and "2000 of 2000 collisions already done" in again[1]
    alone = []
    api.run_sweep(raw, tmp_path / "t", workers=1, log=alone.append)
    assert "in 1 chunks" in alone[0]  # one worker: the default chunk


def test_a_local_pair_sweep_is_estimated_at_its_probed_steps_and_a_job_at_its_fine_rule():
    """A pair chunk's job asks for the fine rule's steps (what a batch whose probe fails runs) and 2 ms a pair;
    a local sweep is estimated at what the probe settles on (~400 steps a contact, `bench` measured 182 and 362)
    and the references' measured cost. Estimated at the bound, an 800,000-pair sweep (about 80 s here: `bench`
    measures ~10,000 pairs/s) was refused as 1.13 core-hours; now it runs, and the job bound stays above it."""
    from spinbounce.model.timestep import MAX_CORE_HOURS
    from spinbounce.sweeps import spec_from_dict
    from spinbounce.sweeps.cost import chunk_cost, sweep_seconds

    states = {"n": 800_000, "v_n": [-1.5, -0.1], "v_t": [-2, 2], "r_omega": [-2, 2]}
    for model in ({"scene": "pair"}, {"scene": "pair", "mu": 0.3}):
        spec = spec_from_dict({"model": model, "states": states})
        assert sweep_seconds(spec, processes=1) < MAX_CORE_HOURS * 3600 < sweep_seconds(spec)
        cost = chunk_cost(spec, 0, spec.chunk_sizes[0])
        assert cost.likely_seconds < cost.seconds / 5  # the bound: 50 times the steps, 13 times the references
    wall = spec_from_dict({"states": states})  # a wall chunk's steps are its probe's already: one estimate
    assert chunk_cost(wall, 0, wall.chunk_sizes[0]).expected_seconds is None
