"""One declared parameter: what a number means, its unit, default and accepted range, and why.

A :class:`Parameter` is the unit of every declaration in spinbounce: the sphere's and the
scene's (:mod:`spinbounce.model.parameters`) and each contact sub-model's own coefficients
(:mod:`spinbounce.laws`). Every front end derives its options, keys and columns from them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from .errors import SceneError

__all__ = ["Parameter", "finite_number", "positive_number"]


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
    #: Command-line flags besides the name with dashes (``gamma_n`` -> ``--gamma-n``); the first is shown.
    aliases: tuple[str, ...] = ()
    #: What a table holds for none: NaN (no value), or a number that means the same (mu: inf,
    #: since no cap is infinite friction), which grouping and filtering keep. Given as a value,
    #: that number is read as none.
    none_value: float = math.nan

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

    def to_column(self, value):
        """The value as a table holds it (none: :attr:`none_value`)."""
        return self.none_value if value is None else value

    def from_column(self, value):
        """A table's value as the model takes it (NaN, or :attr:`none_value`, is none)."""
        if isinstance(value, float) and (math.isnan(value) or value == self.none_value):
            return None
        return value

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
        if self.optional and (value is None or (isinstance(value, float) and value == self.none_value)
                              or (isinstance(value, str) and value.strip().lower() == "none")):
            return None  # the word none too, as a scene file and a command line write it
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
