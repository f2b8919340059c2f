"""Analytic theory of a frictional sphere bouncing off a flat wall.

Wang and Harrowell's model: a Hookean normal spring kn, a tangential spring kt acting on
the elastic slip displacement u (Cundall-Strack), optional viscous terms gamma_n and
gamma_t, and no Coulomb limit. Equation numbers refer to their paper.

Conventions used everywhere in this package:

* state vectors are ordered (v_n, v_t, r*omega);
* omega is positive anticlockwise (the paper's sign), so the slip rate is
  ``u_dot = v_t + r*omega`` (Eq. 2) and rolling means ``v_t + r*omega = 0``;
* ``alpha = I / (m r^2)`` is the particle's one shape property.

This module is pure numpy and knows nothing of LAMMPS.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = [
    "collision_time",
    "restitution",
    "max_overlap",
    "Q",
    "damping_rate",
    "Omega",
    "Omega_paper_damped",
    "Omega_exact",
    "scattering_matrix",
    "Omega_of_matrix",
    "block_matrix",
    "block_from",
    "rough_matrix",
    "rolling_matrix",
    "magic_kt_over_kn",
    "slip_rate_ratio",
    "frozen_velocities",
    "frozen_velocities_paper_damped",
    "frozen_means",
    "frozen_extremes",
    "frozen_slope",
    "exit_time",
    "gamma_n_for_restitution",
    "energy",
    "energy_change",
    "dissipation",
]


# ---------------------------------------------------------------------------
# Normal motion
# ---------------------------------------------------------------------------

def _normal_rates(m: float, kn: float, gamma_n: float, tensile: bool = True) -> tuple[float, float, float]:
    """(beta, omega_d, phi) of m z'' = -kn z - gamma_n z': decay rate, damped frequency, and the
    omega_d t at which the normal force ends: pi (z back at r) when the force may turn tensile;
    else where kn x + gamma_n x' = 0 on the way out (the dashpot would pull)."""
    beta = gamma_n / (2.0 * m)
    omega_d_sq = kn / m - beta * beta
    # compare gamma_n itself too: at gamma_n = 2 sqrt(m kn) rounding can leave omega_d^2 ~ 1e-16
    if omega_d_sq <= 0.0 or gamma_n >= 2.0 * math.sqrt(m * kn):
        raise ValueError(
            f"gamma_n = {gamma_n:g} is at or above critical normal damping "
            f"2*sqrt(m*kn) = {2.0 * math.sqrt(m * kn):g}: the sphere never leaves the wall"
        )
    omega_d = math.sqrt(omega_d_sq)
    if tensile or gamma_n == 0.0:
        return beta, omega_d, math.pi
    # x = (v/omega_d) e^(-beta t) sin(phi): kn sin(phi) + gamma_n (omega_d cos(phi) - beta sin(phi)) = 0
    return beta, omega_d, math.pi - math.atan2(gamma_n * omega_d, kn - gamma_n * beta)


def collision_time(m: float, kn: float, gamma_n: float = 0.0, tensile: bool = True) -> float:
    """Duration of the contact force, Eq. 16: tau = pi sqrt(m/kn), independent of v_n.

    With normal damping (gamma_n > 0) and a tensile force allowed (LAMMPS's default) the
    contact lasts half a damped period, pi / omega_d. With ``tensile = False`` (LAMMPS's
    ``limit_damping``) the force ends earlier, when the dashpot would start to pull; the
    sphere then drifts out of the overlap with no force on it (:func:`exit_time`). Every
    one of these is independent of v_n: the linear equations scale with it.
    """
    _, omega_d, phi = _normal_rates(m, kn, gamma_n, tensile)
    return phi / omega_d


def exit_time(m: float, kn: float, gamma_n: float = 0.0, tensile: bool = True) -> float:
    """When the centre is back at z = r: the force's end plus the force-free drift out."""
    beta, omega_d, phi = _normal_rates(m, kn, gamma_n, tensile)
    t = phi / omega_d
    overlap = math.exp(-beta * t) * math.sin(phi) / omega_d  # per unit |v_n(0)|
    speed = math.exp(-beta * t) * (beta * math.sin(phi) - omega_d * math.cos(phi)) / omega_d
    return t + (overlap / speed if overlap > 0.0 else 0.0)


def restitution(m: float, kn: float, gamma_n: float = 0.0, tensile: bool = True) -> float:
    """Normal coefficient of restitution e = -v_n(out)/v_n(0) (1 for the paper's model).

    exp(-beta pi/omega_d) with a tensile force allowed; with ``tensile = False`` the
    speed when the force ends, which is higher (the dashpot never pulls).
    """
    beta, omega_d, phi = _normal_rates(m, kn, gamma_n, tensile)
    return math.exp(-beta * phi / omega_d) * (beta * math.sin(phi) - omega_d * math.cos(phi)) / omega_d


def gamma_n_for_restitution(e: float, m: float, kn: float) -> float:
    """The normal damping that gives restitution e (tensile force allowed): inverts
    e = exp(-beta pi/omega_d) with beta = gamma_n/(2m), omega_d^2 = kn/m - beta^2."""
    if not 0.0 < e <= 1.0:
        raise ValueError(f"e = {e!r}: must lie in (0, 1]")
    q = -math.log(e) / math.pi  # beta / omega_d
    return 2.0 * m * q * math.sqrt(kn / m / (1.0 + q * q))


def max_overlap(v_n, m: float, kn: float, gamma_n: float = 0.0):
    """Largest overlap r - z during a collision that starts touching with speed v_n.

    Undamped: |v_n| sqrt(m/kn) (from Eq. 15). Damped: the overlap
    |v_n|/omega_d exp(-beta t) sin(omega_d t) peaks where tan(omega_d t) = omega_d/beta.
    """
    beta, omega_d, _ = _normal_rates(m, kn, gamma_n)
    t_peak = math.atan2(omega_d, beta) / omega_d
    return np.abs(v_n) / omega_d * math.exp(-beta * t_peak) * math.sin(omega_d * t_peak)


# ---------------------------------------------------------------------------
# Tangential motion: the frozen contact (Section 3) and its damped generalisation
# ---------------------------------------------------------------------------

def Q(kt: float, m: float, alpha: float) -> float:
    """Eq. 8: Q = kt (1/m + r^2/I) = (kt/m)(1 + alpha)/alpha, the slip's squared frequency."""
    return kt / m * (1.0 + alpha) / alpha


def damping_rate(gamma_t: float, m: float, alpha: float) -> float:
    """zeta in u'' + 2 zeta u' + Q u = 0: zeta = gamma_t (1 + alpha) / (2 alpha m).

    The tangential force -kt u - gamma_t u' acts on both v_t (mass m) and r*omega
    (inertia alpha m r^2), so the slip feels the reduced mass alpha m / (1 + alpha).
    """
    return gamma_t * (1.0 + alpha) / (2.0 * alpha * m)


def slip_rate_ratio(t, kt: float, m: float, alpha: float, gamma_t: float = 0.0):
    """u'(t)/u'(0) for a contact that starts with u = 0, exactly, for any damping.

    Solves u'' + 2 zeta u' + Q u = 0 with u(0) = 0:
    u'(t)/u'(0) = exp(-zeta t) [C(t) - zeta S(t)] with C = cos(w t), S = sin(w t)/w and
    w = sqrt(Q - zeta^2). Written with a complex w and sinc, the one expression is exact
    and smooth through critical damping; in the overdamped regime it switches to the
    sum of two decaying exponentials for large times, where cosh would overflow.
    Without damping this is cos(t sqrt(Q)), the bracket of Eq. 10.
    """
    t = np.asarray(t, dtype=float)
    flat = np.atleast_1d(t).ravel()
    q = Q(kt, m, alpha)
    zeta = damping_rate(gamma_t, m, alpha)
    ratio = np.empty_like(flat)
    late = np.zeros(flat.shape, dtype=bool)
    if zeta * zeta > q:  # overdamped: w = i kappa
        kappa = math.sqrt(zeta * zeta - q)
        late = kappa * flat > 1.0
        tl = flat[late]
        ratio[late] = 0.5 * (1.0 - zeta / kappa) * np.exp((kappa - zeta) * tl) + 0.5 * (
            1.0 + zeta / kappa
        ) * np.exp(-(kappa + zeta) * tl)
    te = flat[~late]
    wt = np.sqrt(complex(q - zeta * zeta)) * te
    sin_over_w = te * np.sinc(wt / np.pi)
    ratio[~late] = (np.exp(-zeta * te) * (np.cos(wt) - zeta * sin_over_w)).real
    return ratio.reshape(t.shape) if t.ndim else float(ratio[0])


def frozen_velocities(t, v_t0, r_omega0, kt: float, m: float, alpha: float, gamma_t: float = 0.0):
    """(v_t(t), r*omega(t)) with the sphere held at a fixed height in contact.

    gamma_t = 0 gives Eq. 10. For gamma_t > 0 this is the exact solution (under-,
    critically or over-damped): since m dv_t/dt = F_t and I domega/dt = r F_t,
    Delta v_t = alpha/(1+alpha) Delta u' and r Delta omega = Delta u'/(1+alpha).
    """
    s0 = np.asarray(v_t0, dtype=float) + np.asarray(r_omega0, dtype=float)
    delta = (slip_rate_ratio(t, kt, m, alpha, gamma_t) - 1.0) * s0
    return v_t0 + alpha / (1.0 + alpha) * delta, r_omega0 + delta / (1.0 + alpha)


def frozen_velocities_paper_damped(
    t, v_t0, r_omega0, kt: float, m: float, alpha: float, gamma_t: float
):
    """The paper's damped recipe (Section 5): Eq. 10 with cos(t sqrt(Q)) times exp(-gamma_t t/m).

    An approximation: compare with :func:`frozen_velocities`, which is exact.
    """
    s0 = np.asarray(v_t0, dtype=float) + np.asarray(r_omega0, dtype=float)
    t = np.asarray(t, dtype=float)
    bracket = np.exp(-gamma_t * t / m) * np.cos(t * math.sqrt(Q(kt, m, alpha))) - 1.0
    return v_t0 + alpha / (1.0 + alpha) * bracket * s0, r_omega0 + bracket * s0 / (1.0 + alpha)


def frozen_means(v_t0, r_omega0, alpha: float):
    """Eq. 11: the centre of the frozen oscillation, which is the rolling state."""
    s0 = v_t0 + r_omega0
    return v_t0 - s0 * alpha / (1.0 + alpha), r_omega0 - s0 / (1.0 + alpha)


def frozen_extremes(v_t0, r_omega0, alpha: float):
    """Eq. 12: the far end (v_t^m, r*omega^m) of the undamped frozen trajectory.

    2 kt/(m Q) = 2 alpha/(1+alpha) and 2 r^2 kt/(I Q) = 2/(1+alpha), so kt drops out.
    """
    s0 = v_t0 + r_omega0
    return v_t0 - 2.0 * s0 * alpha / (1.0 + alpha), r_omega0 - 2.0 * s0 / (1.0 + alpha)


def frozen_slope(alpha: float) -> float:
    """Eq. 13: d v_t / d(r omega) = I/(m r^2) = alpha along every frozen trajectory."""
    return alpha


# ---------------------------------------------------------------------------
# Scattering matrix (Section 4, 5)
# ---------------------------------------------------------------------------

def Omega(kn: float, kt: float, alpha: float) -> float:
    """Eq. 18: Omega = cos(pi sqrt(kt/kn (1+alpha)/alpha)) - 1 (always in [-2, 0])."""
    return math.cos(math.pi * math.sqrt(kt / kn * (1.0 + alpha) / alpha)) - 1.0


def Omega_paper_damped(m: float, kn: float, kt: float, alpha: float, gamma_t: float) -> float:
    """Eq. 22: the paper's damped Omega, exp(-pi gamma_t/sqrt(m kn)) cos(...) - 1 (approximate)."""
    return math.exp(-math.pi * gamma_t / math.sqrt(m * kn)) * (Omega(kn, kt, alpha) + 1.0) - 1.0


def Omega_exact(
    m: float, kn: float, kt: float, alpha: float, gamma_t: float = 0.0, gamma_n: float = 0.0,
    tensile: bool = True,
) -> float:
    """Exact Omega = u'(tau)/u'(0) - 1 for the Hookean contact with viscous damping.

    Equals Eq. 18's Omega when gamma_t = gamma_n = 0. The tangential spring does not
    depend on the overlap, so the slip obeys the frozen equation for the whole contact
    time tau (Eq. 16, or its damped form).
    """
    # LAMMPS caps |F_t| at mu |F_n|: once limit_damping zeroes F_n, F_t is zero as well,
    # so the slip stops evolving when the normal force ends
    tau = collision_time(m, kn, gamma_n, tensile)
    return float(slip_rate_ratio(tau, kt, m, alpha, gamma_t)) - 1.0


def scattering_matrix(alpha: float, Omega: float, e: float = 1.0) -> np.ndarray:
    """Eq. 18: the 3x3 map from (v_n, v_t, r omega) before to after a collision.

    ``e`` is the normal restitution (1 in the paper's undamped model).
    """
    a = alpha / (1.0 + alpha)
    b = 1.0 / (1.0 + alpha)
    return np.array(
        [
            [-e, 0.0, 0.0],
            [0.0, 1.0 + a * Omega, a * Omega],
            [0.0, b * Omega, 1.0 + b * Omega],
        ]
    )


def Omega_of_matrix(m3, alpha: float):
    """Eq. 18 read backwards: Omega from a scattering matrix's (v_t -> v_t) entry, 1 + alpha Omega/(1 + alpha)
    (``m3``: one 3x3 matrix or a stack of them)."""
    return (np.asarray(m3)[..., 1, 1] - 1.0) * (1.0 + alpha) / alpha


def block_matrix(alpha: float, Omega: float, e: float = 1.0) -> np.ndarray:
    """The 6x6 map of a 3-D collision, states (v_n, v_t, r omega, v_s, r omega_s, r omega_n).

    Without a Coulomb cap the tangential spring acts on each tangential direction alone,
    so the second pair (v_s, r omega_s), whose slip is v_s + r omega_s, scatters by the same
    2x2 block as (v_t, r omega); the spin about the normal moves no contact point and so
    passes through unchanged. ``scattering_matrix`` is the top-left 3x3 block.
    """
    return block_from(scattering_matrix(alpha, Omega, e))


def block_from(m3: np.ndarray) -> np.ndarray:
    """The 6x6 block map built from a 3x3 one (see :func:`block_matrix`)."""
    out = np.zeros((6, 6))
    out[:3, :3] = m3
    out[3:5, 3:5] = m3[1:, 1:]
    out[5, 5] = 1.0
    return out


def rough_matrix(alpha: float) -> np.ndarray:
    """Eq. 20: the energy-conserving rough sphere, Eq. 18 with Omega = -2."""
    return scattering_matrix(alpha, -2.0)


def rolling_matrix(alpha: float) -> np.ndarray:
    """Eq. 23: the rolling collision (rapid tangential damping), Eq. 18 with Omega = -1."""
    return scattering_matrix(alpha, -1.0)


def magic_kt_over_kn(alpha: float) -> float:
    """The ratio kt/kn = alpha/(1+alpha) that makes tau = pi/sqrt(Q), hence Omega = -2."""
    return alpha / (1.0 + alpha)


# ---------------------------------------------------------------------------
# Energy (Section 5)
# ---------------------------------------------------------------------------

def energy(state, m: float, alpha: float):
    """Kinetic energy of states (..., 3) ordered (v_n, v_t, r omega), or (..., 6) with
    (v_s, r omega_s, r omega_n) after them: I omega^2/2 = alpha m (r omega)^2/2 per axis."""
    s = np.asarray(state, dtype=float)
    moving, spinning = ((0, 1), (2,)) if s.shape[-1] == 3 else ((0, 1, 3), (2, 4, 5))
    return 0.5 * m * (sum(s[..., k] ** 2 for k in moving) + alpha * sum(s[..., k] ** 2 for k in spinning))


def energy_change(initial, final, m: float, alpha: float):
    """Eq. 21: Delta E = E(final) - E(initial)."""
    return energy(final, m, alpha) - energy(initial, m, alpha)


def dissipation(initial, final, m: float, alpha: float):
    """f = -Delta E / E(0), the fraction of the initial kinetic energy lost (Fig. 6)."""
    return -energy_change(initial, final, m, alpha) / energy(initial, m, alpha)
