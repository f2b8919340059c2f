"""The paper's planar theory generalized to two free spheres a and b.

The wall's derivation (Eqs. 1-18) carries over if the line of centres ``n`` (unit vector
from b to a) is held fixed during the contact. The normal overlap then obeys
m* x'' = -kn x - gamma_n x' with the reduced mass m* = m_a m_b/(m_a + m_b), so the
contact lasts tau = pi sqrt(m*/kn) (Eq. 16 with m -> m*). The slip at the contact point,

    u' = (v_a - v_b)_t - (r_a w_a + r_b w_b) x n,

feels the tangential force F_t = -kt u - gamma_t u' on a (and -F_t on b), which acts at
lever arms r_a and r_b; so u'' = K F_t with the slip mobility

    K = 1/m_a + 1/m_b + r_a^2/I_a + r_b^2/I_b.

That is the wall's slip equation (Eq. 8) for a sphere of mass m* and
alpha_eq = 1/(m* K - 1), since (1 + alpha)/(alpha m) = K then. The slip rate after the
contact is (1 + Omega) u'(0) with the wall's Omega of (m*, alpha_eq) (Eq. 18's, or the
exact damped one), and the tangential impulse on a is Omega u'(0)/K.

1/alpha_eq = (m_b/(m_a + m_b))/alpha_a + (m_a/(m_a + m_b))/alpha_b: with equal alpha,
alpha_eq = alpha whatever the masses and radii, so every such pair has the wall's Omega.
As m_b grows, m* -> m_a and alpha_eq -> alpha_a: the wall is recovered.

The theory is not exact: the line of centres turns by about eps = v_t tau/(r_a + r_b)
during the contact (:mod:`.pair_exact` integrates what LAMMPS does). Arrays are per pair:
vectors (P, 3) in LAMMPS's frame, sphere properties (P,) or scalars. Pure numpy.
"""

from __future__ import annotations

import numpy as np

from . import linear

__all__ = ["reduced_mass", "slip_mobility", "equivalent_alpha", "contact_time", "restitution", "Omega",
           "tangent_frame", "wall_states", "from_wall",
           "slip_rate", "predict", "angular_momentum_about_contact", "line_turn", "centrifugal_ratio"]


def reduced_mass(m_a, m_b):
    return m_a * m_b / (m_a + m_b)


def slip_mobility(m_a, r_a, alpha_a, m_b, r_b, alpha_b):
    """K = 1/m_a + 1/m_b + r_a^2/I_a + r_b^2/I_b, with I = alpha m r^2: u'' = K F_t."""
    return 1.0 / m_a + 1.0 / m_b + 1.0 / (alpha_a * m_a) + 1.0 / (alpha_b * m_b)


def equivalent_alpha(m_a, alpha_a, m_b, alpha_b):
    """The alpha of the wall problem with the pair's slip equation, 1/(m* K - 1): a mass-weighted
    harmonic mean of the two alphas (independent of the radii), so it lies between them."""
    mean = 1.0 / (m_b / (m_a + m_b) / alpha_a + m_a / (m_a + m_b) / alpha_b)
    inside = np.clip(mean, np.minimum(alpha_a, alpha_b), np.maximum(alpha_a, alpha_b))  # rounding kept inside
    return float(inside) if np.ndim(inside) == 0 else inside


def _each_distinct(function, *args):
    """``function`` (of numbers) over ``args`` broadcast together, evaluated once per distinct combination:
    a batch's thousands of pairs share a few spheres and one law."""
    arrays = np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in args))
    if arrays[0].size == 0:
        return np.zeros(arrays[0].shape)
    firsts = [a.flat[0] for a in arrays]
    if all(np.array_equal(a, np.broadcast_to(f, a.shape), equal_nan=True) for a, f in zip(arrays, firsts, strict=True)):
        return np.full(arrays[0].shape, float(function(*map(float, firsts)))) + 0.0  # one combination: no sort
    distinct, back = np.unique(np.stack([a.ravel() for a in arrays], axis=1), axis=0, return_inverse=True)
    values = np.array([function(*row) for row in distinct.tolist()], dtype=float)
    return values[back.ravel()].reshape(arrays[0].shape) + 0.0


def contact_time(m_a, m_b, kn, gamma_n=0.0):
    """Eq. 16 with the reduced mass: pi sqrt(m*/kn) (its damped form when gamma_n > 0)."""
    return _each_distinct(linear.collision_time, reduced_mass(m_a, m_b), kn, gamma_n)


def restitution(m_a, m_b, kn, gamma_n=0.0):
    """Normal restitution of the relative velocity (1 without damping)."""
    return _each_distinct(linear.restitution, reduced_mass(m_a, m_b), kn, gamma_n)


def Omega(m_a, alpha_a, m_b, alpha_b, kn, kt, gamma_t=0.0, gamma_n=0.0):
    """The pair's Omega: the wall's exact Omega of (m*, alpha_eq); cos(pi sqrt((kt/kn) m* K)) - 1
    without damping (Eq. 18's)."""
    return _each_distinct(linear.Omega_exact, reduced_mass(m_a, m_b), kn, kt,
                          equivalent_alpha(m_a, alpha_a, m_b, alpha_b), gamma_t, gamma_n)


def _column(x):
    return np.asarray(x, dtype=float)[..., None]


def slip_rate(n, v_a, v_b, w_a, w_b, r_a, r_b):
    """u' = (v_a - v_b)_t - (r_a w_a + r_b w_b) x n: the contact points' relative tangential velocity."""
    n = np.asarray(n, dtype=float)
    v_rel = np.asarray(v_a, dtype=float) - np.asarray(v_b, dtype=float)
    v_t = v_rel - np.sum(v_rel * n, axis=-1, keepdims=True) * n
    spin = _column(r_a) * np.asarray(w_a, dtype=float) + _column(r_b) * np.asarray(w_b, dtype=float)
    return v_t - np.cross(spin, n)


def predict(n, v_a, v_b, w_a, w_b, m_a, r_a, alpha_a, m_b, r_b, alpha_b, kn, kt, gamma_n=0.0, gamma_t=0.0):
    """Final (v_a, v_b, w_a, w_b) of the planar theory: each (P, 3).

    Normal impulse m* (1 + e) |v_n| along n; tangential impulse Omega u'(0)/K on a, acting
    at the contact point (-r_a n from a's centre, +r_b n from b's); spins about n unchanged.
    """
    n = np.asarray(n, dtype=float)
    m_star = reduced_mass(m_a, m_b)
    v_rel = np.asarray(v_a, dtype=float) - np.asarray(v_b, dtype=float)
    v_n = np.sum(v_rel * n, axis=-1)
    e = restitution(m_a, m_b, kn, gamma_n)
    normal_impulse = _column(-m_star * (1.0 + e) * v_n) * n
    K = slip_mobility(m_a, r_a, alpha_a, m_b, r_b, alpha_b)
    omega = Omega(m_a, alpha_a, m_b, alpha_b, kn, kt, gamma_t, gamma_n)
    tangential_impulse = _column(omega / K) * slip_rate(n, v_a, v_b, w_a, w_b, r_a, r_b)
    return _applied(normal_impulse + tangential_impulse, np.cross(n, tangential_impulse), v_a, v_b, w_a, w_b, m_a,
                    r_a, alpha_a, m_b, r_b, alpha_b)


def _applied(impulse, lever, v_a, v_b, w_a, w_b, m_a, r_a, alpha_a, m_b, r_b, alpha_b):
    """(v_a, v_b, w_a, w_b) after the contact's ``impulse`` on a (minus it on b), ``lever`` = n x its tangential
    part: the torque impulse on a is (-r_a n) x P = -r_a lever, on b (r_b n) x (-P) = -r_b lever."""
    return (np.asarray(v_a, dtype=float) + impulse / _column(m_a),
            np.asarray(v_b, dtype=float) - impulse / _column(m_b),
            np.asarray(w_a, dtype=float) - lever / _column(alpha_a * m_a * r_a),
            np.asarray(w_b, dtype=float) - lever / _column(alpha_b * m_b * r_b))


def tangent_frame(n):
    """Unit t and s = n x t across each unit ``n`` ((P, 3)): t along n x e, e the axis least along n."""
    n = np.atleast_2d(np.asarray(n, dtype=float))
    axis = np.eye(3)[np.argmin(np.abs(n), axis=1)]
    t = np.cross(n, axis)
    t /= np.linalg.norm(t, axis=1, keepdims=True)
    return t, np.cross(n, t)


def wall_states(n, v_a, v_b, w_a, w_b, r_a, r_b):
    """The equivalent wall's initial (v_n, v_t, r omega, v_s, r omega_s, r omega_n) of each pair ((P, 6)): the
    relative velocity along n, t and s (:func:`tangent_frame`), r omega = u' - v along t and s (u' the slip rate:
    u' = v_t + r omega, the wall's), and no spin about n (the line held, nothing turns it)."""
    n = np.atleast_2d(np.asarray(n, dtype=float))
    t, s = tangent_frame(n)
    v = np.asarray(v_a, dtype=float) - np.asarray(v_b, dtype=float)
    spin = slip_rate(n, v_a, v_b, w_a, w_b, r_a, r_b) - v
    along = [np.sum(x * y, axis=-1) for x, y in ((v, n), (v, t), (spin, t), (v, s), (spin, s))]
    return np.column_stack([*along, np.zeros(len(n))])


def from_wall(n, v_a, v_b, w_a, w_b, m_a, r_a, alpha_a, m_b, r_b, alpha_b, final):
    """Final (v_a, v_b, w_a, w_b) ((P, 3) each) of pairs whose line of centres is held, from their equivalent
    wall's final states ``final`` ((P, 5) or (P, 6) rows of v_n, v_t, r omega, v_s, r omega_s: what the wall's
    exact solver, a cap included, gives for :func:`wall_states`): the impulse on a, m* (v' - v), and its
    torques at the contact point, as :func:`predict` applies them."""
    n = np.atleast_2d(np.asarray(n, dtype=float))
    t, s = tangent_frame(n)
    final = np.asarray(final, dtype=float)
    v = np.asarray(v_a, dtype=float) - np.asarray(v_b, dtype=float)
    v_final = _column(final[:, 0]) * n + _column(final[:, 1]) * t + _column(final[:, 3]) * s
    impulse = _column(reduced_mass(m_a, m_b)) * (v_final - v)
    return _applied(impulse, np.cross(n, impulse), v_a, v_b, w_a, w_b, m_a, r_a, alpha_a, m_b, r_b, alpha_b)


def angular_momentum_about_contact(n, v, w, m, r, alpha, side):
    """One sphere's angular momentum about the contact point: I w + m (x - c) x v.

    ``side`` is +1 for a (centre at +r n from the contact point) and -1 for b. With n held
    fixed the contact force passes through that point, so this is conserved.
    """
    offset = _column(side * np.asarray(r, dtype=float)) * np.asarray(n, dtype=float)
    return _column(alpha * m * r * r) * np.asarray(w, dtype=float) + _column(m) * np.cross(offset, v)


def line_turn(v_t, tau, r_a, r_b):
    """eps = |v_t| tau/(r_a + r_b): about how far (radians) the line of centres turns in contact."""
    return np.abs(v_t) * tau / (r_a + r_b)


def centrifugal_ratio(v_t, v_n, tau, r_a, r_b):
    """v_t^2 tau/(pi (r_a + r_b) |v_n|): the centrifugal acceleration v_t^2/(r_a + r_b) over
    the normal spring's peak deceleration pi |v_n|/tau (it equals eps |v_t/v_n|/pi)."""
    return v_t**2 * tau / (np.pi * (r_a + r_b) * np.abs(v_n))
