"""Full 3-D collisions: both tangential components, spin about any axis.

Without a Coulomb cap the tangential spring acts on each direction alone, so the 6x6 map
is block diagonal (exact.block_matrix). Tolerance 2e-4 (the acceptance line; LAMMPS's
error at the default dt is at most 3e-5 over these ranges, as in the plane). The spin
about the normal moves no contact point, so LAMMPS must leave it exactly as it was.
"""

import numpy as np
import pytest

from spinbounce import exact
from spinbounce.exact import oracle
from spinbounce.studies.validation import refined_dt
from spinbounce.fitting import fit_matrix
from spinbounce.pipeline import run_scene
from spinbounce.scenes.collision import Collision, STATE_3D
from spinbounce.model.contact import ContactModel

RNG = np.random.default_rng(7)
N = 300
STATES = {"v_n": RNG.uniform(-1.5, -0.1, N), "v_t": RNG.uniform(-2, 2, N), "omega": RNG.uniform(-4, 4, N),
          "v_s": RNG.uniform(-2, 2, N), "omega_s": RNG.uniform(-4, 4, N), "omega_n": RNG.uniform(-4, 4, N)}


def test_block_matrix_has_the_paper_block_twice_and_a_one():
    m3 = exact.scattering_matrix(0.4, -1.3, 0.8)
    m6 = exact.block_matrix(0.4, -1.3, 0.8)
    assert np.array_equal(m6[:3, :3], m3) and np.array_equal(m6[3:5, 3:5], m3[1:, 1:])
    assert m6[5, 5] == 1.0 and np.count_nonzero(m6) == np.count_nonzero(m3) + 4 + 1


def test_a_scene_with_out_of_plane_motion_has_six_state_columns():
    assert Collision(ContactModel()).state_names == STATE_3D[:3]
    scene = Collision(ContactModel(), v_n=-1.0, v_t=1.0, omega=0.0, omega_n=2.0)
    assert scene.state_names == STATE_3D and scene.initial.shape == (1, 6)


@pytest.mark.lammps
@pytest.mark.parametrize("model", [ContactModel(), ContactModel(alpha=0.1, kt=4.0), ContactModel(gamma_n=0.5)],
                         ids=["defaults", "alpha=0.1 rigid body", "gamma_n"])
def test_lammps_3d_matches_the_block_matrix_and_keeps_normal_spin(tmp_path, model):
    # damped contacts converge at first order (7.4e-4 at the default dt here): 32 times finer,
    # with the contact's end kept mid-step (refined_dt); ending on a step would leave a
    # first-order tangential error of 3e-4 at this dt, in the plane as in 3-D
    dt = refined_dt(model, 32) if model.gamma_n else None
    result = run_scene(Collision(model, **STATES, dt=dt), tmp_path, atoms="library", record=False)
    t = result.table
    assert result.max_abs_error < 2e-4
    # the spin about the normal passes through: to rounding (fix rigid recomputes omega
    # from the angular momentum, a relative 1e-15), exactly with fix nve/sphere
    assert np.abs(t.r_omega_n_lammps - t.r_omega_n_initial).max() <= 1e-14 * np.abs(t.r_omega_n_initial).max()
    # a least-squares fit of the 6x6 map recovers the block matrix
    initial = t[[f"{s}_initial" for s in STATE_3D]].to_numpy()
    final = t[[f"{s}_lammps" for s in STATE_3D]].to_numpy()
    fitted, _, _ = fit_matrix(initial, final)
    assert np.abs(fitted - model.block_matrix()).max() < 2e-4


@pytest.mark.lammps
def test_lammps_3d_sliding_matches_the_oracle(tmp_path):
    # with a finite mu the two tangential directions share one cap |F_t| <= mu F_n, so they
    # couple; the oracle integrates the 3-D slide (its direction turns with the slip)
    model = ContactModel(mu=0.3)
    states = {k: v[:8] for k, v in STATES.items()}
    coarse = Collision(model, **states)
    result = run_scene(Collision(model, **states, dt=coarse.dt / 8), tmp_path, atoms="library", record=False)
    assert result.max_abs_error < 1e-4
    # the coupling is real: treating each direction as its own 2-D problem misses by far more
    apart = [np.concatenate([oracle.bounce(model, states["v_n"][i], states["v_t"][i], states["omega"][i]).final[:3],
                             oracle.bounce(model, states["v_n"][i], states["v_s"][i], states["omega_s"][i]).final[1:3]])
             for i in range(8)]
    t = result.table
    final = t[["v_n_lammps", "v_t_lammps", "r_omega_lammps", "v_s_lammps", "r_omega_s_lammps"]].to_numpy()
    assert np.abs(final - np.array(apart)).max() > 1e-2


def _spec_3d(**states):
    from spinbounce.sweeps import spec_from_dict

    base = {"n": 4000, "v_n": [-1.5, -0.1], "v_t": [-2, 2], "omega": [-4, 4], "v_s": [-2, 2],
            "omega_s": [-4, 4], "r_omega_n": [-2, 2]}
    return spec_from_dict({"seed": 3, "chunk_size": 2000, "states": {**base, **states}})


def test_a_3d_sweep_needs_every_out_of_plane_axis():
    from spinbounce.sweeps import SweepError, spec_from_dict

    with pytest.raises(SweepError, match="states.omega_n"):
        spec_from_dict({"states": {"n": 10, "v_n": [-1, -0.5], "v_t": [0, 1], "omega": [0, 1], "v_s": [0, 1],
                                   "omega_s": [0, 1]}})
    assert _spec_3d().initial_states(0, 0, 5).shape == (5, 6)


@pytest.mark.lammps
def test_a_3d_sweep_and_its_fit_recover_the_block_matrix(tmp_path):
    from spinbounce.fitting import fit_groups
    from spinbounce.sweeps import read_results, run_sweep

    out = run_sweep(_spec_3d(), tmp_path / "sweep", workers=1, log=lambda *a, **k: None)
    rows = read_results(out)
    assert len(rows) == 4000
    (fitted,) = fit_groups(rows)
    assert np.array(fitted["matrix"]).shape == (6, 6)
    assert fitted["max_element_diff"] < 2e-4  # the acceptance line
    assert np.array_equal(rows["r_omega_n_lammps"], rows["r_omega_n_initial"])
