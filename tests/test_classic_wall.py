"""The classic wall (fix wall/gran hooke/history) as a model: LAMMPS against its exact theory.

The classic wall (``wall = classic``: ``fix wall/gran hooke/history``) as a first-class
model: LAMMPS's classic wall at the default settings against the exact theory of what this
build integrates (spinbounce.exact.classic), in collisions and in the frozen contact.

Tolerance: the default accuracy, 1e-4 of the size of the initial state; the classic theory
is solved to about 1e-9, so the whole margin is LAMMPS's step.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from spinbounce.cli import main
from spinbounce.exact import per_state
from spinbounce.model.contact import ContactModel
from spinbounce.model.parameters import SceneError
from spinbounce.scenes.collision import Collision
from spinbounce.scenes.frozen import Frozen
from spinbounce.model.timestep import ACCURACY
from spinbounce.pipeline import run_scene, run_series

pytestmark = pytest.mark.lammps

#: (v_n, v_t, omega): slow and fast, sliding and rolling, topspin and backspin.
STATES = ((-1.0, 1.0, 0.0), (-0.3, 0.5, 2.0), (-1.2, -0.4, -3.0), (-0.6, 1.5, 0.5))
MODELS = [dict(kt=kt, mu=mu) for kt in (1.0, 10 * 2 / 7, 5.0) for mu in (None, 0.3, 1.0)]


@pytest.mark.parametrize("params", MODELS, ids=lambda p: f"kt={p['kt']:.3g},mu={p['mu']}")
def test_classic_collisions_match_their_theory_at_the_defaults(params, tmp_path):
    model = ContactModel(wall="classic", **params)
    states = dict(zip(("v_n", "v_t", "omega"), (list(c) for c in zip(*STATES, strict=True)), strict=True))
    result = run_scene(Collision(model, **states), tmp_path, atoms="library", record=False)
    assert result.table["error"].max() <= ACCURACY, result.table[["error", "status"]]
    assert (result.table["status"] == "ok").all() and not result.warnings


def test_a_larger_sphere_and_a_faster_impact_change_the_classic_outcome(tmp_path):
    """The factor sqrt(r delta) makes Omega depend on r and v_n (the paper's depends on kt/kn only)."""
    finals = []
    for r, v_n in ((0.5, -1.0), (2.0, -1.0), (0.5, -0.2)):
        model = ContactModel(wall="classic", r=r)
        result = run_scene(Collision(model, v_n=v_n, v_t=1.0, omega=0.0), tmp_path / f"{r}-{v_n}",
                               atoms="library", record=False)
        assert result.table["error"].max() <= ACCURACY
        row = result.table.iloc[0]
        finals.append((row["v_t_lammps"] - 1.0) / (1.0 * 0.4 / 1.4))  # Omega as Eq. 19 defines it
    assert np.ptp(finals) > 0.1


@pytest.mark.parametrize("z", [0.45, 0.4, 0.3])
def test_the_classic_frozen_contact_oscillates_at_its_own_frequency(z, tmp_path):
    scene = Frozen(ContactModel(wall="classic"), z=z, v_t=1.0, omega=0.0, t_end=5.0)
    result = run_series(scene, tmp_path)
    assert result.max_abs_error <= ACCURACY
    uncapped = Frozen(ContactModel(), z=z, v_t=1.0, omega=0.0, t_end=5.0).predicted(result.table["t"].to_numpy())
    assert np.abs(result.table["v_t"] - uncapped[0]).max() > 0.1  # not the granular wall's Eq. 10


@pytest.mark.parametrize("z", [0.45, 0.4, 0.3])
def test_the_classic_frozen_contact_to_a_tolerance(z, tmp_path):
    """Held at one height the classic spring is the constant kt sqrt(r delta0): the error is smooth in
    dt and the ladder extrapolates it; every sample is within 1e-6 of the classic frozen theory."""
    from spinbounce.extrapolation import frozen_to_tolerance

    model = ContactModel(wall="classic")
    result = frozen_to_tolerance(model, z, 1.0, 0.0, 5.0, 1e-6, tmp_path)
    exact = np.column_stack(Frozen(model, z=z, v_t=1.0, omega=0.0, t_end=5.0).predicted(result.t))
    true = np.abs(result.values - exact).max(axis=1)
    assert true.max() <= 1e-6 and (true <= result.estimate.max(axis=1)).all()


def test_a_classic_sweep_from_flags_records_the_wall(tmp_path, capsys):
    argv = ["sweep", "--out", str(tmp_path / "s"), "--n", "12", "--workers", "1", "--wall", "classic", "granular",
            "--mu", "none", "0.5"]
    assert main(argv) == 0
    rows = pd.read_parquet(tmp_path / "s" / "chunks")
    assert set(rows["wall"]) == {"classic", "granular"} and (rows["status"] == "ok").all()
    assert set(rows.loc[rows["wall"] == "classic", "theory"]) == {"classic_wall"}
    assert "12 ok" not in capsys.readouterr().out  # 48 rows: four groups of 12


@pytest.mark.parametrize("params", [{}, {"mu": 0.3}, {"mu": 0.3, "gamma_n": 1.0, "gamma_t": 0.5}],
                         ids=["no cap", "cap", "cap and dashpots"])
def test_3d_classic_collisions_match_the_oracle_s_classic_cap_at_the_defaults(params, tmp_path):
    # out of the plane the classic form's theory is exact.oracle with its cap reset by kt alone (the same
    # sub-models inside granular; no cap: the form's largest, 1e4); measured 1.4e-5 to 4.4e-5 on one state each
    model = ContactModel(wall="classic", **params)
    states = {"v_n": [-1.0, -0.4, -1.3], "v_t": [0.5, -0.3, 1.0], "omega": [0.2, 1.5, -1.0], "v_s": [0.4, 0.2, -0.6],
              "omega_s": [-0.6, 0.0, 0.8], "omega_n": [0.3, -1.0, 0.0]}
    result = run_scene(Collision(model, **states), tmp_path, atoms="library", record=False)
    assert (result.table["status"] == "ok").all() and result.table["error"].max() <= ACCURACY


@pytest.mark.parametrize("params, parameter", [({"normal": "hertz"}, "normal"),
                                               ({"limit_damping": True, "gamma_n": 1.0}, "limit_damping")])
def test_what_the_classic_form_cannot_express_is_refused(params, parameter):
    with pytest.raises(SceneError) as info:
        ContactModel(wall="classic", **params)
    assert info.value.parameter == parameter


@pytest.mark.slow
def test_a_classic_sweep_to_a_tolerance_is_within_it_row_by_row(tmp_path):
    """Its error has no smooth expansion in dt (the spring kt sqrt(r delta) has an infinite slope
    at contact), so the tolerance is met by measurement against the classic theory: 24 states x
    kt/kn (0.1, 0.5) x mu (none, 0.3) = 96 rows, each within 1e-5 of it, its estimate that distance.
    1e-5 is ten times below the default accuracy: every group steps 9 to 50 times finer than its default
    step (measured), which is what the test exercises (1e-6 held too, at five times the cost: 100 s)."""
    from spinbounce.sweeps import read_results, run_sweep, spec_from_dict

    raw = {"seed": 5, "tolerance": 1e-5,
           "model": {"wall": "classic", "kt_over_kn": [0.1, 0.5], "mu": ["none", 0.3]},
           "states": {"n": 24, "v_n": [-1.5, -0.1], "v_t": [-2.0, 2.0], "r_omega": [-2.0, 2.0]}}
    run_sweep(spec_from_dict(raw), tmp_path / "out", workers=1, log=lambda *_: None)
    rows = read_results(tmp_path / "out")
    true = np.abs(rows[["v_n_error", "v_t_error", "r_omega_error"]].to_numpy()).max(axis=1)
    assert len(rows) == 96 and set(rows["theory"]) == {"classic_wall"}
    assert true.max() <= 1e-5 and (true <= rows["v_n_estimate"].to_numpy() * (1 + 1e-12)).all()


def test_a_tolerance_below_the_theory_s_own_accuracy_is_refused_before_any_run(tmp_path, capsys):
    argv = ["collide", "--wall", "classic", "--tolerance", "1e-9", "--out", str(tmp_path / "t")]
    try:
        code = main(argv)
    except SystemExit as exc:
        code = exc.code
    assert code == 2 and "tolerance" in capsys.readouterr().err and not (tmp_path / "t").exists()


def test_a_cap_above_the_classic_forms_largest_runs_at_it_against_its_own_theory():
    # LAMMPS refuses MU > 1e4 in the classic form: the deck writes 1e4, the theory keeps the mu asked for
    from spinbounce.lammps.decks import wall_parameters

    model = ContactModel(mu=1e5, wall="classic")
    assert wall_parameters(model)["mu"] == 1e4 and "mu = 100000 asked for" in wall_parameters(model)["comment"]
    assert per_state.classic_wall(model).mu == 1e5
