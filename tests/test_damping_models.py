"""LAMMPS's damping models mass_velocity, tsuji, coeff_restitution: dashpots, refusals, LAMMPS vs reference.

Each makes the paper's gamma_n and gamma_t from a coefficient LAMMPS scales by the contact
(spinbounce.laws.damping.scaled); with the Hookean force those dashpots are constant, so the
exact damped references (closed form, the Coulomb solver with a cap, the pair references in a
pair's effective mass) answer. The LAMMPS runs show it: at the default step every row is within the default accuracy
of the reference, and LAMMPS extrapolated to dt = 0 meets it to 1e-6, which dashpots off by a
part in a thousand could not do (they move the restitution by ~1e-4).
"""

import math

import numpy as np
import pytest

import spinbounce
from spinbounce.lammps.decks import wall_parameters
from spinbounce.model.contact import ContactModel
from spinbounce.model.parameters import SceneError
from spinbounce.pipeline import run_scene
from spinbounce.scenes.collision import Collision
from spinbounce.scenes.two_walls import TwoWalls, run_two_walls, theory_path

LAWS = {
    "mass_velocity": {"gamma_n_per_mass": 0.8, "x_t": 0.7},
    "tsuji": {"e_n": 0.5, "x_t": 0.5},
    "coeff_restitution": {"e_n": 0.3, "x_t": 1.2},
}


def damped(name: str, **kw) -> ContactModel:
    return ContactModel(damping=name, **LAWS[name], **kw)


def test_the_dashpots_are_lammps_prefactors():
    # by hand, m = 2, kn = 10: mass_velocity gamma_n = 0.8 * 2; coeff_restitution
    # 2 beta sqrt(m kn) with beta = -ln e / sqrt(pi^2 + ln^2 e); tsuji Marshall's polynomial at
    # e = 0.5 (0.340894...) times sqrt(m kn), with no sqrt(2) in this build
    assert damped("mass_velocity", m=2.0).gamma_n == pytest.approx(1.6, rel=1e-15)
    log_e = math.log(0.3)
    beta = -log_e / math.sqrt(math.pi**2 + log_e**2)
    assert damped("coeff_restitution", m=2.0).gamma_n == pytest.approx(2 * beta * math.sqrt(20.0), rel=1e-14)
    poly = 1.2728 - 4.2783 / 2 + 11.087 / 4 - 22.348 / 8 + 27.467 / 16 - 18.022 / 32 + 4.8218 / 64
    assert damped("tsuji", m=2.0).gamma_n == pytest.approx(poly * math.sqrt(20.0), rel=1e-14)
    for name in LAWS:
        model = damped(name)
        assert model.gamma_t == pytest.approx(LAWS[name]["x_t"] * model.gamma_n, rel=1e-15)


def test_coeff_restitution_gives_its_restitution_exactly_with_hooke():
    for e in (0.05, 0.3, 0.9, 1.0):
        assert ContactModel(damping="coeff_restitution", e_n=e).restitution == pytest.approx(e, rel=1e-12)


def test_the_deck_gives_the_coefficient_and_the_keyword():
    style = wall_parameters(damped("tsuji", kt=2.0))["style"]
    assert style.startswith("granular hooke 10.0 0.5 damping tsuji tangential linear_history 2.0 0.5 ")


def test_a_record_names_the_damping_only_when_it_is_not_the_default():
    # digests, run folders and stored references of velocity-damped models are unchanged
    assert "damping" not in ContactModel().as_record() and "x_t" not in ContactModel().as_record()
    record = damped("tsuji").as_record()
    assert record["damping"] == "tsuji" and record["e_n"] == 0.5 and "gamma_n" not in record


def test_a_copy_derives_the_dashpots_anew():
    model = damped("coeff_restitution")
    assert model.replace(e_n=0.6).restitution == pytest.approx(0.6, rel=1e-12)
    assert model.replace(kt=3.0).gamma_n == model.gamma_n
    assert ContactModel(**{f: getattr(model, f) for f in model.__dataclass_fields__}) == model  # from its columns


@pytest.mark.parametrize("given, name", [
    ({"damping": "tsuji"}, "e_n"),                                                     # its coefficient is needed
    ({"x_t": 0.5}, "x_t"),                                                             # velocity takes gamma_t
    ({"damping": "tsuji", "e_n": 0.5, "gamma_n": 0.3}, "gamma_n"),                   # made from e_n
    ({"damping": "tsuji", "e_n": 0.5, "gamma_n_per_mass": 1.0}, "gamma_n_per_mass"),  # mass_velocity's
    ({"damping": "coeff_restitution", "e_n": 0.0}, "e_n"),
    ({"damping": "coeff_restitution", "e_n": 1.5}, "e_n"),
    ({"damping": "mass_velocity", "gamma_n_per_mass": 100.0}, "gamma_n_per_mass"),   # over critical
    ({"damping": "tsuji", "e_n": 0.5, "wall": "classic"}, "damping"),                 # a fixed assembly
    ({"damping": "viscous"}, "damping"),
])
def test_each_refusal_names_the_parameter(given, name):
    with pytest.raises(SceneError) as info:
        ContactModel(**given)
    assert info.value.parameter == name


def test_the_default_step_refuses_a_creeping_exit_by_the_coefficient_given():
    # e_n = 1e-3 is the declared limit and runs; a dashpot that leaves at 8e-5 of the speed is
    # refused naming gamma_n_per_mass, the number the user typed, not the gamma_n it made
    damped("coeff_restitution").replace(e_n=1e-3).check_default_step()
    with pytest.raises(SceneError) as info:
        damped("mass_velocity").replace(gamma_n_per_mass=6.0).check_default_step()
    assert info.value.parameter == "gamma_n_per_mass"


def test_a_pair_takes_the_dashpots_of_its_effective_mass():
    # LAMMPS scales ETA_N by the pair's m_eff = m m_b/(m + m_b): here 1 * 3/4
    from spinbounce.scenes.pair.kind import pair_contact, sphere_b

    contact = pair_contact(damped("mass_velocity"), sphere_b(m_b=3.0))
    assert contact.gamma_n == pytest.approx(0.8 * 0.75, rel=1e-15)
    assert contact.gamma_t == pytest.approx(0.7 * 0.8 * 0.75, rel=1e-15)


def test_a_capped_pair_takes_tangential_damping_by_its_coefficient():
    # the capped pair reference with the tangential dashpot x_t eta_n: no matrix, an outcome that the
    # dashpot changes (the first trial force, 0.5 |u'| against the cap 0.3 |v_n|, is 1.67 times it)
    def outcome(x_t):
        return spinbounce.theory(v_n=-1.0, v_t=1.0, scene="pair", damping="tsuji", e_n=0.5, x_t=x_t, mu=0.3)

    assert spinbounce.theory(scene="pair", damping="tsuji", e_n=0.5, x_t=0.5, mu=0.3)["matrix"] is None
    assert abs(outcome(0.5)["theory"]["v_t"] - outcome(0.0)["theory"]["v_t"]) > 1e-3


def _random_states(rng, n: int) -> np.ndarray:
    return np.column_stack([-rng.uniform(0.2, 1.5, n), rng.uniform(-1.0, 1.0, n), rng.uniform(-2.0, 2.0, n)])


@pytest.mark.lammps
@pytest.mark.parametrize("name", sorted(LAWS))
@pytest.mark.parametrize("mu", [None, 0.3])
def test_lammps_at_the_default_step_meets_the_reference(name, mu, tmp_path):
    # the default step is probed for the default accuracy, 1e-4 of each state's size
    states = _random_states(np.random.default_rng(sum(map(ord, name))), 8)
    scene = Collision(damped(name, m=1.7, mu=mu), v_n=states[:, 0], v_t=states[:, 1], omega=states[:, 2] / 0.5)
    result = run_scene(scene, tmp_path, record=False)
    assert (result.table["status"] == "ok").all()
    assert result.table["error"].max() <= 1e-4


@pytest.mark.lammps
@pytest.mark.parametrize("name", sorted(LAWS))
def test_lammps_extrapolated_to_dt_zero_meets_the_reference(name, tmp_path):
    # Richardson extrapolation of LAMMPS's own runs (spinbounce.extrapolation) to 1e-6; the
    # extrapolated state meets the exact reference within its estimate and 1e-6
    report = spinbounce.collide(-0.9, 0.6, 1.4, m=1.3, damping=name, **LAWS[name], tolerance=1e-6, out=tmp_path / "t")
    assert report.record["estimate"] <= 1e-6
    assert np.abs(report.table["error"]).max() <= 1e-6


@pytest.mark.lammps
def test_two_walls_run_the_damping_asked_for(tmp_path):
    # the two-wall deck writes the same wall words as the collision deck (it once wrote
    # "damping velocity" with e_n as its ETA_N: v_n 0.861 where the theory said 0.300). At its
    # 1000 steps per half-period, first order in the dashpots, two bounces measured 8.4e-5
    model = damped("coeff_restitution")
    scene = TwoWalls((model,), [[-1.0, 0.5, 0.0]], bounces=2)
    states = run_two_walls(scene, tmp_path).states
    expected = theory_path(model, scene.initial, 2)
    assert np.abs(states.reshape(expected.shape) - expected).max() <= 5e-4


@pytest.mark.lammps
def test_a_sweep_resumed_across_the_new_columns_still_fits(tmp_path):
    # a velocity sweep begun before these parameters existed has chunks without their columns;
    # its digest is unchanged, so it resumes, and the fit groups on the columns every chunk has
    import pandas as pd

    from spinbounce.fitting_stream import fit_dataset

    spinbounce.sweep(n=20, out=tmp_path / "sweep")
    rows = pd.concat(pd.read_parquet(f) for f in sorted((tmp_path / "sweep").rglob("*.parquet")))
    rows.iloc[:8].to_parquet(tmp_path / "new.parquet")
    rows.iloc[8:].drop(columns=["damping", "e_n", "x_t", "gamma_n_per_mass"]).to_parquet(tmp_path / "old.parquet")
    (group,) = fit_dataset([tmp_path / "new.parquet", tmp_path / "old.parquet"])
    assert group["n"] == 20


@pytest.mark.lammps
@pytest.mark.parametrize("name", sorted(LAWS))
@pytest.mark.parametrize("mu", [None, 0.3])
def test_a_pair_sweep_meets_the_pair_reference(name, mu, tmp_path):
    # an aligned pair batch runs each pair in its own time units, the dashpot's ETA_N scaled
    # by each class's scale to the law's power (velocity 1, mass_velocity -1, a restitution 0):
    # every row within the default accuracy of the exact pair reference, b heavier than a
    coefficients = {**LAWS[name], **({"x_t": None} if mu is not None else {})}  # capped: no gamma_t
    rows = spinbounce.sweep(n=12, out=tmp_path / "sweep", scene="pair", m_b=1.9, damping=name, mu=mu,
                            **coefficients)
    assert (rows["status"] == "ok").all()
    assert rows["error"].max() <= 1e-4


@pytest.mark.parametrize("name", ["velocity", *sorted(LAWS)])
def test_eta_n_follows_a_time_scale_by_the_laws_power(name):
    # a pair run s times slower (masses s^2, speeds 1/s) needs the dashpot s gamma_n; the deck
    # gets it by writing ETA_N s^power: check it with each law's own prefactor (checked against
    # LAMMPS above) at s = 1.7, where a wrong power is off by a factor 1.7 or more
    model = ContactModel(gamma_n=0.4, gamma_t=0.2) if name == "velocity" else damped(name)
    law, s, m_eff = model.damping_law, 1.7, 0.6
    coefficient = law.normal_coefficient
    slower = model.replace(m=model.m * s**2, **{coefficient: getattr(model, coefficient) * s**law.eta_time_power})
    assert law.contact_dashpots(slower, m_eff * s**2)[0] == pytest.approx(s * law.contact_dashpots(model, m_eff)[0],
                                                                          rel=1e-14)


def test_a_contact_its_normal_dashpot_holds_closed_is_refused_by_its_v_n_not_followed_for_ever():
    """Hertz's force vanishes at the surface as delta^1.5 while damping velocity's dashpot does not: a slow enough
    impact never leaves (the overlap creeps towards zero; LAMMPS's sphere at v_n = -0.16, gamma_n = 2 was still
    3e-5 deep after 200,000 steps). The wall's reference followed that creep without end (a collide ran for minutes)
    and the pair's failed mid-sweep; both now refuse the state by its v_n at once, a pair sweep before it starts."""
    from spinbounce.sweeps import SweepError, spec_from_dict

    with pytest.raises(SceneError, match="the contact does not end") as refused:
        Collision(ContactModel(normal="hertz", gamma_n=2.0), v_n=-0.16, v_t=0.0, omega=0.0)
    assert refused.value.parameter == "v_n" and refused.value.value == -0.16
    with pytest.raises(SceneError, match="the contact does not end"):
        spinbounce.collide(scene="pair", normal="hertz", gamma_n=1.0, v_n=-0.16, v_t=0.0, omega=0.0, out=None)
    states = {"n": 300, "v_n": [-0.8, -0.1], "v_t": [-2, 2], "r_omega": [-2, 2]}
    with pytest.raises(SweepError, match="states.v_n: v_n = -0.1: the contact does not end"):
        spec_from_dict({"model": {"scene": "pair", "normal": "hertz", "gamma_n": 1.0}, "states": states})
    # limit_damping cuts the tensile dashpot: the same impact ends; a dashpot that fades with the contact
    # (viscoelastic's, a^1 against Hertz's delta^1.5) cannot hold it, however strong: a slow exit, not a refusal
    assert Collision(ContactModel(normal="hertz", gamma_n=2.0, limit_damping=True), v_n=-0.16).nsteps > 0
    fading = ContactModel(normal="hertz", damping="viscoelastic", gamma_n_per_mass_radius=50.0)
    assert Collision(fading, v_n=-0.2).nsteps > Collision(fading.replace(gamma_n_per_mass_radius=5.0), v_n=-0.2).nsteps


def test_the_pair_reference_itself_refuses_a_held_contact_rather_than_answer_past_its_window():
    """The pair reference alone (a batch checks its equivalent wall at its fastest pair only): its tails stall
    again and again as the overlap creeps (t = 0.95, 4.1, 12.8, then past the window); it once restarted past
    the window, integrated backwards in time and answered spheres approaching after 40 time units."""
    from spinbounce.errors import ContactHeld
    from spinbounce.exact import pair_exact

    pair = dict(n=(0.0, 0.0, 1.0), v_a=(0.0, 0.0, -0.17), v_b=(0.0, 0.0, 0.0), w_a=(0.0, 0.0, 0.0),
                w_b=(0.0, 0.0, 0.0), m_a=1.0, r_a=0.5, alpha_a=0.4, m_b=1.0, r_b=0.5, alpha_b=0.4, kn=10.0, kt=0.0)
    with pytest.raises(ContactHeld, match="the contact does not end"):
        pair_exact.solve(**pair, gamma_n=1.0, **{**pair_exact.HERTZ_MINDLIN, "damping_power": 0.0})
    ended = pair_exact.solve(**pair, gamma_n=1.0, tensile=False, **{**pair_exact.HERTZ_MINDLIN, "damping_power": 0.0})
    assert ended.v_a[2] - ended.v_b[2] > 0.0 and ended.contact_time < 10.0  # limit_damping: they part
