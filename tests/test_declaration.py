"""The parameter declaration reaches every command, and every value is honoured.

For every declared model parameter and every command (theory, collide, frozen, sweep,
fit), the parameter is set to a value other than its default in a tiny case. The test
then checks that the value arrived (records, rows, groups) and that the result is what
the theory that applies predicts *with that value*; where that theory says the result
moves, it must have moved. A flag that a command accepted and ignored fails here.
"""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from spinbounce.cli import build_parser, main
from spinbounce.model import parameters
from spinbounce.model.contact import ContactModel
from spinbounce.scenes.collision import Collision
from spinbounce.scenes.frozen import Frozen
from spinbounce.exact import choose

_MATERIAL = {"normal": "hertz/material", "youngs_modulus": 1.0e4, "poisson_ratio": 0.3, "kt": 200.0}
#: One non-default setting per parameter, on a base where it matters: limit_damping cuts
#: a tensile normal force, which needs normal damping to exist.
CASES = {
    "m": ({}, {"m": 2.0}),
    "r": ({}, {"r": 0.6}),
    "alpha": ({}, {"alpha": 0.3}),
    "kn": ({}, {"kn": 20.0}),
    "kt": ({}, {"kt": 2.0}),
    "gamma_n": ({}, {"gamma_n": 0.5}),
    "gamma_t": ({}, {"gamma_t": 0.3}),
    "mu": ({}, {"mu": 0.2}),
    "limit_damping": ({"gamma_n": 0.5}, {"gamma_n": 0.5, "limit_damping": True}),
    "normal": ({}, {"normal": "hertz"}),
    "wall": ({}, {"wall": "classic"}),
    # hertz/material's own coefficients, on a stiff tangential spring whose outcome follows the
    # contact time (kt = 200: the slip turns through most of a half-period)
    "youngs_modulus": (_MATERIAL, {**_MATERIAL, "youngs_modulus": 2.0e4}),
    "poisson_ratio": (_MATERIAL, {**_MATERIAL, "poisson_ratio": 0.45}),
    # the damping sub-models' coefficients, each on a base of its own damping
    "damping": ({}, {"damping": "coeff_restitution", "e_n": 0.5}),
    "e_n": ({"damping": "tsuji", "e_n": 0.5}, {"damping": "tsuji", "e_n": 0.3}),
    "gamma_n_per_mass": ({"damping": "mass_velocity", "gamma_n_per_mass": 0.5},
                         {"damping": "mass_velocity", "gamma_n_per_mass": 1.0}),
    "x_t": ({"damping": "coeff_restitution", "e_n": 0.5}, {"damping": "coeff_restitution", "e_n": 0.5, "x_t": 1.0}),
    "gamma_n_per_mass_radius": ({"damping": "viscoelastic", "gamma_n_per_mass_radius": 0.5},
                                {"damping": "viscoelastic", "gamma_n_per_mass_radius": 1.5}),
    # the Mindlin sub-models on a Hookean force: a stiffness k_t of its own (no material for NULL)
    "tangential": ({}, {"tangential": "mindlin_rescale", "mindlin_kt": 100.0}),
    "mindlin_kt": ({"tangential": "mindlin", "mindlin_kt": 100.0}, {"tangential": "mindlin", "mindlin_kt": 300.0}),
}
STATE = {"v_n": -0.6, "v_t": 0.8, "omega": 0.5}
#: LAMMPS at the default step against the theory. Damped contacts converge at first order
#: and reach about 1e-3 of the impact speed (1 here) at the default step; ignoring any of
#: these parameters moves a result by more than MOVES, which is what this file tests.
LAMMPS_TOLERANCE = 2e-3
#: Where the theory moves a result by more than this, the command's result must move too.
MOVES = 1e-3


def _flags(values: dict) -> list[str]:
    out = []
    for name, value in values.items():
        p = parameters.by_name(name)
        out += [p.flag] if p.kind == "flag" else [p.flag, str(value)]
    return out


def test_the_declaration_covers_the_model_and_every_case():
    assert [p.name for p in parameters.MODEL] == [f.name for f in ContactModel.__dataclass_fields__.values()]
    assert set(CASES) == {p.name for p in parameters.MODEL}
    for p in parameters.MODEL:
        assert getattr(ContactModel(), p.name) == p.default


def test_every_model_parameter_is_an_option_of_every_model_command():
    parser = build_parser()
    commands = parser._subparsers._group_actions[0].choices
    for command in ("theory", "collide", "frozen", "sweep", "fit"):
        options = {s for a in commands[command]._actions for s in a.option_strings}
        for p in parameters.MODEL:
            assert p.flag in options, f"{command} lacks {p.flag}"


@pytest.mark.parametrize("name", list(CASES))
def test_theory_honours(name, capsys):
    base, changed = CASES[name]
    state_flags = ["--vn", str(STATE["v_n"]), "--vt", str(STATE["v_t"]), "--omega", str(STATE["omega"])]
    outputs = []
    for values in (base, changed):
        assert main(["theory", "--json", *state_flags, *_flags(values)]) == 0
        report = json.loads(capsys.readouterr().out)
        expected = Collision(ContactModel(**values), **STATE).predicted()[0]
        got = np.array(list(report["theory"].values()))
        assert np.abs(got - expected).max() < 1e-12  # the same function: only rounding differs
        outputs.append((got, expected, report["contact_time"]))
    (got0, exp0, t0), (got1, exp1, t1) = outputs
    model0, model1 = ContactModel(**base), ContactModel(**changed)
    if np.abs(exp1 - exp0).max() > MOVES:
        assert np.abs(got1 - got0).max() > MOVES
    # parameters that leave the final state alone (m) still change the contact time
    expected_times = (model0.contact_times(STATE["v_n"])[0], model1.contact_times(STATE["v_n"])[0])
    assert t0 == pytest.approx(expected_times[0], rel=1e-12) and t1 == pytest.approx(expected_times[1], rel=1e-12)
    assert np.abs(exp1 - exp0).max() > MOVES or abs(t1 - t0) > MOVES, f"{name} changes nothing in theory"


@pytest.mark.lammps
@pytest.mark.parametrize("name", list(CASES))
def test_collide_honours(name, capsys, tmp_path):
    base, changed = CASES[name]
    finals = []
    for k, values in enumerate((base, changed)):
        out = tmp_path / f"run{k}"
        state_flags = ["--vn", str(STATE["v_n"]), "--vt", str(STATE["v_t"]), "--omega", str(STATE["omega"])]
        assert main(["collide", "--json", "--out", str(out), *state_flags, *_flags(values)]) == 0
        report = json.loads(capsys.readouterr().out)
        record = json.loads((out / "result.json").read_text())
        for key, value in values.items():
            assert record["parameters"]["model"][key] == value  # the value reached the run
        expected = Collision(ContactModel(**values), **STATE).predicted()[0]
        lammps = np.array([report["lammps"][s] for s in ("v_n", "v_t", "r_omega")])
        assert np.abs(lammps - expected).max() < LAMMPS_TOLERANCE
        finals.append((lammps, expected))
    if np.abs(finals[1][1] - finals[0][1]).max() > MOVES:
        assert np.abs(finals[1][0] - finals[0][0]).max() > MOVES


@pytest.mark.lammps
@pytest.mark.parametrize("name", list(CASES))
def test_frozen_honours_or_refuses(name, capsys, tmp_path):
    base, changed = CASES[name]
    scene = {"z": 0.3, "v_t": 1.0, "omega": 0.5, "t_end": 1.0}
    scene_flags = ["--z", "0.3", "--vt", "1", "--omega", "0.5", "--t-end", "1"]
    ends = []
    for k, values in enumerate((base, changed)):
        run = tmp_path / f"r{k}"
        assert main(["frozen", "--out", str(run), *scene_flags, *_flags(values)]) == 0
        capsys.readouterr()
        table = pd.read_csv(run / "frozen.csv")
        meta = json.loads((run / "result.json").read_text())
        for key, value in values.items():
            assert meta["parameters"]["model"][key] == value
        frozen = Frozen(ContactModel(**values), **scene)
        vt, rw = frozen.predicted(table["t"].to_numpy())
        assert np.abs(table["v_t"] - vt).max() < LAMMPS_TOLERANCE and np.abs(table["r_omega"] - rw).max() < LAMMPS_TOLERANCE
        ends.append((table["r_omega"].iloc[-1], rw[-1]))
    # held at a fixed height, kn, gamma_n, limit_damping and the normal law leave the slip alone
    if abs(ends[1][1] - ends[0][1]) > MOVES:
        assert abs(ends[1][0] - ends[0][0]) > MOVES


def _exit_code(argv) -> int:
    try:
        return main(argv)
    except SystemExit as exc:
        return exc.code


@pytest.mark.lammps
@pytest.mark.parametrize("name", list(CASES))
def test_sweep_and_fit_honour(name, capsys, tmp_path):
    _, changed = CASES[name]
    out = tmp_path / "sweep"
    sweep_flags = ["--n", "6", "--vn", "-0.8", "-0.3", "--vt", "-1", "1", "--r-omega", "-1", "1", "--workers", "1"]
    assert main(["sweep", "--out", str(out), *sweep_flags, *_flags(changed)]) == 0
    capsys.readouterr()
    rows = pd.read_parquet(out / "chunks")
    model = ContactModel(**changed)
    for key, value in changed.items():
        assert (rows[key] == value).all()  # the Parquet column holds the value
    initial = rows[["v_n_initial", "v_t_initial", "r_omega_initial"]].to_numpy()
    theory = rows[["v_n_theory", "v_t_theory", "r_omega_theory"]].to_numpy()
    assert np.abs(theory - choose.predict(model, initial)).max() < 1e-12
    lammps = rows[["v_n_lammps", "v_t_lammps", "r_omega_lammps"]].to_numpy()
    assert np.abs(lammps - theory).max() < LAMMPS_TOLERANCE
    assert (rows["theory"] == choose.which(model).kind).all()
    value = changed[name]
    select = [parameters.by_name(name).flag] + ([] if value is True else [str(value)])
    if value is True:
        select.append("true")
    assert main(["fit", str(out), "--json", *select]) == 0
    (group,) = json.loads(capsys.readouterr().out)
    assert group["parameters"][name] == value and group["n"] == 6
    assert group["has_matrix"] == choose.which(model).has_matrix
