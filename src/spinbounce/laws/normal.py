"""The normal sub-models, registered by LAMMPS keyword: one class and one entry each in :data:`NORMAL`."""

from __future__ import annotations

import math

import numpy as np

from ..declaration import Parameter
from ..errors import SceneError
from ..exact import hertz, linear
from .base import STIFFNESS, NormalLaw, lookup

__all__ = ["NORMAL", "NormalLaw", "Hooke", "Hertz", "HertzMaterial", "normal_law", "normal_parameter",
           "normal_coefficients", "stiffness", "YOUNGS_MODULUS", "POISSON_RATIO"]

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


class Hooke(NormalLaw):
    """``hooke``: the paper's linear spring, F = kn delta (Eq. 1), with LAMMPS's ``damping velocity``.

    Exact reference: the damped oscillator of Eq. 15 (:mod:`spinbounce.exact.linear`); its contact
    time does not depend on the impact speed, so the paper's matrix (Eq. 18) holds for every state.
    """

    keyword = "hooke"
    summary = "the paper's linear spring, F = kn delta"

    def contact_times(self, model, v_n) -> np.ndarray:
        v = np.atleast_1d(np.asarray(v_n, dtype=float))
        return np.full(v.shape, linear.exit_time(model.m, model.kn, model.gamma_n, not model.limit_damping))

    def force_times(self, model, v_n) -> np.ndarray:
        v = np.atleast_1d(np.asarray(v_n, dtype=float))
        return np.full(v.shape, linear.collision_time(model.m, model.kn, model.gamma_n, not model.limit_damping))

    def tunnelling_speed(self, model) -> float:
        return model.r / float(linear.max_overlap(1.0, model.m, model.kn, model.gamma_n))

    def max_overlap(self, model, speed) -> np.ndarray:
        return np.asarray(linear.max_overlap(speed, model.m, model.kn, model.gamma_n), dtype=float)

    def normal_mode(self, model, speed: float | None) -> tuple[float, float]:
        return math.sqrt(model.kn / model.m), model.gamma_n / model.m


class Hertz(NormalLaw):
    """``hertz``: LAMMPS's Hertzian force F = kn a delta, with contact radius a = sqrt(r delta).

    kn is LAMMPS's K (force/length^2); against a flat wall m delta'' = -kn sqrt(r) delta^(3/2).
    Exact reference: :mod:`spinbounce.exact.hertz` (the contact time grows as |v_n|^(-1/5), so
    Omega depends on the impact speed, sphere by sphere). No exact reference of the damped Hertzian
    contact is here, so normal damping is refused.
    """

    keyword = "hertz"
    summary = "Hertz, F = kn a delta with contact radius a = sqrt(r delta)"
    contact_radius = True
    damped_theory = False

    def contact_times(self, model, v_n) -> np.ndarray:
        v = np.atleast_1d(np.asarray(v_n, dtype=float))
        return np.asarray(hertz.contact_time(v, model.m, model.kn, model.r), dtype=float)

    def tunnelling_speed(self, model) -> float:
        return hertz.tunnelling_speed(model.m, model.kn, model.r)

    def max_overlap(self, model, speed) -> np.ndarray:
        return np.asarray(hertz.max_overlap(speed, model.m, model.kn, model.r), dtype=float)

    def normal_mode(self, model, speed: float | None) -> tuple[float, float]:
        if speed is None:
            raise ValueError("a Hertzian collision's normal mode needs the fastest |v_n| (speed)")
        return float(hertz.normal_frequency(speed, model.m, model.kn, model.r)), 0.0


class HertzMaterial(Hertz):
    """``hertz/material``: the Hertzian force with its stiffness made from the material, as LAMMPS
    makes it: Young's modulus E and Poisson's ratio nu.

    LAMMPS (``GranSubModNormalHertzMaterial``) sets k = 4/3 E*, with E* = E/(2 (1 - nu^2)) against
    a wall (``mix_stiffnessE_wall``) and E* = 1/((1 - nu^2)/E + (1 - nu^2)/E), the same number,
    between two spheres of one material (``mix_stiffnessE``); the force is then ``hertz``'s,
    F = k a delta with a = sqrt(R delta). So this sub-model is ``hertz`` with kn = 2 E/(3 (1 - nu^2)),
    which the model holds as its kn (the stiffness LAMMPS uses, shown in every table) and its deck
    gives as E and nu. The exact reference, the contact's times and the step rule are hertz's.
    """

    keyword = "hertz/material"
    summary = "Hertz with kn = 2 E/(3 (1 - nu^2)) from youngs_modulus E and poisson_ratio nu"
    coefficients = (YOUNGS_MODULUS, POISSON_RATIO)
    derived = ("kn",)

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

    def deck_terms(self, model, eta_n: float) -> tuple:
        return (self.keyword, float(model.youngs_modulus), float(eta_n), float(model.poisson_ratio))


#: Every normal sub-model, by its LAMMPS keyword.
NORMAL: dict[str, NormalLaw] = {law.keyword: law for law in (Hooke(), Hertz(), HertzMaterial())}


def normal_law(keyword: str) -> NormalLaw:
    """The sub-model of ``keyword``, or a :class:`SceneError` listing the registered ones."""
    return lookup(NORMAL, "normal", keyword)


def normal_coefficients() -> tuple[Parameter, ...]:
    """Every normal sub-model's coefficients, each once, in registry order."""
    return tuple(dict.fromkeys(p for law in NORMAL.values() for p in law.coefficients))


def normal_parameter() -> Parameter:
    """The ``normal`` choice: one of the registered keywords."""
    laws = "; ".join(f"{law.keyword}: {law.summary}" for law in NORMAL.values())
    return Parameter("normal", f"normal force law ({laws})", "-", NormalLaw.default_keyword, kind="choice",
                     choices=tuple(NORMAL),
                     deck="wall/gran granular NORMAL ... | pair_coeff * * NORMAL ...")
