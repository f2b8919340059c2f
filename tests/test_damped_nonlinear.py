"""Damped contacts whose force, spring or dashpot grows with the contact radius: reference and LAMMPS.

The reference (spinbounce.exact.contact_phases) integrates the contact in time, and in
sqrt(delta) near its exit. It is held here to the closed forms it must reproduce (the Hookean
damped oscillator, the undamped Hertzian contact), to a property of LAMMPS's Hertzian
coeff_restitution (its prefactor makes the restitution e_n at every impact speed), and to LAMMPS:
at the default step within the default accuracy, converged within 1e-6.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from converged import converged

from spinbounce.exact import choose, contact_phases, hertz, linear
from spinbounce.model.contact import ContactModel
from spinbounce.pipeline import run_scene
from spinbounce.scenes.collision import Collision

MATERIAL = {"normal": "hertz/material", "youngs_modulus": 1.0e4, "poisson_ratio": 0.3}
#: One of each damping sub-model on a Hertzian force, with a spring of each kind, and a damped
#: Mindlin spring on a Hookean force.
ASSEMBLIES = {
    "hertz velocity": {"normal": "hertz", "kn": 1000.0, "gamma_n": 0.5, "gamma_t": 0.2},
    "hertz mass_velocity": {"normal": "hertz", "kn": 1000.0, "damping": "mass_velocity", "gamma_n_per_mass": 0.8,
                            "x_t": 0.5},
    "hertz tsuji mindlin": {**MATERIAL, "damping": "tsuji", "e_n": 0.5, "x_t": 1.0, "tangential": "mindlin"},
    "hertz coeff_restitution mindlin_rescale": {**MATERIAL, "damping": "coeff_restitution", "e_n": 0.7,
                                                "tangential": "mindlin_rescale"},
    "hooke mindlin/force": {"kn": 50.0, "gamma_n": 0.8, "tangential": "mindlin/force", "mindlin_kt": 300.0},
    "hooke linear_history_classic": {"kn": 50.0, "gamma_n": 0.8, "tangential": "linear_history_classic",
                                     "kt": 100.0},
    "hooke viscoelastic": {"damping": "viscoelastic", "gamma_n_per_mass_radius": 0.5, "x_t": 0.5},
    "hertz viscoelastic mindlin": {"normal": "hertz", "kn": 1000.0, "damping": "viscoelastic",
                                   "gamma_n_per_mass_radius": 2.0, "x_t": 0.5, "tangential": "mindlin",
                                   "mindlin_kt": 400.0},
}


def test_the_integration_meets_the_damped_oscillator():
    # Hooke, velocity damping, the paper's spring with a dashpot: restitution and Omega in closed form
    model = ContactModel(gamma_n=0.6, gamma_t=0.3, kt=2.0)
    for v in (-0.3, -1.4):
        v_out, v_t, r_omega, time = contact_phases.bounce(contact_phases.Law.of(model), v, 1.0, 0.0)
        assert v_out / -v == pytest.approx(linear.restitution(model.m, model.kn, model.gamma_n), abs=1e-10)
        assert v_t + r_omega - 1.0 == pytest.approx(model.Omega, abs=1e-10)
        assert time == pytest.approx(linear.exit_time(model.m, model.kn, model.gamma_n), abs=1e-10)


def test_the_integration_meets_the_undamped_hertzian_contact():
    model = ContactModel(normal="hertz", kn=1000.0, kt=30.0, gamma_t=0.1)
    for v in (-0.2, -1.1):
        v_out, v_t, r_omega, time = contact_phases.bounce(contact_phases.Law.of(model), v, 1.0, 0.0)
        assert v_out == pytest.approx(-v, abs=1e-10)
        assert time == pytest.approx(float(hertz.contact_time(v, model.m, model.kn, model.r)), rel=1e-10)
        assert v_t + r_omega - 1.0 == pytest.approx(float(hertz.Omega(v, model.m, model.kn, model.r, model.kt,
                                                                       model.alpha, model.gamma_t)), abs=1e-10)


def test_hertzian_coeff_restitution_gives_e_n_at_every_speed():
    # LAMMPS's Hertzian prefactor sqrt(3/2) 2 sqrt(5/6) beta sqrt(m_eff F/delta): the dashpot scales
    # as the Hertzian force does, so the restitution is one number, and it is e_n
    for e in (0.2, 0.6, 0.95):
        model = ContactModel(**MATERIAL, damping="coeff_restitution", e_n=e)
        assert model.normal_law.restitutions(model, [-0.05, -0.5, -2.0]) == pytest.approx([e] * 3, abs=1e-9)
    tsuji = ContactModel(**MATERIAL, damping="tsuji", e_n=0.5)  # the same form: one restitution, not e_n
    e_tsuji = tsuji.normal_law.restitutions(tsuji, [-0.05, -0.5, -2.0])
    assert np.ptp(e_tsuji) < 1e-9 and abs(e_tsuji[0] - 0.5) > 0.05


def test_a_viscoelastic_dashpot_makes_the_hookean_restitution_depend_on_the_speed():
    # c = gamma_n_per_mass_radius m a grows with the overlap, which grows with |v_n|
    model = ContactModel(damping="viscoelastic", gamma_n_per_mass_radius=0.5)
    slow, fast = model.normal_law.restitutions(model, [-0.05, -1.5])
    assert fast < slow < 1.0 and not choose.which(model).has_matrix


def test_velocity_damping_on_a_hertzian_force_depends_on_the_speed():
    model = ContactModel(normal="hertz", kn=1000.0, gamma_n=0.5)
    slow, fast = model.normal_law.restitutions(model, [-0.05, -2.0])
    assert slow < fast  # a slow contact is softer and longer: its dashpot takes more of it
    assert not choose.which(model).has_matrix


def _states(rng, n: int) -> np.ndarray:
    return np.column_stack([-rng.uniform(0.2, 1.2, n), rng.uniform(-1.0, 1.0, n), rng.uniform(-1.0, 1.0, n)])


@pytest.mark.lammps
@pytest.mark.parametrize("name", sorted(ASSEMBLIES))
@pytest.mark.parametrize("n", [1, 5])
def test_lammps_at_the_default_step_meets_the_reference(name, n, tmp_path):
    # one speed (aligned, probed) and a batch of speeds (a dashpot cannot be time-scaled: the
    # fixed fine rule); every row within the default accuracy, 1e-4 of its state's size
    rng = np.random.default_rng(sum(map(ord, name)) + n)
    s = _states(rng, n)
    scene = Collision(ContactModel(**ASSEMBLIES[name]), v_n=s[:, 0], v_t=s[:, 1], omega=s[:, 2] / 0.5)
    result = run_scene(scene, tmp_path, record=False)
    assert (result.table["status"] == "ok").all() and result.table["error"].max() <= 1e-4


@pytest.mark.slow
@pytest.mark.lammps
@pytest.mark.parametrize("name", ["hertz velocity", "hertz tsuji mindlin", "hooke mindlin/force", "hooke viscoelastic",
                                  "hertz viscoelastic mindlin"])
def test_converged_lammps_meets_the_reference(name, tmp_path):
    # dt halved (the contact's end mid-step) until two runs differ by less than 1e-7; the
    # reference within 1e-6 (the damped runs converge at first order: the last is ~1e-7 away)
    model = ContactModel(**ASSEMBLIES[name])
    state = np.array([-0.8, 0.6, -0.3])
    final = converged(model, state, tmp_path)
    assert np.abs(final - choose.predict(model, state[None, :])[0]).max() <= 1e-6


def test_hertz_mindlin_with_a_restitution_dashpot_has_one_matrix_at_every_speed():
    # dashpots sqrt(m_eff kn a) on the Hertzian force with a Mindlin spring: every contact is the
    # same one scaled, so one restitution and one Omega (checked here by integrating three speeds)
    model = ContactModel(**MATERIAL, damping="coeff_restitution", e_n=0.7, x_t=0.3, tangential="mindlin")
    assert choose.which(model).has_matrix
    speeds = (0.05, 0.5, 2.0)
    finals = [contact_phases.bounce(contact_phases.Law.of(model), -v, 1.0, 0.0) for v in speeds]
    assert np.ptp([f[1] + f[2] for f in finals]) < 1e-9  # the slip ratio, 1 + Omega
    assert np.ptp([f[0] / v for f, v in zip(finals, speeds)]) < 1e-9  # the restitution
    assert model.matrix()[0, 0] == pytest.approx(-0.7, abs=1e-9)


@pytest.mark.parametrize("limit_damping", [False, True])
@pytest.mark.parametrize("tangential", ["mindlin", "mindlin_rescale/force", "linear_history"])
def test_many_slips_on_one_normal_motion_are_each_one_s_own_bounce(tangential, limit_damping):
    # exit_slips (the calibration scan's) carries many springs and dashpots on one normal motion; each must be
    # its own bounce's exit slip, limit_damping's turn included (with it the force ends before the contact does).
    # Both are DOP853 at rtol 1e-12; 1e-9 leaves their rounding room (they differ by 8e-12 at most here, and
    # by up to 3e-10 on the calibration scan: tests/test_calibrate_mindlin.py)
    model = ContactModel(normal="hertz/material", youngs_modulus=1e4, poisson_ratio=0.3, damping="viscoelastic",
                         gamma_n_per_mass_radius=60.0, x_t=0.5, tangential=tangential,
                         limit_damping=limit_damping)
    law = contact_phases.Law.of(model)
    springs, dashpots = law.k * np.array([0.05, 0.4, 1.0, 3.0]), law.c_t * np.array([0.0, 0.5, 1.0, 2.0])
    slips = contact_phases.exit_slips(law, springs, dashpots, v_n=-0.7)
    for k, c_t, slip in zip(springs, dashpots, slips):
        _, v_t, r_omega, _ = contact_phases.bounce(dataclasses.replace(law, k=k, c_t=c_t), -0.7, 1.0, 0.0)
        assert slip == pytest.approx(v_t + r_omega, abs=1e-9)
