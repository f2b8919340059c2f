"""Bad input is refused before LAMMPS starts, with the parameter, its value and the limit."""

import math
import warnings

from pathlib import Path

import pytest

from spinbounce import exact
from spinbounce.scenes.collision.deck import render_collision
from spinbounce.scenes.frozen.deck import render_frozen
from spinbounce.model.timestep import ACCURACY, SAFETY, SECOND_ORDER
from spinbounce.scenes.collision import Collision
from spinbounce.model.contact import ContactModel
from spinbounce.scenes.frozen import Frozen
from spinbounce.errors import PhysicsWarning, SceneError
from spinbounce.model.stability import stability_limit


@pytest.mark.parametrize(
    "kwargs, parameter, limit",
    [
        ({"m": 0.0}, "m", "> 0"),
        ({"m": -1.0}, "m", "> 0"),
        ({"r": 0.0}, "r", "> 0"),
        ({"kn": -10.0}, "kn", "> 0"),
        ({"kt": -1.0}, "kt", ">= 0"),
        ({"gamma_n": -0.1}, "gamma_n", ">= 0"),
        ({"gamma_t": -0.1}, "gamma_t", ">= 0"),
        ({"mu": -0.5}, "mu", ">= 0"),
        ({"alpha": 0.0}, "alpha", "(0, 1]"),
        ({"alpha": 1.5}, "alpha", "(0, 1]"),
        ({"kn": float("nan")}, "kn", "finite"),
        ({"gamma_n": 2 * math.sqrt(10.0)}, "gamma_n", "critical"),
    ],
)
def test_model_parameters_out_of_range(kwargs, parameter, limit):
    with pytest.raises(SceneError) as info:
        ContactModel(**kwargs)
    assert info.value.parameter == parameter
    message = str(info.value)
    assert message.startswith(f"{parameter} = ")
    assert limit in message


def test_alpha_above_shell_warns_about_phantom_mass():
    with pytest.warns(PhysicsWarning, match="phantom"):
        ContactModel(alpha=0.8)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        ContactModel(alpha=2 / 3)  # the thin shell itself is fine


def test_tunnelling_speed_is_refused_with_the_limit():
    # facts: with kn = 10, r = 0.5 the centre reaches the wall for |v_n| > 1.58
    limit = 0.5 / math.sqrt(1 / 10)
    Collision(ContactModel(), v_n=-0.999 * limit, v_t=0.0, omega=0.0)
    with pytest.raises(SceneError, match=r"v_n = -1\.6.*below 1\.58114") as info:
        Collision(ContactModel(), v_n=-1.6, v_t=0.0, omega=0.0)
    assert info.value.parameter == "v_n"


def test_normal_damping_lowers_the_overlap_so_a_faster_sphere_is_allowed():
    model = ContactModel(gamma_n=3.0)
    assert exact.max_overlap(1.7, model.m, model.kn, model.gamma_n) < model.r
    Collision(model, v_n=-1.7, v_t=0.0, omega=0.0)


def test_sphere_must_move_towards_the_wall():
    with pytest.raises(SceneError, match="towards the wall"):
        Collision(ContactModel(), v_n=0.5, v_t=0.0, omega=0.0)


@pytest.mark.parametrize("bad_dt", [0.0, -1e-3])
def test_dt_must_be_positive(bad_dt):
    with pytest.raises(SceneError, match="dt = .*> 0"):
        Collision(ContactModel(), v_n=-1, v_t=0, omega=0, dt=bad_dt)


def test_dt_above_stability_limit_or_too_coarse_is_refused():
    model = ContactModel()
    w = math.sqrt(model.kn / model.m)  # undamped normal mode is the stiffest
    with pytest.raises(SceneError, match="stability limit 0.632456 of the normal mode"):
        Collision(model, v_n=-1, v_t=0, omega=0, dt=1.1 * 2.0 / w)
    # stable, but 1.7 steps per half-period: refused, naming the coarsest dt accepted (pi/w/20)
    with pytest.raises(SceneError, match=rf"^dt = .*only 1\.75 steps per half-period: must be at most {math.pi / w / 20:.6g}"):
        Collision(model, v_n=-0.3, v_t=0, omega=0, dt=0.9 * 2.0 / w)
    assert Collision(model, v_n=-1, v_t=0, omega=0, dt=math.pi / w / 20).dt == math.pi / w / 20


def test_frozen_refuses_a_dt_collide_refuses():
    """The same rule (ContactModel.check_dt) for the frozen contact's slip mode: at z = 0.45,
    dt = 1 would be 1.7 steps per half-period (its one step erred by 0.32)."""
    model = ContactModel()
    with pytest.raises(SceneError, match=r"^dt = 1\.0: resolves the fastest contact mode with only 1\.68 steps"):
        Frozen(model, z=0.45, v_t=1.0, omega=0.0, t_end=1.0, dt=1.0)


@pytest.mark.parametrize("scene", [lambda dt: Collision(ContactModel(), v_n=-1, v_t=0, omega=0, dt=dt),
                                   lambda dt: Frozen(ContactModel(), z=0.45, v_t=1.0, omega=0.0, t_end=1.0, dt=dt)],
                         ids=["collision", "frozen"])
def test_a_dt_too_fine_for_the_step_cap_is_refused_naming_dt(scene):
    # 5e-324 (the smallest double) makes t_end/dt infinite: refused, not an overflow
    with pytest.raises(SceneError, match=r"^dt = 5e-324: needs inf steps .* more than the limit of 1e\+08"):
        scene(5e-324)
    with pytest.raises(SceneError, match=r"^dt = 1e-12: needs (9\.93e\+11|1e\+12) steps"):
        scene(1e-12)


def test_stiff_tangential_spring_sets_the_limit():
    model = ContactModel(kt=100.0, alpha=0.1)  # sqrt(Q) = 33 >> sqrt(kn/m) = 3.2
    limit, mode = model.dt_limit(frozen=False)
    assert mode == "slip"
    assert limit == pytest.approx(2 / math.sqrt(model.Q), rel=1e-9)


def test_damping_lowers_the_stability_limit():
    undamped = stability_limit(3.0)
    assert undamped == pytest.approx(2 / 3.0, rel=1e-9)
    assert stability_limit(3.0, c=50.0) < 0.1 * undamped
    # pure damping (no spring): the explicit step is stable only below dt = 2/c
    assert stability_limit(0.0, c=5.0) == pytest.approx(0.4, rel=1e-9)


def test_coarse_dt_is_refused():
    with pytest.raises(SceneError, match="^dt = 0.1: resolves the fastest contact mode with only 9.93 steps"):
        Collision(ContactModel(), v_n=-1, v_t=0, omega=0, dt=0.1)


def test_default_dt_puts_contact_end_mid_step():
    scene = Collision(ContactModel(), v_n=-1, v_t=1, omega=0)
    steps = scene.model.tau / scene.dt
    assert steps - math.floor(steps) == pytest.approx(0.5, abs=1e-9)
    # the second-order estimate meets half the target, and the step is no finer than that asks
    w_dt = math.sqrt(10.0) * scene.dt
    assert SECOND_ORDER * w_dt**2 <= SAFETY * ACCURACY < 1.05 * SECOND_ORDER * w_dt**2
    assert scene.nsteps > steps  # the run ends after the contact does


def test_default_dt_follows_the_fastest_mode():
    soft = Collision(ContactModel(), v_n=-1, v_t=0, omega=0)
    stiff = Collision(ContactModel(kt=40.0, alpha=0.1), v_n=-1, v_t=0, omega=0)
    # sqrt(Q) = 21 vs sqrt(kn/m) = 3.2, and the slip turns sqrt(Q) tau/pi = 6.6 half-periods in one
    # contact, each adding its phase error: 6.6 * sqrt(6.6) = 17 times more steps per contact
    w = math.sqrt(stiff.model.Q)
    expected = w / math.sqrt(10.0) * math.sqrt(w * stiff.model.t_exit / math.pi)
    assert soft.dt / stiff.dt == pytest.approx(expected, rel=2e-2)  # 2e-2: each dt is rounded mid-step


@pytest.mark.parametrize("z", [0.0, -0.1, 0.5, 0.7])
def test_frozen_height_must_be_in_contact(z):
    with pytest.raises(SceneError, match=r"z = .*\(0, r\)"):
        Frozen(ContactModel(), z=z, v_t=1, omega=0, t_end=1)


def test_frozen_run_ends_on_a_dump_frame():
    scene = Frozen(ContactModel(), z=0.1, v_t=1, omega=0, t_end=1.0, dt=1e-3, every=7)
    assert scene.nsteps % 7 == 0 and scene.nsteps * scene.dt >= 1.0


def test_sequences_must_match_and_scalars_broadcast():
    scene = Collision(ContactModel(), v_n=[-1, -0.5], v_t=0.3, omega=[0, 1])
    assert scene.v_t.tolist() == [0.3, 0.3]
    with pytest.raises(ValueError, match="read-only"):  # a scene's states are its own: immutable
        scene.v_n[0] = -2.0
    with pytest.raises(SceneError, match="lengths"):
        Collision(ContactModel(), v_n=[-1, -0.5], v_t=[0.3, 0.2, 0.1], omega=0)
    with pytest.raises(SceneError, match="number"):
        Collision(ContactModel(), v_n="fast", v_t=0, omega=0)


def _commands(deck_text: str) -> str:
    """The deck without its comments: what LAMMPS executes."""
    return "\n".join(line.split("#")[0] for line in deck_text.splitlines())


def test_decks_hold_only_what_the_scene_needs():
    text = render_collision(Collision(ContactModel(), v_n=-1, v_t=1, omega=0)).text
    for stage in ("1. setup", "2. initial state", "3. model", "4. output", "5. run"):
        assert f"# ---- {stage}" in text
    plain = _commands(text)
    assert "nve/sphere" in plain and "rigid" not in plain
    for absent in ("damping", "gravity", "pair_style", "setforce"):
        assert absent not in plain
    damped = _commands(render_collision(Collision(ContactModel(gamma_t=0.5), v_n=-1, v_t=1, omega=0)).text)
    assert "damping velocity" in damped
    rigid = _commands(render_frozen(Frozen(ContactModel(alpha=0.1))).text)
    assert "fix             motion all rigid single infile bodies.txt" in rigid
    assert "setforce NULL NULL 0.0" in rigid


def test_missing_template_value_is_an_error():
    import jinja2

    import spinbounce.scenes.collision as collision
    from spinbounce.lammps.decks import render_template

    with pytest.raises(jinja2.UndefinedError):
        render_template(Path(collision.__file__).parent, "collision.lmp.j2")
