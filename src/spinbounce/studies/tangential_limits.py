"""Closed forms of the coefficient of tangential restitution in its two rigid limits, for the
capped linear spring-dashpot of Becker, Schwager & Poeschel (:mod:`.tangential`) against a flat
wall (the paper's scene of Wang & Harrowell).

**Sign convention.** g_t = u' = v_t + r omega is the tangential velocity of the contact
point (the slip rate, Eq. 2) and

    beta = -g_t' / g_t        (after / before the collision),

Walton's (1993) and Foerster et al.'s (1994) convention: beta = -1 leaves the slip alone
(a smooth sphere), beta = +1 reverses it elastically (a perfectly rough one). The ratio
on the horizontal axis is psi = |g_t| / |v_n|.

**Gross slip (Walton).** If the contact slides in one direction from first touch to exit,
the tangential force is mu |F_n| throughout, against the slip. The slip rate obeys
u'' = -s F_t with s = (1 + 1/alpha)/m (Eq. 8's reduced mass: the force slows the centre by
F_t/m and spins it by r F_t r/I), so u' changes by -s mu J, J = int |F_n| dt. If the normal
force never pulls (gamma_n = 0, or limit_damping), J is the normal impulse m (1 + e)|v_n|,
and

    beta = -1 + mu (1 + e) (1 + 1/alpha) |v_n| / |g_t| = -1 + W/psi,   W = mu (1 + e)(1 + 1/alpha):

linear in 1/psi, exact (no limit taken) wherever the contact slides throughout. For an
undamped contact (e = 1) that is psi >= psi_g = mu max(kn/kt, 2 (1 + 1/alpha) - kn/kt):
sliding starts at first touch if the spring would outgrow the cap, kt g_t > mu kn |v_n|,
and it goes on while sticking would push the force outwards faster than the cap grows,
kt u'(t) > mu F_n'(t). With F_n = kn |v_n| sin(w t)/w and u'(t) = g_t - (1 + 1/alpha) mu
|v_n| (1 - cos w t) that condition is linear in cos(w t), and its worst case over
cos(w t) in [-1, 1] gives psi_g.

**Sticking plateau.** If the contact never slides, its tangential motion is the uncapped
one of Eq. 18: Delta u' = Delta v_t + r Delta omega = (alpha Omega/(1 + alpha) + Omega/
(1 + alpha)) u'(0) = Omega u'(0) (Eq. 19 summed), so g_t' = (1 + Omega) g_t and

    beta_stick = -(1 + Omega) = -cos(pi sqrt(kt/kn (1 + alpha)/alpha))   (undamped),

with Eq. 22's exact damped Omega otherwise. A capped contact sticks throughout only at
the magic ratio kt/kn = alpha/(1 + alpha) (Eq. 20, Omega = -2), for psi <= mu kn/kt: there
the spring force kt u' sin(w t)/w and the cap mu kn |v_n| sin(w t)/w keep a fixed ratio.
At any other ratio the spring still holds a force when the normal force vanishes, so the
last moments slide and the plateau is the limit psi/mu -> 0. Its own error is first
order: near the end the cap falls as mu kn |v_n| (tau - t) below the stuck spring force
A = kt g_t sin(w_t tau)/w_t (w_t = sqrt(kt s)), the contact slides for A/(mu kn |v_n|)
and the slip gains s A^2/(2 mu kn |v_n|), so

    beta = beta_stick - (kt/kn) sin(w_t tau) |sin(w_t tau)| psi / (2 mu) + O(psi^2).

**The switch.** The two lines meet at psi* = W/(-Omega), i.e. at W/psi = -Omega: on the
reduced axis W/psi every gross-slip branch is the one line beta = -1 + W/psi and each
plateau ends where that line reaches it. At the magic ratio psi* = psi_g and the exact
curve is the two branches, kinked at psi*; elsewhere the exact curve leaves the
gross-slip line at psi_g (above psi* for kt/kn = 1/10 and 1/2, below it for kt/kn = 0.8,
where beta overshoots the plateau) and reaches the plateau only as psi -> 0.
"""

from __future__ import annotations

import math

import numpy as np

from ..model.parameters import SceneError
from ..exact import rigid_body

__all__ = ["slip_rate", "beta", "walton_scale", "gross_slip", "plateau", "switch_ratio", "gross_slip_onset",
           "plateau_slope", "is_magic", "states_at"]

#: kt/kn within this of alpha/(1 + alpha) counts as the magic ratio (its rounding in kt = 20/7).
MAGIC_TOLERANCE = 1e-12


def slip_rate(states: np.ndarray) -> np.ndarray:
    """g_t = v_t + r omega of (n, 3) states (v_n, v_t, r omega)."""
    states = np.atleast_2d(states)
    return states[:, 1] + states[:, 2]


def beta(initial: np.ndarray, final: np.ndarray) -> np.ndarray:
    """beta = -g_t'/g_t for each row."""
    return -slip_rate(final) / slip_rate(initial)


def states_at(psi) -> np.ndarray:
    """(n, 3) states of speed 1 with |g_t|/|v_n| = psi and no spin: (-1, psi, 0)/sqrt(1 + psi^2)."""
    psi = np.asarray(psi, dtype=float)
    size = np.sqrt(1.0 + psi**2)
    return np.column_stack([-1.0 / size, psi / size, np.zeros_like(psi)])


def _capped(model) -> None:
    if model.mu is None:
        raise SceneError("mu", model.mu, "the tangential-restitution limits need a Coulomb cap (a finite mu)")
    if model.normal_law.contact_radius:
        raise SceneError("normal", model.normal, "the closed forms are the linear (Hookean) dashpot's")


def walton_scale(model) -> float:
    """W = mu (1 + e)(1 + 1/alpha): beta = -1 + W/psi on the gross-slip branch."""
    _capped(model)
    if model.gamma_n > 0.0 and not model.limit_damping:
        raise SceneError("limit_damping", model.limit_damping, "with gamma_n > 0 the normal force pulls at the end "
                         "and int |F_n| dt is not m (1 + e)|v_n|: Walton's branch needs limit_damping = True")
    return model.mu * (1.0 + model.restitution) * (1.0 + 1.0 / model.alpha)


def gross_slip(model, psi) -> np.ndarray:
    """Walton's gross-slip branch, beta = -1 + W/psi: :func:`exact.rigid_body.gross_slip`'s
    outcome of the unit-speed states at psi (a test holds it to the line)."""
    walton_scale(model)  # refuses a model the branch is not exact for
    initial = states_at(np.atleast_1d(psi))
    final = rigid_body.gross_slip(model, initial[:, 0], initial[:, 1], initial[:, 2] / model.r, model.restitution)
    return beta(initial, final)


def plateau(model) -> float:
    """The sticking plateau beta = -(1 + Omega) (Eq. 18; Eq. 22's exact damped Omega)."""
    _capped(model)
    return -(1.0 + model.Omega)


def switch_ratio(model) -> float:
    """psi* where the gross-slip line meets the plateau: W/(-Omega)."""
    return walton_scale(model) / (-model.Omega)


def _undamped(model) -> bool:
    return model.gamma_n == 0.0 and model.gamma_t == 0.0


def gross_slip_onset(model) -> float | None:
    """psi_g, from which an undamped contact slides throughout (the branch is exact); None
    with damping, where no closed form is derived here."""
    _capped(model)
    if not _undamped(model):
        return None
    ratio = model.kn / model.kt
    return model.mu * max(ratio, 2.0 * (1.0 + 1.0 / model.alpha) - ratio)


def is_magic(model) -> bool:
    """kt/kn = alpha/(1 + alpha) (Eq. 20)."""
    return abs(model.kt / model.kn - model.alpha / (1.0 + model.alpha)) <= MAGIC_TOLERANCE


def plateau_slope(model) -> float | None:
    """d beta/d psi at psi -> 0 of an undamped capped contact: -(kt/kn) sin|sin|(w_t tau)/(2 mu)
    (zero at the magic ratio, where sin(w_t tau) = 0); None with damping."""
    _capped(model)
    if not _undamped(model):
        return None
    if is_magic(model):
        return 0.0
    phase = math.pi * math.sqrt(model.kt / model.kn * (1.0 + model.alpha) / model.alpha)
    sine = math.sin(phase)
    return -(model.kt / model.kn) * sine * abs(sine) / (2.0 * model.mu)
