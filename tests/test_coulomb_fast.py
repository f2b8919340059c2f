"""The closed-form Coulomb solver (exact.coulomb) against the scipy oracle and closed forms.

Tolerances, in units of the impact speed |v|:
* against the oracle, 1e-9 in the plane and 1e-8 with the Hertzian force (the acceptance
  line). The solver is exact to rounding; the oracle integrates at rtol 1e-12 and locates
  its switches as events. Measured with studies.solver_speed.agreement: 10,000 random
  cases in the plane (seed 2026, the oracle's defaults) worst 1.2e-11, median 7e-16, none
  refused; 1,000 Hertzian (seed 2027, rtol 1e-13) worst 1.1e-10, median 2.4e-13, none
  refused. Before the oracle's event handling was made robust, 10 of the 10,000 plane
  cases exceeded 1e-9 (up to 1.8e-5) and 1 was refused as chattering, as were 46 of the
  1,000 Hertzian ones (each kind is a named regression case below). Each plane failure
  was the oracle's error: a brute-force integration (the exact sticking propagator over up to
  1.28 million fixed steps per contact, the trial force projected onto the cap, the
  turn of the normal force a grid point, no event logic) converges to the solver;
* against closed forms (gross slip, the rough sphere at the magic ratio), 1e-12: both
  sides are exact there, and the solver's only error is rounding in a few dozen
  operations on numbers of order one (its switching functions must also pass 1e-13 of
  their scale below zero to count, which moves no outcome by more than that).
"""

import math
import warnings

import numpy as np
import pytest

from spinbounce import exact
from spinbounce.model.contact import ContactModel
from spinbounce.errors import PhysicsWarning
from spinbounce.studies.solver_speed import agreement
from spinbounce.exact import coulomb, oracle, rigid_body

ORACLE_TOLERANCE = 1e-9
#: the acceptance line in 3-D and with the Hertzian force
ORACLE_TOLERANCE_3D = 1e-8
EXACT_TOLERANCE = 1e-12


def _against_oracle(model, states):
    """Largest deviation from the oracle over the states, per unit impact speed; and the
    oracle's regime patterns."""
    states = np.asarray(states, dtype=float)
    fast = coulomb.bounce_2d(model, *states.T)
    results = [oracle.bounce(model, *s) for s in states]
    slow = np.array([r.final[:3] for r in results])
    speed = np.hypot(states[:, 0], states[:, 1])
    return (np.abs(fast - slow).max(axis=1) / speed).max(), [r.pattern for r in results]


@pytest.mark.slow  # ten seconds of the oracle; the quick run keeps tests/test_coulomb.py's cases
@pytest.mark.parametrize("kind, n", [("2-D", 300), ("Hertz", 100)])
def test_random_models_and_states_agree_with_the_oracle(kind, n):
    # the acceptance sample's kind (studies.solver_speed.random_case), a fresh seed:
    # mu log-uniform on [1e-3, 1e3], damping from none to over-critical (tangential),
    # limit_damping on and off, kt/kn from 0.05 to 2, alpha from 0.1 to 1, incidence
    # from head-on to 89 degrees, spin from none to 30 |v|
    row = agreement(n, 7, kind)
    assert row["refused"] == 0
    assert row["worst"] < row["tolerance"], (kind, row["worst_case"])


#: name -> (the model's parameters, state (v_n, v_t, omega)): the random cases (seed 2026
#: of studies.solver_speed.random_cases, the number in the name) where the oracle was wrong,
#: by the brute-force integration of the module's docstring, named by what it got wrong
ORACLE_REGRESSIONS = {
    # a scipy event is the root of its function over the step: a function held at zero past
    # the exit (F_n clamped) handed it the step's end, hiding the normal force's turn
    # just before the exit, and the tensile slide after it (4e-8 to 2e-6)
    "turn before the exit hidden (6432)": (
        {"kt": 20.0, "alpha": 0.1, "gamma_n": 0.0031747696955334525, "mu": 0.014569101033041132},
        (-0.019882729884448586, 0.5347895349495696, -0.013752224484918233)),
    "turn before the exit hidden (7409)": (
        {"kt": 0.5, "alpha": 0.4, "gamma_n": 0.005494322076866516, "gamma_t": 0.6292150020636141,
         "mu": 84.97251536890445},
        (-0.15287550715647738, 1.5420158056270736, 56.79694980406359)),
    "turn before the exit hidden (9277)": (
        {"kt": 2.8571428571428568, "alpha": 1.0, "gamma_n": 0.0011863940536455636,
         "gamma_t": 2.461582596156527, "mu": 0.0037006382694959004},
        (-0.1961957521073117, 0.2738237957870437, -0.41409361103627335)),
    # |A| against a cap clamped at zero past the turn has a second root there: the root
    # search took it, and the short slide before the turn was missed (1.4e-7)
    "slide just before the turn missed (5881)": (
        {"kt": 2.8571428571428568, "alpha": 0.6666666666666666, "gamma_n": 2.012918052850979,
         "gamma_t": 1.4620972312686493, "mu": 1.839342506156155},
        (-0.38203013912011935, 0.12301730956580076, -0.0149520595664789)),
    # a step straddling the turn integrated the kink of a clamped cap or normal force
    # (1e-9 to 2e-8)
    "slide into the turn (2105)": (
        {"kt": 5.0, "alpha": 0.1, "gamma_n": 2.0146781031429404, "gamma_t": 0.7409263565828628,
         "mu": 362.8062136232693},
        (-0.30221379953664335, 0.23167787778894372, -16.885827915660393)),
    "slide into the turn (5904)": (
        {"kt": 10.0, "alpha": 0.6666666666666666, "gamma_n": 4.2946317574222554,
         "gamma_t": 3.4490797773184116, "mu": 185.16654067031118},
        (-1.8876825304782936, 0.4169805548206736, 12.121082552553034)),
    "gross slip through the turn (6061)": (
        {"kt": 20.0, "alpha": 0.25, "gamma_n": 0.45306567017790106, "gamma_t": 1.235635763792998,
         "mu": 0.014742158841432991},
        (-0.601815694338184, 1.789516474645945, 4.19113526620702)),
    "limit_damping's end of force (283)": (
        {"kt": 20.0, "alpha": 1.0, "gamma_n": 0.463363059776869, "mu": 0.14963653047416497,
         "limit_damping": True},
        (-0.1183161628261822, 0.03556076499656335, 0.02149262042054772)),
    "limit_damping's end of force (8230)": (
        {"kt": 20.0, "alpha": 1.0, "gamma_n": 2.6989350046488245, "gamma_t": 11.113238974551317,
         "mu": 28.698401474832618, "limit_damping": True},
        (-0.6144339411678096, 0.6007830971130652, -0.2644053014440863)),
    # a stick begun on the cap at a tangency was left at once (rounding put |A| a hair
    # over the cap), and the slide that followed ran with the contact pushing inwards (1.8e-5)
    "zero-length stick between slides (574)": (
        {"kt": 20.0, "alpha": 0.4, "gamma_n": 3.8993844775310724, "mu": 26.06686999338582},
        (-0.4443956525483975, 0.8106090551970458, 1.8111741239339734)),
    # the same at every stick -> slip switch of a stick-slip oscillation: refused
    "stick-slip refused as chattering (3993)": (
        {"kt": 20.0, "alpha": 0.1, "gamma_n": 6.10661602496008, "mu": 18.739713193147146},
        (-0.13387272617645035, 0.9391218502341084, 0.0)),
    # Hertzian cases (seed 2027 of random_cases(..., "hertz")) refused as chattering
    "Hertz slip-stick refused as chattering (8)": (
        {"normal": "hertz", "kt": 2.8571428571428568, "alpha": 0.4, "gamma_t": 1.2982656704843512,
         "mu": 1.9525127555153192},
        (-1.4894553320066453, 0.6238671930421212, -10.238185108529983)),
    "Hertz slip-stick refused as chattering (10)": (
        {"normal": "hertz", "kt": 0.5, "alpha": 0.4, "mu": 1.2764603935077736,
         "limit_damping": True},
        (-1.0710840724788102, 0.149111374358191, -12.661427100608638)),
}


@pytest.mark.parametrize("name", list(ORACLE_REGRESSIONS))
@pytest.mark.parametrize("tolerances", [(1e-12, 1e-14), (1e-13, 1e-16)], ids=["default", "tight"])
def test_cases_the_oracle_once_got_wrong(name, tolerances, monkeypatch):
    # found at the tight setting; where its steps fall decides whether a bug bites, so both
    monkeypatch.setattr(oracle, "RTOL", tolerances[0])
    monkeypatch.setattr(oracle, "ATOL", tolerances[1])
    kw, state = ORACLE_REGRESSIONS[name]
    with warnings.catch_warnings():  # alpha = 1 is a thin shell's inertia, on purpose
        warnings.simplefilter("ignore", PhysicsWarning)
        model = ContactModel(kn=10.0, **kw)
    tolerance = ORACLE_TOLERANCE_3D if kw.get("normal") == "hertz" else ORACLE_TOLERANCE
    assert _against_oracle(model, [state])[0] < tolerance


#: name -> (model, states, the oracle's regime pattern for every state)
REGIMES = {
    "never sliding (magic ratio)": ({"kt": 8.0 / 3.0, "alpha": 0.5, "kn": 8.0, "mu": 0.5},
                                    [(-1.0, 0.5, 0.0), (-0.7, 0.2, 1.6)], "stick"),
    "gross slip": ({"mu": 0.02}, [(-1.0, 0.5, -60.0), (-0.6, 2.0, 40.0)], "slip"),
    "stick-slip": ({"mu": 1.0, "kt": 4.0, "alpha": 0.1, "gamma_t": 0.2},
                   [(-1.0, 0.2, -5.0), (-1.0, 1.0, 3.0)], "stick-slip"),
    "slip-stick-slip": ({"kt": 8.0, "mu": 0.1}, [(-1.0, 0.3, 0.0)], "slip-stick-slip"),
    "ends sticking (tensile damping)": ({"mu": 0.5, "gamma_n": 2.0},
                                        [(-1.0, 0.3, 0.0), (-1.0, 1.5, 0.0)], "stick-slip-stick"),
    "tensile turn": ({"kt": 8.0, "mu": 0.1, "gamma_n": 1.5}, [(-1.0, 0.3, 0.0)],
                     "stick-slip-stick-slip"),
    "limit_damping": ({"kt": 8.0, "mu": 0.1, "gamma_n": 1.5, "limit_damping": True},
                      [(-1.0, 0.3, 0.0), (-1.0, 1.0, 0.0)], None),
    "overdamped slip": ({"mu": 0.3, "gamma_t": 3.0, "gamma_n": 1.0}, [(-1.0, 0.4, 2.0)], None),
}


@pytest.mark.parametrize("name", list(REGIMES))
def test_each_regime_agrees_with_the_oracle(name):
    kw, states, pattern = REGIMES[name]
    deviation, patterns = _against_oracle(ContactModel(**kw), states)
    if pattern is not None:  # the case is the regime it is named after
        assert set(patterns) == {pattern}
    assert deviation < ORACLE_TOLERANCE


def test_a_slide_that_reverses_agrees_with_the_oracle():
    # stiff tangential spring: the contact slides, sticks, and leaves sliding the other way
    model = ContactModel(kt=8.0, mu=0.1)
    state = (-1.0, 0.3, 0.0)
    final = coulomb.bounce_2d(model, *state)[0]
    assert final[1] + final[2] < 0.0 < state[1]
    assert _against_oracle(model, [state])[0] < ORACLE_TOLERANCE


def test_one_batch_holds_many_regimes_at_once():
    # spheres in one batch go through different switches at different times
    model = ContactModel(kt=8.0, mu=0.1, gamma_n=1.5)
    states = [(-1.0, v_t, w) for v_t in np.linspace(-1.5, 1.5, 9) for w in (-4.0, 0.0, 2.0)]
    deviation, patterns = _against_oracle(model, states)
    assert len(set(patterns)) >= 3
    assert deviation < ORACLE_TOLERANCE


# -- closed forms ---------------------------------------------------------------------

@pytest.mark.parametrize("kw", [{}, {"kt": 8.0}, {"gamma_t": 0.5}, {"alpha": 0.1, "kt": 3.0}])
def test_gross_slip_is_the_rigid_body_impulse(kw):
    # sliding throughout in one direction: impulse mu (1 + e) m |v_n| against the slip
    model = ContactModel(mu=0.02, **kw)
    states = [(-1.0, 0.5, -60.0), (-0.6, 2.0, 40.0), (-1.2, -1.0, 50.0), (-0.3, 1.0, 10.0)]
    got = coulomb.bounce_2d(model, *np.transpose(states))
    closed = np.array([rigid_body.gross_slip(model, *s, model.restitution) for s in states])
    assert np.abs(got - closed).max() < EXACT_TOLERANCE


def test_gross_slip_through_a_tensile_turn_takes_mu_times_the_absolute_normal_impulse():
    # the cap is mu |F_n|: once F_n turns tensile (at collision_time(tensile=False)) the
    # friction impulse keeps its direction while the normal impulse changes sign, so the
    # friction impulse is mu m (|v_n| - 2 x'(t_turn) + x'(t_exit)), x' the overlap rate of
    # the damped oscillator; gamma_t |u'| > mu gamma_n |v_n| makes the slide start at once
    model = ContactModel(mu=0.02, gamma_n=1.0, gamma_t=0.5)
    beta = model.gamma_n / (2.0 * model.m)
    omega_d = math.sqrt(model.kn / model.m - beta**2)

    def overlap_rate(t, speed):
        phase = omega_d * t
        return speed * math.exp(-beta * t) * (math.cos(phase) - beta / omega_d * math.sin(phase))

    t_turn = exact.collision_time(model.m, model.kn, model.gamma_n, tensile=False)
    for v_n, v_t, omega in [(-1.0, 0.5, -60.0), (-0.6, 2.0, 40.0), (-1.2, -1.0, 50.0)]:
        speed = -v_n
        impulse = model.mu * model.m * (speed - 2.0 * overlap_rate(t_turn, speed)
                                        + overlap_rate(math.pi / omega_d, speed))
        dv_t = -impulse / model.m * math.copysign(1.0, v_t + model.r * omega)
        closed = [model.restitution * speed, v_t + dv_t, model.r * omega + dv_t / model.alpha]
        assert np.abs(coulomb.bounce_2d(model, v_n, v_t, omega)[0] - closed).max() < EXACT_TOLERANCE


@pytest.mark.parametrize("alpha", [0.4, 0.25, 0.5])
def test_no_slip_at_the_magic_ratio_is_the_rough_sphere(alpha):
    # kt/kn = alpha/(1 + alpha): slip and overlap stay in proportion, so a contact that
    # sticks at first touch (kt |u'| < mu kn |v_n|) sticks to the end: Eq. 20
    model = ContactModel(kt=10.0 * exact.magic_kt_over_kn(alpha), alpha=alpha, mu=0.8)
    states = np.array([(-1.0, 0.5, 0.0), (-0.7, 0.2, 0.8), (-1.2, -1.0, -1.0), (-0.5, 0.0, 1.5)])
    assert np.all(model.kt * np.abs(states[:, 1] + model.r * states[:, 2])
                  < model.mu * model.kn * np.abs(states[:, 0]))
    got = coulomb.bounce_2d(model, *states.T)
    rough = (exact.rough_matrix(alpha) @ (states * [1.0, 1.0, model.r]).T).T
    assert np.abs(got - rough).max() < EXACT_TOLERANCE


@pytest.mark.parametrize("kw", [{}, {"gamma_n": 1.0, "limit_damping": True},
                                {"kt": 4.0, "alpha": 0.1}])
def test_a_huge_mu_is_the_uncapped_theory(kw):
    # the cap only acts in a final slide of ~ |A| / (mu |dF_n/dt|): an O(1/mu) deviation,
    # ~1e-8 at mu = 1e8 (as for the oracle, test_coulomb.py)
    model = ContactModel(mu=1e8, **kw)
    states = np.array([(-1.0, 0.5, 0.0), (-0.7, 0.2, 0.8), (-1.2, -1.0, -3.0)])
    exact = (ContactModel(**kw).matrix() @ (states * [1.0, 1.0, model.r]).T).T
    assert np.abs(coulomb.bounce_2d(model, *states.T) - exact).max() < 1e-7


# -- exact ties -----------------------------------------------------------------------

def _continuous(model, state, vary, step=1e-9):
    """The outcome at a tie, and its largest jump against states 'step' to either side."""
    at = coulomb.bounce_2d(model, *state)[0]
    sides = [coulomb.bounce_2d(model, *vary(sign * step))[0] for sign in (-1.0, 1.0)]
    return at, max(np.abs(side - at).max() for side in sides)


def test_tie_mu_exactly_at_the_first_touch_threshold():
    # kt |u'| = mu kn |v_n| exactly (1 = 1 in binary): sticking and sliding start alike
    model = ContactModel(kn=8.0, kt=2.0, mu=0.125)
    state = (-1.0, 0.5, 0.0)
    at, jump = _continuous(model, state, lambda d: (-1.0, 0.5 + d, 0.0))
    assert jump < 1e-8  # the outcome is Lipschitz in the state: no jump at the tie
    assert _against_oracle(model, [state])[0] < ORACLE_TOLERANCE


def test_tie_riding_the_cap_from_first_touch_to_exit():
    # the magic ratio (kt/kn = 1/4 at alpha = 1/3) with kt |u'| = mu kn |v_n| exactly: the
    # trial force equals the cap all through the contact, where sticking and sliding are
    # the same motion; the outcome is the rough sphere's (Eq. 20) and nothing chatters
    model = ContactModel(kn=8.0, kt=2.0, alpha=1.0 / 3.0, mu=0.125)
    state = np.array([-1.0, 0.5, 0.0])
    rough = exact.rough_matrix(model.alpha) @ state
    assert np.abs(coulomb.bounce_2d(model, *state)[0] - rough).max() < EXACT_TOLERANCE


def test_tie_a_slide_meets_the_sticking_condition_at_the_exit():
    # m = 1, alpha = 1/4 (s = 5), kt = 4, kn = 10, mu = 1/8, |v_n| = 1: a slide from first
    # touch has g(t) = kt u'(0) - kt s mu (1 - x'(t)) - mu kn x'(t), falling to zero exactly
    # at the exit (x' = -1) when u'(0) = 2 s mu - mu kn / kt = 0.9375: the slide reverses
    # and would stick at the instant the contact ends; the outcome is still gross slip
    model = ContactModel(kn=10.0, kt=4.0, alpha=0.25, mu=0.125)
    state = (-1.0, 0.9375, 0.0)
    at, jump = _continuous(model, state, lambda d: (-1.0, 0.9375 + d, 0.0))
    assert np.abs(at - rigid_body.gross_slip(model, *state, 1.0)).max() < EXACT_TOLERANCE
    assert at[1] + at[2] < 0.0  # reversed
    assert jump < 1e-8


def test_tie_no_slip_at_the_tensile_turn():
    # u' = 0 with tensile damping: the cap passes through zero at the turn with nothing to
    # hold; the sphere leaves exactly as it came in, tangentially
    model = ContactModel(mu=0.3, gamma_n=1.0, gamma_t=0.5)
    got = coulomb.bounce_2d(model, -1.0, 0.4, -0.8)[0]  # v_t + r omega = 0
    assert np.abs(got[1:] - [0.4, -0.4]).max() < EXACT_TOLERANCE
    assert math.isclose(got[0], model.restitution, rel_tol=1e-14)


# -- the Hertzian normal force ------------------------------------------------------------

HERTZ_STATES = [(-0.2, 0.5, 0.0), (-1.0, 1.5, -2.0), (-1.8, -0.4, 3.0), (-0.6, 0.1, -4.0),
                (-1.3, 2.0, 6.0)]


@pytest.mark.parametrize("kw", [{"mu": 0.1}, {"mu": 0.1, "kt": 8.0}, {"mu": 0.02},
                                {"mu": 0.3, "gamma_t": 2.0, "kn": 100.0}])
def test_hertz_agrees_with_the_oracle(kw):
    # the Hertzian overlap is exact (an inverse incomplete beta function), so the solver is
    # exact to rounding here too; 1e-8 is the acceptance line for the Hertzian contact
    deviation, _ = _against_oracle(ContactModel(normal="hertz", **kw), HERTZ_STATES)
    assert deviation < 1e-8


def test_hertz_gross_slip_is_the_rigid_body_impulse():
    # the friction impulse mu (1 + e) m |v_n| holds for any normal law (e = 1 here)
    model = ContactModel(normal="hertz", mu=0.02)
    states = [(-1.0, 0.5, -60.0), (-0.6, 2.0, 40.0), (-1.9, -1.0, 50.0), (-0.1, 1.0, 10.0)]
    got = coulomb.bounce_2d(model, *np.transpose(states))
    closed = np.array([rigid_body.gross_slip(model, *s, 1.0) for s in states])
    assert np.abs(got - closed).max() < EXACT_TOLERANCE


def test_hertz_approaches_the_uncapped_theory_as_mu_to_the_minus_two_thirds():
    # at each end of the contact the cap mu K x^(3/2), x ~ |v_n| |t - t_end|, is below the
    # spring's force A for a time ~ (A / mu)^(2/3), and the contact slides then: the outcome
    # leaves exact.hertz's per-sphere Eq. 18 by an amount proportional to mu^(-2/3)
    # (a factor 100^(2/3) = 21.5 per factor 100 in mu), not 1/mu as with Hooke's linear cap
    states = np.array(HERTZ_STATES)
    initial = states * [1.0, 1.0, 0.5]
    deviations = []
    for mu in (1e4, 1e6):
        model = ContactModel(normal="hertz", mu=mu, kt=3.0)
        exact = np.einsum("nij,nj->ni", model.replace(mu=None).matrices(states[:, 0]), initial)
        deviations.append(np.abs(coulomb.bounce_2d(model, *states.T) - exact).max())
    assert deviations[1] < 1e-3
    assert 18.0 < deviations[0] / deviations[1] < 25.0


# -- 3-D ------------------------------------------------------------------------------

def _rigid_3d(model, state, restitution):
    """Gross slip in 3-D: the impulse mu (1 + e) m |v_n| against the slip's direction."""
    v_n, v_t, omega, v_s, omega_s, omega_n = state
    slip = np.array([v_t + model.r * omega, v_s + model.r * omega_s])
    dv = -model.mu * (1.0 + restitution) * abs(v_n) * slip / np.hypot(*slip)
    return [-restitution * v_n, v_t + dv[0], model.r * omega + dv[0] / model.alpha,
            v_s + dv[1], model.r * omega_s + dv[1] / model.alpha, model.r * omega_n]


STATES_3D = [(-1.0, 0.5, -60.0, 2.0, 30.0, 1.0), (-0.6, 2.0, 40.0, -1.0, -50.0, -3.0),
             (-1.2, -1.0, 50.0, 0.5, 20.0, 0.0)]


@pytest.mark.parametrize("kw", [{}, {"normal": "hertz"}, {"kt": 8.0, "gamma_t": 0.5}])
def test_3d_gross_slip_is_the_rigid_body_impulse(kw):
    # the slide keeps the direction of the first slip: its impulse is the plane's, along it
    model = ContactModel(mu=0.02, **kw)
    got = coulomb.bounce_3d(model, *np.transpose(STATES_3D))
    closed = np.array([_rigid_3d(model, s, 1.0) for s in STATES_3D])
    assert np.abs(got - closed).max() < EXACT_TOLERANCE


def test_3d_no_slip_at_the_magic_ratio_is_the_rough_block_matrix():
    model = ContactModel(kt=10.0 * exact.magic_kt_over_kn(0.4), mu=0.8)
    states = np.array([(-1.0, 0.5, 0.0, -0.3, 0.4, 2.0), (-0.7, 0.2, 0.8, 0.1, -0.2, -1.0)])
    got = coulomb.bounce_3d(model, *states.T)
    rough = (exact.block_matrix(0.4, -2.0) @ (states * [1, 1, model.r, 1, model.r, model.r]).T).T
    assert np.abs(got - rough).max() < EXACT_TOLERANCE


@pytest.mark.parametrize("kw", [{"mu": 1.0}, {"mu": 1.0, "gamma_n": 1.0, "gamma_t": 0.5},
                                {"mu": 3.0, "kt": 8.0, "gamma_n": 1.5, "limit_damping": True}])
def test_3d_agrees_with_the_oracle(kw):
    # contacts that mostly stick, with the damping on and off; random 3-D contacts of
    # every regime and the oracle's former refusals are in test_coulomb_3d.py
    model = ContactModel(**kw)
    states = [(-0.8, 0.7, -2.0, -0.9, 1.5, 2.5), (-1.3, -0.2, 1.0, 0.6, 0.3, -1.0)]
    for state in states:
        slow = oracle.bounce(model, state[0], state[1], state[2], v_s=state[3],
                             omega_s=state[4], omega_n=state[5]).final
        fast = coulomb.bounce_3d(model, *state)[0]
        assert np.abs(fast - slow).max() / math.hypot(state[0], state[1], state[3]) < 1e-8


def test_3d_turning_the_tangential_axes_turns_the_outcome():
    # the wall has no preferred tangential direction: rotate (t, s) by an angle, and the
    # tangential velocities and spins of the outcome rotate with it
    model = ContactModel(mu=0.3, kt=8.0, gamma_n=1.0)
    state = np.array([-0.9, 0.4, 1.2, -0.7, 0.5, 0.8])
    angle = 0.7
    turn = np.eye(6)
    for a, b in ((1, 3), (2, 4)):
        turn[[a, a, b, b], [a, b, a, b]] = [math.cos(angle), -math.sin(angle),
                                            math.sin(angle), math.cos(angle)]
    turned = turn @ state
    got = coulomb.bounce_3d(model, *turned)[0]
    assert np.abs(got - turn @ coulomb.bounce_3d(model, *state)[0]).max() < EXACT_TOLERANCE
    in_plane = coulomb.bounce_3d(model, -0.9, 0.4, 1.2, 0.0, 0.0, 0.8)[0]
    assert np.abs(in_plane[:3] - coulomb.bounce_2d(model, -0.9, 0.4, 1.2)[0]).max() == 0.0


# -- contract -------------------------------------------------------------------------

def test_refusals():
    with pytest.raises(ValueError, match="finite mu"):
        coulomb.bounce_2d(ContactModel(), -1.0, 1.0, 0.0)
    with pytest.raises(ValueError, match="v_n"):
        coulomb.bounce_2d(ContactModel(mu=0.3), [-1.0, 0.0], 1.0, 0.0)
