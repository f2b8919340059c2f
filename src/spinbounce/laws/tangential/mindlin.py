"""``tangential mindlin K_T X_T MU`` and its variants: a tangential stiffness that grows with the
contact radius, F_t = -k_t a h with a = sqrt(R delta), h the slip history (a displacement; or,
``/force``, the elastic force itself, h' = -k_t a u'), rescaled by a_new/a_old while a shrinks
(``_rescale``). K_T = NULL (``mindlin_kt`` none) is LAMMPS's 8 G* from the material's E and nu.

Their exact references are :mod:`spinbounce.exact.mindlin` (no cap, an undamped normal force)
and :mod:`spinbounce.exact.contact_phases` (normal damping; or a Coulomb cap, in the paper's
plane, with no dashpot). The step rule resolves the slip's spring at its
stiffest, k_t sqrt(r delta_max) at the fastest speed.
"""

from __future__ import annotations

import math

from ...declaration import Parameter
from ...errors import SceneError
from ..base import NormalLaw, TangentialLaw
from ..normal import normal_law
from .linear_history import KT, MU

__all__ = ["RadiusSpring", "Mindlin", "MINDLIN_KT", "LAW"]

MINDLIN_KT = Parameter(
    "mindlin_kt", "Mindlin variants: tangential stiffness k_t, F_t = k_t a xi with contact radius a = sqrt(R delta) "
    "(LAMMPS's k_t); none: LAMMPS's NULL, 8 G* from hertz/material's youngs_modulus and poisson_ratio",
    "force/length^2", None, low=0.0, optional=True,
    why="a negative stiffness would push the slip away (LAMMPS: Illegal Mindlin tangential model)",
    deck="tangential mindlin|mindlin/force|mindlin_rescale|mindlin_rescale/force K_T|NULL X_T MU")


class RadiusSpring(TangentialLaw):
    """A spring k a on the slip history whose stiffness grows with the contact radius a = sqrt(r delta)
    (the Mindlin variants, and this build's ``linear_history_classic``): its stiffness at an overlap."""

    contact_radius = True

    def stiffness(self, model) -> float:
        """k: the spring is k sqrt(r delta)."""
        raise NotImplementedError

    def slip_stiffness(self, model, speed: float | None) -> float:
        if speed is None:
            raise ValueError(f"a {self.keyword} collision's slip mode needs the fastest |v_n| (speed)")
        return self.frozen_stiffness(model, float(model.max_overlap(speed)))

    def frozen_stiffness(self, model, overlap: float | None) -> float:
        if overlap is None:
            raise ValueError(f"a {self.keyword} spring needs its overlap")
        return self.stiffness(model) * math.sqrt(model.r * overlap)


class Mindlin(RadiusSpring):
    coefficients = (MINDLIN_KT, MU)
    lammps_coefficients = ("mindlin_kt", "x_t", "mu")

    def __init__(self, keyword: str):
        self.keyword = keyword
        #: (force, rescale): its history is the elastic force (``/force``), not a displacement; it
        #: is rescaled by a_new/a_old while the contact radius shrinks (``_rescale``).
        self.variant = ("/force" in keyword, "_rescale" in keyword)
        history = "force" if self.variant[0] else "displacement"
        self.summary = (f"Mindlin, F_t = k_t a xi with a {history} history"
                        + (", rescaled as a shrinks" if self.variant[1] else ""))

    def settle(self, values: dict, foreign: tuple[Parameter, ...]) -> dict:
        super().settle(values, foreign)
        kt = values.get("kt", KT.default)
        if kt != KT.default:
            raise SceneError("kt", kt, f"is linear_history's spring, not a coefficient of tangential = {self.keyword}: "
                                       "give mindlin_kt (none: 8 G* from the material)")
        normal = normal_law(values.get("normal", NormalLaw.default_keyword))
        if values.get("mindlin_kt") is None and not normal.material:
            raise SceneError("mindlin_kt", None, f"must be given with normal = {normal.keyword}: none is LAMMPS's "
                                                 "NULL, 8 G* from normal = hertz/material's youngs_modulus and "
                                                 "poisson_ratio")
        return {}

    def stiffness(self, model) -> float:
        """k_t: the model's ``mindlin_kt``, or LAMMPS's NULL, 8 G* of the normal law's material."""
        return model.normal_law.shear_stiffness(model) if model.mindlin_kt is None else model.mindlin_kt



LAW = Mindlin("mindlin")
