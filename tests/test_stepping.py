"""The probe's convergence (stepping.converge) near a scene's step limit, on a made-up error law."""

from __future__ import annotations

from spinbounce.stepping import LIMIT_REACH, converge


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
