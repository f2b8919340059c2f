"""One model, every entry point: flags, scene files, 3-D, theory and fit agree.

One model, every entry point: flags and scene files give the same sweep, 3-D from the
command line, the theory command for a capped contact, the fit that claims a matrix only
where one applies, and the refusals a user meets before anything runs.
"""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from spinbounce.cli import main
from spinbounce.model.contact import ContactModel
from spinbounce.scenes.collision import Collision
from spinbounce.exact import choose

SCENE = """seed = 3
[model]
mu = 0.3
kt_over_kn = 0.2
[states]
n = 40
v_n = [-1.2, -0.2]
v_t = [-1.5, 1.5]
r_omega = [-1.0, 1.0]
"""
FLAGS = ["--n", "40", "--seed", "3", "--mu", "0.3", "--kt-over-kn", "0.2", "--vn", "-1.2", "-0.2",
         "--vt", "-1.5", "1.5", "--r-omega", "-1.0", "1.0", "--workers", "1"]


def _exit(argv) -> int:
    try:
        return main(argv)
    except SystemExit as exc:
        return exc.code


@pytest.mark.lammps
def test_a_sweep_from_flags_equals_the_same_sweep_from_a_scene_file(tmp_path, capsys):
    scene = tmp_path / "scene.toml"
    scene.write_text(SCENE)
    assert main(["sweep", str(scene), "--out", str(tmp_path / "file"), "--workers", "1"]) == 0
    assert main(["sweep", "--out", str(tmp_path / "flags"), *FLAGS]) == 0
    capsys.readouterr()
    keys = ["group", "index"]
    by_file = pd.read_parquet(tmp_path / "file" / "chunks").sort_values(keys).reset_index(drop=True)
    by_flags = pd.read_parquet(tmp_path / "flags" / "chunks").sort_values(keys).reset_index(drop=True)
    pd.testing.assert_frame_equal(by_file, by_flags)  # to the last bit, the digest label included


def test_flags_beside_a_scene_file_are_refused_by_name(tmp_path, capsys):
    scene = tmp_path / "scene.toml"
    scene.write_text(SCENE)
    assert _exit(["sweep", str(scene), "--out", str(tmp_path / "o"), "--alpha", "0.3", "--n", "25"]) == 2
    err = capsys.readouterr().err
    assert "--n, --alpha" in err and "scene file is the whole sweep" in err


@pytest.mark.lammps
def test_collide_runs_a_3d_collision_from_flags(tmp_path, capsys):
    argv = ["collide", "--json", "--out", str(tmp_path / "c"), "--vn", "-0.8", "--vt", "0.3", "--omega", "1",
            "--vs", "-0.5", "--omega-s", "2", "--omega-n", "3", "--mu", "0.4"]
    assert main(argv) == 0
    report = json.loads(capsys.readouterr().out)
    assert set(report["lammps"]) >= {"v_n", "v_t", "r_omega", "v_s", "r_omega_s", "r_omega_n"}
    scene = Collision(ContactModel(mu=0.4), v_n=-0.8, v_t=0.3, omega=1.0, v_s=-0.5, omega_s=2.0, omega_n=3.0)
    expected = scene.predicted()[0]
    theory = np.array([report["theory"][k] for k in ("v_n", "v_t", "r_omega", "v_s", "r_omega_s", "r_omega_n")])
    assert np.abs(theory - expected).max() < 1e-12  # the same theory, asked through the command
    assert report["theory_kind"] == "coulomb" and report["error_estimate"] <= 1e-4 and report["status"] == "ok"


def test_theory_of_a_capped_contact_gives_an_outcome_or_says_why_there_is_no_matrix(capsys):
    assert main(["theory", "--mu", "0.1", "--json"]) == 0
    report = json.loads(capsys.readouterr().out)
    assert report["matrix"] is None and "not linear in the initial state" in report["why_no_matrix"]
    assert main(["theory", "--mu", "0.1", "--vn", "-1", "--vt", "1.8", "--romega", "0.2", "--json"]) == 0
    report = json.loads(capsys.readouterr().out)
    expected = choose.predict(ContactModel(mu=0.1), np.array([[-1.0, 1.8, 0.2]]))[0]
    assert np.array(list(report["theory"].values())) == pytest.approx(expected, abs=1e-15)
    # gross slip: the spring's rate kt u'(0) = 2 beats the cap's mu kn |v_n| = 1 from first touch,
    # and the slip (2, falling by (1 + 1/alpha) 0.2 = 0.7) never stops: the tangential impulse is
    # mu (1 + e) m |v_n| = 0.2 exactly, not the uncapped matrix's
    assert report["theory"]["v_t"] == pytest.approx(1.6, abs=1e-12)


def _json_tail(capsys) -> list[dict]:
    out = capsys.readouterr().out
    return json.loads(out[out.index("[\n"):])


@pytest.mark.lammps
def test_fit_claims_no_matrix_for_a_sliding_group(tmp_path, capsys):
    out = tmp_path / "slide"
    assert main(["sweep", "--out", str(out), "--n", "300", "--workers", "1", "--mu", "0.3"]) == 0
    assert main(["fit", str(out), "--json"]) == 0
    (group,) = _json_tail(capsys)
    assert not group["has_matrix"] and "matrix" not in group and "no single matrix" in group["regime"]
    assert group["worst_relative_deviation"] <= 1e-4  # the default accuracy, per collision
    assert group["median_deviation"] <= group["worst_deviation"]


@pytest.mark.lammps
def test_fit_gives_the_frictionless_matrix_where_every_collision_sticks(tmp_path, capsys):
    """At kt/kn = alpha/(1+alpha) the spring and the cap rise and fall together; with
    |u'(0)| <= 0.6 < mu (kn/kt) |v_n| = 0.875 every contact sticks from first touch to the end,
    and the frictionless matrix applies exactly."""
    out = tmp_path / "stick"
    states = ["--vn", "-1.5", "-0.5", "--vt", "-0.3", "0.3", "--r-omega", "-0.3", "0.3"]
    assert main(["sweep", "--out", str(out), "--n", "300", "--workers", "1", "--mu", "0.5",
                 "--kt-over-kn", str(0.4 / 1.4), *states]) == 0
    assert main(["fit", str(out), "--json"]) == 0
    (group,) = _json_tail(capsys)
    assert group["has_matrix"] and group["regime"].startswith("sticks throughout")
    uncapped = ContactModel(kt=10 * 0.4 / 1.4).matrix()
    assert np.abs(np.array(group["matrix_theory"]) - uncapped).max() < 1e-15
    assert group["max_element_diff"] < 1e-4 and group["Omega_theory"] == pytest.approx(-2.0, abs=1e-12)


@pytest.mark.lammps
def test_a_sweep_flags_grazing_impacts_and_strict_fails_on_them(tmp_path, capsys):
    argv = ["sweep", "--out", str(tmp_path / "g"), "--n", "20", "--workers", "1", "--vn", "-1e-10", "-1e-11",
            "--vt", "0.5", "1", "--strict"]
    assert _exit(argv) == 1
    out = capsys.readouterr().out
    assert "20 grazing" in out
    rows = pd.read_parquet(tmp_path / "g" / "chunks")
    assert (rows["status"] == "grazing").all() and rows["error"].notna().all()


@pytest.mark.parametrize("argv, words", [
    (["frozen", "--z", "0.1", "--vt", "1", "--omega", "0", "--t-end", "1e9", "--out", "x"], "t_end = 1000000000.0"),
    (["collide", "--vn", "-1", "--vt", "1", "--omega", "0", "--gamma-t", "1e6"], "steps"),
])
def test_runs_out_of_reach_are_refused_with_their_cost_before_lammps(argv, words, capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert _exit(argv) == 2
    err = capsys.readouterr().err
    assert words in err and "Traceback" not in err and not (tmp_path / "spinbounce-runs").exists()


@pytest.mark.lammps
def test_no_cap_is_a_value_that_grouping_and_filtering_keep(tmp_path, capsys):
    # mu none is stored as inf (infinite friction): groupby("mu") has both groups, a fit's
    # table holds the same, and inf given anywhere means none
    import spinbounce

    rows = spinbounce.sweep(n=6, out=str(tmp_path / "s"), mu=[None, 0.3])
    sizes = rows.groupby("mu").size()
    assert sizes.to_dict() == {0.3: 6, float("inf"): 6}
    assert spinbounce.fit(rows).groupby("mu").size().to_dict() == {0.3: 1, float("inf"): 1}
    assert ContactModel(mu=float("inf")).mu is None
    assert main(["fit", str(tmp_path / "s"), "--mu", "inf"]) == 0 and "mu=None" in capsys.readouterr().out
    assert _exit(["theory", "--gamma-t", "inf"]) == 2 and "must be finite" in capsys.readouterr().err
