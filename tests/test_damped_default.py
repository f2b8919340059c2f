"""A damped wall collision's default: the ladder's runs extrapolated to dt = 0, at most 3x the undamped steps.

LAMMPS's damping force sees the half-step velocity, so one damped run is first order in dt and
needs ~18x the undamped steps for the default accuracy (1e-4 of the state's size). The default
instead extrapolates a ladder of runs (spinbounce.extrapolation.default_tolerance). Each test
holds the result against the exact damped theory (exact to rounding) and the extrapolation's
own estimate against the true error: an estimate below the error would be a false claim.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import spinbounce
from spinbounce.extrapolation import default_tolerance
from spinbounce.model.contact import ContactModel
from spinbounce.model.timestep import ACCURACY

pytestmark = pytest.mark.lammps

#: How many times the undamped default's steps a damped default may take (issue 27).
STEP_RATIO = 3.0


def test_only_a_damped_law_with_an_error_smooth_in_dt_is_extrapolated_by_default():
    assert default_tolerance(ContactModel(gamma_t=1.0)) == ACCURACY
    assert default_tolerance(ContactModel(gamma_n=0.5)) == ACCURACY
    assert default_tolerance(ContactModel()) is None  # second order: one run at the rule's step
    assert default_tolerance(ContactModel(gamma_t=1.0, mu=0.3)) is None  # a cap's kinks: the probe
    assert default_tolerance(ContactModel(gamma_n=0.5, normal="hertz")) is None  # a law on the radius


@pytest.mark.parametrize("damping", [{"gamma_t": 1.0}, {"gamma_n": 1.0}, {"gamma_n": 0.3, "gamma_t": 0.7}])
def test_a_damped_collision_meets_the_default_accuracy_at_a_few_times_the_undamped_steps(tmp_path, damping):
    rng = np.random.default_rng(len(damping))
    state = {"v_n": -rng.uniform(0.2, 1.5), "v_t": rng.uniform(-2, 2), "omega": rng.uniform(-4, 4)}
    damped = spinbounce.collide(**state, **damping, out=tmp_path / "damped")
    undamped = spinbounce.collide(**state, out=tmp_path / "undamped")
    assert damped.step["method"].startswith("extrapolated")
    assert damped.nsteps <= STEP_RATIO * undamped.nsteps
    assert damped.status == "ok" and damped.error <= ACCURACY
    assert damped.error <= damped.step["estimate"] <= ACCURACY  # the estimate bounds the true error


def test_a_damped_3d_collision_is_extrapolated_too(tmp_path):
    report = spinbounce.collide(v_n=-0.8, v_t=0.4, omega=1.0, v_s=-0.3, omega_s=0.5, omega_n=2.0, gamma_t=0.8,
                                out=tmp_path / "3d")
    assert report.step["method"].startswith("extrapolated") and report.status == "ok"
    assert report.error <= report.step["estimate"] <= ACCURACY


def test_a_given_dt_is_one_run_at_that_step(tmp_path):
    report = spinbounce.collide(v_n=-1.0, v_t=0.5, gamma_t=1.0, dt=0.002, out=tmp_path / "given")
    assert report.step["method"] == "given" and report.dt == 0.002


def test_a_sweep_of_damped_and_undamped_groups_has_one_set_of_columns(tmp_path):
    """The damped group is laddered, the undamped one run once; every chunk has the same columns (a
    dataset reads the first file's), the undamped rows' estimates NaN."""
    out = tmp_path / "sweep"
    spinbounce.sweep(n=60, gamma_t=[0.0, 1.0], out=out, workers=1)
    table = pd.read_parquet(out / "chunks")
    assert len(table) == 120 and (table["status"] == "ok").all()
    steps = table.groupby("gamma_t")["nsteps"].max()
    assert steps[1.0] <= STEP_RATIO * steps[0.0]
    damped, undamped = table[table["gamma_t"] == 1.0], table[table["gamma_t"] == 0.0]
    assert undamped["v_t_estimate"].isna().all() and (damped["tolerance"] == ACCURACY).all()
    for s in ("v_n", "v_t", "r_omega"):  # each component's estimate bounds its true error
        assert (damped[f"{s}_error"].abs() <= damped[f"{s}_estimate"]).all()
    assert np.allclose(damped["omega_lammps"], damped["r_omega_lammps"] / damped["r"])


def test_the_step_table_shows_the_damped_default_within_three_times_the_undamped():
    from spinbounce.studies.accuracy import default_step_table

    table = default_step_table(["defaults", "damped_t", "damped"]).set_index("case")
    for case in ("damped_t", "damped"):
        assert table.loc[case, "steps_per_collision"] <= STEP_RATIO * table.loc["defaults", "steps_per_collision"]
        assert table.loc[case, "within_target"]
        assert table.loc[case, "error_reached"] <= table.loc[case, "estimate"] <= table.loc[case, "target"]


def test_the_accuracy_asked_of_the_ladder_is_relative_to_the_state(tmp_path):
    """The default accuracy is 1e-4 of the state's size: a fast state (|v_t| = 30) takes the same four
    runs as a slow one, not more for an absolute 1e-4."""
    fast = spinbounce.collide(v_n=-1.0, v_t=30.0, gamma_t=1.0, out=tmp_path / "fast")
    slow = spinbounce.collide(v_n=-1.0, v_t=0.5, gamma_t=1.0, out=tmp_path / "slow")
    assert fast.step["method"].startswith("extrapolated") and fast.nsteps == slow.nsteps
    assert fast.error <= fast.step["estimate"] <= ACCURACY


def test_a_ladder_whose_coarse_rung_fails_gives_way_to_one_probed_run(tmp_path, monkeypatch):
    """A coarsest rung that LAMMPS fails (here made to lose its sphere, as a rung too coarse for its
    sphere's travel once did): the default is then one probed run, as before there was a ladder, within
    the accuracy, its rung folders removed."""
    from spinbounce import pipeline
    from spinbounce.errors import LammpsError

    run = pipeline._run

    def losing_the_first_rung(scene, out_dir, *args):
        if Path(out_dir).name == "level-0":
            raise LammpsError("ERROR: Lost atoms: original 1 current 0", Path(out_dir) / "in.lammps")
        return run(scene, out_dir, *args)

    monkeypatch.setattr(pipeline, "_run", losing_the_first_rung)
    out = tmp_path / "fast"
    report = spinbounce.collide(v_n=-1.0, v_t=3.0, gamma_t=1.0, out=out)
    assert report.step["method"] == "probe" and report.status == "ok" and report.error <= ACCURACY
    assert not list(out.glob("level-*"))
    rows = spinbounce.sweep(n=10, v_t=[2.5, 3.0], gamma_t=1.0, out=tmp_path / "sweep", workers=1)
    assert (rows["status"] == "ok").all() and rows["v_t_estimate"].isna().all()


def test_a_fast_sliding_sphere_keeps_its_ladder(tmp_path):
    """At |v_t| = 300 a coarse rung moves the sphere several box widths a step along the wall: the box is
    made wide enough (LAMMPS maps an atom back by one period only), and the default ladder answers."""
    report = spinbounce.collide(v_n=-1.0, v_t=300.0, gamma_t=1.0, out=tmp_path / "fast")
    assert report.step["method"].startswith("extrapolated") and report.status == "ok" and report.error <= ACCURACY


def test_resuming_chunks_written_without_the_estimates_is_refused(tmp_path):
    """A damped sweep begun before its default carried estimates has chunks without those columns: a
    resume that would add chunks with them is refused (a dataset reads the first file's columns)."""
    import pyarrow.parquet as pq

    from spinbounce.errors import SweepError

    out = tmp_path / "sweep"
    spinbounce.sweep(n=40, gamma_t=[0.0, 1.0], out=out, workers=1)
    chunks = sorted((out / "chunks").glob("chunk-*.parquet"))
    old = pq.read_table(chunks[0])
    pq.write_table(old.drop([c for c in old.column_names if c.endswith("_estimate") or c == "tolerance"]), chunks[0])
    chunks[-1].unlink()
    with pytest.raises(SweepError, match="earlier spinbounce"):
        spinbounce.sweep(n=40, gamma_t=[0.0, 1.0], out=out, workers=1)
