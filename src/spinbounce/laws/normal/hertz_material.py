"""``hertz/material``: the Hertzian force with its stiffness made from the material, as LAMMPS
makes it: Young's modulus E and Poisson's ratio nu.

LAMMPS (``GranSubModNormalHertzMaterial``) sets k = 4/3 E*, with E* = E/(2 (1 - nu^2)) against
a wall (``mix_stiffnessE_wall``) and E* = 1/((1 - nu^2)/E + (1 - nu^2)/E), the same number,
between two spheres of one material (``mix_stiffnessE``); the force is then ``hertz``'s,
F = k a delta with a = sqrt(R delta). So this sub-model is ``hertz`` with kn = 2 E/(3 (1 - nu^2)),
which the model holds as its kn (the stiffness LAMMPS uses, shown in every table) and its deck
gives as E and nu. The exact reference, the contact's times and the step rule are hertz's.
"""

from __future__ import annotations

import math

from ...declaration import Parameter
from ...errors import SceneError
from ..base import STIFFNESS
from .hertz import Hertz

__all__ = ["HertzMaterial", "LAW", "YOUNGS_MODULUS", "POISSON_RATIO", "stiffness", "shear_stiffness"]

YOUNGS_MODULUS = Parameter(
    "youngs_modulus", "hertz/material: Young's modulus E (LAMMPS's E); none for any other normal law",
    "force/length^2", None, low=0.0, low_open=True, optional=True, why="a modulus is positive",
    deck="granular hertz/material E ETA_N NU")
POISSON_RATIO = Parameter(
    "poisson_ratio", "hertz/material: Poisson's ratio nu (LAMMPS's nu); none for any other normal law", "1", None,
    low=-1.0, low_open=True, high=0.5, optional=True,
    why="an isotropic elastic material has -1 < nu <= 1/2 (at -1 its stiffness 1/(1 - nu^2) would be infinite)",
    deck="granular hertz/material E ETA_N NU")


def stiffness(youngs_modulus: float, poisson_ratio: float) -> float:
    """LAMMPS's k = 4/3 E* with E* = E/(2 (1 - nu^2)): a wall, or two spheres of one material."""
    return 4.0 / 3.0 * youngs_modulus / (2.0 * (1.0 - poisson_ratio**2))


def shear_stiffness(youngs_modulus: float, poisson_ratio: float) -> float:
    """LAMMPS's NULL Mindlin stiffness 8 G*, G* = E/(4 (2 - nu)(1 + nu)) (``mix_stiffnessG_wall``; the
    same number between two spheres of one material, ``mix_stiffnessG``)."""
    return 8.0 * youngs_modulus / (4.0 * (2.0 - poisson_ratio) * (1.0 + poisson_ratio))


class HertzMaterial(Hertz):
    keyword = "hertz/material"
    summary = "Hertz with kn = 2 E/(3 (1 - nu^2)) from youngs_modulus E and poisson_ratio nu"
    coefficients = (YOUNGS_MODULUS, POISSON_RATIO)
    derived = ("kn",)
    material = True
    lammps_coefficients = ("youngs_modulus", "eta_n", "poisson_ratio")

    def settle(self, values: dict, foreign: tuple[Parameter, ...]) -> dict:
        super().settle(values, foreign)
        for parameter in self.coefficients:
            if values.get(parameter.name) is None:
                raise SceneError(parameter.name, None, f"must be given with normal = {self.keyword} "
                                                       f"({parameter.meaning.split(': ', 1)[1].split(';')[0]})")
        k = stiffness(values["youngs_modulus"], values["poisson_ratio"])
        kn = values.get("kn", STIFFNESS.default)
        if kn != STIFFNESS.default and not math.isclose(kn, k, rel_tol=1e-12):
            raise SceneError("kn", kn, f"is made from the material with normal = {self.keyword} (k = 2 E/(3 (1 - nu^2)) "
                                       f"= {k:.6g}): give youngs_modulus and poisson_ratio only")
        return {"kn": k}

    def shear_stiffness(self, model) -> float:
        return shear_stiffness(model.youngs_modulus, model.poisson_ratio)



LAW = HertzMaterial()
