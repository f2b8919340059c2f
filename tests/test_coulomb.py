"""Coulomb sliding (finite mu): the oracle against closed forms, LAMMPS against the oracle.

Coulomb sliding (finite mu): the oracle against the rigid-body closed forms, and LAMMPS
against the oracle on a mu sweep from 0.01 to 10 at incidence angles from 5 to 85 degrees.

Tolerances:
* oracle vs closed forms, 1e-6 (the acceptance line). The oracle integrates at rtol 1e-12
  with every regime switch located as an event, so it reaches these to about 1e-12;
* LAMMPS vs oracle, 1e-4 (the acceptance line). LAMMPS's error with a finite mu is
  second order in dt without damping (measured: 4e-4 at the default dt for mu = 10,
  3e-5 at dt/4, 5e-6 at dt/8, 1.9e-6 at dt/16) and first order with normal damping
  (1.9e-4 at dt/16 for mu = 10 with limit_damping; 1.8e-4 at dt/32 with the tensile
  force allowed); each case's dt below is finer by a further factor of two or more.
"""

import math

import numpy as np
import pytest

from spinbounce import exact
from spinbounce.exact import oracle, rigid_body
from spinbounce.pipeline import run_scene
from spinbounce.scenes.collision import Collision
from spinbounce.model.contact import ContactModel

MUS = (0.01, 0.03, 0.1, 0.3, 1.0, 3.0, 10.0)
ANGLES = np.radians([5.0, 20.0, 35.0, 50.0, 65.0, 80.0, 85.0])
# unit speed at each incidence angle, then topspin, backspin and a slow sphere with spin
V_N = np.concatenate([-np.cos(ANGLES), [-1.0, -1.0, -0.5]])
V_T = np.concatenate([np.sin(ANGLES), [0.0, 0.5, -0.3]])
OMEGA = np.concatenate([np.zeros(ANGLES.size), [4.0, -6.0, 8.0]])
E_07 = exact.gamma_n_for_restitution(0.7, 1.0, 10.0)
#: model variants of the sweep -> how much finer than the default dt LAMMPS runs
VARIANTS = {
    "e=1": ({}, 16),
    "e=0.7, limit_damping": ({"gamma_n": E_07, "limit_damping": True}, 64),
    "e=0.7, tensile": ({"gamma_n": E_07}, 256),
}


def _final(result):
    t = result.table
    return np.column_stack([t.v_n_lammps, t.v_t_lammps, t.r_omega_lammps])


def _run(model, v_n, v_t, omega, refine, tmp_path):
    coarse = Collision(model, v_n=v_n, v_t=v_t, omega=omega)
    scene = Collision(model, v_n=v_n, v_t=v_t, omega=omega, dt=coarse.dt / refine)
    return run_scene(scene, tmp_path, atoms="library", record=False)


# -- the oracle against closed forms ----------------------------------------------------

@pytest.mark.parametrize("kw", [{}, {"gamma_n": E_07, "limit_damping": True},
                                {"gamma_t": 0.3, "gamma_n": E_07, "limit_damping": True}, {"kt": 4.0, "alpha": 0.1}])
def test_oracle_with_a_huge_mu_is_the_exact_uncapped_theory(kw):
    # with mu = 1e8 the cap only acts in a final slide lasting ~ |A|/(mu |dF_n/dt|), where A
    # is the spring's force then, so the capped and uncapped outcomes differ by about
    # |A|^2/(mu |dF_n/dt|): up to 1.3e-8 here (fast spin, limit_damping). Two cases have no such limit,
    # since the cap mu |F_n| is exactly zero at an instant inside the contact, whatever mu:
    # gamma_t > 0 with gamma_n = 0 (the damping force gamma_t u' meets a zero cap at first
    # touch) and a normal force that turns tensile (the cap passes through zero and the
    # spring's load is shed there). See test_limits_that_do_not_commute.
    model = ContactModel(mu=1e8, **kw)
    exact = np.column_stack([V_N, V_T, OMEGA * model.r]) @ ContactModel(**kw).matrix().T
    got = oracle.bounce_many(model, V_N, V_T, OMEGA)[:, :3]
    assert np.abs(got - exact).max() < 1e-7


#: fast slip (spin against the sliding direction or with it): the slide never stops
GROSS = [(-1.0, 0.5, -60.0), (-0.6, 2.0, 40.0), (-1.2, -1.0, 50.0)]
#: with gamma_n > 0 the cap starts at mu gamma_n |v_n| > 0, so a sliding contact first
#: sticks for ~ mu gamma_n |v_n| / (kt |u'|) and misses the rigid-body impulse by about
#: half the cap times that (3.5e-6 at |u'| = 30): the limit needs |u'| ~ 300
GROSS_DAMPED = [(-1.0, 0.5, -600.0), (-0.6, 2.0, 600.0), (-1.2, -1.0, 1000.0)]


@pytest.mark.parametrize("kw", [{}, {"gamma_n": E_07, "limit_damping": True}, {"kt": 8.0}])
def test_oracle_gross_slip_is_the_rigid_body_outcome(kw):
    # a contact that slides throughout takes the impulse mu (1 + e) m |v_n| against the slip
    model = ContactModel(mu=0.02, **kw)
    states = GROSS_DAMPED if kw.get("gamma_n") else GROSS + list(zip(V_N[3:7], V_T[3:7], OMEGA[3:7], strict=True))
    for v_n, v_t, omega in states:
        got = oracle.bounce(model, v_n, v_t, omega)
        assert got.pattern in ("slip", "stick-slip")
        closed = rigid_body.gross_slip(model, v_n, v_t, omega, model.restitution)
        assert np.abs(got.final[:3] - closed).max() < 1e-6


def test_oracle_no_slip_at_the_magic_ratio_is_the_rough_sphere():
    # at kt/kn = 2/7 (alpha = 2/5) the slip and the overlap stay in proportion, so a contact
    # that sticks at first touch (kt |u'| < mu kn |v_n|) sticks to the end: Eq. 20 exactly
    model = ContactModel(kt=10.0 * exact.magic_kt_over_kn(0.4), mu=0.5)
    for v_n, v_t, omega in [(-1.0, 0.5, 0.0), (-0.7, 0.2, 0.8), (-1.2, -1.0, -1.0)]:
        assert model.kt * abs(v_t + model.r * omega) < model.mu * model.kn * abs(v_n)
        got = oracle.bounce(model, v_n, v_t, omega)
        assert got.pattern == "stick"
        rough = exact.rough_matrix(0.4) @ np.array([v_n, v_t, model.r * omega])
        assert np.abs(got.final[:3] - rough).max() < 1e-6


def test_oracle_approaches_the_no_slip_outcome_as_the_slip_shrinks():
    # away from the magic ratio the contact always slides at the end (F_n -> 0 while
    # kt u != 0); that slide moves the outcome by O(u'^2 / (mu |v_n|)): quadratic in u'
    model = ContactModel(mu=1.0)
    deviations = []
    for slip in (1e-2, 1e-3, 1e-4):
        got = oracle.bounce(model, -1.0, slip, 0.0).final[:3]
        deviations.append(np.abs(got - model.replace(mu=None).matrix() @ np.array([-1.0, slip, 0.0])).max())
    assert deviations[-1] < 1e-6
    assert 70 < deviations[0] / deviations[1] < 130 and 70 < deviations[1] / deviations[2] < 130


def test_oracle_finds_slip_stick_slip_above_the_magic_ratio():
    # above kt/kn = 2/7 a contact that slides at first touch can stick mid-way and slide
    # again at the end; at kt/kn = 1/10 it never re-sticks
    stiff = ContactModel(kt=8.0, mu=0.1)
    patterns = {oracle.bounce(stiff, -1.0, vt, 0.0).pattern for vt in np.linspace(0.05, 1.5, 30)}
    assert {"stick-slip", "slip-stick-slip", "slip"} <= patterns
    soft = ContactModel(kt=1.0, mu=0.1)
    assert not any("slip-stick" in oracle.bounce(soft, -1.0, vt, 0.0).pattern for vt in np.linspace(0.05, 1.5, 30))


def test_oracle_refuses_an_uncapped_model():
    with pytest.raises(ValueError, match="finite mu"):
        oracle.bounce(ContactModel(), -1.0, 1.0, 0.0)


# -- LAMMPS against the oracle and the closed forms ----------------------------------------

@pytest.mark.lammps
@pytest.mark.parametrize("variant", list(VARIANTS))
def test_lammps_matches_the_oracle_across_mu(tmp_path, variant):
    kw, refine = VARIANTS[variant]
    worst = 0.0
    for k, mu in enumerate(MUS):
        result = _run(ContactModel(mu=mu, **kw), V_N, V_T, OMEGA, refine, tmp_path / str(k))
        worst = max(worst, result.max_abs_error)  # the theory columns are the oracle's
    assert worst < 1e-4


@pytest.mark.lammps
def test_lammps_gross_slip_and_no_slip_match_the_closed_forms(tmp_path):
    for name, slide, states in (("e=1", ContactModel(mu=0.02), GROSS),
                                ("e=0.7", ContactModel(mu=0.02, gamma_n=E_07, limit_damping=True), GROSS_DAMPED)):
        result = _run(slide, *np.array(states).T, 64, tmp_path / name)
        closed = np.array([rigid_body.gross_slip(slide, *s, slide.restitution) for s in states])
        assert np.abs(_final(result) - closed).max() < 1e-4
    rough = ContactModel(kt=10.0 * exact.magic_kt_over_kn(0.4), mu=0.5)
    states = np.array([(-1.0, 0.5, 0.0), (-0.7, 0.2, 0.8), (-1.2, -1.0, -1.0)])
    result = _run(rough, *states.T, 4, tmp_path / "rough")
    expected = (states * [1.0, 1.0, rough.r]) @ exact.rough_matrix(0.4).T
    assert np.abs(_final(result) - expected).max() < 1e-4


@pytest.mark.lammps
def test_lammps_with_tangential_damping_converges_to_the_oracle_at_first_order(tmp_path):
    # gamma_t > 0 with a finite mu: LAMMPS's first step projects the damping force
    # gamma_t u' onto a cap of one step's normal force, mu kn |v_n| dt, and the spring keeps
    # that preload: an error of first order in dt whose size grows with mu
    model = ContactModel(mu=1.0, gamma_t=0.3)
    errors = [_run(model, V_N, V_T, OMEGA, f, tmp_path / str(f)).max_abs_error for f in (4, 8)]
    assert math.isclose(errors[0] / errors[1], 2.0, rel_tol=0.1)


def test_limits_that_do_not_commute():
    # where the cap is zero at an instant inside the contact, every finite mu sheds the
    # spring's load there, so mu -> infinity does not give back the uncapped theory;
    # LAMMPS at a fixed dt does, because no step lands in the shrinking window
    for kw in ({"gamma_n": E_07}, {"gamma_t": 0.3}):
        uncapped = ContactModel(**kw).matrix() @ np.array([-1.0, 0.5, 0.0])
        for mu in (1e2, 1e8):
            got = oracle.bounce(ContactModel(mu=mu, **kw), -1.0, 0.5, 0.0).final[:3]
            assert np.abs(got - uncapped).max() > 1e-3
