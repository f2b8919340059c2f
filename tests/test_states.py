"""A state is given as components or as speed and incidence angle, with the same names everywhere.

collide, theory, sweep and the API take ``speed`` and ``angle_deg`` (degrees from the wall's
normal, positive for v_t > 0) instead of ``v_n`` and ``v_t``; giving both ways, or half of one, is
refused naming the parameter; an unknown option's hint is the subcommand's own help.
"""

import math

import pytest

from spinbounce import api
from spinbounce.cli import main
from spinbounce.model.parameters import SceneError


def test_theory_takes_speed_and_angle_as_the_components_they_make():
    # 30 degrees from the normal at speed 2: v_n = -2 cos 30 = -sqrt(3), v_t = 2 sin 30 = 1 (to rounding)
    polar = api.theory(speed=2.0, angle_deg=30.0)
    components = api.theory(v_n=-math.sqrt(3.0), v_t=1.0)
    for name, value in components["theory"].items():
        assert polar["theory"][name] == pytest.approx(value, abs=1e-15)


@pytest.mark.parametrize("keywords, named", [({"speed": 1.0}, "angle_deg"), ({"angle_deg": 20.0}, "speed"),
                                             ({"speed": 1.0, "angle_deg": 20.0, "v_n": -1.0}, "speed"),
                                             ({"speed": 0.0, "angle_deg": 20.0}, "speed"),
                                             ({"speed": 1.0, "angle_deg": 90.0}, "angle_deg")])
def test_half_a_state_or_both_ways_is_refused_naming_the_parameter(keywords, named):
    with pytest.raises(SceneError) as info:
        api.theory(**keywords)
    assert info.value.parameter == named


@pytest.mark.lammps
def test_collide_takes_speed_and_angle_from_the_command_line(tmp_path, capsys):
    assert main(["collide", "--speed", "1", "--angle-deg", "30", "--json", "--out", str(tmp_path / "c")]) == 0
    initial = __import__("json").loads(capsys.readouterr().out)["initial"]
    assert initial["v_n"] == pytest.approx(-math.cos(math.radians(30.0)), abs=1e-15)
    assert initial["v_t"] == pytest.approx(0.5, abs=1e-15)


def test_theory_refuses_both_ways_on_the_command_line(capsys):
    with pytest.raises(SystemExit) as info:
        main(["theory", "--vn", "-1", "--speed", "1", "--angle-deg", "10"])
    assert info.value.code == 2 and "speed = 1.0" in capsys.readouterr().err


@pytest.mark.lammps
def test_the_apis_sweep_takes_the_states_a_scene_file_takes(tmp_path):
    rows = api.sweep(20, tmp_path / "s", speed=[0.5, 1.0], angle_deg=[-30.0, 30.0], omega=[-1.0, 1.0])
    speed = (rows["v_n_initial"] ** 2 + rows["v_t_initial"] ** 2) ** 0.5
    assert speed.between(0.5, 1.0).all() and (rows["status"] == "ok").all()
    with pytest.raises(TypeError, match="angle_deg"):  # an unknown keyword's error lists the states taken
        api.sweep(20, tmp_path / "t", angle=[0.0, 10.0])


@pytest.mark.parametrize("command", ["collide", "sweep", "theory", "fit"])
def test_an_unknown_options_hint_is_the_subcommands_help(command, capsys):
    with pytest.raises(SystemExit) as info:
        main([command, "x", "--no-such-option"] if command == "fit" else [command, "--no-such-option"])
    err = capsys.readouterr().err
    assert info.value.code == 2 and f"(see spinbounce {command} --help)" in err
