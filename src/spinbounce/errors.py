"""What spinbounce raises to a user, declared once and importing nothing heavy.

Every front end (the CLI, the API, the workflow) catches these by name; the module that
raises one imports it from here. A refusal names the parameter, its value and the limit.
"""

from __future__ import annotations

from pathlib import Path

__all__ = ["SceneError", "ContactHeld", "contact_held", "PhysicsWarning", "NoMatrix", "NoLimit", "SweepError",
           "FileFault", "DumpError", "LammpsError", "ResultError"]


class SceneError(ValueError):
    """A parameter is outside its accepted range. Raised before LAMMPS starts."""

    def __init__(self, parameter: str, value, limit: str):
        self.parameter = parameter
        self.value = value.item() if hasattr(value, "item") and getattr(value, "ndim", None) == 0 else value
        self.limit = limit
        super().__init__(f"{parameter} = {self.value!r}: {limit}")  # a numpy scalar as the number it is

    def __reduce__(self):  # whole across processes (a worker's refusal reaches its parent as raised, notes too)
        return type(self), (self.parameter, self.value, self.limit), self.__dict__


class PhysicsWarning(UserWarning):
    """A scene is allowed but physically unusual or numerically marginal."""


class NoMatrix(ValueError):
    """No single scattering matrix describes this model's collisions; the reason says why."""


class NoLimit(NoMatrix):
    """LAMMPS's outcome of this state has no dt -> 0 limit, so no reference can be given; the reason says why."""


class SweepError(ValueError):
    """A sweep cannot start: a bad scene file, or an output folder that is not ours."""


class FileFault(ValueError):
    """A file a command reads is missing, unreadable, truncated, corrupt or not what it should be:
    the message names the file and the fault, and nothing has been written."""


class DumpError(ValueError):
    """A dump file is not in the expected format."""


class LammpsError(RuntimeError):
    """LAMMPS refused or failed a deck. Carries LAMMPS's own ERROR line and the deck path."""

    def __init__(self, error_line: str, deck: Path, input_line: str | None = None):
        self.error_line = error_line
        self.deck = Path(deck)
        self.input_line = input_line
        where = f"\n  deck: {self.deck}" + (f"\n  input line: {input_line}" if input_line else "")
        super().__init__(f"{error_line}{where}")

    def __reduce__(self):
        return type(self), (self.error_line, self.deck, self.input_line), self.__dict__


class ResultError(RuntimeError):
    """LAMMPS finished but its output cannot be trusted (NaN, lost spheres, contact not over), or the exact
    reference it is judged against gives no outcome."""


class ContactHeld(SceneError):
    """An impact whose contact never ends (:func:`contact_held`): a refusal of the state, whatever the step, which
    a handler of a step refused (a rung too coarse, a run too long) must pass on."""


def contact_held(v_n: float) -> SceneError:
    """The refusal of an impact at ``v_n`` whose contact a normal dashpot holds closed: near the surface a force on
    the contact radius vanishes (Hertz's as delta^1.5) while a dashpot that does not fade with the contact (damping
    velocity, mass_velocity) does not, and the overlap creeps towards zero without reaching it (LAMMPS's
    too: a wall's sphere at v_n = -0.16, gamma_n = 2 on Hertz, kn 10, still 3e-5 deep after 200,000 steps)."""
    return ContactHeld("v_n", v_n, "the contact does not end: its normal dashpot, which does not fade as the overlap "
                                  "closes, holds it closed (the overlap creeps towards zero without reaching it); "
                                  "a faster impact, limit_damping, or a damping model that fades with the contact "
                                  "(tsuji, viscoelastic, coeff_restitution) ends it")
