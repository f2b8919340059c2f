"""The extremes matrix: each case matches the theory within its reported error, or is refused.

The extremes matrix: every case either matches the exact theory within the error it
reports, or is refused (or flagged) with a message naming the parameter and its limit.

Results are obtained with --tolerance (Richardson-extrapolated ladders), so each carries
its own error estimate; the check is |LAMMPS - theory| <= estimate <= TOL per sphere.
"""

import warnings

import numpy as np
import pytest

from spinbounce.scenes.collision import Collision
from spinbounce.model.contact import ContactModel
from spinbounce.errors import PhysicsWarning, SceneError
from spinbounce.extrapolation import collide_to_tolerance, collision_frame

TOL = 1e-6
SLIPS = dict(v_t=[-1.0, 0.3, 1.2], omega=[2.0, 0.0, -3.0])


def _check(model, v_n, tmp_path, **state):
    state = {**SLIPS, **state}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", PhysicsWarning)  # flagged, and still checked below
        result, scene = collide_to_tolerance(model, v_n, state["v_t"], state["omega"], TOL, tmp_path)
    frame = collision_frame(result, scene)
    true = np.abs(frame[["v_n_error", "v_t_error", "r_omega_error"]].to_numpy()).max(axis=1)
    assert (true <= frame["v_n_estimate"].to_numpy()).all(), (true, frame["v_n_estimate"].to_numpy())
    assert result.max_estimate <= TOL


MODELS = {
    "kt/kn=1e-4": ContactModel(kt=1e-3),
    "kt/kn=1e-2": ContactModel(kt=0.1),
    "kt/kn=1": ContactModel(kt=10.0),
    "kt/kn=10": ContactModel(kt=100.0),
    "alpha=0.01": ContactModel(alpha=0.01),
    "alpha=1": ContactModel(alpha=1.0),  # warns (> 2/3: phantom mass) and still must match
    "gamma_t=0.1": ContactModel(gamma_t=0.1),
    "gamma_t=critical": ContactModel(gamma_t=2 * np.sqrt(0.4 / 1.4 * 3.5)),  # zeta^2 = Q
    "gamma_t=overdamped": ContactModel(gamma_t=50.0),
}


@pytest.mark.lammps
@pytest.mark.parametrize("name", list(MODELS))
def test_models_at_the_extremes(tmp_path, name):
    _check(MODELS[name], -0.8, tmp_path)


@pytest.mark.lammps
@pytest.mark.parametrize("v_n, r_omega", [(-1e-4, None), (-1.58, None), (-0.01, 1.0)],
                         ids=["grazing-1e-4", "just-under-tunnelling", "spin-100x-v_n"])
def test_states_at_the_extremes(tmp_path, v_n, r_omega):
    model = ContactModel()
    state = {} if r_omega is None else {"v_t": [0.0, 0.5], "omega": [r_omega / model.r, -r_omega / model.r]}
    _check(model, v_n, tmp_path, **state)


def test_tunnelling_speed_is_refused():
    with pytest.raises(SceneError, match=r"v_n = -1\.6: \|v_n\| must be below 1\.58114"):
        Collision(ContactModel(), v_n=-1.6, v_t=0.0, omega=0.0)


@pytest.mark.parametrize("fraction", [0.5, 0.9, 1.1])
def test_dt_near_the_stability_limit_is_refused_before_lammps(fraction):
    # above the limit the step diverges; below it the step is stable but a caricature (2 to
    # 3 steps per half-period: at 1.7 a frozen contact erred by 0.32): refused either way
    model = ContactModel()
    limit, mode = model.dt_limit(frozen=False)
    dt = fraction * limit
    why = rf"stability limit {limit:.6g} of the {mode} mode" if fraction > 1 else r"steps per half-period: must be at most"
    with pytest.raises(SceneError, match=rf"^dt = .*{why}"):
        Collision(model, v_n=-0.5, v_t=1.0, omega=0.0, dt=dt)


@pytest.mark.slow
@pytest.mark.lammps
def test_100000_spheres_in_one_batch(tmp_path):
    rng = np.random.default_rng(8)
    n = 100_000
    result, scene = collide_to_tolerance(ContactModel(), rng.uniform(-1.5, -0.1, n), rng.uniform(-2, 2, n),
                                         rng.uniform(-4, 4, n), 1e-5, tmp_path)
    frame = collision_frame(result, scene)
    true = np.abs(frame[["v_n_error", "v_t_error", "r_omega_error"]].to_numpy()).max(axis=1)
    assert len(frame) == n and (true <= frame["v_n_estimate"].to_numpy()).all()
