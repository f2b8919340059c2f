"""The pair as a scene kind: declared once, swept, fitted, and taken or refused by every command.

The pair as a scene kind: declared once, swept from flags and scene files, fitted with its regime,
and taken (or refused with the reason) by theory, collide and the Python API.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

import spinbounce
from spinbounce import exact
from spinbounce.cli import main
from spinbounce.fitting import fit_groups
from spinbounce.fitting_stream import fit_dataset
from spinbounce.model import parameters
from spinbounce.model.contact import ContactModel
from spinbounce.model.parameters import SceneError
from spinbounce.model.timestep import ACCURACY
from spinbounce.scenes.pair import QUANTITIES
from spinbounce.scenes.pair.kind import pair_contact, planar_matrix, sphere_b
from spinbounce.sweeps import SweepError, load_spec, read_results, run_sweep, spec_from_dict

#: Radii of 5e3 make the line of centres turn by ~1e-4 of what it does at r ~ 1 (eps ~ 1e-4):
#: the planar theory's model error is then below the accuracy and its matrix can be claimed.
LARGE = 5e3
PAIR_SCENE = """
seed = 2
chunk_size = 3
[model]
r = {r}
scene = "pair"
m_b = {m_b}
r_b = {r_b}
alpha_b = 0.25
[states]
n = 5
v_n = [-1.5, -0.5]
v_t = [{vt_low}, {vt_high}]
r_omega = [-1.0, 1.0]
"""


def _scene(tmp_path, name="pair.toml", r=LARGE, m_b=3.0, r_b=8e3, vt=(-1.0, 1.0)):
    path = tmp_path / name
    path.write_text(PAIR_SCENE.format(r=r, m_b=m_b, r_b=r_b, vt_low=vt[0], vt_high=vt[1]))
    return path


def test_scene_is_declared_with_range_flag_and_column():
    scene, m_b, r_b, alpha_b = parameters.SCENE
    assert scene.choices == ("wall", "pair") and scene.default == "wall" and not scene.sweepable
    assert [p.flag for p in (m_b, r_b, alpha_b)] == ["--m-b", "--r-b", "--alpha-b"]
    assert [p.column for p in (m_b, r_b, alpha_b)] == ["m_b", "r_b", "alpha_b"]
    for p in (m_b, r_b, alpha_b):
        assert parameters.by_name(p.name) is p and p.changes_outcome and p.why
        with pytest.raises(SceneError, match=p.name):
            p.check(-1.0)
    assert "scene" not in ContactModel.__dataclass_fields__  # the wall's model is unchanged


def test_a_wall_sweep_has_no_scene_keys_and_b_needs_a_pair(tmp_path):
    wall = spec_from_dict({"states": {"n": 3, "v_n": [-1.5, -0.1], "v_t": [-1.0, 1.0], "r_omega": [-1.0, 1.0]}})
    assert wall.scene == "wall" and not {"scene", "m_b", "r_b", "alpha_b"} & set(wall.groups[0])
    with pytest.raises(SweepError, match="m_b = 2.0: is sphere b's: give scene = pair"):
        spec_from_dict({"model": {"m_b": 2.0}, "states": wall.raw["states"]})


@pytest.mark.parametrize("model,needle", [({"scene": ["wall", "pair"]}, "one scene per sweep"),
                                          ({"alpha_b": 1.5}, "alpha_b = 1.5: must lie in"),
                                          ({"m_b": "heavy"}, "m_b = 'heavy': must be a number")])
def test_a_pair_sweep_refuses_what_the_pair_cannot_run(model, needle):
    states = {"n": 3, "v_n": [-1.5, -0.1], "v_t": [-1.0, 1.0], "r_omega": [-1.0, 1.0]}
    with pytest.raises(SweepError, match=needle):
        spec_from_dict({"model": {"scene": "pair", **model}, "states": states})
    with pytest.raises(SweepError, match="tolerance = 1e-05: is for the wall only"):
        spec_from_dict({"tolerance": 1e-5, "model": {"scene": "pair"}, "states": states})


def test_planar_matrix_becomes_the_walls_as_m_b_grows():
    # The pair's correction is O(m_a/m_b): 1e-14 at m_b = 1e14, so 1e-12 holds with room for rounding.
    model = ContactModel(alpha=0.3, r=0.7, kt=2.0)
    for three_d in (False, True):
        wall = exact.block_matrix(0.3, exact.Omega(10.0, 2.0, 0.3)) if three_d else model.matrix()
        for m_b, bound in ((1e6, 1e-5), (1e10, 1e-9), (1e14, 1e-12)):
            assert np.abs(planar_matrix(model, sphere_b(m_b, 0.4, 0.4), three_d) - wall).max() < bound


def test_pair_contact_names_what_a_pair_cannot_run():
    for model, needle in ((ContactModel(wall="classic"), "wall"),):
        with pytest.raises(SceneError, match=needle):
            pair_contact(model, sphere_b())  # against sphere b, as every caller gives it


@pytest.mark.lammps
def test_pair_sweep_from_flags_equals_the_scene_file_and_has_the_walls_columns(tmp_path):
    from_file = run_sweep(load_spec(_scene(tmp_path)), tmp_path / "file", workers=1, log=lambda *_: None)
    assert main(["sweep", "--scene", "pair", "--radius", str(LARGE), "--m-b", "3", "--r-b", "8e3",
                 "--alpha-b", "0.25", "--seed", "2", "--chunk-size", "3", "--n", "5", "--vn", "-1.5", "-0.5",
                 "--vt", "-1", "1", "--r-omega", "-1", "1", "--out", str(tmp_path / "flags"), "--workers", "1"]) == 0
    rows, flags = read_results(from_file), read_results(tmp_path / "flags")
    pd.testing.assert_frame_equal(rows, flags)  # the same sweep, to the bit and the digest
    spinbounce.sweep(n=3, out=tmp_path / "wall", v_t=(-1.0, 1.0), r_omega=(-1.0, 1.0))
    wall = read_results(tmp_path / "wall")
    assert set(wall.columns) <= set(rows.columns)
    assert set(QUANTITIES) <= set(rows.columns) and {"m_b", "r_b", "alpha_b", "planar_error"} <= set(rows.columns)
    assert (rows["scene"] == "pair").all() and (rows["theory"] == "pair_exact").all()
    # each row within the default accuracy of the exact reference (both spheres), status ok
    assert rows["error"].max() < ACCURACY and (rows["status"] == "ok").all()
    # momentum: b's final velocity is what a lost, as LAMMPS ran it (rounding of 8000 steps)
    for axis in "xyz":
        a0 = {"x": rows["v_t_initial"], "y": 0.0, "z": rows["v_n_initial"]}[axis]
        assert np.abs(rows[f"a_v{axis}"] - a0 + 3.0 * rows[f"b_v{axis}"]).max() < 1e-12


@pytest.mark.lammps
def test_fit_of_a_pair_sweep_reports_its_regime(tmp_path, capsys):
    # Large radii: the planar model error (3e-5 measured) is within the accuracy, so the
    # planar matrix is claimed and the fit lands on it within 2e-4 (LAMMPS's 1e-4 of the
    # speed plus the model's). Radii of 0.5 at the same speeds: a model error of 1e-2 and
    # more, so no matrix may be claimed.
    run_sweep(load_spec(_scene(tmp_path, "valid.toml")), tmp_path / "valid", workers=1, log=lambda *_: None)
    run_sweep(load_spec(_scene(tmp_path, "off.toml", r=0.5, r_b=0.8)), tmp_path / "off", workers=1,
              log=lambda *_: None)
    (valid,) = fit_groups(read_results(tmp_path / "valid"))
    assert valid["has_matrix"] and "planar matrix valid" in valid["regime"]
    b = sphere_b(3.0, 8e3, 0.25)
    want = planar_matrix(ContactModel(r=LARGE), b)
    assert np.abs(np.array(valid["matrix_theory"]) - want).max() < 1e-15
    assert valid["max_element_diff"] < 2e-4
    assert valid["Omega_theory"] == pytest.approx(float(np.cos(np.pi * np.sqrt(
        0.1 * 0.75 * (1 + 1 / 3 + 1 / 0.4 + 1 / 0.75))) - 1), abs=1e-12)  # cos(pi sqrt((kt/kn) m* K)) - 1
    (off,) = fit_groups(read_results(tmp_path / "off"))
    assert not off["has_matrix"] and "planar theory not exact here" in off["regime"] and "matrix" not in off
    assert off["worst_relative_deviation"] < ACCURACY  # LAMMPS still agrees with the exact reference
    streamed = fit_dataset(tmp_path / "valid")[0]
    assert streamed["regime"] == valid["regime"]
    assert np.abs(np.array(streamed["matrix"]) - np.array(valid["matrix"])).max() < 1e-12
    assert main(["fit", str(tmp_path / "off")]) == 0
    assert "planar theory not exact here" in capsys.readouterr().out


@pytest.mark.lammps
def test_a_dense_second_sphere_in_a_sweep_is_the_wall(tmp_path):
    # m_b = 1e8: the pair's own correction is 1e-8. Each row's a must be the wall's Eq. 18
    # outcome to the default accuracy (1e-4 of the speed), and the fit's matrix the wall's.
    path = _scene(tmp_path, m_b=1e8, r_b=LARGE)
    run_sweep(load_spec(path), tmp_path / "dense", workers=1, log=lambda *_: None)
    rows = read_results(tmp_path / "dense")
    names = ["v_n", "v_t", "r_omega"]
    initial, final = rows[[f"{s}_initial" for s in names]].to_numpy(), rows[[f"{s}_lammps" for s in names]].to_numpy()
    wall = ContactModel(r=LARGE).matrix()
    speed = np.linalg.norm(initial, axis=1)
    assert (np.abs(final - initial @ wall.T).max(axis=1) / speed).max() < 1e-4
    (fitted,) = fit_groups(rows)
    assert np.abs(np.array(fitted["matrix"]) - wall).max() < 1e-4


def test_theory_takes_the_pair_scene_or_refuses_b_without_it(capsys):
    assert main(["theory", "--scene", "pair", "--m-b", "3", "--r-b", "0.8", "--json"]) == 0
    import json

    report = json.loads(capsys.readouterr().out)
    assert report["Omega"] == pytest.approx(exact.Omega(10.0, 1.0, 0.4), abs=1e-14)  # equal alpha: the wall's
    with pytest.raises(SystemExit) as stop:
        main(["theory", "--m-b", "3"])
    assert stop.value.code == 2 and "m_b = 3.0: is sphere b's: give scene = pair" in capsys.readouterr().err
    assert main(["theory", "--scene", "pair", "--mu", "0.3"]) == 0  # no matrix, and why: as the wall's
    assert "no single scattering matrix: mu = 0.3: a capped pair has no matrix" in capsys.readouterr().out
    with pytest.raises(SystemExit):
        main(["pair", "--mass", "nan"])
    assert "'nan': must be finite" in capsys.readouterr().err


@pytest.mark.lammps
def test_collide_runs_the_pair_scene(tmp_path, capsys):
    assert main(["collide", "--scene", "pair", "--m-b", "2", "--r-b", "0.7", "--alpha-b", "0.3", "--vt", "0.3",
                 "--out", str(tmp_path), "--json"]) == 0
    import json

    row = json.loads(capsys.readouterr().out)
    assert row["m_b"] == 2.0 and row["alpha_b"] == 0.3 and row["error_estimate"] < ACCURACY
    report = spinbounce.collide(scene="pair", m_b=2.0, r_b=0.7, alpha_b=0.3, v_t=0.3, out=tmp_path / "api")
    assert report.error == pytest.approx(row["error_estimate"], rel=1e-9)
    # one shape for wall and pair: every key of the wall's report, in the same meaning
    assert main(["collide", "--vt", "0.3", "--out", str(tmp_path / "wall"), "--json"]) == 0
    wall = json.loads(capsys.readouterr().out)
    assert set(wall) - set(row) == set() and row["theory_kind"] == "pair_exact"
    for name, value in row["error"].items():
        assert value == pytest.approx(row["lammps"][name] - row["theory"][name], abs=1e-15), name
    assert row["theory"]["omega_b"] == pytest.approx(row["theory"]["r_omega_b"] / 0.7, rel=1e-15)
    size = max(abs(v) for k, v in row["error"].items() if k.startswith(("v_", "r_"))) / row["speed"]
    assert size == pytest.approx(row["error_estimate"], rel=1e-9)  # the wall's measure, over the pair's speed


@pytest.mark.lammps
def test_a_stiff_pair_s_first_probe_is_a_step_it_accepts(tmp_path):
    """A stiff Hertzian pair with a dashpot: the probe's first step (100 a contact) resolved its fastest mode with
    15 steps a half-period, below the 20 every step must have, and the default was refused; it starts from the
    coarsest accepted step now, and meets the default accuracy."""
    report = spinbounce.collide(scene="pair", v_n=-0.3351, v_t=-0.2881, omega=1.34, out=tmp_path,
                                contact="hertz/material 23110.0 18.92 0.2227 damping velocity tangential "
                                        "linear_history 4258.0 0.8431 1e12")
    assert report.error <= ACCURACY and report.status == "ok"


@pytest.mark.lammps
def test_a_wall_and_a_pair_collision_run_through_one_pipeline_and_one_record(tmp_path, monkeypatch):
    """The same probe, row checks and record writer serve both scenes: each call is counted."""
    import json

    from spinbounce import checks, pipeline, stepping

    calls = []
    for module, name in ((stepping, "tune"), (checks, "add_row_checks"), (pipeline, "write_record")):
        real = getattr(module, name)
        monkeypatch.setattr(module, name, lambda *a, _real=real, _name=name, **k: calls.append(_name) or _real(*a, **k))
    monkeypatch.setattr(pipeline, "tune", stepping.tune)  # the pipeline's own name for the probe
    # a capped contact is probed in both scenes (a damped one alone, the wall extrapolates a ladder
    # of runs): the outer run and its probes each check their rows
    wall = spinbounce.collide(v_n=-1.0, v_t=0.5, mu=0.3, out=tmp_path / "wall")
    pair = spinbounce.collide(v_n=-1.0, v_t=0.5, mu=0.3, scene="pair", out=tmp_path / "pair")
    assert calls.count("tune") >= 2 and calls.count("write_record") == 2
    assert calls.count("add_row_checks") >= 2 * 3  # two probes and the run, per scene
    records = [json.loads((tmp_path / kind / "result.json").read_text()) for kind in ("wall", "pair")]
    assert set(records[0]) == set(records[1])  # one writer: the same fields, whichever scene
    assert records[0]["scene"] == "collision" and records[1]["scene"] == "pair"
    assert wall.status == pair.status == "ok" and wall.step["method"] == pair.step["method"] == "probe"


def test_a_pair_with_limit_damping_has_no_planar_matrix_and_its_planar_column_cuts_the_force_too():
    # the closed planar theory lets the normal force pull; with limit_damping the planar column is the
    # exact reference with the line held, so a head-on pair (no turn) has no model error (0.027 when the
    # column took the closed form's restitution)
    report = spinbounce.theory(scene="pair", gamma_n=1.0, limit_damping=True)
    assert report["matrix"] is None and "limit_damping" in report["why_no_matrix"]
    outcome = spinbounce.theory(v_n=-1.0, scene="pair", gamma_n=1.0, limit_damping=True)
    assert outcome["planar_error"] < 1e-9
    assert outcome["theory"]["v_n"] != pytest.approx(spinbounce.theory(v_n=-1.0, scene="pair", gamma_n=1.0)[
        "theory"]["v_n"], abs=1e-3)  # the cut changes the rebound


def test_a_pairs_cached_outcome_cannot_be_changed_by_a_caller():
    from spinbounce.scenes.pair import Pair, PairContact

    outcome = PairContact(mu=0.3).solve(Pair(v_a=(1.0, 0.0, -1.0)))
    with pytest.raises(ValueError, match="read-only"):
        outcome.v_a[0] += 1.0
