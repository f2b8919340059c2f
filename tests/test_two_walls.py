"""A sphere between two parallel walls: LAMMPS against the product of scattering matrices.

The top wall's map is the bottom wall's conjugated by the mirror R = diag(-1, 1, -1)
(docs/theory.md, "Two parallel walls"). Tolerances:

* undamped, uncapped: 1e-4 after 20 bounces (the acceptance line). At 1000 steps per
  half-period each contact starts at the same phase of a step (the default gap) and LAMMPS's
  error is second order: measured 2.0e-5 after 20 bounces, growing by 1e-6 a bounce (v_n);
* damped or capped: the contacts no longer start at one phase of a step (e < 1 changes
  every flight; a cap's slides are not aligned), so the error is first order: measured
  2.9e-4 (damped) and 2.4e-4 (mu = 0.3) at 4000 steps per half-period, 1.2e-3 and 9.6e-4
  at 1000; the bound is twice the measured value at 4000.
"""

import numpy as np
import pytest

from spinbounce import exact
from spinbounce.model.parameters import SceneError
from spinbounce.model.contact import ContactModel
from spinbounce.scenes.two_walls import TwoWalls, matrix_product, mirror, run_two_walls, theory_path

STATES = np.array([[-1.0, 1.0, 0.0], [-1.0, -0.5, 0.8], [-1.0, 0.3, -1.2]])
STATES_3D = np.array([[-1.0, 1.0, 0.0, 0.4, -0.7, 0.9], [-1.0, -0.5, 0.8, -1.1, 0.2, -1.5]])


def _tangential_blocks(model):
    m3 = model.matrix()
    r = mirror(3)
    return m3[1:, 1:], (r @ m3 @ r)[1:, 1:]


@pytest.mark.parametrize("kt", [1.0, 0.3, 2.5])
def test_only_the_still_state_rolls_on_both_walls(kt):
    # the paper's Conclusions: rolling on the bottom wall (v_t + r omega = 0) is left alone by
    # the bottom wall, rolling on the top (v_t - r omega = 0) by the top; a state both leave
    # alone must lie in the null space of both (B - 1), which is {0}
    bottom, top = _tangential_blocks(ContactModel(kt=kt))
    assert np.allclose(bottom @ [1.0, -1.0], [1.0, -1.0]) and np.allclose(top @ [1.0, 1.0], [1.0, 1.0])
    both = np.vstack([bottom - np.eye(2), top - np.eye(2)])
    assert np.linalg.matrix_rank(both, tol=1e-9) == 2


def test_two_bounces_shrink_every_tangential_state_unless_energy_is_conserved():
    # each bounce keeps the energy only of the state that rolls on that wall; two walls share
    # no such state, so the two-bounce map contracts (|eigenvalues| < 1), except at the magic
    # kt/kn = 2/7 (Omega = -2), where every bounce conserves energy and nothing decays
    bottom, top = _tangential_blocks(ContactModel())
    assert np.abs(np.linalg.eigvals(top @ bottom)).max() < 0.9
    magic = ContactModel(kt=10.0 * exact.magic_kt_over_kn(0.4))
    bottom, top = _tangential_blocks(magic)
    assert np.allclose(np.abs(np.linalg.eigvals(top @ bottom)), 1.0, atol=1e-12)


def test_bounce_by_bounce_theory_is_the_matrix_product():
    model = ContactModel(gamma_n=0.3, gamma_t=0.2)
    path = theory_path(model, STATES, 7)
    assert np.allclose(path[-1], STATES @ matrix_product(model, 7).T, rtol=0, atol=1e-14)


def test_a_scene_refuses_what_it_cannot_run():
    with pytest.raises(SceneError, match="gap"):
        TwoWalls((ContactModel(),), STATES[:1], gap=0.9)
    with pytest.raises(SceneError, match="Hertzian"):
        TwoWalls((ContactModel(normal="hertz", kn=40.0),), STATES[:1])
    with pytest.raises(SceneError, match="v_n"):
        TwoWalls((ContactModel(),), np.array([[0.5, 1.0, 0.0]]))


@pytest.mark.lammps
def test_lammps_matches_the_matrix_product_after_20_bounces(tmp_path):
    model = ContactModel()
    scene = TwoWalls((model,) * 3, STATES, bounces=20, steps_per_half_period=1000)
    result = run_two_walls(scene, tmp_path)
    assert np.abs(result.states[-1] - STATES @ matrix_product(model, 20).T).max() < 1e-4
    # every contact lasts the exit time of Eq. 16 (measured to 4e-7 at this step)
    assert np.abs(result.contact_durations() / model.t_exit - 1.0).max() < 1e-5


@pytest.mark.lammps
def test_lammps_3d_between_two_walls_keeps_the_spin_about_the_normal(tmp_path):
    model = ContactModel()
    scene = TwoWalls((model,) * 2, STATES_3D, bounces=20, steps_per_half_period=1000)
    result = run_two_walls(scene, tmp_path)
    assert np.abs(result.states[-1] - STATES_3D @ matrix_product(model, 20, width=6).T).max() < 1e-4
    # omega_z moves no contact point on either wall: it survives every bounce exactly, so in
    # 3-D the states that roll on both walls are (0, 0, 0, 0, 0, any r omega_n)
    assert np.array_equal(result.states[:, :, 5], np.broadcast_to(STATES_3D[:, 5], result.states[:, :, 5].shape))


@pytest.mark.lammps
def test_lammps_rolling_on_one_wall_is_undone_by_the_other(tmp_path):
    model = ContactModel()
    rolling = np.array([[-1.0, 1.0, -1.0], [-1.0, 0.0, 0.0]])  # rolls on the bottom wall; still
    result = run_two_walls(TwoWalls((model,) * 2, rolling, bounces=2, steps_per_half_period=1000), tmp_path)
    tangential = result.states[:, :, 1:]
    assert np.abs(tangential[1, 0] - [1.0, -1.0]).max() < 1e-5  # the bottom wall leaves it alone
    assert np.abs(tangential[2, 0] - [1.0, -1.0]).max() > 0.5  # the top wall does not
    assert np.abs(tangential[:, 1]).max() == 0.0  # no slip on either wall, ever


@pytest.mark.lammps
@pytest.mark.parametrize("model, bound", [(ContactModel(gamma_n=0.5, gamma_t=0.3), 6e-4),
                                          (ContactModel(mu=0.3), 5e-4)], ids=["damped", "mu=0.3"])
def test_lammps_damped_and_capped_walls_follow_the_theory_bounce_by_bounce(tmp_path, model, bound):
    scene = TwoWalls((model,) * 3, STATES, bounces=20, steps_per_half_period=4000)
    result = run_two_walls(scene, tmp_path)
    expected = theory_path(model, STATES, 20)
    assert np.abs(result.states - expected).max() < bound
    # and both lose the tangential state, as only the still state rolls on both walls
    assert np.abs(result.states[-1, :, 1:]).max() < 1e-4


@pytest.mark.slow
@pytest.mark.lammps
def test_the_command_writes_the_figure_with_its_provenance(tmp_path, capsys):
    import argparse
    import json

    from spinbounce.cli import two_walls as command

    parser = argparse.ArgumentParser(prog="spinbounce")
    command.register(parser.add_subparsers(dest="command"))
    args = parser.parse_args(["two-walls", "--out", str(tmp_path), "--json"])
    assert args.handler(args) == 0
    report = json.loads(capsys.readouterr().out)
    assert {p.name for p in tmp_path.iterdir()} >= {"two_walls.png", "two_walls.pdf", "two_walls.json"}
    record = json.loads((tmp_path / "two_walls.json").read_text())
    assert record["lammps_version"] and len(record["cases"]) == len(report["cases"]) == 4
    # the same bounds as the tests above: 1e-4 undamped, 6e-4 damped or capped (first order)
    for case in record["cases"]:
        assert case["max_abs_deviation"] < (1e-4 if case["theory"] == "linear" else 6e-4)
