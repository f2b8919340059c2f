"""The default accuracy holds for every model the tool accepts, or the model is refused.

Each case is a contact model and a handful of states from head-on to grazing, spinning
and, for the 3-D cases, out of the plane. At the default settings (no dt, no tolerance)
every row must come within the default target, 1e-4 of the size of its initial state,
of the exact theory that applies, with status ``ok`` and no warning; or the scene must be
refused before LAMMPS starts, with a message that names the parameter and the limit.
The rows' errors are measured against theories exact to 1e-9 or better, so 1e-4 is the
target itself, not a loosened bound.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from spinbounce.model.contact import ContactModel
from spinbounce.model.parameters import SceneError
from spinbounce.scenes.collision import Collision
from spinbounce.model.timestep import ACCURACY
from spinbounce.pipeline import run_scene

pytestmark = pytest.mark.lammps

#: (v_n, v_t, omega): head-on, the paper's default, topspin, backspin, grazing (85 degrees
#: from the normal), a slow sphere spinning fast, and one fast at 45 degrees.
PLANE_STATES = ((-1.0, 0.0, 0.0), (-1.0, 1.0, 0.0), (-0.5, 0.5, 3.0), (-0.8, 0.4, -4.0),
                (-0.087155743, 0.996194698, 0.0), (-0.05, 0.0, 10.0), (-1.2, 1.2, 1.0))
#: 3-D states: the plane's, plus v_s, omega_s and omega_n.
SPACE_STATES = ((-1.0, 0.3, 1.0, 0.6, -1.0, 2.0), (-0.4, -1.0, 0.0, 1.0, 2.0, -3.0), (-0.9, 0.0, 0.0, 0.0, 0.0, 5.0))

ACCEPTED = {
    "paper": {},
    "magic ratio": {"kt": 10 * 0.4 / 1.4},
    "kt/kn = 1e-4": {"kt": 1e-3},
    "kt/kn = 10": {"kt": 100.0},
    "kt/kn = 1e4": {"kt": 1e5},
    "kt/kn = 1e5 (the slip turns 1900 times a contact)": {"kt": 1e6},
    "alpha = 0.01": {"alpha": 0.01},
    "alpha = 2/3": {"alpha": 2 / 3},
    "gamma_t = 0.01": {"gamma_t": 0.01},
    "gamma_t = 0.5": {"gamma_t": 0.5},
    "gamma_t = 1": {"gamma_t": 1.0},
    "gamma_t = 20 (overdamped slip)": {"gamma_t": 20.0},
    "gamma_n = 0.1": {"gamma_n": 0.1},
    "gamma_n = 3": {"gamma_n": 3.0},
    "gamma_n = 5.5 (restitution 4e-3)": {"gamma_n": 5.5},
    "gamma_n = 1, limit_damping": {"gamma_n": 1.0, "limit_damping": True},
    "gamma_n = gamma_t = 1": {"gamma_n": 1.0, "gamma_t": 1.0},
    "gamma_n = 3, gamma_t = 0.5, limit_damping": {"gamma_n": 3.0, "gamma_t": 0.5, "limit_damping": True},
    "mu = 1e-3": {"mu": 1e-3},
    "mu = 0.01": {"mu": 0.01},
    "mu = 0.1": {"mu": 0.1},
    "mu = 0.3": {"mu": 0.3},
    "mu = 1": {"mu": 1.0},
    "mu = 3": {"mu": 3.0},
    "mu = 10": {"mu": 10.0},
    "mu = 100": {"mu": 100.0},
    "mu = 1e3 (the cap acts only near the contact's ends)": {"mu": 1e3},
    "mu = 3e4": {"mu": 3e4},
    "mu = 1e5 (as LAMMPS scripts say 'no sliding')": {"mu": 1e5},
    "hertz, mu = 1e3": {"normal": "hertz", "mu": 1e3},
    "classic, mu = 1e3": {"wall": "classic", "mu": 1e3},
    "classic, mu = 1e5 (above the classic form's largest MU, 1e4)": {"wall": "classic", "mu": 1e5},
    "mu = 0 (frictionless)": {"mu": 0.0},
    "mu = 0.5, gamma_n = 1": {"mu": 0.5, "gamma_n": 1.0},
    "mu = 0.5, gamma_n = 1, limit_damping": {"mu": 0.5, "gamma_n": 1.0, "limit_damping": True},
    "mu = 10, gamma_t = 1": {"mu": 10.0, "gamma_t": 1.0},
    "mu = 0.3, gamma_n = gamma_t = 0.5": {"mu": 0.3, "gamma_n": 0.5, "gamma_t": 0.5},
    "mu = 0.3, alpha = 0.1": {"mu": 0.3, "alpha": 0.1},
    "mu = 0.3, kt/kn = 2": {"mu": 0.3, "kt": 20.0},
    "hertz": {"normal": "hertz"},
    "hertz, gamma_t = 0.5": {"normal": "hertz", "gamma_t": 0.5},
    "hertz, mu = 0.3": {"normal": "hertz", "mu": 0.3},
    "hertz, kt/kn = 1": {"normal": "hertz", "kt": 10.0},
    "m = 3, r = 2, kn = 1000": {"m": 3.0, "r": 2.0, "kn": 1000.0},
}
ACCEPTED_3D = {
    "3-D paper": {},
    "3-D gamma_t = 0.5": {"gamma_t": 0.5},
    "3-D mu = 0.3": {"mu": 0.3},
    "3-D mu = 1e3": {"mu": 1e3},
    "3-D alpha = 0.1 (rigid)": {"alpha": 0.1},
    "3-D hertz": {"normal": "hertz"},
}
#: Refused before LAMMPS starts: (model, the parameter the message names, words it must say).
REFUSED = {
    "alpha = 1e-9": ({"alpha": 1e-9}, "dt", "steps"),
    "gamma_t = 1e6": ({"gamma_t": 1e6}, "dt", "steps"),
    "gamma_n at critical": ({"gamma_n": 2 * np.sqrt(10.0)}, "gamma_n", "critical"),
    "gamma_n = 6 (restitution 8e-5)": ({"gamma_n": 6.0}, "gamma_n", "restitution"),
    "kt/kn = 1e9": ({"kt": 1e10}, "dt", "steps"),
    "alpha = 1.5": ({"alpha": 1.5}, "alpha", "in (0, 1]"),
    "mu < 0": ({"mu": -0.1}, "mu", "not negative"),
}


def _states(rows, three_d: bool) -> dict:
    names = ("v_n", "v_t", "omega", "v_s", "omega_s", "omega_n")[: 6 if three_d else 3]
    return dict(zip(names, (list(column) for column in zip(*rows, strict=True)), strict=True))


def _run(tmp_path, params: dict, three_d: bool):
    model = ContactModel(**params)
    rows = SPACE_STATES if three_d else PLANE_STATES
    if model.normal == "hertz":  # below the Hertzian wall's tunnelling speed (1.0 here)
        rows = [(max(v_n, -0.8), *rest) for v_n, *rest in rows]
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # a warning at the default settings is a failure
        if model.alpha > 2 / 3 - 1e-12:
            warnings.simplefilter("ignore")  # alpha = 2/3 exactly is the thin shell: allowed, no phantom mass
        result = run_scene(Collision(model, **_states(rows, three_d)), tmp_path, atoms="library", record=False)
    return result


@pytest.mark.parametrize("name", list(ACCEPTED))
def test_default_accuracy_holds_in_the_plane(name, tmp_path):
    result = _run(tmp_path, ACCEPTED[name], three_d=False)
    table = result.table
    assert result.step.target == ACCURACY
    assert table["error"].max() <= ACCURACY, table[["v_n_initial", "v_t_initial", "r_omega_initial", "error"]]
    assert (table["status"] == "ok").all() and not result.warnings


@pytest.mark.parametrize("name", list(ACCEPTED_3D))
def test_default_accuracy_holds_in_3d(name, tmp_path):
    result = _run(tmp_path, ACCEPTED_3D[name], three_d=True)
    assert result.table["error"].max() <= ACCURACY
    assert (result.table["status"] == "ok").all() and not result.warnings


@pytest.mark.parametrize("name", list(REFUSED))
def test_out_of_reach_is_refused_before_lammps(name):
    params, parameter, words = REFUSED[name]
    with pytest.raises(SceneError) as info:
        Collision(ContactModel(**params), **_states(PLANE_STATES, three_d=False))
    assert info.value.parameter == parameter and words in info.value.limit


def test_the_matrix_has_at_least_forty_cases():
    assert len(ACCEPTED) + len(ACCEPTED_3D) + len(REFUSED) >= 40


def test_rows_a_probe_missed_are_probed_again_but_a_sweeps_chunk_keeps_its_groups_step(tmp_path):
    """mu = 3e4: a probe of the first states may choose a step that other states miss; a scene probed on
    its own rows is probed again on those that erred and rerun within the target, while a scene given
    its group's probe states (a sweep's chunk: every chunk of a group shares one step) keeps that step
    and reports its rows. A grazing row, whose error is double precision's at any step, is not re-probed."""
    model = ContactModel(mu=3e4)
    easy = [(-1.0, 0.0, 0.0)] * 4
    hard = [(-0.05, 3.0, 3.0), (-0.02, 3.0, -3.0), (-0.01, -2.5, 4.0)]
    scene = Collision(model, **_states(easy + hard, three_d=False))
    own = run_scene(scene, tmp_path / "own", atoms="library", record=False)
    assert own.table["error"].max() <= ACCURACY and (own.table["status"] == "ok").all()
    shared = run_scene(scene, tmp_path / "shared", atoms="library", record=False,
                       probe_states=Collision(model, **_states(easy, three_d=False)))
    assert shared.step.method == "probe" and shared.scene.dt >= own.scene.dt
    grazing = Collision(ContactModel(mu=0.5), **_states([(-1.0, 0.3, 0.0), (-3e-12, 0.0, 0.0)] * 3, three_d=False))
    result = run_scene(grazing, tmp_path / "grazing", atoms="library", record=False)
    assert set(result.table["status"]) == {"ok", "grazing"}
