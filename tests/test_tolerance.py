"""--tolerance: Richardson-extrapolated results whose true error is within their own estimate.

The true error is measured against the exact theory. The saving is measured against the
plain refinement that would reach the same error: its steps follow from the finest raw
run's error and the raw order (2, or 1 with damping), both measured in the same ladder.
"""

import math

import numpy as np
import pytest

from spinbounce.exact import linear
from spinbounce.cli import main
from spinbounce.scenes.collision import Collision, STATE_ARGS
from spinbounce.model.contact import ContactModel
from spinbounce.errors import SceneError
from spinbounce.pipeline import run_scene
from spinbounce.studies.accuracy import FROZEN_T_END, FROZEN_Z, collision_scene
from spinbounce.studies.accuracy import cases as accuracy_cases
from spinbounce.extrapolation import (
    START_STEPS,
    collide_to_tolerance,
    collision_frame,
    collision_rung_dt,
    frozen_rung_dt,
    frozen_to_tolerance,
)

TOL = 1e-6
RNG = np.random.default_rng(21)
STATES = (RNG.uniform(-1.5, -0.1, 40), RNG.uniform(-2, 2, 40), RNG.uniform(-4, 4, 40))

COLLISION_CASES = {
    "defaults": ContactModel(),
    "magic": ContactModel(kt=10 * 2 / 7),
    "stiff": ContactModel(kt=50.0),
    "alpha-0.1": ContactModel(alpha=0.1),
    "gamma_t-1": ContactModel(gamma_t=1.0),
    "gamma_n-1": ContactModel(gamma_n=1.0),
    "overdamped": ContactModel(gamma_t=20.0),
}


@pytest.mark.lammps
@pytest.mark.parametrize("name", list(COLLISION_CASES))
def test_collision_to_tolerance(tmp_path, name):
    result, scene = collide_to_tolerance(COLLISION_CASES[name], *STATES, TOL, tmp_path)
    frame = collision_frame(result, scene)
    true = np.abs(frame[["v_n_error", "v_t_error", "r_omega_error"]].to_numpy()).max(axis=1)
    estimate = frame["v_n_estimate"].to_numpy()  # one estimate per sphere (the same in each column)
    assert true.max() <= TOL
    assert (true <= estimate).all(), (true - estimate).max()
    assert result.plain_steps_for(true.max()) >= 5 * result.steps


@pytest.mark.lammps
@pytest.mark.parametrize("gamma_t", [0.0, 1.0])
def test_frozen_to_tolerance(tmp_path, gamma_t):
    model = ContactModel(gamma_t=gamma_t)
    result = frozen_to_tolerance(model, 0.1, 1.0, 1.0, 10.0, TOL, tmp_path)
    exact = np.column_stack(linear.frozen_velocities(result.t, 1.0, 0.5, model.kt, model.m, model.alpha, gamma_t))
    true = np.abs(result.values - exact)
    assert true.max() <= TOL
    assert (true <= result.estimate).all()
    assert result.plain_steps_for(true.max()) >= 5 * result.steps


@pytest.mark.parametrize("bad", [0.0, 1e-13, 2.0, float("nan")])
def test_unreachable_tolerance_is_refused_before_lammps(tmp_path, bad):
    with pytest.raises(SceneError, match="tolerance"):
        collide_to_tolerance(ContactModel(), -1.0, 1.0, 0.0, bad, tmp_path)
    assert not any(tmp_path.iterdir())


@pytest.mark.lammps
def test_a_coulomb_cap_meets_its_tolerance_by_measurement(tmp_path):
    """A finite cap's switches leave no smooth error to extrapolate: the step is probed against the
    exact stick-slip solver for the tolerance, and each row's estimate is its distance to it."""
    from spinbounce.exact import choose

    vn, vt, omega = np.array([-1.0, -0.4, -1.3]), np.array([2.0, 0.3, -1.0]), np.array([0.0, 3.0, 1.0])
    model = ContactModel(mu=0.5)
    result, scene = collide_to_tolerance(model, vn, vt, omega, TOL, tmp_path)
    exact = choose.predict(model, np.column_stack([vn, vt, model.r * omega]))
    true = np.abs(result.values - exact).max(axis=1)
    assert result.how == "measured against the exact theory" and true.max() <= TOL
    assert np.allclose(result.estimate.max(axis=1), true, rtol=1e-12, atol=0)
    with pytest.raises(SceneError, match="^tolerance = 1e-09"):
        collide_to_tolerance(model, vn, vt, omega, 1e-9, tmp_path / "finer")


@pytest.mark.lammps
def test_collide_cli_tolerance(tmp_path, capsys):
    assert main(["collide", "--vn", "-1", "--vt", "1", "--omega", "0", "--tolerance", "1e-6",
                 "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "estimated error" in out and (tmp_path / "tolerance.json").is_file()


@pytest.mark.lammps
def test_sweep_with_a_tolerance(tmp_path):
    from spinbounce.sweeps import SweepError, read_results, run_sweep, spec_from_dict

    raw = {"seed": 2, "chunk_size": 150, "tolerance": TOL,
           "states": {"n": 300, "v_n": [-1.5, -0.1], "v_t": [-2.0, 2.0], "r_omega": [-2.0, 2.0]}}
    run_sweep(spec_from_dict(raw), tmp_path / "out", workers=1, log=lambda *_: None)
    rows = read_results(tmp_path / "out")
    true = np.abs(rows[["v_n_error", "v_t_error", "r_omega_error"]].to_numpy()).max(axis=1)
    assert len(rows) == 300 and true.max() <= TOL and (true <= rows["v_n_estimate"].to_numpy()).all()
    with pytest.raises(SweepError, match="^tolerance"):
        spec_from_dict({**raw, "model": {"dt": 0.001}})
    with pytest.raises(SweepError, match="^tolerance"):
        spec_from_dict({**raw, "tolerance": 0.0})


STUDY = {case.name: case for case in accuracy_cases()}


@pytest.mark.lammps
@pytest.mark.parametrize("name", list(STUDY))
def test_every_case_of_the_accuracy_study_to_tolerance(tmp_path, name):
    """The acceptance of --tolerance, case by case of `spinbounce accuracy`'s study."""
    case = STUDY[name]
    model = case.model
    states = np.array(case.states, dtype=float)
    if case.kind == "frozen":
        _, vt0, rw0 = states[0]
        result = frozen_to_tolerance(model, FROZEN_Z, vt0, rw0 / model.r, FROZEN_T_END, TOL, tmp_path)
        exact = np.column_stack(linear.frozen_velocities(result.t, vt0, rw0, model.kt, model.m, model.alpha,
                                                         model.gamma_t))
        true = np.abs(result.values - exact).max(axis=1)
    else:
        scene = collision_scene(case, None)
        out_of_plane = {name: getattr(scene, name) for name in STATE_ARGS[3:]} if scene.is_3d else {}
        result, scene = collide_to_tolerance(model, scene.v_n, scene.v_t, scene.omega, TOL, tmp_path,
                                             **out_of_plane)
        frame = collision_frame(result, scene)
        true = np.abs(frame[[f"{s}_error" for s in case.state_names]].to_numpy()).max(axis=1)
    estimate = result.estimate[:, 0]
    assert true.max() <= TOL and (true <= estimate * (1 + 1e-12)).all()
    if result.order:  # an extrapolation saves steps; a measured result (finite cap) is one plain run
        assert result.plain_steps_for(true.max()) >= 5 * result.steps


def test_tolerance_climbs_mid_step_rungs_of_its_own():
    """The rungs end the contact mid-step (M of tau/(M + 1/2) whole, to rounding) at the
    requested resolution or finer, like the scenes' default step; the ladder starts at
    START_STEPS, coarser than that default, which targets a plain run's accuracy."""
    for model in (ContactModel(), ContactModel(kt=50.0), ContactModel(gamma_n=1.0)):
        half_period = math.pi / model.fastest_rate(frozen=False)
        for k in range(4):
            dt = collision_rung_dt(model, START_STEPS * 2**k)
            m = model.tau / dt - 0.5
            assert m == pytest.approx(round(m), abs=1e-9) and half_period / dt >= START_STEPS * 2**k
        assert collision_rung_dt(model, START_STEPS) > Collision(model).dt
    damped = ContactModel(gamma_t=1.0)
    dt = frozen_rung_dt(damped, START_STEPS, 10.0)
    assert 10.0 / dt == pytest.approx(round(10.0 / dt), abs=1e-9)
    assert math.pi / damped.fastest_rate(frozen=True) / dt >= START_STEPS


@pytest.mark.lammps
def test_a_ladder_to_1e6_costs_less_than_one_run_at_the_default_step(tmp_path):
    """Why the ladder keeps its own start: at the paper's defaults every rung it climbs to reach
    1e-6 together takes fewer steps than one plain run at the default step (which reaches only
    its 1e-4 target)."""
    result, _ = collide_to_tolerance(ContactModel(), *STATES, TOL, tmp_path)
    default = Collision(ContactModel(), v_n=STATES[0], v_t=STATES[1], omega=STATES[2])
    assert result.steps < default.nsteps, (result.steps, default.nsteps)


@pytest.mark.lammps
def test_tolerance_with_a_hertzian_wall_is_measured_against_its_exact_theory(tmp_path):
    """A force on the contact radius has no smooth error in dt to extrapolate (each contact ends anywhere inside a
    step: at the step chosen here the deviation was 5.6e-7, at half of it 9.5e-6); it was refused, and is now
    answered as a capped contact is, by the measured route: LAMMPS's state at a step a probe against the exact
    theory (exact.hertz) chooses, its estimate that measured deviation. The values are LAMMPS's at that step (a
    fresh run there gives them again) and within the tolerance of the exact theory."""
    model = ContactModel(normal="hertz")
    result, scene = collide_to_tolerance(model, -0.5, 1.0, 0.0, TOL, tmp_path)
    frame = collision_frame(result, scene)
    true = np.abs(frame[[f"{s}_error" for s in scene.state_names]].to_numpy()).max()
    assert result.order == 0 and true <= TOL
    again = run_scene(Collision(model, v_n=-0.5, v_t=1.0, omega=0.0, dt=result.levels[-1]["dt"]), tmp_path / "again",
                      record=False)
    fresh = again.table[[f"{s}_lammps" for s in scene.state_names]].to_numpy()
    assert np.array_equal(fresh, result.values)
