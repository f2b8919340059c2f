"""What the damping sub-models share whose ETA_N LAMMPS turns into a dashpot itself (``damping
mass_velocity``, ``tsuji``, ``coeff_restitution``): their tangential coefficient X_T, and the
paper's gamma_n and gamma_t made from their own coefficient.

LAMMPS (``GranSubModDamping*``) multiplies the normal sub-model's ETA_N by a prefactor of the
contact (its effective mass, its stiffness) and the tangential damping is X_T times the result.
With the Hookean force that prefactor is constant through a contact (but viscoelastic's), so the
dashpots are the paper's gamma_n and gamma_t, which every exact reference takes; the effective
mass is the sphere's against a wall, m m_b/(m + m_b) in a pair. Where the prefactor grows with
the contact radius a (:meth:`radius_power` s > 0), gamma_n and gamma_t are the coefficients of
a^s, and the reference is the contact integrated in time (spinbounce.exact.contact_phases).
"""

from __future__ import annotations

import math

from ...declaration import Parameter
from ...errors import SceneError
from ..base import DampingLaw, NormalLaw
from ..normal import normal_law

__all__ = ["Scaled", "FromRestitution", "X_T", "E_N"]

X_T = Parameter("x_t", "tangential damping over normal damping, gamma_t/gamma_n (LAMMPS's X_T), with a damping "
                "other than velocity; none: 0", "1", None, low=0.0, optional=True,
                why="negative damping would create energy", deck="tangential linear_history KT X_T")

#: Below it the sphere creeps out of the overlap too slowly for a run to see the end (as the
#: model's own lower limit on the restitution, spinbounce.model.contact.MIN_RESTITUTION).
E_N = Parameter(
    "e_n", "damping tsuji or coeff_restitution: the restitution LAMMPS makes the dashpot from (its ETA_N; "
    "coeff_restitution gives it exactly, with hooke or hertz; tsuji does not); none for any other damping", "1", None, low=1e-3, high=1.0, optional=True,
    why="at e_n = 1 there is no damping; below 1e-3 the sphere creeps out too slowly for a run to see it leave",
    deck="granular hooke KN ETA_N damping tsuji|coeff_restitution")


class Scaled(DampingLaw):
    """A damping sub-model whose one coefficient LAMMPS scales into the normal dashpot."""

    #: The coefficient LAMMPS reads as ETA_N.
    coefficient: Parameter
    derived = ("gamma_n", "gamma_t")

    def gamma_n(self, values: dict, m_eff: float) -> float:
        """The normal dashpot of a Hookean contact of effective mass ``m_eff``."""
        raise NotImplementedError

    @property
    def normal_coefficient(self) -> str:
        return self.coefficient.name

    def settle(self, values: dict, foreign: tuple[Parameter, ...]) -> dict:
        super().settle(values, foreign)
        given = values.get(self.coefficient.name)
        if given is None:
            raise SceneError(self.coefficient.name, None, f"must be given with damping = {self.keyword} "
                                                          f"({self.coefficient.meaning.split(';')[0]})")
        gamma_n = self.gamma_n(values, values["m"])
        critical = 2.0 * math.sqrt(values["m"] * values["kn"])
        normal = normal_law(values.get("normal", NormalLaw.default_keyword))
        if not normal.contact_radius and self.radius_power(normal) == 0.0 and gamma_n >= critical:
            raise SceneError(self.coefficient.name, given, f"makes gamma_n = {gamma_n:.6g}, at or above critical "
                                                           f"damping 2 sqrt(m kn) = {critical:.6g}: the sphere "
                                                           "would never leave the wall")
        made = {"gamma_n": gamma_n, "gamma_t": (values.get("x_t") or 0.0) * gamma_n}
        for name, value in made.items():
            if values.get(name) and not math.isclose(values[name], value, rel_tol=1e-12):
                raise SceneError(name, values[name], f"is made from {self.coefficient.name} and x_t with damping = "
                                                     f"{self.keyword}: give those, or damping = velocity")
        return made

    def from_lammps(self, eta_n: float, x_t: float) -> dict:
        return {self.coefficient.name: eta_n, "x_t": x_t or None}  # X_T = 0 is x_t none

    def contact_dashpots(self, model, m_eff: float) -> tuple[float, float]:
        gamma_n = self.gamma_n(vars(model), m_eff)
        return gamma_n, (model.x_t or 0.0) * gamma_n

    def dashpots(self, model) -> tuple[float, float, bool, list[str]]:
        return float(getattr(model, self.coefficient.name)), float(model.x_t or 0.0), True, []


class FromRestitution(Scaled):
    """A dashpot set from a restitution e_n: a factor of e_n times sqrt(m_eff kn)."""

    coefficient = E_N
    coefficients = (E_N, X_T)
    eta_time_power = 0  # sqrt(m_eff kn) already brings s: a restitution does not follow time

    def factor(self, e: float, normal) -> float:
        """gamma_n / sqrt(m_eff kn) for the restitution ``e`` with the ``normal`` sub-model."""
        raise NotImplementedError

    def radius_power(self, normal) -> float:
        return normal.power - 1.0  # sqrt(m_eff F/delta): F/delta = kn a^(2 (p - 1))

    def gamma_n(self, values: dict, m_eff: float) -> float:
        normal = normal_law(values.get("normal", NormalLaw.default_keyword))
        return self.factor(values[self.coefficient.name], normal) * math.sqrt(m_eff * values["kn"])
