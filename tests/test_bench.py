"""The benchmark runs all three methods on the same states and reports honest numbers.

Speeds are not asserted here (a shared, noisy machine): ``spinbounce bench`` prints them.
What is checked is what would make its ratios meaningless if it broke: every method ran
the requested collisions, on the same sample, each within the collision tolerance.
"""

import json
import os

import numpy as np
import pytest

from spinbounce.studies.speed import measure_speed
from spinbounce.cli import main
from spinbounce.lammps.dumps import read_dump
from spinbounce.sweeps import read_results

#: The default collision step's largest error over this sample is 3e-5 (test_lammps_runs).
COLLISION_TOL = 2e-4


@pytest.mark.lammps
def test_bench_measures_three_methods_on_one_sample(tmp_path):
    report = measure_speed(n_lmp=2, n_inprocess=5, n_batched=3000, chunk_size=1000, keep=tmp_path / "runs",
                       n_needs=200, log=lambda *_: None)
    methods = report["methods"]
    assert [methods[k]["collisions"] for k in ("a_lmp_process", "b_in_process", "c_batched")] == [2, 5, 3000]
    for m in methods.values():
        assert m["max_abs_error"] < COLLISION_TOL
        assert 0.0 < m["outside_loop_share"] < 1.0  # a Loop time was found in every log
        assert m["collisions_per_second"] > 0
    # (a) ran the sweep's first states, one per lmp process, and parsed each dump: its
    # final states are the sweep's first rows (the same per-sphere arithmetic, to rounding)
    rows = read_results(tmp_path / "runs" / "c-batched").sort_values("index").reset_index(drop=True)
    for i in range(2):
        dump = read_dump(tmp_path / "runs" / "a-lmp" / f"{i:06d}" / "state.dump")
        last = dump[dump["step"] == dump["step"].max()]
        assert last["vz"].iloc[0] == pytest.approx(rows["v_n_lammps"][i], abs=1e-14)
        assert last["vx"].iloc[0] == pytest.approx(rows["v_t_lammps"][i], abs=1e-14)
    assert report["ratios"]["batched_over_in_process"] > 0
    # both decks of the contact-only comparison really bounced the spheres: same physics,
    # different work around it (the free-flight deck also wrote a frame every step)
    needs = report["scene_needs"]
    for deck in ("contact_only", "free_flight_and_dump_every_step"):
        assert needs[deck]["max_abs_vn_error"] < COLLISION_TOL
    assert needs["free_flight_and_dump_every_step"]["steps"] > needs["contact_only"]["steps"]
    dump = tmp_path / "runs" / "d-scene-needs" / "free_flight_and_dump_every_step" / "every.dump"
    assert dump.read_text().count("ITEM: TIMESTEP") == needs["free_flight_and_dump_every_step"]["steps"] + 1


def test_bench_refuses_a_batch_smaller_than_the_baselines():
    with pytest.raises(ValueError, match="n_batched"):
        measure_speed(n_lmp=10, n_inprocess=10, n_batched=5)


@pytest.mark.slow
@pytest.mark.lammps
def test_bench_cli_writes_json(tmp_path, capsys):
    """Every section of the full bench follows the counts given (issue 28: tiny counts once still ran
    the waits' 800,000-collision sweeps for over a minute); --n-scenes sizes every scene's sweep."""
    from spinbounce.studies import engine

    out = tmp_path / "bench.json"
    assert main(["bench", "--n-lmp", "1", "--n-inprocess", "2", "--n-batched", "500", "--n-needs", "100",
                 "--n-models", "200", "--n-pairs", "2", "--n-scenes", "60", "--out", str(out)]) == 0
    report = json.loads(out.read_text())
    assert set(report["ratios"]) == {"batched_over_lmp_process", "batched_over_in_process"}
    assert report["lammps_version"].startswith("2025.7.22")
    printed = capsys.readouterr().out
    assert "batched / lmp process" in printed and "what a user waits for" in printed
    waits = report["waits"]
    assert {s["scene"] for s in waits["scenes"]} == set(engine.SCENES)
    assert {s["collisions"] for s in waits["scenes"]} == {60} == {waits["frictionless"]["collisions"]}
    assert waits["frictionless"]["repeats"] == 2  # the full bench's sweep and engine each the faster of two
    # workers against one, each on as many CPUs (one worker free to use more beside them), the fastest of three
    cores = waits["cores"]
    assert cores["repeats"] == 3 and set(cores["wall_seconds"]) == {"one", "all", "free"}
    assert cores["pinned"] == (len(os.sched_getaffinity(0)) >= cores["workers"])
    assert waits["gas"]["spheres"] == 1000  # the smallest gas, for a count of 60
    assert len(waits["gas"]["measuring_shares"]) == 3  # one a pair of runs, the full bench's three
    assert waits["references"]["pairs"] == 60 and waits["references"]["capped_per_second"] > 0.0
    assert {m["collisions"] for m in report["models"]["sweeps"]} == {200}
    # the pairs' classes: the sweep's two runs combined take fewer steps than one probed run of the same pairs
    classes = report["models"]["pairs"]["batches"]
    combined, plain = classes["default radii, two runs combined"], classes["default radii"]
    assert combined["pair_steps"] < plain["pair_steps"] and combined["pair_max_error"] <= 1e-4


@pytest.mark.slow
@pytest.mark.lammps
def test_bench_quick_prints_every_ratio_with_its_target(tmp_path, capsys):
    """bench --quick: each scene's sweep beside the bare engine (LAMMPS's own seconds below the sweep's,
    every row within the default accuracy), the frictionless sweep against the engine, two workers,
    start-up, the damped steps and the gas deck beside its bare self, each printed beside its target."""
    out = tmp_path / "bench.json"
    assert main(["bench", "--quick", "--out", str(out)]) == 0
    printed = capsys.readouterr().out
    for line in ("pair / wall per collision", "of it (target 85%)", "of twice one worker (target 90%)",
                 "(target 0.5 s)", "undamped: ", "pairs/s uncapped (target 100,000)", "measuring costs",
                 "paid once over the target's 800,000", "one worker's start-up paid once (an estimate)"):
        assert line in printed
    waits = json.loads(out.read_text())["waits"]
    assert waits["quick"] and [s["scene"] for s in waits["scenes"]][0] == "wall"
    for scene in waits["scenes"]:
        assert 0.0 < scene["engine_seconds"] < scene["wall_seconds"] and scene["lammps_runs"] >= 1
        assert scene["max_error"] <= 1e-4  # the sweeps it times reach the default accuracy
    assert waits["damped"]["damped_error"] <= waits["damped"]["damped_estimate"] <= waits["damped"]["target"]
    machine = waits["cores"]["machine"]  # two bare engines at once, where two CPUs can be had (a measurement on a
    if waits["cores"]["pinned"]:  # shared machine: its value is not held to a bound here)
        assert "the machine's own ceiling, the bare engine in 2 processes at once" in printed
        assert machine["workers"] == 2 and len(machine["lone_seconds"]) == len(machine["together_seconds"]) == 2
        assert np.isfinite(machine["efficiency"]) and machine["efficiency"] > 0.0
    assert waits["gas"]["sphere_steps_per_second"] > 0.0 and waits["gas"]["bare_sphere_steps_per_second"] > 0.0


_BREAKDOWN = """Loop time of 2.2 on 1 procs for 12000 steps with 5000 atoms

MPI task timing breakdown:
Section |  min time  |  avg time  |  max time  |%varavg| %total
---------------------------------------------------------------
Pair    | 0.52       | 0.5        | 0.54       |   0.0 | 23.41
Neigh   | 0.2        | 0.2        | 0.2        |   0.0 | 10.17
Comm    | 0.4        | 0.4        | 0.4        |   0.0 | 17.47
Output  | 0.0001     | 0.0001     | 0.0001     |   0.0 |  0.01
Modify  | 0.85       | 0.8        | 0.85       |   0.0 | 38.32
Other   |            | 0.1        |            |       | 10.62
"""


def test_section_times_reads_each_runs_average_seconds(tmp_path):
    """Each run's breakdown, the average column (not the min), Other's lone column included."""
    from spinbounce.lammps.runner import section_times

    log = tmp_path / "log.lammps"
    log.write_text(_BREAKDOWN + "\n" + _BREAKDOWN.replace("0.8 ", "0.9 "))
    first, second = section_times(log)
    assert first == {"Pair": 0.5, "Neigh": 0.2, "Comm": 0.4, "Output": 0.0001, "Modify": 0.8, "Other": 0.1}
    assert second["Modify"] == 0.9 and section_times(tmp_path / "none") == []


def test_measuring_share_takes_the_machines_drift_out():
    """A measured run on a machine 10% slower, whose Modify adds 0.05 s to the drifted bare one's: the share is
    0.05 s over the rest, not the 12% its loop time differs by; no added cost reads zero at any drift."""
    from spinbounce.studies.engine import measuring_share

    bare = {"Pair": 0.5, "Neigh": 0.2, "Comm": 0.4, "Output": 0.0, "Modify": 0.8, "Other": 0.1}
    slower = {k: 1.1 * v for k, v in bare.items()}
    assert measuring_share(bare, slower) == pytest.approx(0.0, abs=1e-12)
    measured = {**slower, "Modify": slower["Modify"] + 0.05}
    assert measuring_share(bare, measured) == pytest.approx(0.05 / sum(slower.values()), rel=1e-12)


def test_a_short_sweep_read_at_the_full_count_pays_its_start_up_once():
    """10 s for 200,000 collisions, 2 s of it start-up: 800,000 take 2 + 4 x 8 s. Two workers taking 6 s against
    one's 10 s (the same start-up) are 83% of twice one here, and over 800,000 (2 + 4 x 4 = 18 s against 34 s)
    34 / (2 x 18) = 94%."""
    from spinbounce.studies.engine import _cores_at_full, at_count

    assert at_count(10.0, 2.0, 200_000, 800_000) == pytest.approx(34.0)
    line = _cores_at_full({"collisions": 200_000, "workers": 2, "wall_seconds": {"one": 10.0, "all": 6.0}}, 2.0)
    assert line.endswith(f": {34.0 / (2 * 18.0):.0%}")
    assert _cores_at_full({"collisions": 800_000, "workers": 2, "wall_seconds": {"one": 1.0, "all": 1.0}}, 2.0) == ""
    # a sweep no longer than its start-up, or of another count than the quick bench's, is not carried
    assert _cores_at_full({"collisions": 200_000, "workers": 2, "wall_seconds": {"one": 10.0, "all": 1.5}}, 2.0) == ""
    assert _cores_at_full({"collisions": 60, "workers": 2, "wall_seconds": {"one": 10.0, "all": 6.0}}, 2.0) == ""
