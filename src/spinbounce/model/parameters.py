"""The contact model and the initial state, declared once.

Each :class:`Parameter` says what a number means, its unit, its default, the range
accepted and why, how a user gives it (command-line flag, scene-file key, Python keyword:
all the same name), whether a sweep can vary it, its Parquet column and whether it
changes a collision's outcome (and so separates fit groups). Everything else derives
from this table: :class:`~spinbounce.model.contact.ContactModel`'s fields and checks,
every command's options (:mod:`spinbounce.cli.options`), sweep scene files and flags,
the sweep table's columns, the fit's groups and the README's parameter table.
Units are LAMMPS's ``lj`` units: mass, length and time are whatever the user's are.
"""

from __future__ import annotations

from ..declaration import Parameter, finite_number, positive_number
from ..errors import SceneError
from ..laws import (damping_coefficients, damping_parameter, normal_coefficients, normal_parameter, style_parameter,
                    tangential_parameter)
from ..laws.tangential.linear_history import KT, MU
from ..laws.tangential.mindlin import MINDLIN_KT

__all__ = ["finite_number", "positive_number", "Parameter", "MODEL", "STATE", "POLAR", "velocity_from_polar", "velocity", "RUN", "SCENE", "STATE_B", "PAIR_SPHERE", "PAIR_ONLY", "ALL",
           "by_name", "SceneError", "markdown_table"]


#: The contact model (the fields of ContactModel, in order): the sphere, then the sub-models'
#: coefficients as each declares them (:mod:`spinbounce.laws`: normal, tangential, damping, the
#: cap), limit_damping and the law's choices.
MODEL: tuple[Parameter, ...] = (
    Parameter("m", "sphere mass", "mass", 1.0, low=0.0, low_open=True, why="a mass is positive",
              deck="set type 1 mass", aliases=("--mass",)),
    Parameter("r", "sphere radius", "length", 0.5, low=0.0, low_open=True, why="a radius is positive",
              deck="set type 1 diameter (2r)", aliases=("--radius",)),
    Parameter("alpha", "I/(m r^2): moment of inertia over m r^2 (2/5 for a solid sphere)", "1", 0.4,
              low=0.0, low_open=True, high=1.0, why="above 1 the mass would lie beyond the radius",
              deck="fix nve/sphere (alpha = 2/5) or fix rigid with a centre point"),
    *normal_coefficients(),
    KT,
    *damping_coefficients(),
    MU,
    MINDLIN_KT,
    Parameter("limit_damping", "never let the normal force pull (LAMMPS's limit_damping)", "-", False, kind="flag",
              deck="wall/gran ... limit_damping"),
    normal_parameter(),
    damping_parameter(),
    tangential_parameter(),
    style_parameter(),
)

#: The initial state of a collision (per sphere). Spins are angular velocities; a sweep may
#: give each as r times it instead (``r_omega``, ``r_omega_s``, ``r_omega_n``).
STATE: tuple[Parameter, ...] = (
    Parameter("v_n", "normal velocity (< 0: towards the wall)", "length/time", -1.0, high=0.0, high_open=True,
              why="a sphere moving away never meets the wall", changes_outcome=False, aliases=("--vn",)),
    Parameter("v_t", "tangential velocity (the paper's plane, LAMMPS's x)", "length/time", 1.0,
              changes_outcome=False, aliases=("--vt",)),
    Parameter("omega", "angular velocity in the paper's plane, anticlockwise positive (LAMMPS's -omega_y)",
              "1/time", 0.0, changes_outcome=False),
    Parameter("v_s", "second tangential velocity (3-D, LAMMPS's y)", "length/time", 0.0, changes_outcome=False,
              aliases=("--vs",)),
    Parameter("omega_s", "spin that rolls the sphere along v_s (3-D, LAMMPS's omega_x)", "1/time", 0.0,
              changes_outcome=False),
    Parameter("omega_n", "spin about the wall's normal (3-D, LAMMPS's omega_z)", "1/time", 0.0,
              changes_outcome=False),
)

#: The velocity by its size and direction instead of v_n and v_t (collide, theory, the API and, as
#: ranges, a sweep's states): the same names everywhere.
POLAR: tuple[Parameter, ...] = (
    Parameter("speed", "impact speed |v| (with angle_deg, instead of v_n and v_t)", "length/time", None, low=0.0,
              low_open=True, optional=True, why="a sphere at rest never meets the wall", changes_outcome=False,
              sweepable=False),
    Parameter("angle_deg", "incidence angle from the wall's normal, in degrees, positive for v_t > 0 (with speed)",
              "degree", None, low=-90.0, high=90.0, low_open=True, high_open=True, optional=True,
              why="at 90 degrees or more the sphere never meets the wall", changes_outcome=False, sweepable=False),
)


def velocity_from_polar(speed, angle_deg):
    """(v_n, v_t) of a sphere arriving at ``speed`` and ``angle_deg`` from the wall's normal (arrays too)."""
    import numpy as np

    angle = np.radians(angle_deg)
    return -speed * np.cos(angle), speed * np.sin(angle)


def velocity(v_n, v_t, speed, angle_deg, defaults) -> tuple:
    """(v_n, v_t): as given, or from ``speed`` and ``angle_deg`` (:func:`velocity_from_polar`),
    the one way or the other; what is not given takes ``defaults``."""
    if speed is None and angle_deg is None:
        return (defaults[0] if v_n is None else v_n), (defaults[1] if v_t is None else v_t)
    if speed is None or angle_deg is None:
        missing = "speed" if speed is None else "angle_deg"
        raise SceneError(missing, None, "give speed and angle_deg together (or v_n and v_t)")
    if v_n is not None or v_t is not None:
        raise SceneError("speed", speed, "give v_n and v_t, or speed and angle_deg, not both")
    speed, angle_deg = (p.check(value) for p, value in zip(POLAR, (speed, angle_deg), strict=True))
    return tuple(float(x) for x in velocity_from_polar(speed, angle_deg))


#: Sphere b's state at first touch in a pair (default: at rest), in sphere a's frame and sign: the
#: normal runs along the line of centres from b to a (the wall's normal), the spins are signed as
#: a's. One collision's (collide, theory, the API); a sweep samples a's state with b at rest.
STATE_B: tuple[Parameter, ...] = tuple(
    Parameter(f"{p.name}_b", f"pair: sphere b's {p.meaning.split(' (')[0]} at first touch, in a's frame and sign",
              p.unit, 0.0, changes_outcome=False, sweepable=False,
              deck="pairs.data: b's velocity and angular velocity")
    for p in STATE)

#: How a run is resolved: a step, or an accuracy to reach.
RUN: tuple[Parameter, ...] = (
    Parameter("dt", "timestep (default: from the timestep rule, model/timestep.py)", "time", None,
              low=0.0, low_open=True, optional=True, why="a step is positive", deck="timestep"),
    Parameter("tolerance", "accuracy to reach instead of a dt (Richardson extrapolation over a ladder of steps)",
              "length/time", None, low=0.0, low_open=True, optional=True, sweepable=False,
              why="an accuracy is positive"),
)

#: The scene: sphere a (the model's m, r, alpha) against the wall, or against a second free
#: sphere b with its own m_b, r_b and alpha_b (:mod:`spinbounce.scenes.pair`; b starts at rest,
#: the line of centres along LAMMPS's z, so a's state is the wall's). Not fields of
#: ContactModel: a wall scene has none of b's columns, and its rows and groups are unchanged.
SCENE: tuple[Parameter, ...] = (
    Parameter("scene", "what sphere a hits: the wall, or a second free sphere b at rest (pair granular)", "-",
              "wall", kind="choice", choices=("wall", "pair"), sweepable=False,
              deck="fix wall/gran | pair_style granular (spinbounce.scenes.pair.deck)"),
    Parameter("m_b", "pair: sphere b's mass", "mass", 1.0, low=0.0, low_open=True, why="a mass is positive",
              deck="pairs.data: b's density"),
    Parameter("r_b", "pair: sphere b's radius", "length", 0.5, low=0.0, low_open=True, why="a radius is positive",
              deck="pairs.data: b's diameter (2 r_b)"),
    Parameter("alpha_b", "pair: sphere b's I/(m r^2)", "1", 0.4, low=0.0, low_open=True, high=1.0,
              why="above 1 the mass would lie beyond the radius",
              deck="fix nve/sphere (alpha_b = 2/5) or fix rigid with a centre point"),
)
#: Sphere b's own parameters, and with its state every parameter that only a pair has.
PAIR_SPHERE = tuple(p.name for p in SCENE[1:])
PAIR_ONLY = PAIR_SPHERE + tuple(p.name for p in STATE_B)

ALL = MODEL + STATE + STATE_B + RUN + SCENE


def by_name(name: str) -> Parameter:
    return {p.name: p for p in ALL}[name]


def markdown_table(parameters=MODEL) -> str:
    """The README's parameter table, made from the declaration."""
    rows = ["| parameter (flag) | meaning | unit | default | accepted | sweepable |", "|---|---|---|---|---|---|"]
    for p in parameters:
        default = "none" if p.default is None else str(p.default).lower() if p.kind == "flag" else p.default
        accepted = p.range_text()
        meaning = p.meaning.replace("|", "\\|")  # a table cell may not hold a bare |
        rows.append(f"| `{p.name}` (`{p.flag}`) | {meaning} | {p.unit} | {default} | {accepted} "
                    f"| {'yes' if p.sweepable else 'no'} |")
    return "\n".join(rows)
