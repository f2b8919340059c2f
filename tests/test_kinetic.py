"""The two-temperature theory of a rough-sphere gas against the collision draws it is measured with, and its limits.

spinbounce.exact.kinetic's closed form and clock; spinbounce.scenes.gas.collisions' draws."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.linalg import expm

from spinbounce.api import model
from spinbounce.exact import kinetic
from spinbounce.exact import pair as planar
from spinbounce.scenes.gas import collisions, predict


def _rule_average(m, count: int, seed: int) -> np.ndarray:
    """L from the rough-sphere rule of the pair's planar theory, averaged over drawn collisions (T_tr = T_rot = 1)."""
    sample = collisions.draws(count, seed)
    g, w = sample.velocities(1.0, m.m), sample.spin(1.0, m.inertia)
    law = {"m_a": m.m, "r_a": m.r, "alpha_a": m.alpha, "m_b": m.m, "r_b": m.r, "alpha_b": m.alpha, "kn": m.kn,
           "kt": m.kt, "gamma_n": m.gamma_n, "gamma_t": m.gamma_t}
    n, zero = np.tile([0.0, 0.0, 1.0], (count, 1)), np.zeros((count, 3))
    changes = {}
    for name, spins in (("still", 0.0 * w), ("spun", w), ("reversed", -w)):
        va, vb, wa, wb = planar.predict(n, g, zero, spins[:, :3], spins[:, 3:], **law)
        changes[name] = np.array(collisions._energy_changes(m, (g, spins), (va - vb, np.hstack([wa, wb]))))
    spun = (changes["spun"] + changes["reversed"]) / 2.0 - changes["still"]
    return np.column_stack([changes["still"].mean(axis=1), spun.mean(axis=1)]) / 3.0


@pytest.mark.parametrize("law", [{"kt": 1e4 * 2 / 7}, {"kt": 1e3}, {"kt": 2e3, "gamma_n": 5.0, "gamma_t": 3.0}])
def test_the_closed_form_is_the_rough_sphere_rule_averaged_over_drawn_collisions(law):
    """Two derivations that share only the collision rule and the energy bookkeeping: the closed form (A, B, C of
    eta) and the average over draws (the collision-weighted closing speed, Maxwellian spins). 200,000 draws give each entry to about 1e-3 of its
    size (measured spread); 6e-3 is six of those."""
    m = model(kn=1e4, **law)
    e_n, beta = predict.restitutions(m)
    closed = kinetic.rough_sphere_matrix(e_n, beta, m.alpha)
    drawn = _rule_average(m, 200_000, seed=5)
    assert np.max(np.abs(drawn - closed)) < 6e-3 * np.max(np.abs(closed))


def test_rough_elastic_spheres_conserve_energy_and_smooth_ones_cool_by_haffs_law():
    rough = kinetic.rough_sphere_matrix(1.0, 1.0, 0.4)
    assert np.allclose(rough.sum(axis=0), 0.0, atol=1e-15)
    assert kinetic.steady_ratio(rough) == pytest.approx(1.0, abs=1e-14)
    smooth = kinetic.rough_sphere_matrix(0.8, -1.0, 0.4)
    assert smooth[0, 0] == pytest.approx(-(1.0 - 0.8**2) / 3.0, rel=1e-14)
    assert np.all(smooth[1] == 0.0) and smooth[0, 1] == 0.0


def test_the_magic_ratio_gives_a_pair_a_tangential_restitution_of_one():
    e_n, beta = predict.restitutions(model(kn=1e4, kt=1e4 * 2 / 7))
    assert (e_n, beta) == (pytest.approx(1.0, abs=1e-12), pytest.approx(1.0, abs=1e-12))


@pytest.mark.parametrize("matrix", [kinetic.rough_sphere_matrix(1.0, 1.0, 0.4),
                                    kinetic.rough_sphere_matrix(0.9, 0.3, 0.4)])
def test_the_evolution_is_the_matrix_exponential_and_keeps_the_steady_ratio(matrix):
    averages = kinetic.Averages(np.array([1.0]), matrix[None], np.array([0.02]))
    path = kinetic.evolve(averages, 1.0, 0.0, 30.0, 0.05, 1.0, 1.0)
    expected = np.array([expm(matrix * tau) @ [1.0, 0.0] for tau in path.tau])
    assert np.max(np.abs(np.column_stack([path.t_tr, path.t_rot]) - expected)) < 1e-9
    late = kinetic.evolve(averages, 1.0, 0.0, 300.0, 0.05, 1.0, 1.0)  # the ratio settles as exp of the eigenvalues' gap
    assert late.ratio[-1] == pytest.approx(kinetic.steady_ratio(matrix), rel=1e-6)
    r = kinetic.steady_ratio(matrix)
    (l00, l01), (l10, l11) = matrix
    assert l01 * r**2 + (l00 - l11) * r - l10 == pytest.approx(0.0, abs=1e-14)


def test_real_time_is_the_enskog_clock():
    """At constant T_tr (no translational change) t = tau / omega_E; omega_E grows as sqrt(T_tr)."""
    averages = kinetic.Averages(np.array([1.0]), np.zeros((1, 2, 2)), np.array([0.02]))
    path = kinetic.evolve(averages, 2.0, 0.0, 10.0, 0.05, 1.0, 1.0)
    rate = kinetic.enskog_rate(2.0, 0.05, 1.0, 1.0)
    assert path.t[-1] == pytest.approx(10.0 / rate, rel=1e-10)
    density = 6 * 0.05 / math.pi
    assert rate == pytest.approx(4 * density * kinetic.contact_value(0.05) * math.sqrt(2.0 * math.pi), rel=1e-14)


def test_drawn_collisions_close_at_the_collision_weighted_speed():
    """|g.n| of a collision has density x exp(-x^2 m / (4 T)): mean sqrt(pi T / m), mean square 4 T / m."""
    g = collisions.draws(400_000, seed=2).velocities(1.5, 2.0)
    closing = -g[:, 2]
    assert np.mean(closing) == pytest.approx(math.sqrt(math.pi * 1.5 / 2.0), rel=5e-3)
    assert np.mean(closing**2) == pytest.approx(4 * 1.5 / 2.0, rel=5e-3)
    assert np.var(g[:, 0]) == pytest.approx(2 * 1.5 / 2.0, rel=5e-3)


def test_the_exact_pairs_of_a_cold_gas_are_the_rough_spheres_of_the_planar_theory():
    """collisions.averages_at by the exact pair references: at T_tr = 1e-6 the line of centres turns by about 1e-5
    rad in a contact, so each collision is the planar rule's. With the rule as control variate L is the closed
    form plus the mean of (reference - rule), which is that small only if every collision agrees: measured
    1.8e-5 of an entry (the plain average's noise from 6,000 draws is 1.5%); 1e-4 is the bound."""
    m = model(kn=1e4, kt=1e3)
    found = collisions.averages_at(m, 1e-6, collisions.draws(6000, seed=9))
    closed = kinetic.rough_sphere_matrix(*predict.restitutions(m), m.alpha)
    assert np.max(np.abs(found["exact"][0] - closed)) < 1e-4 * np.max(np.abs(closed))
    # the contact time is the reference's, located on its step's dense output: to about 1e-5 of itself
    assert found["contact_time"] == pytest.approx(math.pi * math.sqrt(0.5 / 1e4), rel=1e-4)


def test_the_planar_rule_as_control_variate_keeps_the_mean_and_shrinks_its_error(monkeypatch):
    """The pair-level L takes each collision's energy change less the planar rule's and adds the rule's exact mean
    (spinbounce.scenes.gas.rule): the same expectation, so the two estimates from one set of draws agree within
    the plain one's standard errors (three of them), and the variance is that of the small difference (the line
    of centres turns by a few degrees): the standard errors shrink at least fivefold (measured 10 to 25 times at
    kt/kn = 0.1)."""
    from spinbounce.scenes.gas import rule

    m = model(kn=1e4, kt=1e3)
    sample = collisions.draws(6000, 11)
    controlled, control_error = collisions.averages_at(m, 1.0, sample)["exact"]
    monkeypatch.setattr(rule, "has_rule", lambda _: False)
    plain, plain_error = collisions.averages_at(m, 1.0, sample)["exact"]
    assert np.all(np.abs(controlled - plain) < 3.0 * plain_error[:2])
    assert np.all(control_error[:2] < plain_error[:2] / 5.0)
