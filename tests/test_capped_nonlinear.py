"""A Coulomb cap on a contact whose force, spring or dashpot grows with the contact radius.

Two references integrate it: exact.contact_phases (planar, no dashpot: phase by phase, in
sqrt(delta) near the ends) and exact.oracle (any dashpot, 3-D slides, a tensile turn,
limit_damping). They are written apart and held to each other where both apply; the oracle is
held to LAMMPS at the default step (1e-4, the default accuracy) and converged (1e-6), and to the
one thing the law does that no undamped or force-history law does: a damped displacement history
on the contact radius pushes along the slip once the first trial force exceeds the cap.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from converged import converged
from spinbounce.exact import choose, contact_phases, oracle
from spinbounce.model.contact import ContactModel
from spinbounce.pipeline import run_scene
from spinbounce.scenes.collision import Collision
from test_damped_nonlinear import ASSEMBLIES as DAMPED, MATERIAL

VARIANTS = ("mindlin", "mindlin/force", "mindlin_rescale", "mindlin_rescale/force")
#: Each damping sub-model with a cap, on the Hertzian and Hookean forces, with each kind of spring
#: (test_damped_nonlinear's, the restitution dashpot with a tangential one), and Hertz-Mindlin undamped.
ASSEMBLIES = {name: law for name, law in DAMPED.items() if name != "hooke linear_history_classic"}
ASSEMBLIES["hertz coeff_restitution mindlin_rescale"] = {**DAMPED["hertz coeff_restitution mindlin_rescale"],
                                                         "x_t": 0.3}
ASSEMBLIES["hertz-mindlin undamped"] = {**MATERIAL, "tangential": "mindlin_rescale"}
#: How far beyond the law's threshold x_t |u'| = mu |v_n| (a damped displacement history on the
#: contact radius, a dashpot-led start) a random state must lie for LAMMPS at the default step to
#: meet 1e-4: measured above 1e-4 from 1.03 to 1.48 times the threshold (tsuji, mu = 0.5,
#: |v_n| = 0.9, the fixed batch step); just above it LAMMPS converges only slowly (see below).
BAND = (0.9, 1.6)


def _slip_ratio(model: ContactModel, states: np.ndarray) -> np.ndarray:
    """x_t |u'| / (mu |v_n|) of each state: where a damped displacement history pushes along the slip."""
    slip = np.hypot(states[:, 1] + states[:, 2], states[:, 3] + states[:, 4] if states.shape[1] == 6 else 0.0)
    return model.gamma_t / model.gamma_n * slip / (model.mu * np.abs(states[:, 0]))


def _pushes_along(model: ContactModel) -> bool:
    law = model.tangential_law
    return (law.contact_radius and not law.variant[0] and model.gamma_t > 0.0
            and model.damping_law.radius_power(model.normal_law) < 1.0)


def _random_states(rng, n: int, model: ContactModel) -> np.ndarray:
    """Random 3-D states, those in the threshold's band (BAND) of a law that has one drawn again."""
    out = []
    while len(out) < n:
        s = np.array([-rng.uniform(0.2, 1.2), *rng.uniform(-1.0, 1.0, 2), *rng.uniform(-0.5, 0.5, 2),
                      rng.uniform(-1.0, 1.0)])
        if not (_pushes_along(model) and BAND[0] < _slip_ratio(model, s[None, :])[0] < BAND[1]):
            out.append(s)
    return np.array(out)


@pytest.mark.parametrize("variant", VARIANTS)
@pytest.mark.parametrize("law", [MATERIAL, {"kn": 50.0, "mindlin_kt": 700.0}], ids=["hertz", "hooke"])
def test_the_oracle_meets_the_phase_integration_without_dashpots(variant, law):
    # two integrations written apart (in time, A as the state; phase by phase in sqrt(delta)),
    # both at rtol 1e-12: measured 5.1e-11 apart at worst over 64 random states: 1e-9
    model = ContactModel(tangential=variant, mu=0.3, r=0.45, **law)
    rng = np.random.default_rng(len(variant) + len(law))
    for _ in range(4):
        state = np.array([-rng.uniform(0.2, 1.5), rng.uniform(-1, 1), rng.uniform(-1, 1)])
        by_oracle = oracle.bounce(model, state[0], state[1], state[2] / model.r).final[:3]
        by_phases = contact_phases.bounce(contact_phases.Law.of(model), *state)[:3]
        assert by_oracle == pytest.approx(by_phases, abs=1e-9 * np.abs(state).max())


#: Each assembly with a cap that lets the normal force pull, and (where it has a normal dashpot)
#: with limit_damping, which cuts that pull.
CAPS = [(name, 0.3, {}) for name in sorted(ASSEMBLIES)] + [
    (name, 0.1, {"limit_damping": True}) for name in sorted(ASSEMBLIES) if name != "hertz-mindlin undamped"]


@pytest.mark.lammps
@pytest.mark.parametrize("name, mu, extra", CAPS)
def test_lammps_at_the_default_step_meets_the_reference(name, mu, extra, tmp_path):
    # random 3-D states in a batch of speeds and one alone (aligned and probed): every row within
    # the default accuracy, 1e-4 of its state's size
    model = ContactModel(mu=mu, **ASSEMBLIES[name], **extra)
    rng = np.random.default_rng(sum(map(ord, name)) + len(extra))
    for n, folder in ((5, "batch"), (1, "one")):
        s = _random_states(rng, n, model)
        scene = Collision(model, v_n=s[:, 0], v_t=s[:, 1], omega=s[:, 2] / model.r, v_s=s[:, 3],
                          omega_s=s[:, 4] / model.r, omega_n=s[:, 5] / model.r)
        table = run_scene(scene, tmp_path / folder, record=False).table
        assert (table["status"] == "ok").all() and table["error"].max() <= 1e-4


@pytest.mark.slow
@pytest.mark.lammps
@pytest.mark.parametrize("name, mu, state", [
    ("hertz tsuji mindlin", 0.1, (-0.5, 1.0, 0.3)),  # slides at first touch, pushing along the slip
    ("hertz coeff_restitution mindlin_rescale", 0.05, (-0.5, 1.0, 0.3)),
    ("hooke viscoelastic", 0.3, (-0.8, 0.6, -0.3)),
    ("hertz velocity", 0.2, (-0.8, 0.6, -0.3)),
    ("hertz viscoelastic mindlin", 0.2, (-0.8, 0.6, -0.3)),
])
def test_converged_lammps_meets_the_reference(name, mu, state, tmp_path):
    # dt halved until the change is below 1e-7 (measured: LAMMPS within 5e-8 to 8e-8 of the
    # reference there, converging at first order); the reference within 1e-6
    model = ContactModel(mu=mu, **ASSEMBLIES[name])
    state = np.array(state)
    final = converged(model, state, tmp_path)
    assert np.abs(final - choose.predict(model, state[None, :])[0]).max() <= 1e-6


def _energy(model: ContactModel, state) -> float:
    return float(state[0] ** 2 + state[1] ** 2 + state[2] ** 2 / model.alpha)


def test_a_damped_displacement_history_pushes_along_the_slip_above_the_threshold():
    # tsuji, Hertz-Mindlin, mu = 0.5: below x_t |u'| = mu |v_n| the bounce loses energy like any
    # damped contact; above it the first slide pushes along the slip (u' grows) and the bounce
    # gains energy (1.2069 in, 1.2509 out at 1.4 mu). The /force variant, on the same contact,
    # does not.
    model = ContactModel(mu=0.5, **ASSEMBLIES["hertz tsuji mindlin"])
    below, above = (np.array([-0.9, f * 0.5 * 0.9, 0.0]) for f in (0.9, 1.4))
    assert _energy(model, oracle.bounce(model, *below).final) < _energy(model, below)
    assert _energy(model, oracle.bounce(model, *above).final) > _energy(model, above) * 1.03
    force = ContactModel(mu=0.5, **{**ASSEMBLIES["hertz tsuji mindlin"], "tangential": "mindlin/force"})
    assert _energy(force, oracle.bounce(force, *above).final) < _energy(force, above)


@pytest.mark.slow
@pytest.mark.lammps
def test_lammps_converges_to_the_push_along_the_slip(tmp_path):
    # at 1.4 times the threshold, at 1, 1/4, 1/16 and 1/64 of the fixed batch step: measured
    # 2.3e-4, 3.7e-5, 6.4e-6, 1.2e-6 (order ~1.3); each run closer, the last within 3e-6
    model = ContactModel(mu=0.5, **ASSEMBLIES["hertz tsuji mindlin"])
    u = np.array([0.7, 1.4 * 0.5]) * 0.9
    errors = []
    for k in range(4):
        scene = Collision(model, v_n=[-0.9, -0.9], v_t=u, omega=[0.0, 0.0], dt=7.42e-7 / 4**k)
        errors.append(float(run_scene(scene, tmp_path / f"run-{k}", record=False).table["error"].max()))
    assert all(b < a for a, b in zip(errors, errors[1:])) and errors[-1] <= 3e-6, errors


def test_a_3d_capped_mindlin_state_is_answered():
    # a slide that turns: the oracle in 3-D; its plane (v_s = r omega_s = 0) is the planar answer
    model = ContactModel(tangential="mindlin", mu=0.3, **MATERIAL)
    flat, turned = choose.predict(model, np.array([[-1.0, 0.5, 0.0, 0.0, 0.0, 0.2],
                                                   [-1.0, 0.5, 0.0, 0.4, -0.1, 0.2]]))
    assert flat[:3] == pytest.approx(choose.predict(model, np.array([[-1.0, 0.5, 0.0]]))[0], abs=1e-9)
    assert math.hypot(turned[3], turned[4]) > 0.0 and turned[5] == pytest.approx(0.2, abs=1e-15)
