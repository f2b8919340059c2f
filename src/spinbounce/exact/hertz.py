"""Exact theory of the undamped Hertzian wall contact with a Cundall-Strack tangential spring.

The normal force is LAMMPS's ``granular hertz`` against a flat wall: F = kn a delta with
contact radius a = sqrt(R_eff delta), and R_eff = r for a wall (infinite radius), so
m delta'' = -kn sqrt(r) delta^(3/2), delta(0) = 0, delta'(0) = |v_n|; kn is LAMMPS's K
(force/length^2). Energy conservation gives the largest overlap (:func:`max_overlap`) and
dt = d(delta)/delta' the contact time (:func:`contact_time`, substituting y = x^(5/2) in
I), which grows as |v_n|^(-1/5), unlike the Hookean tau of Eq. 16.

The tangential spring acts on the slip history u alone and, with no Coulomb limit, never
sees the normal force: the slip obeys the frozen equation u'' + 2 zeta u' + Q u = 0 for
exactly the contact time, whatever the normal law. So Eq. 18 still holds sphere by
sphere, with Omega(v_n) = u'(tau)/u'(0) - 1 = cos(sqrt(Q) tau(v_n)) - 1 undamped and
restitution e = 1. Energy is conserved when the slip reverses (Omega = -2), i.e. when
sqrt(Q) tau = pi (:func:`energy_conserving_ratio`): kt*/kn grows as |v_n|^(2/5), so with a
Hertzian wall a given kt conserves energy at one normal speed only (the paper's
conclusion). The Hookean limit of the same formula, tau = pi sqrt(m/kn), gives the magic
kt/kn = alpha/(1 + alpha).

Pure Python and numpy; knows nothing of LAMMPS.
"""

from __future__ import annotations

import math

import numpy as np

from . import linear as theory

__all__ = [
    "CONTACT_INTEGRAL",
    "max_overlap",
    "contact_time",
    "normal_frequency",
    "tunnelling_speed",
    "slip_ratio",
    "Omega",
    "scattering_matrices",
    "energy_conserving_kt",
    "energy_conserving_ratio",
    "energy_conserving_speed",
    "contact_time_from_slip_ratio",
    "kt_from_contact_time",
]

#: I = int_0^1 dx / sqrt(1 - x^(5/2)) = (2/5) B(2/5, 1/2), B the Euler beta function.
CONTACT_INTEGRAL = 0.4 * math.gamma(0.4) * math.gamma(0.5) / math.gamma(0.9)


def max_overlap(v_n, m: float, kn: float, r: float):
    """Largest overlap delta_max = (5 m v_n^2 / (4 kn sqrt(r)))^(2/5)."""
    v = np.abs(np.asarray(v_n, dtype=float))
    return (5.0 * m * v * v / (4.0 * kn * math.sqrt(r))) ** 0.4


def contact_time(v_n, m: float, kn: float, r: float):
    """tau(v_n) = 2 I delta_max/|v_n|, I = int_0^1 dx / sqrt(1 - x^(5/2)): how long the overlap
    (and so every force) lasts."""
    v = np.abs(np.asarray(v_n, dtype=float))
    return 2.0 * CONTACT_INTEGRAL * max_overlap(v, m, kn, r) / v


def normal_frequency(v_n, m: float, kn: float, r: float):
    """The fastest normal rate: sqrt(dF/d(delta)/m) at delta_max, where the wall is stiffest.

    dF/d(delta) = (3/2) kn sqrt(r delta); at delta_max this is sqrt(15/8) |v_n|/delta_max.
    It sets the stability limit of the step, 2/w, as the Hookean sqrt(kn/m) does.
    """
    return np.sqrt(1.5 * kn * np.sqrt(r * max_overlap(v_n, m, kn, r)) / m)


def tunnelling_speed(m: float, kn: float, r: float) -> float:
    """|v_n| at which delta_max reaches r (the centre would reach the wall): sqrt(4 kn r^3/(5 m))."""
    return math.sqrt(4.0 * kn * r**3 / (5.0 * m))


def slip_ratio(v_n, m: float, kn: float, r: float, kt: float, alpha: float, gamma_t: float = 0.0):
    """u'(tau)/u'(0): cos(sqrt(Q) tau(v_n)) undamped; the exact damped slip otherwise."""
    return theory.slip_rate_ratio(contact_time(v_n, m, kn, r), kt, m, alpha, gamma_t)


def Omega(v_n, m: float, kn: float, r: float, kt: float, alpha: float, gamma_t: float = 0.0):
    """Eq. 18's Omega for each normal speed: slip_ratio - 1 (-2 conserves energy)."""
    return slip_ratio(v_n, m, kn, r, kt, alpha, gamma_t) - 1.0


def scattering_matrices(v_n, m: float, kn: float, r: float, kt: float, alpha: float,
                        gamma_t: float = 0.0) -> np.ndarray:
    """(n, 3, 3): Eq. 18 per sphere, with that sphere's Omega(v_n) and e = 1."""
    omegas = np.atleast_1d(Omega(v_n, m, kn, r, kt, alpha, gamma_t))
    return np.stack([theory.scattering_matrix(alpha, float(w), 1.0) for w in omegas])


def kt_from_contact_time(tau, m: float, alpha: float):
    """The kt whose slip half-period pi/sqrt(Q) equals tau: m alpha/(1+alpha) (pi/tau)^2."""
    return m * alpha / (1.0 + alpha) * (math.pi / np.asarray(tau, dtype=float)) ** 2


def energy_conserving_kt(v_n, m: float, kn: float, r: float, alpha: float):
    """kt*(v_n) = m alpha/(1+alpha) (pi/tau(v_n))^2: the slip reverses exactly, Omega = -2."""
    return kt_from_contact_time(contact_time(v_n, m, kn, r), m, alpha)


def energy_conserving_ratio(v_n, m: float, kn: float, r: float, alpha: float):
    """kt*/kn in closed form: alpha/(1+alpha) (pi/(2I))^2 (4/5)^(4/5) (m/kn)^(1/5) r^(2/5) |v_n|^(2/5)."""
    v = np.abs(np.asarray(v_n, dtype=float))
    return (alpha / (1.0 + alpha) * (math.pi / (2.0 * CONTACT_INTEGRAL)) ** 2 * 0.8**0.8
            * (m / kn) ** 0.2 * r**0.4 * v**0.4)


def energy_conserving_speed(kt: float, m: float, kn: float, r: float, alpha: float) -> float:
    """The one |v_n| at which a given kt conserves energy (inverts :func:`energy_conserving_ratio`)."""
    return (kt / kn / float(energy_conserving_ratio(1.0, m, kn, r, alpha))) ** 2.5


def contact_time_from_slip_ratio(ratio, kt: float, m: float, alpha: float):
    """Invert the undamped slip ratio cos(sqrt(Q) tau) for tau in [0, pi/sqrt(Q)].

    Most sensitive (d ratio/d tau largest) where sqrt(Q) tau = pi/2, i.e. at kt = kt*/4;
    insensitive at the energy-conserving point, where the ratio has its minimum -1.
    """
    return np.arccos(np.clip(ratio, -1.0, 1.0)) / math.sqrt(theory.Q(kt, m, alpha))
