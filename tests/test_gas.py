"""The gas scene: what it refuses, how it places and starts its spheres, a small gas beside its theories.

The acceptance-sized gases are in tests/test_gas_claims.py (slow)."""

from __future__ import annotations

import json
import math
import shutil
import subprocess
import sys

import numpy as np
import pytest

from spinbounce.api import model
from spinbounce.api import gas
from spinbounce.errors import SceneError
from spinbounce.lammps.runner import run_deck
from spinbounce.scenes.gas.deck import lattice_positions
from spinbounce.scenes.gas.scene import Gas

MAGIC = {"kn": 1e4, "kt": 1e4 * 2 / 7}
#: The contact time of the magic law's collisions at T_tr = 1 (about pi sqrt(m/(2 kn)); the scene takes it given).
T_C = 0.0221


def _gas(**given) -> Gas:
    return Gas(model(**MAGIC), T_C, **given)


@pytest.mark.parametrize("given, named", [({"spheres": 999}, "spheres = 999"), ({"spheres": 2000.5}, "whole number"),
                                          ({"packing": 0.0}, "packing = 0"), ({"packing": 0.5}, "packing = 0.5"),
                                          ({"t_tr": 0.0}, "t_tr = 0"), ({"t_rot": -1.0}, "t_rot = -1"),
                                          ({"samples": 1}, "samples = 1"), ({"dt": T_C / 5}, "dt = .*fastest contact mode")])
def test_a_gas_it_cannot_run_is_refused_naming_the_parameter(given, named):
    with pytest.raises(SceneError, match=named):
        _gas(**given)


def test_a_packing_the_lattice_cannot_hold_is_refused_with_the_densest_it_can():
    """1001 spheres need an 11^3 lattice: the densest packing with a 2% gap is 1001 pi / (6 11^3 1.02^3)."""
    densest = 1001 * math.pi / (6 * 11**3 * 1.02**3)
    with pytest.raises(SceneError, match=f"packing <= {densest:.4g}"):
        _gas(spheres=1001, packing=densest * 1.01)
    assert _gas(spheres=1001, packing=densest * 0.99).packing < densest


def test_another_alpha_or_the_classic_wall_style_is_refused():
    with pytest.raises(SceneError, match="alpha"):
        Gas(model(alpha=0.5, **MAGIC), T_C)
    with pytest.raises(SceneError, match="granular"):
        Gas(model(wall="classic", **MAGIC), T_C)


@pytest.mark.parametrize("packing", [0.05, 0.3])
def test_the_spheres_start_apart_and_fill_the_box(packing):
    scene = _gas(spheres=2000, packing=packing, seed=4)
    x = lattice_positions(scene)
    assert x.shape == (2000, 3) and np.all((x > 0.0) & (x < scene.box))
    d = x[:, None, :] - x[None, :, :]
    d -= scene.box * np.round(d / scene.box)  # the nearest periodic image
    distance = np.sqrt((d**2).sum(axis=-1)) + np.eye(len(x)) * 1e9
    assert distance.min() > scene.sigma * 1.02 - 1e-12
    assert np.ptp(x, axis=0).min() > 0.8 * scene.box


def test_the_step_and_the_reports_follow_the_contact_time():
    scene = _gas(spheres=2000, samples=10, collisions=5)
    assert scene.dt == pytest.approx(T_C / 50, rel=1e-14)
    assert scene.nsteps == 10 * scene.interval and scene.interval % scene.contact_every == 0
    assert scene.nsteps * scene.dt >= 5 / scene.rate(1.0)
    # the intervals are whole contact times: the run overshoots its collisions by less than one a sample
    assert scene.nsteps - scene.samples * scene.contact_steps < 5 / scene.rate(1.0) / scene.dt


@pytest.fixture(scope="module")
def small_magic_gas(tmp_path_factory):
    """2,000 spheres at the magic ratio for 4 collisions per sphere (about 10 s)."""
    folder = tmp_path_factory.mktemp("gas")
    return gas(spheres=2000, collisions=4, samples=16, draws=8000, out=folder / "run", **MAGIC)


def _drawn(folder) -> tuple[float, float]:
    """The temperatures LAMMPS drew (the log's first row of the kinetic energies: the burn's start; in lj units
    thermo reports them per atom)."""
    lines = (folder / "log.lammps").read_text().splitlines()
    row = lines[lines.index(next(x for x in lines if x.split() == ["Step", "Atoms", "c_ke_tr", "c_ke_rot"])) + 1]
    _, _, ke_tr, ke_rot = (float(x) for x in row.split())
    return 2.0 * ke_tr / 3.0, 2.0 * ke_rot / 3.0


def test_a_small_gas_starts_where_asked_and_counts_its_collisions(small_magic_gas):
    """The draw is exact (the velocities are drawn, then scaled); the series starts 3 contact times later
    (0.05 collisions per sphere), when the contacts open at the draw have ended: T_tr within 3% of the
    draw and T_rot a little above 0 (the magic ratio's ratio rises 0.3 a collision at first). LAMMPS's
    collisions counted from its open contacts run at the Enskog rate within 5% (measured 1-2% at 20,000
    spheres; 2,000 spheres' temperatures are noisy to 2%)."""
    s = small_magic_gas.series
    drawn = _drawn(small_magic_gas.csv.parent)
    assert drawn[0] == pytest.approx(1.0, abs=1e-12) and drawn[1] == 0.0
    assert s["t_tr"][0] == pytest.approx(1.0, rel=0.03) and 0.0 < s["t_rot"][0] < 0.03
    assert np.all(np.isfinite(s["energy"])) and np.all(np.diff(s["collisions"]) > 0)
    enskog = small_magic_gas.series["t_enskog_pairs"]
    assert enskog[-1] == pytest.approx(s["t"][-1], rel=0.05)


def test_a_small_gas_heads_for_equipartition_with_its_theories(small_magic_gas):
    """The magic ratio's rough spheres share energy: the ratio rises as each theory says. At 2,000 spheres a
    ratio is noisy to about 3% (two temperatures at sqrt(2/(3N)) each), and the largest of 16 samples'
    differences to about twice that: 0.08."""
    s, record = small_magic_gas.series, small_magic_gas.record
    assert s["ratio"][-1] > 0.6
    for name in ("pairs", "exact_pairs", "matrix"):
        assert record["theories"][name]["max_ratio_difference"] < 0.08
    assert record["theories"]["matrix"]["energy_drift"]["theory"] == pytest.approx(0.0, abs=1e-12)


def test_the_same_gas_finished_in_its_folder_is_read_back_and_no_other(small_magic_gas):
    """reuse (what reproduce's products share, and a reproduce run again): the run in the folder, read back
    bit for bit without running (the deck's log untouched); a gas of other parameters, or one the folder's
    record says other software ran, is not it."""
    from spinbounce.scenes.gas import run as gas_run

    folder, lines = small_magic_gas.csv.parent, []
    logged = (folder / "log.lammps").stat().st_mtime_ns
    again = gas_run.run_gas(model(**MAGIC), spheres=2000, collisions=4, samples=16, draws=8000, out=folder,
                            reuse=True, log=lines.append)
    assert any("read back from" in line for line in lines) and (folder / "log.lammps").stat().st_mtime_ns == logged
    assert again.record == json.loads(small_magic_gas.record_path.read_text())
    assert set(again.series) == set(small_magic_gas.series)
    for name, values in small_magic_gas.series.items():
        assert np.array_equal(again.series[name], values), name
    scene = Gas(model(**MAGIC), small_magic_gas.record["parameters"]["contact_time"], spheres=2000, collisions=4,
                samples=16, draws=8000)
    assert gas_run._finished(folder, scene, ranks=1) is not None and gas_run._finished(folder, scene, ranks=2) is None
    other = Gas(model(**MAGIC), scene.contact_time, spheres=2000, collisions=5, samples=16, draws=8000)
    assert gas_run._finished(folder, other, ranks=1) is None
    older = dict(again.record, lammps_version="2024.8.29")
    copy = folder.parent / "older"
    shutil.copytree(folder, copy)
    (copy / "result.json").write_text(json.dumps(older))
    assert gas_run._finished(copy, scene, ranks=1) is None


def test_a_gas_writes_its_series_and_provenance(small_magic_gas):
    record = json.loads(small_magic_gas.record_path.read_text())
    assert record["scene"] == "gas" and record["lammps_version"] and record["parameters"]["dt"] > 0
    assert record["accuracy"]["temperature_noise"] == pytest.approx(math.sqrt(2 / 6000))
    closure = record["closure"]  # the closure's error, carried by every theory: none for elastic rough spheres
    assert closure["steady_ratio_closed_form"] == pytest.approx(1.0, abs=1e-12) and closure["closure_error"] == 0.0
    for theory in record["theories"].values():
        assert theory["steady_ratio_boltzmann"] == pytest.approx(theory["steady_ratio"] + closure["closure_error"])
    drift = record["closure_drift"]  # the pairs' own: the pair-level theories carry it, the matrix (lossless) not
    for name in ("pairs", "exact_pairs"):
        theory = record["theories"][name]
        assert theory["energy_drift_boltzmann"] == pytest.approx(theory["energy_drift"]["theory"]
                                                                 + drift["dsmc_less_equations"], abs=1e-15)
    assert record["theories"]["matrix"]["energy_drift_boltzmann"] is None
    assert drift["collisions_per_sphere"] == pytest.approx(small_magic_gas.series["collisions"][-1])
    header = small_magic_gas.csv.read_text().splitlines()[0].split(",")
    assert {"t", "t_tr", "t_rot", "energy", "collisions", "ratio_pairs", "energy_matrix"} <= set(header)


def test_the_sampled_collision_count_is_within_its_noise_of_a_tally(small_magic_gas, tmp_path):
    """The open contacts are sampled once in three contact times (a sample costs LAMMPS a neighbour list), so
    the count is a tally's within its stated noise (2.4% for 2,000 spheres over 4 collisions; measured 3.3%). The same
    deck sampled once a contact time sees each contact once (the magic law's contacts last t_c within a few %):
    the trajectory is the same, so the two counts differ by the sampling alone, held to 4 standard errors."""
    folder = small_magic_gas.csv.parent
    deck = (folder / "in.lammps").read_text()
    line = next(x for x in deck.splitlines() if x.startswith("fix") and " open " in x)
    every, repeat, interval = (int(x) for x in line.split()[4:7])
    parameters = small_magic_gas.record["parameters"]
    tally = round(parameters["contact_time"] / parameters["dt"])  # a contact time: the interval is whole ones
    shutil.copy(folder / "gas.data", tmp_path / "gas.data")
    (tmp_path / "in.lammps").write_text(deck.replace(line, line.replace(f"{every} {repeat} {interval}",
                                                                    f"{tally} {interval // tally} {interval}")))
    assert interval % tally == 0 and every == 3 * tally
    run_deck(tmp_path / "in.lammps")
    sampled, tallied = (np.loadtxt(f / "gas.contacts", ndmin=2)[:, 1].sum() for f in (folder, tmp_path))
    noise = small_magic_gas.record["accuracy"]["collisions_noise"]
    assert 0.01 < noise < 0.05 and abs(sampled / tallied - 1.0) < 4.0 * noise


def test_an_hour_long_gas_needs_force(tmp_path):
    with pytest.raises(SceneError, match="hours"):
        gas(spheres=200_000, collisions=1000, out=tmp_path / "long", **MAGIC)
    assert not (tmp_path / "long").exists()


def test_the_command_refuses_bad_input_in_one_line(tmp_path):
    done = subprocess.run([sys.executable, "-m", "spinbounce", "gas", "--packing", "0.7", "--out", str(tmp_path / "x")],
                          capture_output=True, text=True)
    assert done.returncode == 2 and done.stderr.count("\n") == 1 and "packing = 0.7" in done.stderr


def _shared(root: str) -> list[str]:
    """A worker's ask for the tiny gas below (what one of reproduce's products does), with what it logged."""
    from spinbounce.scenes.gas.run import shared_gas

    told: list[str] = []
    shared_gas(root, model(**MAGIC), log=told.append, spheres=1000, collisions=1, samples=2, draws=2000)
    return told


@pytest.mark.slow
def test_two_processes_asking_for_one_gas_at_once_run_it_once(tmp_path):
    """reproduce's products side by side: the second waits on the gas's lock while the first runs it, then reads
    it back (one run, one folder, neither half-written)."""
    import multiprocessing

    with multiprocessing.get_context("spawn").Pool(2) as pool:
        told = pool.map(_shared, [str(tmp_path)] * 2)
    runs = [lines for lines in told if any("steps of dt" in line for line in lines)]
    read = [lines for lines in told if any("read back from" in line for line in lines)]
    assert len(runs) == 1 and len(read) == 1, told
    (folder,) = [p for p in tmp_path.iterdir() if p.is_dir()]
    assert (folder / "result.json").is_file() and not list(folder.glob(".*.tmp"))


def test_two_mpi_ranks_run_the_same_gas(tmp_path):
    """Every draw is made from the atom ids (LAMMPS's loop all), so K ranks start from the same state; the
    forces are summed in another order, so the runs part by rounding, which a gas's chaos grows: after four
    collisions per sphere (two of them settling) they agree to 1e-10 of the temperatures (measured 1.2e-12)."""
    runs = [gas(spheres=2000, collisions=2, samples=8, draws=2000, ranks=k, out=tmp_path / f"ranks{k}", **MAGIC).series
            for k in (1, 2)]
    for q in ("t_tr", "t_rot", "energy", "collisions"):
        assert np.max(np.abs(runs[0][q] - runs[1][q])) < 1e-10


def test_a_gas_too_hot_for_its_spring_is_refused_with_what_would_do():
    """At kn = 10 a collision closing at six times sqrt(2 T_tr/m) = 8.5 presses 1.9 into spheres of radius 0.5."""
    with pytest.raises(SceneError, match=r"too hot.*overlap by 1.9.*kn >= 2.3e\+03, or t_tr \+ t_rot <= 0.00434"):
        Gas(model(kn=10.0, kt=1.0), 0.7)


def test_a_gas_started_spinning_starts_at_its_t_rot_from_the_command(tmp_path):
    """T_rot(0) is a second velocity draw scaled into the spins (the deck's set omega): exact at the draw, as
    T_tr(0) is, and within 3% at the series' start, where the theories start too. Through the command, with a
    seed given (a number the command reads as 5.0). At the magic ratio, whose closure is exact (kt/kn = 0.1 adds a
    10-s DSMC of the closure's error, which tests/test_gas_closure.py holds)."""
    out = tmp_path / "spun"
    done = subprocess.run([sys.executable, "-m", "spinbounce", "gas", "--spheres", "1000", "--kn", "1e4", "--kt-over-kn",
                           "0.2857142857142857", "--t-rot", "0.5", "--collisions", "0.5", "--samples", "4", "--draws", "1000",
                           "--seed", "5", "--out", str(out), "--json"], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    series = json.loads(done.stdout)["series"]
    assert _drawn(out) == pytest.approx((1.0, 0.5), abs=1e-12)
    assert series["t_tr"][0] == pytest.approx(1.0, rel=0.03) and series["t_rot"][0] == pytest.approx(0.5, rel=0.03)
    assert series["ratio_pairs"][0] == series["ratio"][0]


def test_a_short_run_with_many_samples_reports_every_one():
    """One contact sample an interval would make LAMMPS's fix ave/time report step 0 as well: two at least."""
    scene = _gas(spheres=2000, collisions=0.01, samples=50)
    assert scene.interval >= 2 * scene.contact_every and scene.interval % scene.contact_every == 0


def test_a_rerun_stopped_after_lammps_leaves_no_earlier_series_beside_its_deck(tmp_path, monkeypatch):
    """With --force into an earlier run's folder: its gas.csv and result.json go before LAMMPS runs, so an
    interrupt before the new series is written leaves neither (nothing claims the old series is this run's)."""
    from spinbounce.scenes.gas import run

    folder = tmp_path / "rerun"
    folder.mkdir()
    (folder / "gas.csv").write_text("t,t_tr\n0,1\n")
    (folder / "result.json").write_text("{}")

    def interrupted(*_args, **_kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(run, "_judged", interrupted)
    with pytest.raises(KeyboardInterrupt):
        gas(spheres=1000, collisions=0.2, samples=2, draws=1000, out=folder, force=True, **MAGIC)
    assert not (folder / "gas.csv").exists() and not (folder / "result.json").exists()
    assert (folder / "gas.energies").exists()  # LAMMPS did run


def test_late_ratio_and_relaxation_are_read_alike_from_any_series():
    """LAMMPS's series and each theory's are read by the same rules: the late ratio is the mean over the last
    quarter of the collisions, and relaxation the first crossing of 90% of a target from below (linear between
    samples: 0.01 on this grid); a ratio that starts above it has none."""
    from spinbounce.scenes.gas import predict

    tau = np.linspace(0.0, 20.0, 81)
    ratio = 0.5 * (1.0 - np.exp(-tau / 4.0))
    late = predict.late_mean(tau, ratio)
    assert predict.late_samples(tau).sum() == 21 and late == pytest.approx(np.mean(ratio[tau >= 15.0]), rel=1e-15)
    assert predict.relaxation(tau, ratio, late) == pytest.approx(-4.0 * math.log(1.0 - 1.8 * late), abs=0.01)
    assert math.isnan(predict.relaxation(tau, 1.0 - ratio, 0.5))


def test_the_closure_s_error_is_added_to_a_late_ratio_only_near_its_fixed_point():
    """The closure's error is a steady state's: a theory's late ratio more than NEAR_STEADY from its fixed point
    (a short run still relaxing) carries none; its fixed point always does."""
    from spinbounce.scenes.gas.run import NEAR_STEADY, _summary

    base = {"max_ratio_difference": 0.0, "energy_drift": {"theory": -0.01}, "drift_difference": 0.0,
            "relaxation_collisions": 5.0, "relaxation_collisions_late": 4.8, "steady_ratio": 0.5}
    beyond, drift = {"closure_error": -0.01}, {"dsmc_less_equations": 0.001}
    near = _summary(base | {"late_ratio": 0.5 * (1.0 - NEAR_STEADY / 2.0)}, beyond, drift)
    far = _summary(base | {"late_ratio": 0.3}, beyond, drift)
    assert near["late_ratio_boltzmann"] == pytest.approx(0.5 * (1.0 - NEAR_STEADY / 2.0) - 0.01)
    assert far["late_ratio_boltzmann"] is None and far["steady_ratio_boltzmann"] == pytest.approx(0.49)
    assert far["energy_drift_boltzmann"] == pytest.approx(-0.009)
