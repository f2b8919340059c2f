"""--contact: LAMMPS's granular words read into the model, the deck's words read back, refusals.

A contact line is what a LAMMPS user writes after ``fix wall/gran granular`` or in ``pair_coeff``.
spinbounce reads it with the registries that write its own decks (each sub-model's declared
coefficient order), so every deck spinbounce writes reads back into the model it came from.
"""

from __future__ import annotations

import json

import pytest

import spinbounce
from spinbounce.cli import main
from spinbounce.lammps.decks import wall_parameters
from spinbounce.laws.words import parse_contact
from spinbounce.model.contact import ContactModel
from spinbounce.model.parameters import SceneError
from spinbounce.sweeps import spec_from_dict

MATERIAL = {"normal": "hertz/material", "youngs_modulus": 1.0e4, "poisson_ratio": 0.3}


def test_the_issue_s_example_reads_into_validated_parameters():
    assert parse_contact("hertz/material 1e4 0.3 0.3 damping tsuji tangential mindlin NULL 1.0 0.5") == {
        "normal": "hertz/material", "youngs_modulus": 1.0e4, "poisson_ratio": 0.3, "damping": "tsuji",
        "e_n": 0.3, "x_t": 1.0, "tangential": "mindlin", "mindlin_kt": None, "mu": 0.5}


@pytest.mark.parametrize("values", [
    {},
    {"kt": 2.5, "gamma_n": 0.4, "gamma_t": 0.2, "mu": 0.3},
    {"gamma_n": 0.4, "limit_damping": True},
    {"damping": "mass_velocity", "gamma_n_per_mass": 0.8, "x_t": 0.7, "kn": 30.0},
    {"damping": "tsuji", "e_n": 0.5, "x_t": 0.5},
    {"damping": "coeff_restitution", "e_n": 0.3, "mu": 0.2},
    {"normal": "hertz", "kn": 2000.0, "gamma_t": 0.0},
    {**MATERIAL, "tangential": "mindlin_rescale/force"},
    {"tangential": "mindlin", "mindlin_kt": 30.0, "mu": 0.4},
    {"tangential": "linear_history_classic", "kt": 40.0},
])
def test_every_deck_spinbounce_writes_reads_back_into_its_model(values):
    # declare once: the deck's words and --contact's reading come from one coefficient order
    model = ContactModel(**values)
    words = wall_parameters(model)["style"]
    assert words.startswith("granular ")
    assert ContactModel(**parse_contact(words)) == model


@pytest.mark.parametrize("text, word", [
    ("hooke 10 0.5 rolling sds 1 2 3 tangential linear_history 1 0 0.3", "rolling"),
    ("hooke 10 0.5 tangential linear_history 1 0", "linear_history"),   # a coefficient missing
    ("hooke 10 x tangential linear_history 1 0 0.3", "x"),              # not a number
    ("hooke 10 nan tangential linear_history 1 0 0.3", "nan"),          # not finite
    ("hooke NULL 0.5 tangential linear_history 1 0 0.3", "NULL"),       # NULL only for mindlin's k_t
    ("hooke 10 0.5", "hooke 10 0.5"),                                   # LAMMPS needs a tangential
    ("hooke 10 0.5 tangential linear_history 1 0 0.3; shell rm -rf /", "0.3;"),
    ("hooke 10 0.5 tangential linear_history 1 0 0.3 heat area 1", "heat"),
    ("hooke 10 0.5 tangential linear_history 1 0 0.3 tangential linear_history 1 0 0.3", "tangential"),
    ("", ""),
])
def test_a_bad_line_is_refused_naming_the_word(text, word):
    with pytest.raises(SceneError) as info:
        parse_contact(text)
    assert info.value.parameter == "contact" and str(info.value.value) == word


def test_an_unknown_sub_model_is_refused_with_the_registered_ones():
    with pytest.raises(SceneError) as info:
        parse_contact("jkr 1 2 3 4 tangential linear_history 1 0 0.3")
    assert info.value.parameter == "normal" and "hertz/material" in str(info.value)


def test_the_cli_and_the_api_take_a_line_as_they_take_flags(capsys):
    line = "hooke 20 0.4 damping mass_velocity tangential linear_history 3 0.5 0.3"
    flags = ["--kn", "20", "--damping", "mass_velocity", "--gamma-n-per-mass", "0.4", "--x-t", "0.5", "--kt", "3",
             "--mu", "0.3"]
    state = ["--vn", "-0.8", "--vt", "0.6", "--json"]
    outputs = []
    for given in (["--contact", line], flags):
        assert main(["theory", *state, *given]) == 0
        outputs.append(json.loads(capsys.readouterr().out)["theory"])
    assert outputs[0] == outputs[1]
    assert spinbounce.theory(v_n=-0.8, v_t=0.6, contact=line)["theory"] == outputs[0]


def test_a_parameter_given_both_ways_is_refused_even_at_its_default(capsys):
    # --kn 10 is the default value, but the user typed it: the line's kn would silently win
    with pytest.raises(SystemExit):
        main(["theory", "--kn", "10", "--contact", "hooke 20 0 tangential linear_history 1 0 0.3"])
    assert "kn = 10.0: is given by contact too" in capsys.readouterr().err
    with pytest.raises(SceneError) as info:
        spinbounce.theory(kn=10.0, contact="hooke 20 0 tangential linear_history 1 0 0.3")
    assert info.value.parameter == "kn"


def test_a_sweep_takes_lines_each_a_group():
    spec = spec_from_dict({"states": {"n": 4, "v_n": [-1.0, -0.1], "v_t": [-1.0, 1.0], "r_omega": [-1.0, 1.0]}, "model": {
        "contact": ["hooke 10 0 damping velocity tangential linear_history 1 0 1e12",
                    "hooke 10 0.5 damping velocity tangential linear_history 2 0 1e12"],
        "alpha": [0.4, 0.3]}})
    groups = [spec.model(k) for k in range(4)]
    assert sorted((m.kt, m.gamma_n, m.alpha) for m, _ in groups) == [(1.0, 0.0, 0.3), (1.0, 0.0, 0.4),
                                                                       (2.0, 0.5, 0.3), (2.0, 0.5, 0.4)]


@pytest.mark.parametrize("values, name", [
    ({"contact": "hooke 10 0 tangential linear_history 1 -1 0.3"}, "contact"),   # X_T < 0
    ({"contact": "hooke 10 0 tangential linear_history 1 0 0.3", "wall": "classic"}, "wall"),
])
def test_what_a_line_cannot_mean_is_refused_by_name(values, name):
    with pytest.raises(SceneError) as info:
        spinbounce.theory(**values)
    assert info.value.parameter == name


def test_a_sweep_refuses_kt_over_kn_beside_a_line():
    from spinbounce.sweeps import SweepError

    with pytest.raises(SweepError, match="kt_over_kn"):
        spec_from_dict({"states": {"n": 4, "v_n": [-1.0, -0.1], "v_t": [-1.0, 1.0], "r_omega": [-1.0, 1.0]},
                        "model": {"contact": "hooke 10 0 tangential linear_history 2 0 0.3", "kt_over_kn": 0.5}})


@pytest.mark.lammps
def test_a_line_that_names_no_damping_is_lammps_s_viscoelastic(tmp_path):
    """LAMMPS constructs viscoelastic for a granular line without a damping word (it was read as the paper's
    velocity: v_n' 0.78 where LAMMPS gives 0.94). The deck spinbounce writes for the line, run once as written and
    once with its damping word taken out (the user's line), ends the same in LAMMPS."""
    from spinbounce.lammps.decks import prepare_run_dir
    from spinbounce.lammps.runner import run_deck
    from spinbounce.scenes.collision import Collision

    model = ContactModel(**parse_contact("hooke 10 0.5 tangential linear_history 1 0.5 1e12"))
    assert model.damping == "viscoelastic"
    finals = []
    for name, edit in (("written", lambda text: text), ("as-the-user-wrote", lambda text: text.replace(
            " damping viscoelastic", ""))):
        scene = Collision(model, v_n=-1.0, v_t=1.0, omega=0.0)
        deck = scene.render("data_file")
        path = prepare_run_dir(tmp_path / name, deck)
        text = path.read_text()
        assert edit(text) != text or name == "written"
        path.write_text(edit(text))
        columns = scene.read(run_deck(path), deck, tmp_path / name)
        finals.append([float(columns[f"{s}_lammps"][0]) for s in ("v_n", "v_t", "r_omega")])
    assert finals[0] == finals[1]
    velocity = ContactModel(gamma_n=0.5, gamma_t=0.25)  # the same coefficients as the paper's dashpots
    assert abs(finals[0][0] - float(Collision(velocity, v_n=-1.0, v_t=1.0, omega=0.0).predicted()[0, 0])) > 0.1


def test_a_line_that_names_no_damping_and_damps_nothing_is_the_paper_s_undamped_model():
    """ETA_N = 0: LAMMPS's viscoelastic dashpot is zero, as the paper's undamped model's (the decks spinbounce
    writes for it name no damping, and read back into it)."""
    assert ContactModel(**parse_contact("hooke 10 0 tangential linear_history 1 0.5 0.3")) == ContactModel(mu=0.3)
