"""Property-based tests (hypothesis) of the parser, the declaration's checks and the model.

Property-based tests (hypothesis) of the parser, the declaration's checks and the
model's invariants: what must hold for every input, not for a handful of examples.
"""

from __future__ import annotations

import argparse
import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from spinbounce.cli.options import count, number
from spinbounce.model import parameters
from spinbounce.model.contact import ContactModel
from spinbounce.model.parameters import SceneError
from spinbounce.exact import choose, linear

finite = st.floats(allow_nan=False, allow_infinity=False, width=64)


@given(finite)
def test_every_finite_number_parses_as_itself_in_any_notation(x):
    for text in (repr(x), f"{x:e}", f"{x:.17g}"):
        assert number(text) == float(text)


@given(st.sampled_from(["nan", "inf", "-inf", "1e999", "abc", "", "1,5"]))
def test_what_is_not_a_finite_number_is_refused(text):
    with pytest.raises(argparse.ArgumentTypeError):
        number(text)


@given(st.integers(min_value=0, max_value=10**12))
def test_counts_take_integral_floats(n):
    assert count(repr(float(n))) == n and count(str(n)) == n
    assert count(f"{n:.17e}") == n  # e-notation: "--n 1e5" is 100000


@given(st.sampled_from([p for p in parameters.MODEL if p.kind == "number"]), finite)
def test_a_number_is_accepted_exactly_when_it_lies_in_its_declared_range(p, x):
    inside = ((p.low is None or (x > p.low if p.low_open else x >= p.low))
              and (p.high is None or (x < p.high if p.high_open else x <= p.high)))
    try:
        assert p.check(x) == x
        assert inside
    except SceneError as exc:
        assert not inside and exc.parameter == p.name and exc.limit.startswith("must")


states = st.tuples(st.floats(-2.0, -0.05), st.floats(-3.0, 3.0), st.floats(-3.0, 3.0))
models = st.fixed_dictionaries({
    "kt": st.floats(0.0, 30.0), "alpha": st.floats(0.05, 2 / 3),
    "mu": st.one_of(st.none(), st.floats(0.0, 50.0)),
})


@settings(max_examples=60, deadline=None)
@given(models, states)
def test_no_energy_is_gained_without_damping(params, state):
    model = ContactModel(**params)
    initial = np.array([state])
    final = choose.predict(model, initial)
    gain = linear.energy(final, model.m, model.alpha) - linear.energy(initial, model.m, model.alpha)
    assert gain <= 1e-12 * linear.energy(initial, model.m, model.alpha)[0] + 1e-15


@settings(max_examples=60, deadline=None)
@given(models, states, st.floats(0.0, 3.0), st.floats(0.0, 3.0))
def test_mirroring_the_tangential_state_mirrors_the_outcome(params, state, gamma_n, gamma_t):
    """v_t -> -v_t with omega -> -omega is the same collision seen in a mirror."""
    assume(gamma_n < 2.0 * math.sqrt(10.0))
    model = ContactModel(**params, gamma_n=gamma_n, gamma_t=gamma_t)
    v_n, v_t, r_omega = state
    plain = choose.predict(model, np.array([[v_n, v_t, r_omega]]))[0]
    mirrored = choose.predict(model, np.array([[v_n, -v_t, -r_omega]]))[0]
    assert mirrored == pytest.approx(plain * [1.0, -1.0, -1.0], abs=1e-12)


@settings(max_examples=40, deadline=None)
@given(st.floats(0.05, 2 / 3), states)
def test_the_energy_conserving_collision_runs_back_in_time(alpha, state):
    """Time reversal: where no energy is lost (kt/kn = alpha/(1+alpha): the spring is unloaded
    when the contact ends), reversing the final velocities and spin and colliding again gives
    back the reversed initial state. Elsewhere the spring energy left at the end is lost, and
    the collision is not reversible."""
    model = ContactModel(kt=10.0 * alpha / (1.0 + alpha), alpha=alpha)
    initial = np.array(state)
    final = choose.predict(model, initial[None, :])[0]
    back = choose.predict(model, np.array([[-final[0], -final[1], -final[2]]]))[0]
    assert back == pytest.approx(-initial, abs=1e-12)
