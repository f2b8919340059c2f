"""A batch of Hertzian speeds runs each sphere time-scaled to the longest contact, and meets the exact theory at 1e-4.

Sphere i runs in time units s_i = T*/T_i longer (mass m s_i^2, v and omega over s_i), so every
contact lasts T* in the deck and one step ends them all mid-step; its final v and omega are
LAMMPS's times s_i. Measured at the default step (kn = 10, |v_n| from 0.05 to 0.9, 64 random
states): 349 steps a collision, as many as the slowest speed alone (349; the fastest alone:
252), where the fixed first-order rule of a batch that cannot be scaled takes 146,359; the
largest row error 4.2e-5. Hertz-Mindlin (hertz/material, E = 1e4, nu = 0.3, |v_n| up to 0.8):
555 steps, as either end speed alone (the fixed rule: 242,696), error 2.0e-5. A dashpot
cannot be scaled per sphere: such a batch keeps the fixed rule, and its deck, like a
Hookean batch's, is the one rendered before the time scale.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from spinbounce import __version__
from spinbounce.errors import SceneError
from spinbounce.model.contact import ContactModel
from spinbounce.model.timestep import ACCURACY, MIN_STEPS_PER_HALF_PERIOD
from spinbounce.scenes.collision import HERTZ_STEPS_PER_HALF_PERIOD, Collision, scaled_contact_time
from spinbounce.scenes.collision.deck import render_collision

HERTZ = ContactModel(normal="hertz")
MINDLIN = ContactModel(normal="hertz/material", youngs_modulus=1e4, poisson_ratio=0.3, tangential="mindlin")
#: Decks rendered by the code before the time scale (tests/data), for the states below.
GOLDEN = Path(__file__).parent / "data" / "unscaled_decks.json"
GOLDEN_STATES = {"v_n": [-0.3, -0.7, -0.15], "v_t": [0.4, -1.0, 0.0], "omega": [1.0, 0.0, -2.0]}
GOLDEN_SCENES = {"hooke": (ContactModel(), "inline"), "hooke_rigid": (ContactModel(alpha=0.3), "inline"),
                 "hooke_rigid_data_file": (ContactModel(alpha=0.3), "data_file"),
                 "hertz_gamma_t": (ContactModel(normal="hertz", gamma_t=0.5), "inline")}


def _states(seed: int, n: int = 40, v_max: float = 0.9, three_d: bool = False, r: float = 0.5) -> dict:
    """n random states: |v_n| from 0.05 to v_max (both ends), |v_t|, |r omega| (and 3-D's) <= 2."""
    rng = np.random.default_rng(seed)
    states = {"v_n": -np.concatenate([[0.05, v_max], rng.uniform(0.05, v_max, n - 2)]),
              "v_t": rng.uniform(-2, 2, n), "omega": rng.uniform(-2, 2, n) / r}
    if three_d:
        states.update(v_s=rng.uniform(-2, 2, n), omega_s=rng.uniform(-2, 2, n) / r, omega_n=rng.uniform(-2, 2, n) / r)
    return states


def _run(scene, folder, atoms="library"):
    from spinbounce.pipeline import run_scene

    return run_scene(scene, folder, atoms=atoms, record=False)


def _accurate(result) -> None:
    """Every row within the default accuracy of its exact theory, at a probed, time-scaled step."""
    table = result.table
    assert result.scene.time_scaled and result.step.method == "probe"
    assert table["error"].max() <= ACCURACY, table["error"].max()
    assert (table["status"] == "ok").all() and not result.warnings


# ---------------------------------------------------------------------------
# The scale itself (no LAMMPS)
# ---------------------------------------------------------------------------

def test_each_sphere_runs_to_the_longest_contact():
    scene = Collision(HERTZ, **_states(1, 8))
    times = HERTZ.contact_times(scene.v_n)
    assert scene.deck_contact_time == float(times.max()) == scaled_contact_time(HERTZ, scene.v_n)
    assert np.allclose(scene.time_scales, times.max() / times, rtol=1e-15) and scene.time_scales.min() == 1.0
    assert np.allclose(scene.deck_contact_times, times.max(), rtol=1e-14)
    assert np.array_equal(scene.row_dt, scene.dt / scene.time_scales)
    # the deck's step ends the common contact mid-step, and the probe's scenes keep the scale
    n = scene.deck_contact_time / scene.dt - 0.5
    assert n == pytest.approx(round(n), abs=1e-9)
    assert scene.needs_probe()
    assert scene.rows([0, 3]).deck_contact_time == scene.deck_contact_time
    assert scene.at_step(scene.dt / 2).deck_contact_time == scene.deck_contact_time


def test_the_deck_gives_each_sphere_its_mass_and_slower_speeds_on_every_route():
    scene = Collision(HERTZ.replace(alpha=0.3), **_states(2, 4))
    s = scene.time_scales
    inline = render_collision(scene, "inline")
    for i in range(scene.n):  # half the body's mass m s^2 on the sphere, half on its point
        held = repr(float(0.5 * s[i]**2))
        assert f"set             atom {i + 1} mass {held}\n" in inline.text
        assert f"set             atom {i + 1 + scene.n} mass {held}\n" in inline.text
        assert f"vz {repr(float(scene.v_n[i] / s[i]))}" in inline.text
    assert "set             type 1 diameter 1.0\n" in inline.text and "Time-scaled" in inline.text
    library = render_collision(scene, "library")
    assert np.array_equal(library.atoms.mass, np.tile(0.5 * s**2, 2))
    assert np.array_equal(library.atoms.v[: scene.n, 2], np.asarray(scene.v_n) / s)
    bodies = np.loadtxt(library.files["bodies.txt"].splitlines()[1:], ndmin=2)
    assert np.allclose(bodies[:, 1], s**2, rtol=1e-15) and np.allclose(bodies[:, 5], 0.3 * 0.25 * s**2, rtol=1e-15)
    data = render_collision(scene, "data_file").files["spheres.data"]
    assert repr(float(s.max()**2 / 2)) in data  # the point's 'density' is its mass


def test_a_given_step_runs_every_sphere_at_it():
    """A dt of one's own runs as it is (what tests/test_hertz.py measures the first order with)."""
    scene = Collision(HERTZ, dt=1e-4, **_states(3, 6))
    assert scene.deck_contact_time is None and not scene.time_scaled and not scene.needs_probe()
    assert "set             type 1 diameter 1.0 mass 1.0\n" in render_collision(scene, "inline").text


def test_a_dashpot_cannot_be_time_scaled():
    damped = HERTZ.replace(gamma_t=0.5)
    assert scaled_contact_time(damped, [-0.1, -0.8]) is None
    with pytest.raises(SceneError, match="deck_contact_time.*dashpot"):
        Collision(damped, v_n=[-0.1, -0.8], deck_contact_time=3.0)


def test_a_scaled_step_is_checked_at_each_sphere_s_own_step():
    """The coarsest step takes MIN_STEPS_PER_HALF_PERIOD of the deck's fastest mode: each sphere's
    own step dt/s_i then resolves its own modes as finely."""
    scene = Collision(HERTZ, **_states(4, 6))
    coarsest = math.pi / MIN_STEPS_PER_HALF_PERIOD / max(w for w, _ in scene.deck_modes())
    assert scene.at_step(0.99 * coarsest).steps_per_half_period == pytest.approx(MIN_STEPS_PER_HALF_PERIOD / 0.99)
    with pytest.raises(SceneError, match="time-scaled by .*steps per half-period"):
        scene.at_step(1.01 * coarsest)


@pytest.mark.parametrize("name", list(GOLDEN_SCENES))
def test_decks_that_are_not_time_scaled_are_the_ones_rendered_before(name):
    model, atoms = GOLDEN_SCENES[name]
    expected = json.loads(GOLDEN.read_text())[name]
    deck = render_collision(Collision(model, **GOLDEN_STATES), atoms)
    version = f"spinbounce {__version__}"
    assert deck.text.replace(version, "spinbounce VERSION") == expected["text"]
    assert {k: v.replace(version, "spinbounce VERSION") for k, v in deck.files.items()} == expected["files"]
    assert "set             atom 1 mass" not in deck.text
    assert render_collision(Collision(model, **GOLDEN_STATES), "library").atoms.mass is None


# ---------------------------------------------------------------------------
# LAMMPS against the exact theory, at the default step
# ---------------------------------------------------------------------------

CASES = {
    "linear_history": (HERTZ, {}),
    "mindlin on hertz/material": (MINDLIN, {"v_max": 0.8}),
    "Coulomb cap mu = 0.3": (HERTZ.replace(mu=0.3), {}),
    "3-D": (HERTZ, {"three_d": True}),
}


@pytest.mark.lammps
@pytest.mark.parametrize("name", list(CASES))
def test_a_batch_of_speeds_meets_the_theory_at_the_default_step(tmp_path, name):
    model, states = CASES[name]
    _accurate(_run(Collision(model, **_states(11, **states)), tmp_path))


@pytest.mark.lammps
@pytest.mark.parametrize("alpha", [0.4, 0.3])  # fix nve/sphere, and the rigid body with its point
def test_every_route_runs_the_same_scaled_batch(tmp_path, alpha):
    scene = Collision(HERTZ.replace(alpha=alpha), **_states(12, 24))
    results = {atoms: _run(scene, tmp_path / atoms, atoms) for atoms in ("inline", "data_file", "library")}
    for result in results.values():
        _accurate(result)
        assert result.deck.rigid == (alpha != 0.4)
    finals = [r.table[["v_n_lammps", "v_t_lammps", "r_omega_lammps"]].to_numpy() for r in results.values()]
    # the same run: the data file's masses are densities (a few ulps), the rest is exact
    assert np.abs(finals[0] - finals[1]).max() < 1e-12 and np.array_equal(finals[0], finals[2])


@pytest.mark.lammps
def test_a_batch_costs_about_what_its_slowest_speed_costs(tmp_path):
    """349 steps a collision for |v_n| from 0.05 to 0.9 (kn = 10), the slowest speed's 349 alone
    (the fastest's 252); the fixed rule it replaced took 146,359 (module docstring)."""
    states = _states(7, 64)
    batch = _run(Collision(HERTZ, **states), tmp_path / "batch")
    _accurate(batch)
    alone = {v: _run(Collision(HERTZ, v_n=-v, v_t=states["v_t"][:8], omega=states["omega"][:8]),
                     tmp_path / f"alone-{v}").scene.nsteps for v in (0.05, 0.9)}
    assert batch.scene.nsteps <= 1.1 * alone[0.05] and batch.scene.nsteps <= 2 * alone[0.9]
    fixed = math.pi / HERTZ.fastest_rate(frozen=False, speed=0.9) / HERTZ_STEPS_PER_HALF_PERIOD
    assert batch.scene.nsteps < Collision(HERTZ, dt=fixed, **states).nsteps / 100


@pytest.mark.lammps
def test_a_batch_with_a_dashpot_keeps_the_fixed_rule(tmp_path):
    model = HERTZ.replace(gamma_t=0.5)
    scene = Collision(model, **_states(13, 16))
    assert not scene.time_scaled and not scene.needs_probe()
    assert scene.dt == math.pi / model.fastest_rate(frozen=False, speed=scene.speed) / HERTZ_STEPS_PER_HALF_PERIOD
    result = _run(scene, tmp_path)
    assert result.step.method != "probe" and result.scene.dt == scene.dt
    assert result.table["error"].max() <= ACCURACY and (result.table["status"] == "ok").all()


@pytest.mark.lammps
def test_a_sweep_scales_every_chunk_to_one_contact_and_records_each_row_s_step(tmp_path):
    """Every chunk and the group's probe states take the group's slowest possible contact T*, and
    the probe starts from the probe states' rule, so every chunk of the group runs one deck step
    (the group's dt column, which the fit groups on) that ends T* mid-step; each row's own step
    is dt/time_scale, time_scale = s_i = T*/T_i."""
    from spinbounce.sweeps import read_results, run_sweep, spec_from_dict
    from spinbounce.sweeps.cost import chunk_cost

    spec = spec_from_dict({"seed": 3, "chunk_size": 40, "model": {"normal": "hertz"},
                           "states": {"n": 100, "v_n": [-0.8, -0.1], "v_t": [-2.0, 2.0], "r_omega": [-2.0, 2.0]}})
    run_sweep(spec, tmp_path / "sweep", workers=1, log=lambda *_: None)
    rows = read_results(tmp_path / "sweep")
    assert len(rows) == 100 and rows["chunk"].nunique() == 3
    assert rows["error"].max() <= ACCURACY and (rows["status"] == "ok").all()
    t_star = float(HERTZ.contact_times(-0.1)[0])
    assert rows["time_scale"].to_numpy() == pytest.approx(
        t_star / HERTZ.contact_times(rows["v_n_initial"].to_numpy()), rel=1e-12)
    dt = rows["dt"].iloc[0]  # one deck step for the group, which ends T* mid-step
    assert (rows["dt"] == dt).all() and (rows["nsteps"] == rows["nsteps"].iloc[0]).all()
    assert (t_star / dt - 0.5) == pytest.approx(round(t_star / dt - 0.5), abs=1e-6)
    estimate = chunk_cost(spec, 0, 40).steps  # an upper estimate of the probed steps
    assert rows["nsteps"].max() <= estimate <= 2 * rows["nsteps"].min()
