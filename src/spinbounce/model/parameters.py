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

import math
from dataclasses import dataclass

from ..errors import SceneError

__all__ = ["finite_number", "positive_number", "Parameter", "MODEL", "STATE", "RUN", "SCENE", "PAIR_ONLY", "ALL",
           "by_name", "SceneError", "markdown_table"]


def finite_number(name: str, value) -> float:
    """``value`` as a finite float, or a :class:`SceneError` naming ``name``."""
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise SceneError(name, value, "must be a number") from None
    if not math.isfinite(number):
        raise SceneError(name, value, "must be finite")
    return number


def positive_number(name: str, value) -> float:
    number = finite_number(name, value)
    if number <= 0.0:
        raise SceneError(name, value, "must be > 0")
    return number


@dataclass(frozen=True)
class Parameter:
    """One declared parameter. ``kind`` is ``number``, ``choice`` or ``flag`` (true/false).

    ``low``/``high`` bound a number (``None``: unbounded), ``*_open`` excludes the bound;
    ``optional`` numbers may be ``None`` (for ``mu``: no Coulomb cap, the paper's model).
    """

    name: str
    meaning: str
    unit: str
    default: object
    kind: str = "number"
    low: float | None = None
    low_open: bool = False
    high: float | None = None
    high_open: bool = False
    why: str = ""
    #: The reason for the lower bound, where it differs from ``why`` (which then explains the upper).
    why_low: str = ""
    choices: tuple[str, ...] = ()
    optional: bool = False
    sweepable: bool = True
    changes_outcome: bool = True
    deck: str = ""
    #: Where the default step's accuracy stops holding (a LAMMPS run beyond it needs a given dt).
    default_step_high: float | None = None
    default_step_why: str = ""
    #: Command-line flags besides the name with dashes (``gamma_n`` -> ``--gamma-n``); the first is shown.
    aliases: tuple[str, ...] = ()

    @property
    def flags(self) -> tuple[str, ...]:
        return self.aliases + ("--" + self.name.replace("_", "-"),)

    @property
    def flag(self) -> str:
        """The command-line flag a user sees first."""
        return self.flags[0]

    @property
    def column(self) -> str:
        """The sweep table's column: the scene-file key itself."""
        return self.name

    def range_text(self) -> str:
        """The accepted values, as the README, ``--help`` and error messages say them."""
        if self.kind == "choice":
            return "one of " + ", ".join(self.choices)
        if self.kind == "flag":
            return "true or false"
        if self.low is not None and self.high is not None:
            text = (f"in {'(' if self.low_open else '['}{self.low:g}, {self.high:g}"
                    f"{')' if self.high_open else ']'}")
        elif self.low is not None:
            text = f"{'>' if self.low_open else '>='} {self.low:g}"
        elif self.high is not None:
            text = f"{'<' if self.high_open else '<='} {self.high:g}"
        else:
            text = "any finite number"
        return text + (" or none" if self.optional else "")

    def check_default_step(self, value) -> None:
        """Refuse a value beyond which a run at the default step misses the default accuracy."""
        if self.default_step_high is not None and value is not None and value > self.default_step_high:
            raise SceneError(self.name, value, f"must be <= {self.default_step_high:g} at the default step "
                                               f"({self.default_step_why})")

    def check(self, value, where: str | None = None):
        """``value`` as this parameter's type, or a :class:`SceneError` naming the limit."""
        name = where or self.name
        if self.kind == "flag":
            if not isinstance(value, bool):
                raise SceneError(name, value, "must be true or false")
            return value
        if self.kind == "choice":
            if value not in self.choices:
                raise SceneError(name, value, f"must be one of {', '.join(self.choices)}")
            return value
        if value is None and self.optional:
            return None
        return self._check_number(name, value)

    def _check_number(self, name: str, value) -> float:
        if isinstance(value, bool):
            raise SceneError(name, value, "must be a number")
        number = finite_number(name, value)
        below = self.low is not None and (number <= self.low if self.low_open else number < self.low)
        above = self.high is not None and (number >= self.high if self.high_open else number > self.high)
        if below or above:
            bound = self.range_text().removesuffix(" or none")
            why = self.why_low if below and self.why_low else self.why
            raise SceneError(name, value, f"must {'lie ' if bound.startswith('in ') else 'be '}{bound}"
                             + (f" ({why})" if why else ""))
        return number + 0.0  # -0.0 -> 0.0


#: The contact model (the fields of ContactModel, in order).
MODEL: tuple[Parameter, ...] = (
    Parameter("m", "sphere mass", "mass", 1.0, low=0.0, low_open=True, why="a mass is positive",
              deck="set type 1 mass", aliases=("--mass",)),
    Parameter("r", "sphere radius", "length", 0.5, low=0.0, low_open=True, why="a radius is positive",
              deck="set type 1 diameter (2r)", aliases=("--radius",)),
    Parameter("alpha", "I/(m r^2): moment of inertia over m r^2 (2/5 for a solid sphere)", "1", 0.4,
              low=0.0, low_open=True, high=1.0, why="above 1 the mass would lie beyond the radius",
              deck="fix nve/sphere (alpha = 2/5) or fix rigid with a centre point"),
    Parameter("kn", "normal spring constant (Hertz: LAMMPS's K, F = kn sqrt(r) delta^(3/2))", "force/length",
              10.0, low=0.0, low_open=True, why="a positive stiffness keeps the sphere out of the wall",
              deck="wall/gran granular hooke|hertz KN"),
    Parameter("kt", "tangential spring constant on the slip history (Cundall-Strack)", "force/length", 1.0,
              low=0.0, why="a negative spring would push the slip away", deck="tangential linear_history KT"),
    Parameter("gamma_n", "normal viscous damping (below critical 2 sqrt(m kn))", "mass/time", 0.0, low=0.0,
              why="negative damping would create energy", deck="granular ... ETA_N damping velocity"),
    Parameter("gamma_t", "tangential viscous damping on the slip rate", "mass/time", 0.0, low=0.0,
              why="negative damping would create energy", deck="tangential linear_history KT X_T (X_T ETA_N = gamma_t)"),
    Parameter("mu", "Coulomb friction coefficient, |F_t| <= mu |F_n|; none: the paper's model (no cap)", "1", None,
              low=0.0, optional=True, why="a friction coefficient is not negative", default_step_high=100.0,
              default_step_why="above 100 the cap acts only where F_n vanishes, at the contact's ends, and "
                               "LAMMPS's step converges there too slowly for the default accuracy: give none for "
                               "no cap, or a dt of your own (each row then reports its error)",
              deck="tangential linear_history ... MU (none: 1e12)"),
    Parameter("limit_damping", "never let the normal force pull (LAMMPS's limit_damping)", "-", False, kind="flag",
              deck="wall/gran ... limit_damping"),
    Parameter("normal", "normal force law: hooke (the paper's, F = kn delta) or hertz", "-", "hooke",
              kind="choice", choices=("hooke", "hertz"), deck="wall/gran granular hooke|hertz"),
    Parameter("wall", "the wall command: granular (the paper's model) or classic (wall/gran hooke/history, "
              "whose tangential spring this LAMMPS build scales by the contact radius)", "-", "granular",
              kind="choice", choices=("granular", "classic"),
              deck="wall/gran granular ... | wall/gran hooke/history KN KT GAMMA_N/m GAMMA_T/m MU 1"),
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

#: How a run is resolved: a step, or an accuracy to reach.
RUN: tuple[Parameter, ...] = (
    Parameter("dt", "timestep (default: from the timestep rule, model/timestep.py)", "time", None,
              low=0.0, low_open=True, optional=True, why="a step is positive", deck="timestep"),
    Parameter("tolerance", "accuracy to reach instead of a dt (Richardson extrapolation over a ladder of steps)",
              "length/time", None, low=0.0, low_open=True, optional=True, sweepable=False,
              why="an accuracy is positive"),
)

#: The scene: sphere a (the model's m, r, alpha) against the wall, or against a second free
#: sphere b with its own m_b, r_b and alpha_b (:mod:`spinbounce.pairs`; b starts at rest,
#: the line of centres along LAMMPS's z, so a's state is the wall's). Not fields of
#: ContactModel: a wall scene has none of b's columns, and its rows and groups are unchanged.
SCENE: tuple[Parameter, ...] = (
    Parameter("scene", "what sphere a hits: the wall, or a second free sphere b at rest (pair granular)", "-",
              "wall", kind="choice", choices=("wall", "pair"), sweepable=False,
              deck="fix wall/gran | pair_style granular (spinbounce.pairs.deck)"),
    Parameter("m_b", "pair: sphere b's mass", "mass", 1.0, low=0.0, low_open=True, why="a mass is positive",
              deck="pairs.data: b's density"),
    Parameter("r_b", "pair: sphere b's radius", "length", 0.5, low=0.0, low_open=True, why="a radius is positive",
              deck="pairs.data: b's diameter (2 r_b)"),
    Parameter("alpha_b", "pair: sphere b's I/(m r^2)", "1", 0.4, low=0.0, low_open=True, high=1.0,
              why="above 1 the mass would lie beyond the radius",
              deck="fix nve/sphere (alpha_b = 2/5) or fix rigid with a centre point"),
)
#: The scene parameters that only a pair has.
PAIR_ONLY = tuple(p.name for p in SCENE[1:])

ALL = MODEL + STATE + RUN + SCENE


def by_name(name: str) -> Parameter:
    for parameter in ALL:
        if parameter.name == name:
            return parameter
    raise KeyError(name)


def markdown_table(parameters=MODEL) -> str:
    """The README's parameter table, made from the declaration."""
    rows = ["| parameter (flag) | meaning | unit | default | accepted | sweepable |", "|---|---|---|---|---|---|"]
    for p in parameters:
        default = "none" if p.default is None else str(p.default).lower() if p.kind == "flag" else p.default
        accepted = p.range_text() + (f"; default step up to {p.default_step_high:g}" if p.default_step_high else "")
        meaning = p.meaning.replace("|", "\\|")  # a table cell may not hold a bare |
        rows.append(f"| `{p.name}` (`{p.flag}`) | {meaning} | {p.unit} | {default} | {accepted} "
                    f"| {'yes' if p.sweepable else 'no'} |")
    return "\n".join(rows)
