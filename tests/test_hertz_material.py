"""hertz/material: Young's modulus and Poisson's ratio make LAMMPS's Hertzian stiffness, and LAMMPS converges to it.

LAMMPS's hertz/material against a wall (and between two spheres of one material) is its hertz
force with k = 4/3 E/(2 (1 - nu^2)); the sub-model (spinbounce.laws.normal.hertz_material)
says so, and the runs here show LAMMPS converging at second order to the Hertz reference
(spinbounce.exact.hertz) made with that k, which a stiffness off by a part in a thousand
could not do.
"""

import json

import numpy as np
import pandas as pd
import pytest

import spinbounce
from spinbounce.cli import main
from spinbounce.exact import hertz
from spinbounce.lammps.decks import wall_parameters
from spinbounce.model.contact import ContactModel
from spinbounce.model.parameters import SceneError
from spinbounce.scenes.collision import Collision
from spinbounce.pipeline import run_scene

E, NU = 1.0e4, 0.3


def material(**kw) -> ContactModel:
    return ContactModel(normal="hertz/material", youngs_modulus=E, poisson_ratio=NU, **kw)


def test_the_stiffness_is_lammps_k():
    # by hand: 4/3 * 1e4 / (2 * (1 - 0.09)) = 40000/5.46; with nu = 0, k = 2E/3
    assert material().kn == pytest.approx(40000.0 / 5.46, rel=1e-15)
    assert ContactModel(normal="hertz/material", youngs_modulus=3.0, poisson_ratio=0.0).kn == pytest.approx(2.0, rel=1e-15)


def test_the_deck_gives_the_material_not_the_stiffness():
    style = wall_parameters(material(kt=2.0))["style"]
    assert style.startswith("granular hertz/material 10000.0 0.0 0.3 tangential linear_history 2.0 0.0 ")


@pytest.mark.parametrize("given, name", [
    ({"youngs_modulus": E}, "youngs_modulus"),                                   # hooke takes kn, not E
    ({"normal": "hertz", "poisson_ratio": NU}, "poisson_ratio"),                 # nor does hertz
    ({"normal": "hertz/material", "youngs_modulus": E}, "poisson_ratio"),        # both are needed
    ({"normal": "hertz/material", "poisson_ratio": NU}, "youngs_modulus"),
    ({"normal": "hertz/material", "youngs_modulus": E, "poisson_ratio": NU, "kn": 5.0}, "kn"),
    ({"normal": "hertz/material", "youngs_modulus": E, "poisson_ratio": 0.6}, "poisson_ratio"),
    ({"normal": "hertz/material", "youngs_modulus": E, "poisson_ratio": -1.0}, "poisson_ratio"),
    ({"normal": "hertz/material", "youngs_modulus": -E, "poisson_ratio": NU}, "youngs_modulus"),
    ({"normal": "hertz/material", "youngs_modulus": E, "poisson_ratio": NU, "wall": "classic"}, "normal"),
])
def test_each_refusal_names_the_parameter(given, name):
    with pytest.raises(SceneError) as info:
        ContactModel(**given)
    assert info.value.parameter == name


def test_a_copy_derives_the_stiffness_anew():
    model = material()
    assert model.replace(youngs_modulus=2 * E).kn == pytest.approx(2 * model.kn, rel=1e-15)
    assert model.replace(kt=3.0).kn == model.kn
    assert ContactModel(**{f: getattr(model, f) for f in model.__dataclass_fields__}) == model  # from its columns


@pytest.mark.lammps
def test_lammps_converges_to_the_hertz_reference_at_second_order(tmp_path):
    # Steps t_c/(N + 1/2) put the contact's end mid-step, where the error is second order
    # (docs/explanation/numerics.md): measured 7.7e-5 at N = 400 and 1.9e-5 at N = 800, a
    # ratio of 4.0. kt = 2000 turns the slip through most of a half-period, so the outcome
    # moves with the contact time: a k off by 1e-3 moves t_c by 4e-4 and the tangential outcome
    # by ~1e-3, a floor no step could get under.
    model = material(kt=2000.0)
    t_c = float(hertz.contact_time(1.0, model.m, model.kn, model.r))
    errors = []
    for n in (400, 800):
        scene = Collision(model, v_n=-1.0, v_t=1.0, omega=0.0, dt=t_c / (n + 0.5))
        errors.append(float(run_scene(scene, tmp_path / str(n), record=False).table["error"].max()))
    assert errors[1] < 3e-5
    assert 3.5 < errors[0] / errors[1] < 4.5, errors


@pytest.mark.lammps
def test_every_front_end_takes_it(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    flags = ["--normal", "hertz/material", "--youngs-modulus", "1e4", "--poisson-ratio", "0.3"]
    assert main(["collide", *flags, "--vn", "-1", "--vt", "1", "--out", "c", "--json"]) == 0
    report = json.loads(capsys.readouterr().out)
    assert report["status"] == "ok" and report["error_estimate"] < 1e-4 and report["theory_kind"] == "hertzian"
    result = spinbounce.collide(v_n=-0.5, v_t=0.3, normal="hertz/material", youngs_modulus=E, poisson_ratio=NU,
                                out=str(tmp_path / "api"))
    assert result.status == "ok"
    (tmp_path / "s.toml").write_text('[model]\nnormal = "hertz/material"\nyoungs_modulus = 1e4\n'
                                      'poisson_ratio = [0.2, 0.3]\n[states]\nn = 8\nv_n = [-1.5, -0.1]\nv_t = [-1, 1]\n'
                                      'r_omega = [-1, 1]\n')
    assert main(["sweep", "s.toml", "--out", "s", "--workers", "1"]) == 0
    rows = pd.read_parquet(tmp_path / "s" / "chunks")
    groups = rows.groupby("poisson_ratio")
    assert len(groups) == 2 and (rows["status"] == "ok").all()
    assert np.allclose(groups["kn"].first().to_numpy(), [4e4 / 3 / (2 * 0.96), 4e4 / 3 / (2 * 0.91)], rtol=1e-15)
