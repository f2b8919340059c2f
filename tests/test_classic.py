"""The classic wall's exact theory (exact.classic), and LAMMPS's classic wall against it."""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from spinbounce.model.timestep import mid_step_dt
from spinbounce.studies.doctor import run_wall
from spinbounce.exact import classic, linear


@pytest.mark.parametrize("gamma_n, gamma_t", [(0.0, 0.0), (0.3, 0.0), (0.3, 0.2), (1.0, 0.7)])
def test_without_the_contact_radius_it_is_the_papers_exact_omega(gamma_n, gamma_t):
    # a = 1 is the paper's linear spring, solved in closed form by exact.linear; the
    # hybrid integrator at rtol 1e-12 must reproduce it to well below its 1e-9 target
    wall = classic.ClassicWall(10.0, 1.3, gamma_n, gamma_t, None, 0.4, 0.5, 1.0, contact_radius=False)
    result = classic.bounce(wall, -1.0, 1.0, 0.0)
    exact = linear.Omega_exact(1.0, 10.0, 1.3, 0.4, gamma_t, gamma_n)  # m = 1: same dashpots
    assert result.final[1] + result.final[2] - 1.0 == pytest.approx(exact, abs=1e-10)
    assert result.final[0] == pytest.approx(linear.restitution(1.0, 10.0, gamma_n), abs=1e-12)


def _omega_in_phase(group: float) -> float:
    """Independent solve of d2u/ds2 = -group sqrt(sin s) u, u(0) = 0, u'(0) = 1 (Radau, in s)."""
    sol = solve_ivp(lambda s, y: [y[1], -group * math.sqrt(max(math.sin(s), 0.0)) * y[0]], (0.0, math.pi),
                    [0.0, 1.0], method="Radau", rtol=1e-12, atol=1e-14)
    return sol.y[1, -1] - 1.0


@pytest.mark.parametrize("v_n, kn, kt, alpha, r, m", [(-1.0, 10.0, 1.0, 0.4, 0.5, 1.0),
                                                      (-0.3, 7.0, 4.0, 0.25, 2.0, 3.0)])
def test_omega_eff_depends_on_the_stiffness_group_alone(v_n, kn, kt, alpha, r, m):
    # a second integrator in another variable; 1e-8 is its own accuracy with a sqrt(sin s) edge
    group = classic.stiffness_group(v_n, kn, kt, alpha, r, m)
    assert classic.Omega_eff(v_n, kn, kt, alpha, r, m) == pytest.approx(_omega_in_phase(group), abs=1e-8)


def test_omega_eff_changes_with_v_n_and_with_the_length_unit():
    base = classic.Omega_eff(-1.0, 10.0, 1.0, 0.4, 0.5)
    assert abs(classic.Omega_eff(-0.5, 10.0, 1.0, 0.4, 0.5) - base) > 0.01
    # the same collision in a unit of length twice as long: kn, kt (force/length) double,
    # lengths and speeds halve, m stays; a physical Omega could not change, this one does
    assert abs(classic.Omega_eff(-0.5, 20.0, 2.0, 0.4, 0.25) - base) > 0.05
    assert linear.Omega(20.0, 2.0, 0.4) == pytest.approx(linear.Omega(10.0, 1.0, 0.4), abs=1e-15)


def test_with_a_large_radius_and_finite_mu_the_wall_gives_energy():
    result = classic.bounce(classic.ClassicWall(10.0, 3.0, 0.0, 0.0, 0.3, 0.4, 10.0), -1.0, 0.5, 0.5)
    assert result.energy_gain > 0.01
    assert any(name.startswith("slide") for _, name in result.regimes)


# (kn, kt, gamma_n, gamma_t, mu, r, states, steps per contact). gamma_n = 1e-100 stands for
# 0, where LAMMPS's classic form gives NaN. Steps: sticking contacts converge at second
# order (1e-7 at 10^4 steps); a cap event's timing is first order, so capped cases get
# 10^5 steps to stay below 1e-4. Cases with gamma_n > 0 use a finite mu: with mu = 1e4 the
# reset where F_n turns tensile lasts ~|F_t|/(mu kn v_n), far below any practical dt.
STICK = [(-0.5, 1.0, 0.0), (-1.0, 1.0, 0.0), (-1.5, 1.0, 0.0), (-1.0, 0.3, -1.2)]
CASES = [
    (10.0, 1.0, 1e-100, 0.0, 1e4, 0.5, STICK, 10000),
    (10.0, 20 / 7, 1e-100, 0.0, 1e4, 0.5, STICK, 10000),
    (10.0, 5.0, 1e-100, 0.0, 1e4, 0.5, STICK, 10000),
    (10.0, 1.0, 1e-100, 0.0, 1e4, 2.0, [(-1.0, 1.0, 0.5), (-0.5, -1.0, 0.0)], 10000),
    (10.0, 1.0, 1e-100, 0.0, 0.1, 0.5, [(-1.0, 1.0, 0.0), (-1.0, 0.5, -1.0)], 100000),
    (10.0, 1.0, 0.5, 0.3, 0.2, 0.5, [(-1.0, 1.0, 0.0)], 100000),
    (10.0, 3.0, 1e-100, 0.0, 0.3, 10.0, [(-1.0, 0.5, 0.5), (-1.0, 0.0, 1.0)], 100000),
    (10.0, 10.0, 1e-100, 0.0, 0.1, 5.0, [(-1.0, 0.2, 0.0)], 200000),
]


@pytest.mark.lammps
@pytest.mark.parametrize("kn, kt, gamma_n, gamma_t, mu, r, states, steps", CASES)
def test_lammps_classic_wall_follows_the_contact_radius_theory(kn, kt, gamma_n, gamma_t, mu, r, states, steps,
                                                               tmp_path):
    wall = classic.ClassicWall(kn, kt, gamma_n, gamma_t, mu, 0.4, r)
    dt = mid_step_dt(wall.tau, steps)
    style = f"hooke/history {kn!r} {kt!r} {gamma_n!r} {gamma_t!r} {mu!r} 1"
    final = run_wall(style, states, tmp_path, dt, steps + 50, r=r)
    expected = np.array([classic.bounce(wall, *state).final for state in states])
    np.testing.assert_allclose(final, expected, rtol=0.0, atol=1e-4)


@pytest.mark.lammps
def test_lammps_classic_wall_gains_energy_where_the_theory_says(tmp_path):
    wall = classic.ClassicWall(10.0, 3.0, 0.0, 0.0, 0.3, 0.4, 10.0)
    final = run_wall("hooke/history 10.0 3.0 1e-100 0.0 0.3 1", [(-1.0, 0.5, 0.5)], tmp_path,
                     mid_step_dt(wall.tau, 20000), 20050, r=10.0)
    gain = linear.energy(final[0], 1.0, 0.4) / linear.energy(np.array([-1.0, 0.5, 0.5]), 1.0, 0.4) - 1.0
    assert gain == pytest.approx(classic.bounce(wall, -1.0, 0.5, 0.5).energy_gain, abs=1e-4)
    assert gain > 0.03


@pytest.mark.lammps
def test_lammps_frozen_classic_contact_oscillates_at_the_contact_radius_frequency(tmp_path):
    # three heights at once; the exact frozen solution is Eq. 10 with kt -> kt sqrt(r delta0),
    # which LAMMPS follows to ~1e-10 at dt = 1e-4 (measured), so 1e-6 leaves room for rounding
    r, overlaps, dt, steps = 0.5, np.array([0.05, 0.1, 0.2]), 1e-4, 30000
    final = run_wall("hooke/history 10.0 1.0 1e-100 0.0 10000.0 1", [(0.0, 1.0, 1.0)] * 3, tmp_path, dt, steps,
                     heights=r - overlaps)
    for delta0, row in zip(overlaps, final):
        v_t, r_omega = classic.frozen_velocities(steps * dt, 1.0, 1.0, 1.0, 0.4, r, delta0)
        assert row[1:] == pytest.approx([v_t, r_omega], abs=1e-6)
    assert [classic.frozen_frequency(1.0, 0.4, r, d) for d in overlaps] == pytest.approx(
        [0.74391, 0.88466, 1.05204], abs=1e-5)  # LAMMPS_FACTS section 11, measured by its own fit


def test_a_sweep_whose_theory_integrates_each_state_is_estimated_with_it():
    """The classic spring's oracle takes tenths of a second a state capped (its cap's sawtooth), a capped
    Hertz-Mindlin contact's hundredths: a sweep's estimate counts each state's theory (choose.STATE_SECONDS), so
    that its chunks stay within CHUNK_SECONDS (a cluster job's time with them) and a million states are not called
    minutes; a batched theory (the stick-slip solver's microseconds) leaves the frictionless and Hookean chunks at
    25,000."""
    from spinbounce.exact import choose
    from spinbounce.sweeps import cost
    from spinbounce.sweeps.spec import CHUNK_SECONDS, DEFAULT_CHUNK, spec_from_dict

    states = {"n": 1_000_000, "v_n": [-0.8, -0.1], "v_t": [-1, 1], "r_omega": [-1, 1]}
    mindlin = {"normal": "hertz/material", "youngs_modulus": 1e4, "poisson_ratio": 0.3, "tangential": "mindlin"}
    for model, kind in (({"wall": "classic", "mu": 0.5}, "classic_wall"), ({"wall": "classic"}, "classic_wall"),
                        ({"tangential": "linear_history_classic", "mu": 0.3}, "classic_wall"),
                        ({**mindlin, "mu": 0.3}, "capped_nonlinear")):
        spec = spec_from_dict({"model": model, "states": states})
        assert choose.which(spec.model(0)[0]).kind == kind
        size = spec.chunk_sizes[0]
        estimate = cost.chunk_cost(spec, 0, size)
        assert size < DEFAULT_CHUNK and estimate.seconds <= CHUNK_SECONDS
        assert size * choose.STATE_SECONDS[kind, "mu" in model] <= estimate.seconds
    for model in ({}, {"mu": 0.3}, mindlin):
        assert spec_from_dict({"model": model, "states": states}).chunk_sizes == (DEFAULT_CHUNK,)
