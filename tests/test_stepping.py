"""The probe's convergence (stepping.converge) near a scene's step limit, and its fallback, on a made-up error law."""

from __future__ import annotations

import numpy as np
import pytest

from spinbounce.errors import ResultError
from spinbounce.model.timestep import mid_step_dt
from spinbounce.stepping import FALLBACK, FINEST_PROBED, LIMIT_REACH, UNMEASURED, converge, tune


def _sqrt_law(measured: list):
    """An error that falls as sqrt(dt), as LAMMPS's does from a first step set on the cap (viscoelastic beside
    mindlin): 0.1 / sqrt(N) at N steps a contact; each step count measured is kept."""
    def measure(steps: int) -> float:
        measured.append(steps)
        return 0.1 / steps**0.5
    return measure


def test_a_step_asked_for_just_past_the_limit_is_measured_at_the_limit():
    # the order's floor and SAFETY ask for ~4M steps; at the limit 2M the error is 7.1e-5, within the target
    measured = []
    measure = _sqrt_law(measured)
    steps, order, error = converge((100, measure(100)), (200, measure(200)), 1e-4, measure, limit=2_000_000)
    assert steps == 2_000_000 and measured[-1] == 2_000_000 and error <= 1e-4 and order == 0.5


def test_a_step_asked_for_far_past_the_limit_is_not_run():
    # the same law with a limit of 100,000: after 12,800 steps the extrapolation asks for 819,200, more than
    # LIMIT_REACH times the limit; nothing is run at or past it, and the steps returned exceed it (the scene then
    # falls back to its rule)
    measured = []
    measure = _sqrt_law(measured)
    limit = 100_000
    steps, _, _ = converge((100, measure(100)), (200, measure(200)), 1e-4, measure, limit=limit)
    assert steps > LIMIT_REACH * limit and max(measured) < limit


class _Scene:
    """A made-up scene of one row whose error falls as sqrt(dt) (0.1 sqrt(dt / t_contact)), its fine rule at
    ``rule_steps`` a contact and its limit at ``limit`` steps a contact: what :func:`tune` asks of a scene."""

    kind, default_step, n = "made-up", True, 1

    def __init__(self, rule_steps: int, limit: int, dt: float = 0.01):
        self.rule_steps, self.limit, self.dt = rule_steps, limit, dt

    def needs_probe(self):
        return True

    def beyond_reach(self):
        return np.zeros(1, dtype=bool)

    def rows(self, _):
        return self

    def probe_time(self, _):
        return 1.0

    def first_probe_steps(self, _):
        return 100

    def step_limit(self, _):
        return self.limit

    def at_step(self, dt):
        return _Scene(self.rule_steps, self.limit, dt)

    def fallback(self):
        return _Scene(self.rule_steps, self.limit, mid_step_dt(1.0, self.rule_steps))


def _sqrt_run(scene, _folder):
    return np.array([0.1 * scene.dt**0.5])


def test_a_probe_cut_short_by_its_limit_keeps_its_best_point_where_it_is_finer_than_the_rule(tmp_path):
    # the target asks for ~4M steps, past 4 times the limit of 50,000; the probe measured up to 12,800 steps
    # (8.8e-4), finer than the rule's 1,000 (3.2e-3): the scene runs at its best point, not at the rule
    scene, choice = tune(_Scene(rule_steps=1000, limit=50_000), tmp_path, _sqrt_run)
    assert choice.method == FINEST_PROBED and choice.predicted_error == min(choice.probe_errors)
    assert scene.dt == choice.dt < mid_step_dt(1.0, 1000) and _sqrt_run(scene, None)[0] < 0.1 * (1 / 1000) ** 0.5
    # a point only as fine as the rule (a limit at the rule's own steps, as a sweep's pair chunk has) is not kept
    scene, choice = tune(_Scene(rule_steps=12_800, limit=12_800), tmp_path, _sqrt_run)
    assert choice.method == FALLBACK and max(choice.probe_errors) > min(choice.probe_errors) > 0.0
    # a rule finer than every point the probe measured is kept
    scene, choice = tune(_Scene(rule_steps=100_000, limit=50_000), tmp_path, _sqrt_run)
    assert choice.method == FALLBACK and scene.dt == mid_step_dt(1.0, 100_000)


def test_a_probe_with_no_reference_on_any_row_claims_no_error(tmp_path):
    # every probed row without a limit (the pipeline hands over no error): the finer probe's step, its errors
    # unmeasured (NaN, null in JSON), none predicted
    scene, choice = tune(_Scene(rule_steps=1000, limit=50_000), tmp_path, lambda scene, _: np.empty(0))
    assert choice.method == UNMEASURED and choice.predicted_error is None and choice.observed_order is None
    assert np.isnan(choice.probe_errors).all() and scene.dt == mid_step_dt(1.0, 200)


def test_a_row_whose_error_is_nan_is_not_taken_for_a_probe_without_references(tmp_path):
    # one row measured, one NaN (LAMMPS's final state NaN, say): not "unmeasured"; a probe that cannot see its
    # error finish refines, then refuses, as before
    with pytest.raises(ResultError, match="no probe"):
        tune(_Scene(rule_steps=1000, limit=50_000), tmp_path, lambda scene, _: np.array([scene.dt, np.nan]))
