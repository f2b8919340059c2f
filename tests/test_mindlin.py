"""LAMMPS's Mindlin tangential sub-models on a wall: reference, words, refusals, LAMMPS, theory.

The reference (spinbounce.exact.mindlin) integrates a scaled contact in the variable sigma =
sqrt(delta/delta_0) near its ends. Here it is checked against an integration written
independently in the physical variables and the time (for the variants without a rescale:
the time form of a rescale's unloading is too singular at the end for 1e-9), against the
exact solutions of two points it finds (lam = 1: the history follows the overlap, h = delta;
lam = 3/2 with a force history: the slip rate follows the normal velocity), and against
LAMMPS, at the default step (1e-4, the default accuracy) and converged (1e-6).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import spinbounce
from converged import converged
from spinbounce.exact import choose, contact_phases, mindlin
from spinbounce.lammps.decks import wall_parameters
from spinbounce.model.contact import ContactModel
from spinbounce.model.parameters import SceneError
from spinbounce.pipeline import run_scene
from spinbounce.scenes.collision import Collision

VARIANTS = ("mindlin", "mindlin/force", "mindlin_rescale", "mindlin_rescale/force")
MATERIAL = {"normal": "hertz/material", "youngs_modulus": 1.0e4, "poisson_ratio": 0.3}
#: Each variant on the Hertzian force (LAMMPS's NULL stiffness from the material) and on the
#: Hookean force (a stiffness of its own), with a tangential dashpot on the second.
ASSEMBLIES = {"hertz/material": MATERIAL, "hooke": {"kn": 50.0, "mindlin_kt": 700.0, "gamma_t": 0.4}}


def _time_domain_ratio(model: ContactModel, v_n: float) -> float:
    """u'(end)/u'(0) from the contact's physical equations in time: delta'' = -K delta^p/m,
    u'' = (1 + alpha)/(alpha m) F_t with F_t = -k a h - c u' (h' = u') or F_t = h - c u'
    (h' = -k a u'), a = sqrt(r delta); events at the deepest point and the exit."""
    force, rescale = model.tangential_law.variant
    assert not rescale
    power, m, r = model.normal_law.power, model.m, model.r
    K, k, c = model.kn * r ** (power - 1.0), model.tangential_law.stiffness(model), model.gamma_t
    s = (1.0 + model.alpha) / (model.alpha * m)

    def rhs(t, y):
        delta, rate, h, slip = y
        a = math.sqrt(r * max(delta, 0.0))
        force_t, dh = (h - c * slip, -k * a * slip) if force else (-k * a * h - c * slip, slip)
        return [rate, -K * max(delta, 0.0) ** power / m, dh, s * force_t]

    def deepest(t, y):
        return y[1]

    def out(t, y):
        return y[0]

    deepest.terminal = out.terminal = True
    deepest.direction = out.direction = -1
    y = [0.0, abs(v_n), 0.0, 1.0]
    for event in (deepest, out):
        y = solve_ivp(rhs, (0.0, 1e3), y, method="DOP853", rtol=1e-12, atol=1e-16, events=event).y_events[0][0]
    return float(y[3])


@pytest.mark.parametrize("variant", ["mindlin", "mindlin/force"])
@pytest.mark.parametrize("assembly", sorted(ASSEMBLIES))
def test_the_reference_meets_a_time_domain_integration(variant, assembly):
    # 1e-9: both at rtol 1e-12; measured agreement 3e-11 at worst
    model = ContactModel(tangential=variant, m=1.3, r=0.4, alpha=0.35, **ASSEMBLIES[assembly])
    for v_n in (-0.3, -1.2):
        exact = float(choose.omega_per_sphere(model, v_n)[0]) + 1.0
        assert exact == pytest.approx(_time_domain_ratio(model, v_n), abs=1e-9)


@pytest.mark.parametrize("variant", VARIANTS)
def test_the_reference_does_not_depend_on_where_it_changes_variable(variant, monkeypatch):
    # the switch between sigma and the time is a choice of the method, not of the answer
    key = mindlin.VARIANTS[variant]
    answers = []
    for switch in (0.3, 0.5, 0.8):
        monkeypatch.setattr(mindlin, "SWITCH", switch)
        mindlin._ratio.cache_clear()
        answers.append(float(mindlin.slip_ratio(4.3, 0.2, key, 1.5)))
    mindlin._ratio.cache_clear()
    assert np.ptp(answers) < 1e-11


def test_the_exact_solutions_it_finds():
    # lam = 1: h = x solves h'' = -sqrt(x) h (x'' = -x^(3/2)), so the history follows the overlap and
    # the slip leaves reversed; lam = 3/2 with a force history: w = x' solves w'' = -(3/2) sqrt(x) w.
    # The two variants without a rescale give the same ratio at every lam (found here, 1e-10)
    for variant in ("mindlin", "mindlin/force"):
        key = mindlin.VARIANTS[variant]
        assert float(mindlin.slip_ratio(1.0, 0.0, key, 1.5)) == pytest.approx(-1.0, abs=1e-11)
        assert float(mindlin.slip_ratio(1.5, 0.0, key, 1.5)) == pytest.approx(-1.0, abs=1e-11)
        assert float(mindlin.slip_ratio(1.25, 0.0, key, 1.5)) < -1.0  # between them the bounce gains energy
    lams = np.linspace(0.3, 20.0, 9)
    assert np.allclose(mindlin.slip_ratio(lams, 0.0, mindlin.VARIANTS["mindlin"], 1.5),
                       mindlin.slip_ratio(lams, 0.0, mindlin.VARIANTS["mindlin/force"], 1.5), atol=1e-10)


def test_the_hertzian_omega_is_the_same_at_every_speed():
    # the time-domain integration at three speeds, against the one scaled contact theory uses
    model = ContactModel(tangential="mindlin", **MATERIAL)
    one = model.Omega + 1.0
    for v_n in (-0.05, -0.7, -2.0):
        assert _time_domain_ratio(model, v_n) == pytest.approx(one, abs=1e-9)


def test_the_paper_s_magic_ratio_conserves_energy_at_every_speed():
    # k_t/kn = alpha/(1 + alpha) is lam = 1: Omega = -2 (the slip reverses) with the Hertzian force
    alpha = 0.4
    model = ContactModel(normal="hertz", kn=1.0e4, tangential="mindlin", mindlin_kt=1.0e4 * alpha / (1 + alpha))
    report = spinbounce.theory(**{k: getattr(model, k) for k in ("normal", "kn", "tangential", "mindlin_kt")})
    assert report["Omega"] == pytest.approx(-2.0, abs=1e-10) and report["energy"] == "conserved"
    # what was searched is said: lam up to 30, k_t/kn up to 30 alpha/(1 + alpha)
    assert report["energy_conserving_searched_to_k_t_over_kn"] == pytest.approx(30 * alpha / (1 + alpha), rel=1e-12)
    assert report["energy_conserving_k_t_over_kn"]["Omega = -2"][:2] == pytest.approx([alpha / 1.4, 1.5 * alpha / 1.4],
                                                                                     abs=1e-11)
    # the NULL stiffness of a material: k_t/kn = 3 (1 - nu)/(2 - nu) >= 1 > alpha/(1 + alpha) at alpha = 2/5
    report = spinbounce.theory(tangential="mindlin", **MATERIAL)
    assert report["k_t_over_kn"] == pytest.approx(3 * 0.7 / 1.7, rel=1e-14)
    assert report["energy_conserving_poisson_ratio"]["Omega = -2"] == []
    assert report["energy_conserving_poisson_ratio"]["Omega = 0"] == pytest.approx([-0.1, 0.25], abs=1e-10)


def test_the_null_stiffness_is_lammps_s_8_g_star():
    # G* = E/(4 (2 - nu)(1 + nu)) against a wall (mix_stiffnessG_wall): 8 G* = 2 E/((2 - nu)(1 + nu))
    model = ContactModel(tangential="mindlin_rescale", **MATERIAL)
    assert model.tangential_law.stiffness(model) == pytest.approx(2e4 / (1.7 * 1.3), rel=1e-15)


def test_the_deck_writes_null_or_the_stiffness():
    style = wall_parameters(ContactModel(tangential="mindlin/force", **MATERIAL))["style"]
    assert style == "granular hertz/material 10000.0 0.0 0.3 tangential mindlin/force NULL 0.0 1000000000000.0"
    style = wall_parameters(ContactModel(tangential="mindlin", mindlin_kt=7.5, gamma_n=0.0, gamma_t=0.2))["style"]
    assert style.startswith("granular hooke 10.0 ") and " tangential mindlin 7.5 " in style


def test_a_record_names_the_tangential_law_only_when_it_is_not_the_default():
    assert "tangential" not in ContactModel().as_record() and "mindlin_kt" not in ContactModel().as_record()
    record = ContactModel(tangential="mindlin", mindlin_kt=3.0).as_record()
    assert record["tangential"] == "mindlin" and record["mindlin_kt"] == 3.0 and "kt" not in record


@pytest.mark.parametrize("given, name", [
    ({"tangential": "mindlin"}, "mindlin_kt"),                                  # NULL needs a material
    ({"tangential": "mindlin", "mindlin_kt": 3.0, "kt": 2.0}, "kt"),            # linear_history's spring
    ({"mindlin_kt": 3.0}, "mindlin_kt"),                                        # not linear_history's
    ({"tangential": "mindlin", "mindlin_kt": -3.0}, "mindlin_kt"),
    ({"tangential": "mindlin", "mindlin_kt": 3.0, "wall": "classic"}, "tangential"),
    ({"tangential": "mindlin/forced"}, "tangential"),
])
def test_each_refusal_names_the_parameter(given, name):
    with pytest.raises(SceneError) as info:
        ContactModel(**given)
    assert info.value.parameter == name


def test_a_pair_with_a_mindlin_contact_has_no_planar_matrix():
    # the pair's exact references take it, capped or not (tests/test_pairs_nonlinear.py); the
    # planar theory has no closed form for it, and a cap has no matrix
    report = spinbounce.theory(scene="pair", tangential="mindlin", mindlin_kt=3.0)
    assert report["matrix"] is None and "contact radius" in report["why_no_matrix"]
    capped = spinbounce.theory(scene="pair", tangential="mindlin", mindlin_kt=3.0, mu=0.3)
    assert capped["matrix"] is None and "capped pair" in capped["why_no_matrix"]


def test_a_speed_dependent_mindlin_contact_has_a_matrix_per_speed():
    model = ContactModel(tangential="mindlin", mindlin_kt=700.0, kn=50.0)
    assert not choose.which(model).has_matrix
    omegas = choose.omega_per_sphere(model, [-0.3, -1.2])
    assert abs(omegas[0] - omegas[1]) > 0.1  # lam grows as sqrt(|v_n|) with the Hookean force
    with pytest.raises(SceneError):
        model.Omega


def _random_states(rng, n: int) -> np.ndarray:
    return np.column_stack([-rng.uniform(0.2, 1.5, n), rng.uniform(-1.0, 1.0, n), rng.uniform(-1.0, 1.0, n),
                            rng.uniform(-0.5, 0.5, n), rng.uniform(-0.5, 0.5, n), rng.uniform(-1.0, 1.0, n)])


@pytest.mark.lammps
@pytest.mark.parametrize("variant", VARIANTS)
@pytest.mark.parametrize("assembly", sorted(ASSEMBLIES))
@pytest.mark.parametrize("mu", [None, 0.3], ids=["uncapped", "capped"])
def test_lammps_at_the_default_step_meets_the_reference(variant, assembly, mu, tmp_path):
    # random 3-D states across stick and slip, each within the default accuracy (1e-4 of its
    # size) at the default step; with a cap the references are exact.contact_phases (planar, no
    # dashpot) and exact.oracle (the rest)
    rng = np.random.default_rng(sum(map(ord, variant + assembly)) + (mu is not None))
    states = _random_states(rng, 6)
    r = 0.45
    scene = Collision(ContactModel(tangential=variant, r=r, m=1.2, mu=mu, **ASSEMBLIES[assembly]),
                      v_n=states[:, 0], v_t=states[:, 1], omega=states[:, 2] / r, v_s=states[:, 3],
                      omega_s=states[:, 4] / r, omega_n=states[:, 5] / r)
    result = run_scene(scene, tmp_path, record=False)
    assert (result.table["status"] == "ok").all()
    assert result.table["error"].max() <= 1e-4


@pytest.mark.slow
@pytest.mark.lammps
@pytest.mark.parametrize("variant", VARIANTS)
@pytest.mark.parametrize("mu, state", [(None, (-0.8, 0.6, -0.3)), (0.3, (-1.0, 0.5, 0.0))],
                         ids=["uncapped", "capped"])
def test_converged_lammps_meets_the_reference(variant, mu, state, tmp_path):
    # dt halved until the change is below 1e-7 (the force variants converge at first order, so
    # their last run is some 1e-7 from the limit); the reference within 1e-6. The capped state
    # sticks, then slides (mu = 0.3, u'(0) = 0.5 against |v_n| = 1)
    model = ContactModel(tangential=variant, r=0.45, mu=mu, **MATERIAL)
    state = np.array(state)
    final = converged(model, state, tmp_path)
    assert np.abs(final - choose.predict(model, state[None, :])[0]).max() <= 1e-6


# --- with a Coulomb cap ---------------------------------------------------------------------

def test_a_slide_throughout_is_the_rigid_body_impulse():
    # |u'| large against mu |v_n|: the contact slides from first touch to the end, so the
    # tangential impulse is mu times the normal one, 2 mu m |v_n| (e = 1), whatever the spring
    for variant in VARIANTS:
        model = ContactModel(tangential=variant, mu=0.2, **MATERIAL)
        final = choose.predict(model, np.array([[-0.5, 1.5, -0.3]]))[0]
        impulse = 2 * 0.2 * 0.5
        assert final == pytest.approx([0.5, 1.5 - impulse, -0.3 - impulse / 0.4], abs=1e-10)


@pytest.mark.parametrize("variant", VARIANTS)
@pytest.mark.parametrize("assembly", sorted(ASSEMBLIES))
def test_a_cap_that_never_binds_gives_the_uncapped_reference(variant, assembly):
    # two integrations written apart (in time with events; in sqrt(delta) with no cap) of the same
    # contact. mu = 1e12 (what a deck writes for none) binds only where F_n vanishes, at the exit:
    # a displacement history's force vanishes there with a (measured 1e-12 apart), a force history
    # does not, and the last slide moves it by ~ mu^(-2/3) (1.9e-5, 1.9e-7, 1.9e-9 at mu = 1e6, 1e9,
    # 1e12, measured): 1e-8
    law = {k: v for k, v in ASSEMBLIES[assembly].items() if k != "gamma_t"}
    states = np.array([[-0.3, 0.8, -0.2], [-1.2, -0.4, 0.9]])
    capped = choose.predict(ContactModel(tangential=variant, mu=1e12, **law), states)
    assert capped == pytest.approx(choose.predict(ContactModel(tangential=variant, **law), states), abs=1e-8)


def test_mindlin_s_criterion_decides_the_first_phase():
    # against the Hertzian force, the contact starts sliding when k_t |u'(0)| (2/3 of it with a
    # force history) exceeds mu kn |v_n|, and sticking otherwise
    law = dict(m=1.0, r=0.5, alpha=0.4, K=100.0 * math.sqrt(0.5), power=1.5, k=50.0, mu=0.5)
    for force, threshold in ((False, 1.0), (True, 1.5)):  # u' at which k u' (2/3) = mu kn |v_n| = 50
        contact = contact_phases._Contact(contact_phases.Law(**law, force_history=force))
        assert contact.first_phase(1.0, 0.99 * threshold, 1.0)[0] == "stick"
        assert contact.first_phase(1.0, 1.01 * threshold, 1.0)[0] == "slip"


# --- the classic wall's spring inside granular: linear_history_classic ------------------------

CLASSIC = {"tangential": "linear_history_classic", "kt": 100.0, "kn": 50.0}


def test_the_classic_spring_is_mindlin_s_equations_without_a_cap():
    # this build's linear_history_classic: kt a on the displacement history (LAMMPS gives
    # bit-identical outcomes for the two), so without a cap the Mindlin reference answers
    states = np.array([[-0.3, 0.8, -0.2], [-1.2, -0.4, 0.9]])
    classic = choose.predict(ContactModel(**CLASSIC), states)
    mindlin_kt = {k: v for k, v in CLASSIC.items() if k != "kt"} | {"tangential": "mindlin", "mindlin_kt": 100.0}
    assert np.array_equal(classic, choose.predict(ContactModel(**mindlin_kt), states))


@pytest.mark.lammps
def test_the_capped_classic_spring_is_the_classic_wall(tmp_path):
    # with a cap its history resets by kt alone: the classic wall's theory (exact.classic), which
    # the classic wall itself (hooke/history, mass_velocity dashpots gamma/m) runs too
    model = ContactModel(mu=0.3, gamma_n=0.5, gamma_t=0.2, **CLASSIC)
    wall = ContactModel(wall="classic", mu=0.3, gamma_n=0.5, gamma_t=0.2, kt=100.0, kn=50.0)
    states = np.array([[-0.7, 0.5, 0.2], [-0.3, -0.4, 0.9]])
    assert np.array_equal(choose.predict(model, states), choose.predict(wall, states))
    result = run_scene(Collision(model, v_n=states[:, 0], v_t=states[:, 1], omega=states[:, 2] / 0.5), tmp_path,
                       record=False)
    assert (result.table["status"] == "ok").all() and result.table["error"].max() <= 1e-4


@pytest.mark.lammps
@pytest.mark.parametrize("law", [CLASSIC, {**CLASSIC, "normal": "hertz", "kn": 5000.0, "gamma_t": 0.3}])
def test_the_classic_spring_at_the_default_step_meets_the_reference(law, tmp_path):
    states = _random_states(np.random.default_rng(7), 6)
    scene = Collision(ContactModel(**law), v_n=states[:, 0], v_t=states[:, 1], omega=states[:, 2] / 0.5,
                      v_s=states[:, 3], omega_s=states[:, 4] / 0.5, omega_n=states[:, 5] / 0.5)
    result = run_scene(scene, tmp_path, record=False)
    assert (result.table["status"] == "ok").all() and result.table["error"].max() <= 1e-4


def test_the_capped_classic_spring_with_the_hertzian_force_has_the_oracle_s_reference():
    # once refused; now exact.oracle with the classic cap (tests/test_classic_cap.py, test_capped_nonlinear.py)
    model = ContactModel(tangential="linear_history_classic", normal="hertz", kn=5000.0, mu=0.3)
    assert choose.which(model).kind == "classic_wall"
    assert np.isfinite(choose.predict(model, np.array([[-1.0, 0.5, 0.1]]))).all()


def test_a_hookean_capped_contact_that_slides_almost_at_once_has_a_reference(tmp_path):
    # the cap mu kn v t outgrows the trial force k a u' t at first, for t* = (mu kn v/(k sqrt(r v) u'))^2:
    # far below a step here, it starts sliding (it once chattered at t = 0); LAMMPS agrees
    model = ContactModel(tangential="mindlin", mindlin_kt=20.0, mu=1e-4)
    scene = Collision(model, v_n=-1.0, v_t=-2.0, omega=1.0)
    result = run_scene(scene, tmp_path, record=False)
    assert (result.table["status"] == "ok").all() and result.table["error"].max() <= 1e-4


@pytest.mark.parametrize("given, name", [
    ({"normal": "hertz", "tangential": "mindlin", "mindlin_kt": 1e308}, "mindlin_kt"),
    ({"normal": "hertz", "tangential": "mindlin", "mindlin_kt": 5.0, "gamma_t": 1e5}, "gamma_t"),
])
def test_a_slip_beyond_the_reference_s_reach_is_refused_by_name(given, name):
    with pytest.raises(SceneError) as info:
        choose.predict(ContactModel(**given), np.array([[-0.5, 0.3, 0.0]]))
    assert info.value.parameter == name


def test_a_tolerance_sweep_of_a_spring_on_the_contact_radius_is_refused():
    from spinbounce.sweeps import SweepError, spec_from_dict

    with pytest.raises(SweepError, match="tolerance"):
        spec_from_dict({"tolerance": 1e-5, "states": {"n": 4, "v_n": [-1.0, -0.1], "v_t": [-1.0, 1.0],
                        "r_omega": [-1.0, 1.0]}, "model": {"tangential": "mindlin", "mindlin_kt": 20.0}})
