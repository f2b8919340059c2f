"""Unit tests for spinbounce.exact.linear (Wang & Harrowell, frictional sphere on a wall).

Covered: Omega and tau at the paper's defaults; Eq. 18 and its rough (Eq. 20) and rolling
(Eq. 23) cases; the magic kt/kn; the frozen trajectory (Eqs. 10-13); the exact damped
frozen solution, normal damping and a whole collision against scipy's solve_ivp (used
only as an oracle); the paper's damped recipe (Eq. 22); energy change and dissipation.
"""

import math
import warnings

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from spinbounce import exact as th

M, R, KN, KT, ALPHA = 1.0, 0.5, 10.0, 1.0, 0.4  # the paper's defaults
ALPHAS = [0.1, 0.4, 2.0 / 3.0, 1.5]
RNG = np.random.default_rng(12345)
ODE_TOL = dict(rtol=1e-12, atol=1e-14, method="DOP853")  # oracle error seen <= 3e-10


def _frozen_ode(t_eval, vt0, rw0, kt, m, alpha, gamma_t):
    """Integrate m v_t' = F_t, (r omega)' = F_t/(alpha m), u' = v_t + r omega."""

    def rhs(_, y):
        vt, rw, u = y
        f = -kt * u - gamma_t * (vt + rw)
        return [f / m, f / (alpha * m), vt + rw]

    sol = solve_ivp(rhs, (0.0, t_eval[-1]), [vt0, rw0, 0.0], t_eval=t_eval, **ODE_TOL)
    assert sol.success
    return sol.y[0], sol.y[1]


def _leaves(_, y):
    """Terminal solve_ivp event: z = r crossed upward (the sphere leaves the wall)."""
    return y[0] - R


_leaves.terminal, _leaves.direction = True, 1.0


# --- 1. defaults --------------------------------------------------------------------

def test_omega_and_collision_time_at_paper_defaults():
    # the paper quotes -1.2838; 5 significant digits of the closed form: 1e-5
    assert abs(th.Omega(KN, KT, ALPHA) - (-1.28384)) < 1e-5
    # pi/sqrt(10) vs pi*sqrt(1/10): equal up to one ulp of rounding, rel 1e-15
    assert th.collision_time(1.0, 10.0) == pytest.approx(math.pi * math.sqrt(1.0 / 10.0),
                                                         rel=1e-15, abs=0)


# --- 2-4. scattering matrices -----------------------------------------------------

@pytest.mark.parametrize("alpha", ALPHAS)
@pytest.mark.parametrize("omega", [0.0, -0.5, -1.0, -1.2838, -2.0])
def test_rolling_state_is_unchanged_by_scattering(alpha, omega):
    vt = np.array([1.0, -0.3, 2.5])
    states = np.stack([[-1.0, -2.0, -0.7], vt, -vt], axis=-1)  # rows (v_n, v_t, -v_t)
    out = states @ th.scattering_matrix(alpha, omega).T
    # matrix product of O(1) numbers: rounding only, 1e-14
    np.testing.assert_allclose(out[:, 1:], states[:, 1:], rtol=0, atol=1e-14)
    np.testing.assert_array_equal(out[:, 0], -states[:, 0])


@pytest.mark.parametrize("alpha", ALPHAS)
def test_rough_matrix_conserves_energy_and_rolling_matrix_rolls(alpha):
    states = RNG.normal(size=(200, 3))
    rough = states @ th.rough_matrix(alpha).T
    # kinetic energies of O(1) states: rounding only, 1e-12
    np.testing.assert_allclose(th.energy(rough, M, alpha), th.energy(states, M, alpha),
                               rtol=1e-12)
    rolled = states @ th.rolling_matrix(alpha).T
    np.testing.assert_allclose(rolled[:, 1] + rolled[:, 2], 0.0, atol=1e-14)  # rounding
    assert np.all(np.abs(states[:, 1] + states[:, 2]) > 1e-6)  # inputs really slipped


def test_rough_sphere_worked_numbers_for_solid_sphere():
    # Section 4 text: omega(0) = 0 gives r omega = -10/7 v_t(0). For v_t(0) = 0, Eq. 20
    # (and conservation of v_t - alpha r omega) gives v_t = -4/7 r omega(0); the text's
    # "-1/7" disagrees with its own Eq. 20. Exact fractions: rounding only, 1e-15.
    a = th.rough_matrix(0.4)
    np.testing.assert_allclose(a @ [0.0, 1.0, 0.0], [0.0, 3.0 / 7.0, -10.0 / 7.0], atol=1e-15)
    np.testing.assert_allclose(a @ [0.0, 0.0, 1.0], [0.0, -4.0 / 7.0, -3.0 / 7.0], atol=1e-15)


@pytest.mark.parametrize("alpha", [0.1, 0.4, 2.0 / 3.0])
def test_magic_ratio_gives_omega_minus_two(alpha):
    # cos(pi * sqrt(1 + rounding)) + 1 is second order in the rounding: 1e-12
    assert abs(th.Omega(KN, KN * th.magic_kt_over_kn(alpha), alpha) + 2.0) < 1e-12
    assert th.magic_kt_over_kn(2.0 / 5.0) == pytest.approx(2.0 / 7.0, rel=1e-15)  # rounding


# --- 5. undamped frozen trajectory --------------------------------------------------

@pytest.mark.parametrize("vt0, rw0", [(1.0, 0.0), (1.0, -0.5), (-0.2, -0.5), (0.3, 0.5)])
@pytest.mark.parametrize("alpha, kt, m", [(0.4, 1.0, 1.0), (0.1, 3.0, 2.5), (2 / 3, 0.7, 0.4)])
def test_frozen_trajectory_line_mean_and_extremes(vt0, rw0, alpha, kt, m):
    period = 2.0 * math.pi / math.sqrt(th.Q(kt, m, alpha))
    t = np.arange(3 * 97) * (3 * period / (3 * 97))  # 3 whole periods, 97 points each
    vt, rw = th.frozen_velocities(t, vt0, rw0, kt, m, alpha)
    # Eq. 10 written with kt, m, I = alpha m r^2 (r = R) as in the paper; closed forms: 1e-12
    q, inertia, s0 = th.Q(kt, m, alpha), alpha * m * R**2, vt0 + rw0
    c = np.cos(t * math.sqrt(q)) - 1.0
    np.testing.assert_allclose(vt, vt0 + kt * s0 / (m * q) * c, atol=1e-12)
    np.testing.assert_allclose(rw, rw0 + R**2 * kt * s0 / (inertia * q) * c, atol=1e-12)
    # Eq. 13, slope alpha; rounding only: 1e-12
    np.testing.assert_allclose(vt - vt0, th.frozen_slope(alpha) * (rw - rw0), atol=1e-12)
    # Eq. 11: the mean of cos over whole periods on a uniform grid vanishes to rounding: 1e-12
    mean_vt, mean_rw = th.frozen_means(vt0, rw0, alpha)
    assert abs(vt.mean() - mean_vt) < 1e-12 and abs(rw.mean() - mean_rw) < 1e-12
    assert abs(mean_vt + mean_rw) < 1e-14  # the mean is rolling; rounding only
    # Eq. 12 at t = pi/sqrt(Q); rounding only: 1e-12
    ext = th.frozen_velocities(period / 2.0, vt0, rw0, kt, m, alpha)
    np.testing.assert_allclose(ext, th.frozen_extremes(vt0, rw0, alpha), atol=1e-12)
    lo, hi = sorted([vt0, ext[0]])  # the two ends bound the whole trajectory (rounding)
    assert np.all((vt >= lo - 1e-12) & (vt <= hi + 1e-12))


# --- 6. exact damped frozen solution ------------------------------------------------

_GC = 2.0 * ALPHA * M * math.sqrt(th.Q(KT, M, ALPHA)) / (1.0 + ALPHA)  # zeta = sqrt(Q)


@pytest.mark.parametrize(
    "gamma_t", [0.0, 0.3, _GC, _GC * (1 - 1e-9), _GC * (1 + 1e-9), 3.0, 20.0],
    ids=["undamped", "under", "critical", "crit-1e-9", "crit+1e-9", "over", "strongly-over"],
)
def test_damped_frozen_matches_solve_ivp(gamma_t):
    t = np.linspace(0.0, 10.0, 401)
    vt, rw = th.frozen_velocities(t, 1.0, 0.5, KT, M, ALPHA, gamma_t)
    vt_ode, rw_ode = _frozen_ode(t, 1.0, 0.5, KT, M, ALPHA, gamma_t)
    # solve_ivp (DOP853, rtol=1e-12): dense-output error seen <= 3e-10, so 1e-8
    np.testing.assert_allclose(vt, vt_ode, rtol=0, atol=1e-8)
    np.testing.assert_allclose(rw, rw_ode, rtol=0, atol=1e-8)


def test_damped_frozen_with_other_mass_matches_solve_ivp():
    m, kt, alpha, gamma_t = 2.5, 3.0, 0.25, 1.7  # m != 1 exposes a missing 1/m anywhere
    t = np.linspace(0.0, 10.0, 201)
    got = th.frozen_velocities(t, -0.4, 1.1, kt, m, alpha, gamma_t)
    np.testing.assert_allclose(got, _frozen_ode(t, -0.4, 1.1, kt, m, alpha, gamma_t),
                               atol=1e-8)  # solve_ivp with rtol=1e-12: 1e-8


def test_exactly_critical_damping_matches_closed_form():
    # dyadic parameters make zeta^2 == Q exactly in floating point: Q = 6.25, zeta = 2.5
    m, kt, alpha, gamma_t = 1.0, 1.25, 0.25, 1.0
    zeta = th.damping_rate(gamma_t, m, alpha)
    assert zeta * zeta == th.Q(kt, m, alpha)
    t = np.linspace(0.0, 10.0, 101)
    got = th.slip_rate_ratio(t, kt, m, alpha, gamma_t)
    # u'/u'(0) = (1 - zeta t) exp(-zeta t) at critical damping; rounding only: 1e-13
    np.testing.assert_allclose(got, (1.0 - zeta * t) * np.exp(-zeta * t), atol=1e-13)


def test_slip_rate_ratio_is_continuous_across_critical_damping():
    assert th.damping_rate(_GC, M, ALPHA) ** 2 == pytest.approx(th.Q(KT, M, ALPHA), rel=1e-15)
    t = np.linspace(0.0, 10.0, 1001)
    ref = th.slip_rate_ratio(t, KT, M, ALPHA, _GC)
    for g in (_GC * (1 - 1e-9), _GC * (1 + 1e-9)):
        # |d ratio/d gamma| = O(1) and gamma changes by ~1e-9: 1e-7 leaves a margin of 100
        np.testing.assert_allclose(th.slip_rate_ratio(t, KT, M, ALPHA, g), ref, atol=1e-7)
    # the overdamped branch switch at kappa t = 1: two formulas must agree, 1e-12 (rounding)
    zeta = th.damping_rate(3.0, M, ALPHA)
    t_switch = 1.0 / math.sqrt(zeta**2 - th.Q(KT, M, ALPHA))
    below, above = th.slip_rate_ratio(t_switch * np.array([1 - 1e-13, 1 + 1e-13]), KT, M,
                                      ALPHA, 3.0)
    assert abs(below - above) < 1e-12


@pytest.mark.parametrize("gamma_t", [2.0, 20.0, 1e3])
def test_overdamped_slip_rate_ratio_finite_at_large_times(gamma_t):
    t = np.array([0.0, 1.0, 1e2, 1e4])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        ratio = th.slip_rate_ratio(t, KT, M, ALPHA, gamma_t)
        scalar = th.slip_rate_ratio(1e4, KT, M, ALPHA, gamma_t)
        vt, rw = th.frozen_velocities(1e4, 1.0, 0.5, KT, M, ALPHA, gamma_t)
    assert np.all(np.isfinite(ratio)) and math.isfinite(scalar) and ratio[0] == 1.0
    assert np.all(np.abs(ratio) <= 1.0)
    # worst case gamma_t = 1e3: slow-mode share Q/(4 zeta^2) = 3e-7 times e^-10, so
    # |u'/u'(0)| ~ 1.3e-11 at t = 1e4 and the state sits on Eq. 11's rolling mean: 1e-9
    np.testing.assert_allclose([vt, rw], th.frozen_means(1.0, 0.5, ALPHA), atol=1e-9)


# --- 7. the paper's damped recipe ---------------------------------------------------

@pytest.mark.parametrize("gamma_t", [0.1, 0.5, 2.0])
def test_paper_damped_recipe_differs_from_exact(gamma_t):
    t = np.linspace(0.0, 10.0, 2001)
    exact = th.frozen_velocities(t, 1.0, R * 1.0, KT, M, ALPHA, gamma_t)
    paper = th.frozen_velocities_paper_damped(t, 1.0, R * 1.0, KT, M, ALPHA, gamma_t)
    # measured max |diff v_t| is 0.086, 0.119, 0.175: far above rounding, so 0.05
    assert np.max(np.abs(exact[0] - paper[0])) > 0.05


def test_paper_damped_recipe_equals_exact_without_damping():
    t = np.linspace(0.0, 10.0, 1001)
    exact = th.frozen_velocities(t, 1.0, 0.5, KT, M, ALPHA, 0.0)
    paper = th.frozen_velocities_paper_damped(t, 1.0, 0.5, KT, M, ALPHA, 0.0)
    # same formula, different operation order: a few ulps (2e-16 seen), 1e-14
    np.testing.assert_allclose(exact, paper, rtol=0, atol=1e-14)


def test_paper_damped_recipe_is_eq10_times_exp_and_gives_eq22():
    m, kn, kt, alpha, g = 2.0, 10.0, 1.0, 0.4, 0.7  # m != 1 checks the rate gamma_t/m
    t = np.linspace(0.0, 10.0, 201)
    bracket = np.exp(-g * t / m) * np.cos(t * math.sqrt(th.Q(kt, m, alpha))) - 1.0
    vt, rw = th.frozen_velocities_paper_damped(t, 1.0, 0.5, kt, m, alpha, g)
    # Section 5's words written out; closed forms, rounding only: 1e-14
    np.testing.assert_allclose(vt, 1.0 + alpha / (1 + alpha) * bracket * 1.5, atol=1e-14)
    np.testing.assert_allclose(rw, 0.5 + bracket * 1.5 / (1 + alpha), atol=1e-14)
    om = th.Omega_paper_damped(m, kn, kt, alpha, g)
    eq22 = math.exp(-math.pi * g / math.sqrt(m * kn)) * (th.Omega(kn, kt, alpha) + 1) - 1
    assert om == pytest.approx(eq22, abs=1e-14)  # rounding only
    at_tau = th.frozen_velocities_paper_damped(th.collision_time(m, kn), 1.0, 0.5, kt, m, alpha, g)
    out = th.scattering_matrix(alpha, om) @ [0.0, 1.0, 0.5]
    np.testing.assert_allclose(at_tau, out[1:], atol=1e-12)  # tau*sqrt(Q) rounding: 1e-12


# --- 8. Omega variants ----------------------------------------------------------------

@pytest.mark.parametrize("kt", [0.3, 1.0, 2.857142857142857, 7.0])
def test_omega_variants_agree_without_damping(kt):
    om = th.Omega(KN, kt, ALPHA)
    assert abs(th.Omega_exact(M, KN, kt, ALPHA) - om) < 1e-12  # same cosine: 1e-12
    assert abs(th.Omega_paper_damped(M, KN, kt, ALPHA, 0.0) - om) < 1e-15  # exp(0) = 1


@pytest.mark.parametrize("gamma_t, gamma_n", [(0.3, 0.0), (_GC, 0.0), (5.0, 0.0), (0.5, 2.0)])
def test_omega_exact_is_slip_rate_ratio_at_contact_time(gamma_t, gamma_n):
    tau = th.collision_time(M, KN, gamma_n)
    expected = th.slip_rate_ratio(tau, KT, M, ALPHA, gamma_t) - 1.0
    got = th.Omega_exact(M, KN, KT, ALPHA, gamma_t, gamma_n)
    assert got == pytest.approx(expected, abs=1e-15)  # same expression: rounding only


@pytest.mark.parametrize("gamma_t, gamma_n", [(0.0, 0.0), (0.3, 0.0), (0.0, 1.0), (0.5, 2.0),
                                              (5.0, 0.5)])
def test_whole_collision_matches_scattering_matrix_with_exact_omega(gamma_t, gamma_n):
    """Integrate Eq. 1 with the sphere free to move until z = r again."""

    def rhs(_, y):
        z, vn, vt, rw, u = y
        ft = -KT * u - gamma_t * (vt + rw)
        return [vn, (-KN * (z - R) - gamma_n * vn) / M, ft / M, ft / (ALPHA * M), vt + rw]

    before = np.array([-1.3, 0.8, -0.2])
    sol = solve_ivp(rhs, (0.0, 10.0), [R, *before, 0.0], events=_leaves, **ODE_TOL)
    after = sol.y_events[0][0][1:4]
    e = th.restitution(M, KN, gamma_n)
    pred = th.scattering_matrix(ALPHA, th.Omega_exact(M, KN, KT, ALPHA, gamma_t, gamma_n), e)
    np.testing.assert_allclose(after, pred @ before, atol=1e-8)  # solve_ivp rtol=1e-12: 1e-8


# --- 9. normal damping --------------------------------------------------------------

@pytest.mark.parametrize("m, kn, gamma_n", [(1.0, 10.0, 0.0), (1.0, 10.0, 0.5), (1.0, 10.0, 2.0),
                                            (1.0, 10.0, 6.0), (2.5, 3.0, 1.5)])
def test_normal_damping_against_solve_ivp(m, kn, gamma_n):
    def rhs(_, y):
        return [y[1], (-kn * (y[0] - R) - gamma_n * y[1]) / m]

    def turns(_, y):
        return y[1]
    turns.direction = 1.0

    sol = solve_ivp(rhs, (0.0, 100.0), [R, -1.0], events=[_leaves, turns], **ODE_TOL)
    t_end, (_, v_end) = sol.t_events[0][0], sol.y_events[0][0]
    z_min = sol.y_events[1][0][0]
    # solve_ivp with rtol=1e-12 and root-found events: 1e-8
    assert th.collision_time(m, kn, gamma_n) == pytest.approx(t_end, abs=1e-8)
    assert th.restitution(m, kn, gamma_n) == pytest.approx(v_end, abs=1e-8)
    assert th.max_overlap(-1.0, m, kn, gamma_n) == pytest.approx(R - z_min, abs=1e-8)
    # overlap is linear in |v_n| for vector input; same solve_ivp oracle: 1e-8
    np.testing.assert_allclose(th.max_overlap(np.array([-2.0, 0.5]), m, kn, gamma_n),
                               np.array([2.0, 0.5]) * (R - z_min), atol=1e-8)
    if gamma_n == 0.0:  # Eq. 15: |v_n| sqrt(m/kn); closed forms: 1e-14
        assert th.max_overlap(-1.0, m, kn) == pytest.approx(math.sqrt(m / kn), abs=1e-14)
        assert th.restitution(m, kn) == 1.0


# (1, 3) and (3, 7): sqrt(m kn)**2 rounds below m kn, so kn/m - beta^2 is +4e-16 at factor 1
@pytest.mark.parametrize("m, kn", [(1.0, 10.0), (1.0, 2.0), (0.7, 5.0), (1.0, 3.0), (3.0, 7.0)])
@pytest.mark.parametrize("factor", [1.0, 1.01, 10.0])
def test_critical_normal_damping_raises(m, kn, factor):
    # match the module's own message, not math.sqrt's "math domain error"
    for fn in (th.collision_time, th.restitution):
        with pytest.raises(ValueError, match="critical"):
            fn(m, kn, factor * 2.0 * math.sqrt(m * kn))


# --- 10. energy -----------------------------------------------------------------------

def test_dissipation_zero_for_rough_positive_for_eq18():
    states = RNG.normal(size=(100, 3))
    rough = states @ th.rough_matrix(ALPHA).T
    assert np.max(np.abs(th.dissipation(states, rough, M, ALPHA))) < 1e-12  # rounding
    eq18 = states @ th.scattering_matrix(ALPHA, -1.2838).T
    f = th.dissipation(states, eq18, M, ALPHA)
    assert np.all(f > 0.0)
    # slip energy m/2 alpha/(1+alpha) s^2 is scaled by (1+Omega)^2; closed forms: 1e-12
    s = states[:, 1] + states[:, 2]
    d_e = 0.5 * M * ALPHA / (1 + ALPHA) * s**2 * ((1 - 1.2838) ** 2 - 1)
    np.testing.assert_allclose(th.energy_change(states, eq18, M, ALPHA), d_e, atol=1e-12)


def test_dissipation_worked_example_rolling_collision():
    # alpha = 2/5, m = 2, (v_n, v_t, r omega) = (-1, 1, 0), Eq. 23: (1, 5/7, -5/7).
    # E0 = (1 + 1)/2 * 2 = 2, E1 = (1 + 25/49 + (2/5)(25/49)) = 12/7, f = (2 - 12/7)/2 = 1/7
    before = np.array([-1.0, 1.0, 0.0])
    after = th.rolling_matrix(0.4) @ before
    np.testing.assert_allclose(after, [1.0, 5.0 / 7.0, -5.0 / 7.0], atol=1e-15)  # rounding
    # fractions of O(1) numbers: rounding only, 1e-14
    assert th.energy_change(before, after, 2.0, 0.4) == pytest.approx(-2.0 / 7.0, abs=1e-14)
    assert th.dissipation(before, after, 2.0, 0.4) == pytest.approx(1.0 / 7.0, abs=1e-14)


def test_restitution_with_and_without_tensile_force():
    """gamma_n > 0: allowing the dashpot to pull (LAMMPS's default) costs more energy than
    cutting the force at zero (limit_damping), and neither depends on v_n (linear ODE)."""
    from spinbounce.exact.linear import collision_time, exit_time, gamma_n_for_restitution, restitution

    m, kn = 1.0, 10.0
    for e in (0.9, 0.7, 0.5):
        g = gamma_n_for_restitution(e, m, kn)
        assert restitution(m, kn, g) == pytest.approx(e, rel=1e-13)
        assert restitution(m, kn, g, tensile=False) > e
        assert collision_time(m, kn, g, tensile=False) < collision_time(m, kn, g)
        assert exit_time(m, kn, g, tensile=False) > collision_time(m, kn, g, tensile=False)
        assert exit_time(m, kn, g) == collision_time(m, kn, g)


def test_force_free_end_against_an_ode_oracle():
    """limit_damping: integrate m x'' = -(kn x + g x') until that force reaches zero, with
    scipy's event location, and compare the end time and the exit speed."""
    from scipy.integrate import solve_ivp

    from spinbounce.exact.linear import collision_time, restitution

    m, kn, g = 1.0, 10.0, 2.0

    def force_zero(t, y):
        return kn * y[0] + g * y[1] if t > 1e-9 else 1.0

    force_zero.terminal, force_zero.direction = True, -1
    sol = solve_ivp(lambda t, y: [y[1], -(kn * y[0] + g * y[1]) / m], (0, 5), [0.0, 1.0],
                    events=force_zero, rtol=1e-12, atol=1e-14)
    t_end = sol.t_events[0][0]
    assert t_end == pytest.approx(collision_time(m, kn, g, tensile=False), rel=1e-9)
    assert -sol.y_events[0][0][1] == pytest.approx(restitution(m, kn, g, tensile=False), rel=1e-9)
