"""Stiffness and damping of the benchmarks' Hookean contacts, from material constants.

The published benchmarks give a material (E, nu, rho) and a restitution; a Hookean
spring is matched to Hertz's contact time (:func:`hookean_matching_hertz`), its
tangential stiffness to Mindlin's ratio, and its normal damping to the restitution
(:func:`gamma_n_for_restitution_cut`). Units: SI (kg, m, s, N/m).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ... import exact
from ...exact import hertz
from ...exact import pair as planar
from .digitised import KRATOS, YADE_T2

__all__ = ["AL_ALLOY", "ALUMINA", "AL_WALL_T4", "SOLID", "STEEL", "Material", "bisect_damping",
           "gamma_n_for_restitution_cut", "hertz_contact_time", "hertz_mindlin_rigid_wall", "hookean_matching_hertz",
           "matched_pair_contact", "mindlin_ratio"]

#: A solid sphere: I = (2/5) m r^2.
SOLID = 0.4


@dataclass(frozen=True)
class Material:
    """Elastic constants and density of a sphere (SI), with where they come from."""

    name: str
    E: float
    nu: float
    rho: float
    source: str

    def mass(self, r: float) -> float:
        return self.rho * 4.0 / 3.0 * math.pi * r**3

    def effective_modulus(self, wall: Material | None = None) -> float:
        """E* of Hertz's law: 1/E* = (1 - nu^2)/E + (1 - nu_w^2)/E_w (rigid wall: no second term)."""
        inverse = (1.0 - self.nu**2) / self.E
        if wall is not None:
            inverse += (1.0 - wall.nu**2) / wall.E
        return 1.0 / inverse

    def shear_modulus(self, wall: Material | None = None) -> float:
        """G* of Mindlin's law: 1/G* = (2 - nu)/G + (2 - nu_w)/G_w, G = E/(2 (1 + nu)) (rigid wall: no
        second term)."""
        inverse = sum((2.0 - body.nu) * 2.0 * (1.0 + body.nu) / body.E for body in (self, wall) if body is not None)
        return 1.0 / inverse


def hertz_contact_time(m: float, r: float, e_star: float, v: float) -> float:
    """Duration of an elastic Hertzian impact of a sphere (mass m, radius r) on a flat wall.

    With F = (4/3) E* sqrt(r) delta^(3/2), energy conservation gives the largest overlap
    delta_max = (15 m v^2 / (16 E* sqrt(r)))^(2/5), and the approach and the (symmetric)
    rebound last t_H = 2 I delta_max / v, I = :data:`spinbounce.exact.hertz.CONTACT_INTEGRAL`
    (about 2.943 delta_max / v).
    """
    delta_max = (15.0 * m * v * v / (16.0 * e_star * math.sqrt(r))) ** 0.4
    return 2.0 * hertz.CONTACT_INTEGRAL * delta_max / v


def hertz_mindlin_rigid_wall(material: Material, r: float, wall: Material | None = None) -> dict:
    """LAMMPS's Hertz-Mindlin on a wall (rigid, or of the material ``wall``) as model parameters:
    ``hertz`` with kn = 4/3 E* (F = kn sqrt(r) delta^(3/2)) and ``mindlin`` with k_t = 8 G*
    (:meth:`Material.effective_modulus`, :meth:`Material.shear_modulus`). (``hertz/material`` would
    mix the wall as the sphere's own material.)"""
    return {"normal": "hertz", "kn": 4.0 / 3.0 * material.effective_modulus(wall), "tangential": "mindlin",
            "mindlin_kt": 8.0 * material.shear_modulus(wall)}


def mindlin_ratio(nu: float) -> float:
    """kt/kn of Mindlin's no-slip tangential stiffness over Hertz's tangent normal stiffness
    for like elastic bodies (or one on a rigid wall): 8 G* a / (2 E* a) = 2 (1 - nu)/(2 - nu)."""
    return 2.0 * (1.0 - nu) / (2.0 - nu)


def _hookean(m: float, r: float, e_star: float, v: float, nu: float) -> tuple[float, float]:
    """(kn, kt): kn = m (pi / t_H)^2 makes the undamped Hookean contact time pi sqrt(m/kn) equal to
    :func:`hertz_contact_time` at speed v; kt = kn * :func:`mindlin_ratio` (nu)."""
    kn = m * (math.pi / hertz_contact_time(m, r, e_star, v)) ** 2
    return kn, kn * mindlin_ratio(nu)


def hookean_matching_hertz(material: Material, r: float, v_n: float,
                           wall: Material | None = None) -> tuple[float, float, float]:
    """(m, kn, kt): a Hookean spring with the Hertz contact time at normal speed |v_n| (:func:`_hookean`)."""
    m = material.mass(r)
    return (m, *_hookean(m, r, material.effective_modulus(wall), abs(v_n), material.nu))


def matched_pair_contact(material: Material, r_a: float, r_b: float, m_a: float, m_b: float, v_rel: float,
                         b_material: Material | None = None) -> tuple[float, float]:
    """(kn, kt): the Hookean pair contact with Hertz's contact time at relative normal speed v_rel.

    Hertz between two spheres is a sphere of the reduced mass m* and radius r_a r_b/(r_a + r_b)
    on a flat of the combined modulus (:func:`_hookean`).
    """
    e_star = material.effective_modulus(b_material or material)
    return _hookean(planar.reduced_mass(m_a, m_b), r_a * r_b / (r_a + r_b), e_star, v_rel, material.nu)


def bisect_damping(restitution, e: float, critical: float, rtol: float) -> float:
    """The gamma_n in (0, critical) where ``restitution(gamma_n)``, falling as gamma_n grows, crosses
    ``e``, by bisection to ``rtol`` of the bracket's top (at most 200 halvings)."""
    lo, hi = 0.0, critical
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if restitution(mid) > e else (lo, mid)
        if hi - lo <= rtol * hi:
            break
    return 0.5 * (lo + hi)


def gamma_n_for_restitution_cut(e: float, m: float, kn: float) -> float:
    """gamma_n giving restitution ``e`` when the normal force is never tensile (limit_damping).

    :func:`exact.restitution` with ``tensile=False`` rises monotonically as gamma_n falls,
    so bisection between 0 (e = 1) and critical damping finds it to round-off.
    """
    if not 0.0 < e <= 1.0:
        raise ValueError(f"e = {e!r}: must lie in (0, 1]")
    if e == 1.0:
        return 0.0
    return bisect_damping(lambda gamma_n: exact.restitution(m, kn, gamma_n, tensile=False), e,
                          2.0 * math.sqrt(m * kn) * (1.0 - 1e-12), 1e-15)


#: Chung & Ooi Test 2's aluminium alloy, the one Test-6 material whose constants were found.
AL_ALLOY = Material("aluminium alloy", 70e9, 0.30, 2699.0, YADE_T2)
#: Test 4's sphere (alumina) and wall (aluminium alloy).
ALUMINA = Material("alumina", 380e9, 0.23, 4000.0, f"{KRATOS} test4_data/Materials4.json; Yade Test4.py")
AL_WALL_T4 = Material("aluminium alloy (wall)", 70e9, 0.33, 2700.0, f"{KRATOS} test4_data/Materials4.json")
STEEL = Material("steel", 208e9, 0.30, 7850.0, "PySPH Chung-Ooi Test 5 input (repository path not resolved)")
