"""The exact damped theory against LAMMPS, from light damping to overdamped.

The exact damped theory against LAMMPS: gamma_t from 0.01 to overdamped, gamma_n from 0
to restitution 0.5, with the tensile normal force allowed (LAMMPS's default) and cut off
(limit_damping). Results come from --tolerance ladders, so each carries its own error
estimate; the check is |LAMMPS - exact| <= estimate <= 1e-6 for every sphere or time.
"""

import math

import numpy as np
import pytest

from spinbounce.exact import linear
from spinbounce.model.contact import ContactModel
from spinbounce.extrapolation import collide_to_tolerance, collision_frame, frozen_to_tolerance

TOL = 1e-6
RNG = np.random.default_rng(33)
STATES = (RNG.uniform(-1.5, -0.1, 12), RNG.uniform(-2, 2, 12), RNG.uniform(-4, 4, 12))
CRITICAL_T = 2 * math.sqrt(0.4 / 1.4 * 3.5)  # zeta^2 = Q at the defaults: critically damped slip


def _gn(e):
    return linear.gamma_n_for_restitution(e, 1.0, 10.0)


COLLISIONS = {
    "gamma_t=0.01": ContactModel(gamma_t=0.01),
    "gamma_t=0.3": ContactModel(gamma_t=0.3),
    "gamma_t=critical": ContactModel(gamma_t=CRITICAL_T),
    "gamma_t=20": ContactModel(gamma_t=20.0),
    "e=0.9": ContactModel(gamma_n=_gn(0.9)),
    "e=0.7": ContactModel(gamma_n=_gn(0.7)),
    "e=0.5": ContactModel(gamma_n=_gn(0.5)),
    "e=0.5, limit_damping": ContactModel(gamma_n=_gn(0.5), limit_damping=True),
    "e=0.7, gamma_t=0.3, limit_damping": ContactModel(gamma_n=_gn(0.7), gamma_t=0.3, limit_damping=True),
    "e=0.5, gamma_t=1": ContactModel(gamma_n=_gn(0.5), gamma_t=1.0),
}


@pytest.mark.lammps
@pytest.mark.parametrize("name", list(COLLISIONS))
def test_damped_collisions_match_the_exact_theory(tmp_path, name):
    model = COLLISIONS[name]
    result, scene = collide_to_tolerance(model, *STATES, TOL, tmp_path)
    frame = collision_frame(result, scene)
    true = np.abs(frame[["v_n_error", "v_t_error", "r_omega_error"]].to_numpy()).max(axis=1)
    assert (true <= frame["v_n_estimate"].to_numpy()).all() and result.max_estimate <= TOL


@pytest.mark.lammps
@pytest.mark.parametrize("gamma_t", [0.01, 1.0, 5.0])
def test_damped_frozen_contact_matches_the_exact_theory(tmp_path, gamma_t):
    model = ContactModel(gamma_t=gamma_t)
    result = frozen_to_tolerance(model, 0.1, 1.0, 2.0, 8.0, TOL, tmp_path)
    exact = np.column_stack(linear.frozen_velocities(result.t, 1.0, 1.0, model.kt, model.m, model.alpha, gamma_t))
    true = np.abs(result.values - exact).max(axis=1)
    assert (true <= result.estimate[:, 0]).all() and result.max_estimate <= TOL


def test_the_cut_off_changes_the_outcome_measurably():
    """limit_damping is not a detail: at e = 0.5 it moves the restitution (to 0.550) and
    Omega (-1.326 to -1.069) by far more than any tolerance above."""
    tensile, cut = ContactModel(gamma_n=_gn(0.5)), ContactModel(gamma_n=_gn(0.5), limit_damping=True)
    assert cut.restitution - tensile.restitution > 0.04
    assert abs(cut.Omega - tensile.Omega) > 0.2
