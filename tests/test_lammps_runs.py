"""LAMMPS runs against the theory, through the whole pipeline (scene -> deck -> run -> dump -> table).

Tolerances. The default step (model/timestep.py) is chosen for half the default accuracy,
1e-4 of the size of the initial state; the collision's integration error is second order.
Over |v_n| <= 1.5, |v_t| <= 2, |omega| <= 4 that is at most about 1.6e-4 in absolute terms.
Tests allow 2e-4, the acceptance bound: still two orders below any modelling error (a
wrong alpha, a wrong sign, the classic hooke/history wall all miss by more than 1e-2).
"""

import math
import subprocess

import numpy as np
import pytest

from spinbounce import exact
from spinbounce.lammps.dumps import read_dump
from spinbounce.pipeline import ResultError, run_scene, run_series
from spinbounce.lammps.runner import LammpsError, lmp_executable, run_deck
from spinbounce.scenes.collision import Collision
from spinbounce.model.contact import ContactModel
from spinbounce.scenes.frozen import Frozen

pytestmark = pytest.mark.lammps

COLLISION_TOL = 2e-4  # see module docstring


def _errors(result):
    t = result.table
    return np.abs(t[["v_n_error", "v_t_error", "r_omega_error"]].to_numpy())


def test_default_collision_matches_eq18(run_dir):
    scene = Collision(ContactModel(), v_n=-1.0, v_t=1.0, omega=0.0)
    result = run_scene(scene, run_dir)
    assert _errors(result).max() < COLLISION_TOL
    # and the theory it is compared with is the paper's Eq. 18 at Omega = -1.2838
    assert result.table["v_t_theory"].iloc[0] == pytest.approx(1 + 0.4 / 1.4 * exact.Omega(10, 1, 0.4), abs=1e-15)
    assert (run_dir / "in.lammps").is_file() and (run_dir / "result.json").is_file()


@pytest.mark.parametrize(
    "model",
    [
        ContactModel(alpha=0.1),  # point-like mass: rigid-body route
        ContactModel(alpha=2 / 3, kt=4.0),  # thin shell at the magic ratio: Omega = -2
        ContactModel(alpha=0.25, kt=2.5, kn=40.0, m=2.0, r=0.3),  # nothing at its default
    ],
    ids=["alpha0.1", "shell-magic", "all-changed"],
)
def test_alpha_is_honoured_by_lammps(run_dir, model):
    """alpha != 2/5 cannot come from fix nve/sphere; the rigid-body route must give Eq. 18."""
    scene = Collision(model, v_n=[-1.0, -0.3], v_t=[1.0, -0.7], omega=[0.0, 2.5])
    result = run_scene(scene, run_dir)
    assert _errors(result).max() < COLLISION_TOL
    # alpha = 2/5 would give a different answer: the test can tell them apart
    wrong = scene.initial @ exact.scattering_matrix(0.4, exact.Omega(model.kn, model.kt, 0.4)).T
    assert np.abs(result.table[["v_n_lammps", "v_t_lammps", "r_omega_lammps"]].to_numpy() - wrong).max() > 1e-2


def test_magic_ratio_conserves_energy_in_lammps(run_dir):
    alpha = 2 / 3
    model = ContactModel(alpha=alpha, kt=10.0 * exact.magic_kt_over_kn(alpha))
    scene = Collision(model, v_n=[-1.0, -0.5, -0.2], v_t=[1.0, -1.5, 0.3], omega=[0.0, 1.0, -4.0])
    result = run_scene(scene, run_dir)
    # energy is conserved up to the integration error (the same budget as the states)
    assert np.abs(result.table["energy_gain"]).max() < COLLISION_TOL
    assert model.Omega == pytest.approx(-2.0, abs=1e-12)


def test_spin_and_many_spheres_pair_by_id(run_dir):
    rng = np.random.default_rng(7)
    n = 12
    scene = Collision(
        ContactModel(),
        v_n=rng.uniform(-1.5, -0.1, n), v_t=rng.uniform(-2, 2, n), omega=rng.uniform(-4, 4, n),
    )
    result = run_scene(scene, run_dir)
    assert _errors(result).max() < COLLISION_TOL
    # LAMMPS saw the requested initial state (full-precision deck and dump)
    t = result.table
    np.testing.assert_allclose(t["v_t_lammps_initial"], t["v_t_initial"], rtol=0, atol=1e-15)
    np.testing.assert_allclose(t["r_omega_lammps_initial"], t["r_omega_initial"], rtol=0, atol=1e-15)


def test_rigid_route_dumps_initial_spin(run_dir):
    scene = Collision(ContactModel(alpha=0.1), v_n=-0.5, v_t=0.0, omega=3.0)
    result = run_scene(scene, run_dir)
    t = result.table
    assert t["omega_lammps_initial"].iloc[0] == pytest.approx(3.0, abs=1e-12)  # set by the body, exact
    assert _errors(result).max() < COLLISION_TOL


def test_frozen_contact_matches_eq10(run_dir):
    """Acceptance: z = 0.1, v_t(0) = 1, omega(0) = 0 within 1e-5 over 10 time units.

    Velocity Verlet's phase error at the default 1000 steps per half-period is
    about 5e-6 after 10 time units; 1e-5 is the acceptance bound.
    """
    scene = Frozen(ContactModel(), z=0.1, v_t=1.0, omega=0.0, t_end=10.0)
    result = run_series(scene, run_dir)
    assert result.table["t"].iloc[-1] >= 10.0
    assert result.max_abs_error < 1e-5
    # the trajectory really oscillates (not a trivially constant series)
    assert result.table["v_t"].min() < 0.5


@pytest.mark.parametrize("gamma_t", [0.1, 0.5, 2.0, 5.0])
def test_damped_frozen_contact_converges_to_exact_solution(tmp_path, gamma_t):
    """LAMMPS's damping force uses the half-step velocity, so it is first order in dt.

    Measured (z = 0.1, v_t = 1, omega = 1, 10 time units): the largest error against the
    exact damped solution halves with dt to 3 digits (1.5e-4 -> 1.9e-5 for gamma_t = 0.1
    from dt = 4e-4 to 5e-5; 1.4e-3 -> 1.7e-4 for 5.0, which is overdamped). Converging
    at exactly first order to the exact solution is what shows that solution is the
    right limit; the paper's Eq. 22 recipe stays off by more than 0.05.
    """
    model = ContactModel(gamma_t=gamma_t)
    errors = []
    for dt in (2e-4, 1e-4):
        scene = Frozen(model, z=0.1, v_t=1.0, omega=1.0, t_end=10.0, dt=dt, every=int(round(4e-3 / dt)))
        result = run_series(scene, tmp_path / f"dt{dt}")
        errors.append(result.max_abs_error)
    assert errors[0] / errors[1] == pytest.approx(2.0, rel=0.05)  # first order, 5%: rounding-free ratio
    assert errors[1] < 4e-4  # 3.5e-4 measured for the largest gamma_t
    t = result.table
    vt_paper, _ = exact.frozen_velocities_paper_damped(t["t"], 1.0, 0.5, model.kt, model.m, model.alpha, gamma_t)
    if gamma_t <= 2.0:
        assert np.abs(t["v_t"] - vt_paper).max() > 0.05


def test_deck_alone_reproduces_the_run_with_lmp(run_dir, tmp_path):
    scene = Collision(ContactModel(alpha=0.1), v_n=-0.8, v_t=0.6, omega=-1.2)
    result = run_scene(scene, run_dir)
    rerun = tmp_path / "rerun"
    rerun.mkdir()
    (rerun / "in.lammps").write_text((run_dir / "in.lammps").read_text())
    subprocess.run([str(lmp_executable()), "-in", "in.lammps", "-screen", "none", "-log", "none"],
                   cwd=rerun, check=True, timeout=120)
    again = read_dump(rerun / "state.dump")
    first = read_dump(result.dump)
    cols = ["x", "z", "vx", "vz", "omegay"]
    np.testing.assert_allclose(again[cols].to_numpy(), first[cols].to_numpy(), rtol=0, atol=1e-10)


def test_bad_command_raises_typed_error_with_lammps_words(run_dir):
    deck = run_dir / "in.lammps"
    deck.write_text("units lj\natom_style sphere\nfix oops all no_such_fix_style\n")
    with pytest.raises(LammpsError) as info:
        run_deck(deck)
    err = info.value
    assert err.error_line.startswith("ERROR")
    assert "no_such_fix_style" in (err.input_line or "")
    assert err.deck == deck.resolve()
    assert str(deck.resolve()) in str(err)


@pytest.mark.parametrize("atoms", ["inline", "library"])
def test_nan_from_classic_wall_is_caught(run_dir, monkeypatch, atoms):
    """The classic hooke/history wall with gamma_n = 0 gives NaN in this build: the run must
    fail, whether the state comes back through a dump or from LAMMPS's memory."""
    import dataclasses

    real = Collision.render

    def classic(scene, atoms=None, padding=None):
        deck = real(scene, atoms, padding)
        lines = [
            "fix             wall contact wall/gran hooke/history 10.0 1.0 0.0 0.0 1000.0 1 zplane 0.0 NULL"
            if line.startswith("fix             wall ") else line
            for line in deck.text.splitlines()
        ]
        return dataclasses.replace(deck, text="\n".join(lines) + "\n")

    monkeypatch.setattr(Collision, "render", classic)
    with pytest.raises(ResultError, match="non-finite"):
        run_scene(Collision(ContactModel(), v_n=-1.0, v_t=1.0, omega=0.0), run_dir, atoms=atoms)


def test_unfinished_contact_is_caught(run_dir, monkeypatch):
    """A run that stops before the sphere has left the wall is an error, not a result."""
    monkeypatch.setattr(Collision, "nsteps", property(lambda self: math.floor(0.5 * self.model.tau / self.dt)))
    with pytest.raises(ResultError, match="still touch"):
        run_scene(Collision(ContactModel(), v_n=-1.0, v_t=1.0, omega=0.0), run_dir)


def test_half_step_contact_end_beats_integer_alignment(tmp_path):
    """The default dt = tau/(N + 1/2) puts the contact's end mid-step.

    Measured: at N = 1000 the error is 2.7e-7 mid-step and 6.4e-4 with the end on a step
    boundary (dt = tau/N), because the tangential force is cut off at the contact's end.
    A factor of 100 between them leaves a wide margin on both measurements.
    """
    model = ContactModel()
    errors = {}
    for label, steps in (("boundary", 1000.0), ("mid-step", 1000.5)):
        scene = Collision(model, v_n=-1.0, v_t=1.0, omega=0.0, dt=model.tau / steps)
        errors[label] = _errors(run_scene(scene, tmp_path / label)).max()
    assert errors["boundary"] > 100 * errors["mid-step"]


@pytest.mark.parametrize("alpha", [0.4, 0.1])
def test_batch_from_data_file_pairs_by_id(run_dir, alpha):
    """Past INLINE_SPHERES the atoms go to a data file beside the deck; same answers."""
    from spinbounce.lammps.decks import DATA_FILE, INLINE_SPHERES

    rng = np.random.default_rng(11)
    n = 3 * INLINE_SPHERES
    scene = Collision(ContactModel(alpha=alpha), v_n=rng.uniform(-1.5, -0.1, n),
                      v_t=rng.uniform(-2, 2, n), omega=rng.uniform(-4, 4, n))
    result = run_scene(scene, run_dir)
    assert (run_dir / DATA_FILE).is_file()
    assert _errors(result).max() < COLLISION_TOL
    t = result.table
    np.testing.assert_allclose(t["r_omega_lammps_initial"], t["r_omega_initial"], rtol=0, atol=1e-14)


@pytest.mark.parametrize("alpha", [0.4, 0.1])
def test_library_route_equals_the_data_file_route(tmp_path, alpha):
    """Sweeps hand the spheres to LAMMPS in memory and read the final state back from it.

    The arithmetic is the same as with a data file and a dump (17 significant digits
    round-trip every double exactly), so the two routes must agree to the last bit.
    """
    from spinbounce.lammps.decks import INLINE_SPHERES

    rng = np.random.default_rng(5)
    n = 2 * INLINE_SPHERES
    scene = Collision(ContactModel(alpha=alpha), v_n=rng.uniform(-1.5, -0.1, n),
                      v_t=rng.uniform(-2, 2, n), omega=rng.uniform(-4, 4, n))
    by_file = run_scene(scene, tmp_path / "file", atoms="data_file")
    in_memory = run_scene(scene, tmp_path / "memory", atoms="library")
    assert in_memory.dump is None and not (tmp_path / "memory" / "state.dump").exists()
    final = [f"{s}_lammps" for s in ("v_n", "v_t", "r_omega", "z")]
    np.testing.assert_array_equal(in_memory.table[final].to_numpy(), by_file.table[final].to_numpy())
    # The library route reads the initial state just after creating the atoms; the dump's
    # step-0 frame comes after fix rigid's setup, whose omega = (I omega)/I may move 1 ulp.
    start = [f"{s}_lammps_initial" for s in ("v_n", "v_t", "r_omega", "z")]
    np.testing.assert_allclose(in_memory.table[start].to_numpy(), by_file.table[start].to_numpy(), rtol=1e-15, atol=0)
    assert _errors(in_memory).max() < COLLISION_TOL
    assert in_memory.info.loop_seconds > 0  # the log's "Loop time" was found


def test_lmp_process_runner_gives_the_in_process_answer(tmp_path):
    """The benchmark's baseline (one lmp process per collision) computes the same numbers."""
    from spinbounce.lammps.runner import run_deck_lmp

    scene = Collision(ContactModel(), v_n=-0.7, v_t=0.4, omega=1.1)
    a = run_scene(scene, tmp_path / "lmp", runner=run_deck_lmp)
    b = run_scene(scene, tmp_path / "module")
    cols = ["v_n_lammps", "v_t_lammps", "r_omega_lammps"]
    np.testing.assert_array_equal(a.table[cols].to_numpy(), b.table[cols].to_numpy())
    assert a.info.loop_seconds > 0
